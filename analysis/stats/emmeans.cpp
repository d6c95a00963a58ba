// Estimated marginal means and contrasts; see emmeans.h.
#include "analysis/stats/emmeans.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "analysis/stats/apa.h"
#include "analysis/stats/detail/lmm_design.h"
#include "analysis/stats/detail/numbers.h"
#include "analysis/stats/distributions.h"
#include "analysis/stats/posthoc.h"

namespace dtlab::stats {
namespace {

// The fixed design's coding without rows: the X row of any cell (detail/lmm_design.h).
detail::FixedDesign coding(const LmmFit& fit) {
  std::vector<detail::CodedFactor> factors;
  for (size_t f = 0; f < fit.factor_names.size(); ++f) factors.push_back({fit.factor_names[f], fit.factor_levels[f], {}, true});
  return detail::fixed_design(std::move(factors));
}

// Visits every level combination of `factors` (first fastest).
template <class F>
void for_each_cell(const LmmFit& fit, const std::vector<size_t>& factors, std::vector<int>& level, F&& f) {
  std::vector<int> idx(factors.size(), 0);
  while (true) {
    for (size_t k = 0; k < factors.size(); ++k) level[factors[k]] = idx[k];
    f();
    size_t k = 0;
    for (; k < factors.size(); ++k) {
      if (++idx[k] < static_cast<int>(fit.factor_levels[factors[k]].size())) break;
      idx[k] = 0;
    }
    if (k == factors.size()) return;
  }
}

double df_of(const LmmFit& fit, const Eigen::RowVectorXd& L) {
  return fit.family == Family::binomial ? std::numeric_limits<double>::infinity() : satterthwaite_df(fit, L);
}

double critical(double df) {
  return std::isinf(df) ? normal_quantile(0.975) : t_quantile(0.975, df);
}

double back(EmmScale s, double v) {
  if (s == EmmScale::log) return std::exp(v);
  if (s == EmmScale::logit) return 1.0 / (1.0 + std::exp(-v));
  return kNaN;
}

}  // namespace

Result<EmmTable> marginal_means(const LmmFit& fit, const std::vector<std::string>& factors) {
  EmmTable t;
  t.factors = factors;
  t.scale = fit.family == Family::binomial ? EmmScale::logit
            : fit.transform == Transform::log ? EmmScale::log
                                              : EmmScale::identity;
  std::vector<size_t> chosen, others;
  for (const auto& name : factors) {
    size_t f = 0;
    while (f < fit.factor_names.size() && fit.factor_names[f] != name) ++f;
    if (f == fit.factor_names.size()) return Error{"", 0, 0, name, "not a factor of the model"};
    chosen.push_back(f);
  }
  for (size_t f = 0; f < fit.factor_names.size(); ++f)
    if (std::find(chosen.begin(), chosen.end(), f) == chosen.end()) others.push_back(f);
  const detail::FixedDesign design = coding(fit);
  std::vector<int> level(fit.factor_names.size(), 0);
  std::vector<Eigen::RowVectorXd> rows;
  for_each_cell(fit, chosen, level, [&] {
    Eigen::RowVectorXd L = Eigen::RowVectorXd::Zero(static_cast<Eigen::Index>(fit.column_names.size()));
    double count = 0;
    for_each_cell(fit, others, level, [&] {
      L += design.cell_row(level);
      count += 1;
    });
    L /= count;
    EmmRow r;
    for (size_t f : chosen) r.levels.push_back(fit.factor_levels[f][static_cast<size_t>(level[f])]);
    r.estimate = L.dot(fit.beta);
    r.se = std::sqrt((L * fit.vcov * L.transpose())(0, 0));
    r.df = df_of(fit, L);
    const double q = critical(r.df);
    r.ci_low = r.estimate - q * r.se;
    r.ci_high = r.estimate + q * r.se;
    r.response = back(t.scale, r.estimate);
    r.response_ci_low = back(t.scale, r.ci_low);
    r.response_ci_high = back(t.scale, r.ci_high);
    t.means.push_back(r);
    rows.push_back(L);
  });
  auto label = [](const EmmRow& r) {
    std::string s;
    for (const auto& l : r.levels) s += (s.empty() ? "" : " ") + l;
    return s;
  };
  std::vector<double> p;
  for (size_t i = 0; i < rows.size(); ++i)
    for (size_t j = i + 1; j < rows.size(); ++j) {
      const Eigen::RowVectorXd L = rows[i] - rows[j];
      EmmContrast c;
      c.a = label(t.means[i]);
      c.b = label(t.means[j]);
      c.estimate = L.dot(fit.beta);
      c.se = std::sqrt((L * fit.vcov * L.transpose())(0, 0));
      c.df = df_of(fit, L);
      c.statistic = c.estimate / c.se;
      const Tail tail = std::isinf(c.df) ? normal_two_sided(c.statistic) : t_two_sided(c.statistic, c.df);
      c.p = tail.p;
      c.log10_p = tail.log10_p;
      const double q = critical(c.df);
      c.ci_low = c.estimate - q * c.se;
      c.ci_high = c.estimate + q * c.se;
      const bool ratio = t.scale != EmmScale::identity;
      c.ratio = ratio ? std::exp(c.estimate) : kNaN;
      c.ratio_ci_low = ratio ? std::exp(c.ci_low) : kNaN;
      c.ratio_ci_high = ratio ? std::exp(c.ci_high) : kNaN;
      t.contrasts.push_back(c);
      p.push_back(c.p);
    }
  const std::vector<double> adjusted = holm(p);
  for (size_t i = 0; i < adjusted.size(); ++i) t.contrasts[i].p_holm = adjusted[i];
  return t;
}

EmmContrast reversed(const EmmContrast& c) {
  EmmContrast r = c;
  std::swap(r.a, r.b);
  r.estimate = -c.estimate;
  r.statistic = -c.statistic;
  r.ci_low = -c.ci_high;
  r.ci_high = -c.ci_low;
  r.ratio = 1 / c.ratio;
  r.ratio_ci_low = 1 / c.ratio_ci_high;
  r.ratio_ci_high = 1 / c.ratio_ci_low;
  return r;
}

std::string apa_contrast_sentence(const EmmTable& table, const EmmContrast& c, bool time_measure,
                                  const std::string& measure) {
  const bool z = std::isinf(c.df);
  const std::string test = z ? "z = " + apa_number(c.statistic) : "t(" + apa_df(c.df) + ") = " + apa_number(c.statistic);
  const std::string p = apa_p(c.p_holm) + (table.contrasts.size() > 1 ? " (Holm)" : "");
  if (table.scale == EmmScale::log && time_measure)
    return c.a + " trials took " + apa_number(c.ratio) + " times as long as " + c.b + " trials, 95% CI " +
           apa_interval(c.ratio_ci_low, c.ratio_ci_high, false) + ", " + test + ", " + p + ".";
  if (table.scale == EmmScale::log)
    return measure + " for " + c.a + " was " + apa_number(c.ratio) + " times that for " + c.b + ", 95% CI " +
           apa_interval(c.ratio_ci_low, c.ratio_ci_high, false) + ", " + test + ", " + p + ".";
  if (table.scale == EmmScale::logit)
    return measure + " for " + c.a + " were " + apa_number(c.ratio) + " times those for " + c.b +
           " (odds ratio), 95% CI " + apa_interval(c.ratio_ci_low, c.ratio_ci_high, false) + ", " + test + ", " + p + ".";
  return measure + " for " + c.a + " minus " + c.b + ": " + apa_number(c.estimate) + ", 95% CI " +
         apa_interval(c.ci_low, c.ci_high, false) + ", " + test + ", " + p + ".";
}

}  // namespace dtlab::stats

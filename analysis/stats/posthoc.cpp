// Pairwise comparisons with Holm's correction; see posthoc.h.
#include "analysis/stats/posthoc.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numeric>

#include "analysis/stats/descriptives.h"
#include "analysis/stats/detail/design.h"
#include "analysis/stats/detail/multivariate.h"
#include "analysis/stats/distributions.h"

namespace dtlab::stats {

std::vector<double> holm(const std::vector<double>& p) {
  std::vector<std::size_t> idx;
  for (std::size_t i = 0; i < p.size(); ++i)
    if (!std::isnan(p[i])) idx.push_back(i);
  std::stable_sort(idx.begin(), idx.end(), [&](std::size_t a, std::size_t b) { return p[a] < p[b]; });
  std::vector<double> out(p.size(), std::numeric_limits<double>::quiet_NaN());
  const double m = static_cast<double>(idx.size());
  double running = 0.0;
  for (std::size_t j = 0; j < idx.size(); ++j) {
    running = std::max(running, (m - static_cast<double>(j)) * p[idx[j]]);
    out[idx[j]] = std::min(1.0, running);
  }
  return out;
}

Comparison paired_comparison(const std::string& a, const std::string& b, const std::vector<double>& x,
                             const std::vector<double>& y) {
  const PairedTResult t = paired_t(x, y);
  Comparison c;
  c.a = a;
  c.b = b;
  c.test = "paired t";
  c.n = t.n;
  c.estimate = t.mean_difference;
  c.se = t.se;
  c.ci_low = t.ci_low;
  c.ci_high = t.ci_high;
  c.statistic = t.t;
  c.df = t.df;
  c.p = t.p;
  c.dz = t.dz;
  return c;
}

void adjust_holm(std::vector<Comparison>& family) {
  std::vector<double> ps;
  for (const auto& c : family) ps.push_back(c.p);
  const auto adj = holm(ps);
  for (std::size_t i = 0; i < family.size(); ++i) family[i].p_holm = adj[i];
}

Result<std::vector<Comparison>> pairwise_within(const LongData& data, const std::string& factor, PairwiseTest test,
                                                const WilcoxonOptions& options) {
  auto built = detail::build_cell_design(data);
  if (!built) return built.error();
  const detail::CellDesign& d = *built;
  const auto it = std::find(d.within_names.begin(), d.within_names.end(), factor);
  if (it == d.within_names.end()) return Error{data.source, 0, 0, factor, "not a within-subject factor of the design"};
  const std::size_t f = static_cast<std::size_t>(it - d.within_names.begin());
  const std::size_t L = d.within_levels[f].size();
  if (!d.between_names.empty() && test == PairwiseTest::paired_t) {  // a mixed design: emmeans on the afex fit
    auto model = detail::MultivariateModel::fit(d, data.source);
    if (!model) return model.error();
    const std::size_t factor = d.between_names.size() + f;
    std::vector<Comparison> out;
    for (std::size_t i = 0; i < L; ++i)
      for (std::size_t j = i + 1; j < L; ++j) out.push_back(model->pair(factor, i, j, model->averaging()));
    adjust_holm(out);
    return out;
  }
  const detail::FactorMarginals m = detail::factor_marginals(d, f);
  const std::vector<std::vector<double>>& val = m.value;
  const std::vector<std::vector<double>>& del = m.delta;
  std::vector<Comparison> out;
  for (std::size_t i = 0; i < L; ++i)
    for (std::size_t j = i + 1; j < L; ++j) {
      Comparison c = paired_comparison(d.within_levels[f][i], d.within_levels[f][j], del[i], del[j]);
      if (test == PairwiseTest::wilcoxon) {
        const WilcoxonResult w = wilcoxon_signed_rank(val[i], val[j], options);
        c.test = "wilcoxon";
        c.statistic = w.V;
        c.df = std::numeric_limits<double>::quiet_NaN();
        c.p = w.p;
      }
      out.push_back(c);
    }
  adjust_holm(out);
  return out;
}

Result<std::vector<Comparison>> pairwise_between(const LongData& data) {
  if (data.between.empty()) return Error{data.source, 0, 0, "", "no between-subject factor to compare"};
  const Factor& g = data.between.front();
  std::vector<std::string> levels;
  std::map<std::string, std::size_t> lookup;
  std::vector<std::vector<double>> groups;
  for (std::size_t i = 0; i < data.rows(); ++i) {
    auto [it, ins] = lookup.emplace(g.level[i], levels.size());
    if (ins) {
      levels.push_back(g.level[i]);
      groups.emplace_back();
    }
    if (!data.dv.missing(i)) groups[it->second].push_back(data.dv.delta[i]);
  }
  std::vector<Descriptives> desc;
  double pooled_num = 0.0, total_df = 0.0;
  for (const auto& x : groups) {
    desc.push_back(describe(x, 0.0));
    if (x.size() > 1) {
      pooled_num += desc.back().sd * desc.back().sd * static_cast<double>(x.size() - 1);
      total_df += static_cast<double>(x.size() - 1);
    }
  }
  const double pooled_sd = std::sqrt(pooled_num / total_df);
  std::vector<Comparison> out;
  const double q = t_quantile(0.975, total_df);
  for (std::size_t i = 0; i < levels.size(); ++i)
    for (std::size_t j = i + 1; j < levels.size(); ++j) {
      Comparison c;
      c.a = levels[i];
      c.b = levels[j];
      c.test = "pooled t";
      c.n = desc[i].n + desc[j].n;
      c.estimate = desc[i].mean - desc[j].mean;
      c.se = pooled_sd * std::sqrt(1.0 / static_cast<double>(desc[i].n) + 1.0 / static_cast<double>(desc[j].n));
      c.ci_low = c.estimate - q * c.se;
      c.ci_high = c.estimate + q * c.se;
      c.statistic = c.estimate / c.se;
      c.df = total_df;
      c.p = t_two_sided(c.statistic, total_df).p;
      c.dz = std::numeric_limits<double>::quiet_NaN();
      out.push_back(c);
    }
  adjust_holm(out);
  return out;
}

}  // namespace dtlab::stats

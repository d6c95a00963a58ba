// One-way ANOVA; see anova.h.
#include "analysis/stats/anova.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <stdexcept>

#include "analysis/stats/csv.h"
#include "analysis/stats/detail/numbers.h"
#include "analysis/stats/detail/sum.h"
#include "analysis/stats/distributions.h"
#include "analysis/stats/effect_size.h"

namespace dtlab::stats {
namespace {

// Mean of x: exact when all values are equal, else sum / n with a second-pass correction.
double careful_mean(const std::vector<double>& x) {
  bool constant = true;
  for (double v : x) constant = constant && v == x.front();
  if (constant) return x.front();
  detail::Sum s;
  for (double v : x) s.add(v);
  double m = s.value() / static_cast<double>(x.size());
  detail::Sum c;
  for (double v : x) c.add(v - m);
  return m + c.value() / static_cast<double>(x.size());
}

// Sum of squared deviations from the mean, with the corrected two-pass
// formula sum (x - m)^2 - (sum (x - m))^2 / n that cancels the rounding of m.
double sum_of_squares(const std::vector<double>& x, double m) {
  detail::Sum ss, dev;
  for (double v : x) {
    ss.add((v - m) * (v - m));
    dev.add(v - m);
  }
  return std::max(0.0, ss.value() - dev.value() * dev.value() / static_cast<double>(x.size()));
}

void clear_sphericity(Effect& e) {
  e.mauchly_W = e.mauchly_p = e.gg_epsilon = e.hf_epsilon = kNaN;
  e.p_gg = e.log10_p_gg = e.p_hf = e.log10_p_hf = kNaN;
}

// F and p, or the documented degenerate results with their warning.
void test_effect(Effect& e, size_t k, std::vector<std::string>& warnings) {
  if (k < 2) {
    e.F = e.p = e.log10_p = kNaN;
    warnings.push_back("only one group: there is no between-group effect to test (F and p undefined)");
  } else if (e.df2 == 0) {
    e.F = e.p = e.log10_p = kNaN;
    warnings.push_back("one observation per group: no within-group degrees of freedom (F and p undefined)");
  } else if (e.ss_error == 0) {
    if (e.ss > 0) {
      e.F = std::numeric_limits<double>::infinity();
      e.p = 0.0;
      e.log10_p = -std::numeric_limits<double>::infinity();
      warnings.push_back("zero within-group variance with different group means: F is infinite, p = 0");
    } else {
      e.F = e.p = e.log10_p = kNaN;
      warnings.push_back("every value is equal: F = 0/0 is undefined");
    }
  } else {
    e.F = (e.ss / e.df1) / (e.ss_error / e.df2);
    const Tail t = f_upper(e.F, e.df1, e.df2);
    e.p = t.p;
    e.log10_p = t.log10_p;
  }
}

Result<OneWayResult> compute(const std::string& factor, const std::string& source, const std::string& dv,
                             const std::vector<std::string>& labels, const std::vector<std::vector<double>>& deltas,
                             double offset, size_t left_out) {
  OneWayResult r;
  r.factor = factor;
  Effect& e = r.effect;
  e.name = factor;
  clear_sphericity(e);
  if (left_out > 0)
    r.warnings.push_back(std::to_string(left_out) + (left_out == 1 ? " row" : " rows") +
                         " with a missing value left out (na.omit)");
  // Deltas scaled by a power of two (exact) so that no square over- or underflows.
  double largest = 0;
  for (const auto& g : deltas)
    for (double v : g) largest = std::max(largest, std::fabs(v));
  const Error overflow{source, 0, 0, name_for_message(dv),
                       "overflow: the sums of squares exceed the largest double (about 1.8e308), so F and p cannot "
                       "be computed; divide the column by a power of ten (e.g. 1e300) and run again"};
  if (!std::isfinite(largest)) return overflow;
  int exponent = 0;
  if (largest > 0) std::frexp(largest, &exponent);

  std::vector<double> means, all;
  std::vector<std::vector<double>> scaled;
  for (size_t g = 0; g < labels.size(); ++g) {
    if (deltas[g].empty()) continue;
    r.groups.push_back({labels[g], describe(deltas[g], offset)});
    std::vector<double> x;
    for (double v : deltas[g]) x.push_back(std::ldexp(v, -exponent));
    means.push_back(careful_mean(x));
    all.insert(all.end(), x.begin(), x.end());
    r.n += x.size();
    scaled.push_back(std::move(x));
  }
  const size_t k = means.size();
  if (r.n == 0) {
    e.df1 = e.df2 = e.ss = e.ss_error = e.F = e.p = e.log10_p = e.eta_p2 = e.eta_g2 = kNaN;
    r.warnings.push_back("no observations");
    complete_effect(e);
    return r;
  }
  const double grand = careful_mean(all);
  detail::Sum ssb, ssw;
  for (size_t g = 0; g < k; ++g) {
    ssb.add(static_cast<double>(scaled[g].size()) * (means[g] - grand) * (means[g] - grand));
    ssw.add(sum_of_squares(scaled[g], means[g]));
  }
  e.df1 = static_cast<double>(k) - 1.0;
  e.df2 = static_cast<double>(r.n) - static_cast<double>(k);
  e.ss = ssb.value();  // scaled: F and eta squared do not depend on the scale
  e.ss_error = ssw.value();
  e.eta_p2 = e.eta_g2 = e.ss + e.ss_error > 0 ? e.ss / (e.ss + e.ss_error) : kNaN;
  test_effect(e, k, r.warnings);
  const bool positive = e.ss > 0 || e.ss_error > 0;
  e.ss = std::ldexp(e.ss, 2 * exponent);
  e.ss_error = std::ldexp(e.ss_error, 2 * exponent);
  if (!std::isfinite(e.ss) || !std::isfinite(e.ss_error)) return overflow;
  if (positive && std::max(e.ss, e.ss_error) < std::numeric_limits<double>::min())
    r.warnings.push_back(underflow_warning());
  complete_effect(e);
  return r;
}

}  // namespace

std::string underflow_warning() {
  return "the sums of squares are below the smallest normal double (about 2.2e-308): SS, SS_error and MSE are "
         "printed rounded (0 or a subnormal), while F, p and the effect sizes are computed on the values scaled by a "
         "power of two and do not depend on the scale";
}

Result<OneWayResult> one_way_anova(const LongData& data) {
  if (data.between.size() != 1 || !data.within.empty())
    return Error{data.source, 0, 0, "", "one-way ANOVA needs exactly one between-subject factor and no within factor"};
  const Factor& f = data.between.front();
  if (f.level.size() != data.rows()) throw std::invalid_argument("one_way_anova: one level per row is required");
  std::vector<std::string> labels;
  std::map<std::string, size_t> lookup;
  std::vector<std::vector<double>> deltas;
  size_t left_out = 0;
  for (size_t i = 0; i < data.rows(); ++i) {
    auto [it, inserted] = lookup.emplace(f.level[i], labels.size());
    if (inserted) {
      labels.push_back(f.level[i]);
      deltas.emplace_back();
    }
    if (data.dv.missing(i)) {
      ++left_out;
      continue;
    }
    deltas[it->second].push_back(data.dv.delta[i]);
  }
  return compute(f.name, data.source, data.dv_name, labels, deltas, data.dv.offset, left_out);
}

Result<OneWayResult> one_way_anova(const std::vector<std::string>& group, const std::vector<double>& y) {
  if (group.size() != y.size()) throw std::invalid_argument("one_way_anova: group and y differ in length");
  LongData d;
  d.between.push_back({"group", group});
  d.dv = Measurements::from_doubles(y);
  return one_way_anova(d);
}

}  // namespace dtlab::stats

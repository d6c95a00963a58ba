// Noncentral-F confidence intervals and derived ANOVA columns; see effect_size.h.
#include "analysis/stats/effect_size.h"

#include <boost/math/distributions/chi_squared.hpp>
#include <boost/math/distributions/fisher_f.hpp>
#include <boost/math/distributions/non_central_f.hpp>
#include <boost/math/tools/toms748_solve.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

#include "analysis/stats/detail/numbers.h"
#include "analysis/stats/detail/policy.h"

namespace dtlab::stats {
namespace {

namespace bm = boost::math;
using detail::Policy;  // errors become NaN/inf values, never exceptions

constexpr double kLargeLambda = 1e8;

double cdf_at(double f, double df1, double df2, double lambda) {
  if (lambda == 0) return bm::cdf(bm::fisher_f_distribution<double, Policy>(df1, df2), f);
  return bm::cdf(bm::non_central_f_distribution<double, Policy>(df1, df2, lambda), f);
}

// Large-lambda limit: the numerator chi-square is (lambda + df1) to relative
// order lambda^-1/2, so P(F' <= f) = P(chi2(df2) >= df2 (lambda + df1) / (df1 f)).
double large_lambda_root(double f, double df1, double df2, double target) {
  const double q = bm::quantile(bm::complement(bm::chi_squared_distribution<double, Policy>(df2), target));
  return std::max(0.0, df1 * f * q / df2 - df1);
}

}  // namespace

double f_noncentrality_for_cdf(double f, double df1, double df2, double target) {
  if (!(df1 > 0) || !(df2 > 0) || !std::isfinite(f) || !(target > 0 && target < 1)) return kNaN;
  if (f <= 0) return 0.0;
  const double at0 = cdf_at(f, df1, df2, 0.0);
  if (at0 <= target) return 0.0;  // lambda = 0 already puts f at or below the quantile
  // Bracket the root; beyond kLargeLambda the large-lambda limit is used (and
  // Boost's series would need an iteration count past its integer range).
  double lo = 0.0, hi = std::min(kLargeLambda, std::max(1.0, f * df1));
  while (cdf_at(f, df1, df2, hi) > target) {
    if (hi >= kLargeLambda) return large_lambda_root(f, df1, df2, target);
    lo = hi;
    hi = std::min(kLargeLambda, hi * 4.0);
  }
  std::uintmax_t iterations = 200;
  const auto root = bm::tools::toms748_solve([&](double l) { return cdf_at(f, df1, df2, l) - target; }, lo, hi,
                                             bm::tools::eps_tolerance<double>(45), iterations);
  return (root.first + root.second) / 2.0;
}

Interval eta_p2_interval(double F, double df1, double df2, double level) {
  if (!std::isfinite(F) || !(df1 > 0) || !(df2 > 0) || !(level > 0 && level < 1)) return {kNaN, kNaN};
  const double tail = (1.0 - level) / 2.0;
  const double low = f_noncentrality_for_cdf(F, df1, df2, 1.0 - tail);
  const double high = f_noncentrality_for_cdf(F, df1, df2, tail);
  auto eta = [&](double lambda) { return lambda / (lambda + df1 + df2 + 1.0); };
  return {eta(low), eta(high)};
}

void complete_effect(Effect& e) {
  e.mse = e.df2 > 0 ? e.ss_error / e.df2 : kNaN;
  const Interval ci = eta_p2_interval(e.F, e.df1, e.df2);
  e.eta_p2_ci_low = ci.low;
  e.eta_p2_ci_high = ci.high;
  if (!e.within) {
    e.df1_gg = e.df2_gg = e.df1_hf = e.df2_hf = e.mse_gg = e.mse_hf = kNaN;
    return;
  }
  const double gg = e.gg_epsilon;  // 1 for a 1-dimensional within term
  const double hf = std::isnan(e.hf_epsilon) ? e.hf_epsilon : std::min(1.0, e.hf_epsilon);
  e.df1_gg = e.df1 * gg;
  e.df2_gg = e.df2 * gg;
  e.df1_hf = e.df1 * hf;
  e.df2_hf = e.df2 * hf;
  e.mse_gg = e.df2_gg > 0 ? e.ss_error / e.df2_gg : kNaN;
  e.mse_hf = e.df2_hf > 0 ? e.ss_error / e.df2_hf : kNaN;
}

}  // namespace dtlab::stats

// Effect sizes with confidence intervals, and the derived columns of an ANOVA
// row (mean square error, sphericity-corrected df and afex's MSE beside them).
//
// Confidence interval of partial eta squared (Steiger 2004, the method of
// MBESS::conf.limits.ncf and apaTables::get.ci.partial.eta.squared):
//   find the noncentrality bounds of the noncentral F(df1, df2, lambda) that
//   put the observed F at the upper and lower (1 - level)/2 quantiles,
//     P(F' <= F_obs | lambda_low) = 1 - (1 - level)/2,  P(F' <= F_obs | lambda_high) = (1 - level)/2,
//   a bound is 0 when even lambda = 0 leaves F_obs below that quantile; then
//     eta_p2 bound = lambda / (lambda + df1 + df2 + 1).
//   The conventional level is 90% (it pairs with a one-sided F test at .05).
//   Convention: R's effectsize package (F_to_eta2(ci = .9, alternative =
//   "two.sided"), 0.8.3) finds the same noncentrality bounds but converts
//   them as lambda / (lambda + df2), so both its bounds are higher (md_12.1
//   angle, F(2, 18) = 40.72: effectsize [.66, .89], here [.625, .870]);
//   its default is a one-sided 95% interval [low, 1].
//   df are the uncorrected ones, as in those packages. Roots by TOMS 748 on
//   Boost.Math's noncentral F cdf to about 1e-12 relative; beyond lambda =
//   1e8 (F in the millions) the cdf is replaced by its large-lambda limit
//   P(chi2(df2) >= df2 (lambda + df1) / (df1 F)), whose error in eta_p2 is
//   below 1e-11. F infinite or NaN, or df <= 0: both bounds NaN.
// Usage: Interval ci = eta_p2_interval(40.72, 2, 18);  // [.625, .870]
// Validated against: R 4.2 uniroot() on pf(F, df1, df2, ncp) (an independent
// noncentral F, AS 226 / R84), converted as apaTables does, and R effectsize
// 0.8.3's F_to_eta2 (our bounds converted its way give its interval); MSE
// beside corrected df against afex 1.2.1's anova() (tests).
#pragma once

#include "analysis/stats/anova.h"

namespace dtlab::stats {

struct Interval {
  double low = 0, high = 0;
};

// lambda with P(F(df1, df2, lambda) <= f) = cdf_target; 0 when no lambda >= 0 reaches it.
double f_noncentrality_for_cdf(double f, double df1, double df2, double cdf_target);

// `level` CI of partial eta squared from F(df1, df2) (see above).
Interval eta_p2_interval(double F, double df1, double df2, double level = 0.90);

// How the interval is computed, for output next to it.
inline constexpr const char* kEtaP2IntervalMethod =
    "Steiger (2004) noncentral-F interval converted as lambda / (lambda + df1 + df2 + 1), as MBESS::conf.limits.ncf "
    "and apaTables (the effectsize package converts lambda / (lambda + df2): higher bounds)";

// Fills e.mse (uncorrected df), e.df1_gg .. e.df2_hf, e.mse_gg = ss_error /
// df2_gg and e.mse_hf (afex's MSE beside corrected df) and the 90% eta_p2
// interval from the other fields: corrected df and MSE are NaN for between
// effects and where the epsilon is undefined, equal to the uncorrected ones
// for 1-dimensional within terms (epsilon 1), and use min(1, HF) as p_hf does.
void complete_effect(Effect& e);

}  // namespace dtlab::stats

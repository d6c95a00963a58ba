// One-way between-subjects ANOVA, and the Effect row every ANOVA here returns.
//
// One-way ANOVA (R: summary(aov(y ~ g))):
//   SS_between = sum_g n_g (mean_g - mean)^2, df1 = k - 1
//   SS_within  = sum_g sum_i (y_gi - mean_g)^2, df2 = N - k
//   F = (SS_between / df1) / (SS_within / df2), p = P(F(df1, df2) >= F)
//   eta_p2 = eta_g2 = SS_between / (SS_between + SS_within)
// Accuracy: sums of squares from exact-offset deltas (measurements.h) with a
// second-pass mean correction and compensated sums: LRE >= 12 on every NIST
// StRD ANOVA dataset, SmLs07-09 included, when the data come from decimal text.
// Missing data: rows with a missing dv are left out (R's na.omit) with a
// warning; groups with no observation are not counted in k.
// Range: deltas are scaled by a power of two before squaring (F does not
// depend on the scale); a sum of squares beyond the double range is an Error
// naming the overflow (R prints NaN).
// Defined results (also in README "Statistics"):
//   zero within-group variance, groups differ -> F = +inf, p = 0, log10_p = -inf;
//   zero within variance and equal means (0/0) -> F, p = NaN;
//   one group (df1 = 0) or one observation per group (df2 = 0) -> F, p = NaN;
//   each with a warning. A group whose values are all equal has SS exactly 0.
// Where we knowingly differ from R: R's aov takes residuals from a QR fit, so
// zero within-group variance usually prints a huge finite F from rounding
// residue; here a constant group contributes exactly 0 and F is +inf.
// References: NIST StRD ANOVA (Simon & Lesage 1989); Olejnik & Algina (2003).
// Validated against: NIST certified values (15 digits); R 4.x aov().
#pragma once
#include <string>
#include <vector>

#include "analysis/stats/descriptives.h"
#include "analysis/stats/long_data.h"
#include "study/common/error.h"

namespace dtlab::stats {

// One row of an ANOVA table. Values that do not apply are NaN (null in JSON):
// sphericity fields for between-subject effects; Mauchly for 1-df effects.
// mse, the corrected df and the eta_p2 interval are filled by
// complete_effect() (effect_size.h) from the fields above them.
struct Effect {
  std::string name;                   // "angle", "angle:noise", "group:phase"
  bool within = false;                // involves a within-subject factor
  double df1 = 0, df2 = 0;            // uncorrected degrees of freedom
  double ss = 0, ss_error = 0;        // effect and error sums of squares (type III = type I when balanced)
  double mse = 0;                     // mean square error = ss_error / df2 (uncorrected df)
  double F = 0, p = 0, log10_p = 0;
  double eta_p2 = 0, eta_g2 = 0;      // partial and generalized eta squared
  double eta_p2_ci_low = 0, eta_p2_ci_high = 0;  // 90% CI of eta_p2 from the noncentral F (Steiger 2004)
  double mauchly_W = 0, mauchly_p = 0;
  double gg_epsilon = 0, hf_epsilon = 0;  // HF as car/afex compute it: may exceed 1
  double df1_gg = 0, df2_gg = 0;      // df1, df2 times GG epsilon (the df of p_gg); NaN for between effects
  double mse_gg = 0;                  // ss_error / df2_gg: the MSE afex prints beside GG df (anova(fit), nice())
  double df1_hf = 0, df2_hf = 0;      // df1, df2 times min(1, HF epsilon) (the df of p_hf)
  double mse_hf = 0;                  // ss_error / df2_hf (afex with correction = "HF")
  double p_gg = 0, log10_p_gg = 0;    // p with df1, df2 times GG epsilon
  double p_hf = 0, log10_p_hf = 0;    // p with df1, df2 times min(1, HF epsilon)
};

// The warning given when sums of squares fall below the smallest normal double
// (about 2.2e-308, e.g. data near 1e-160 or smaller): SS, SS_error and MSE are
// then printed rounded (subnormal or 0), while F, p and the effect sizes are
// computed on the data scaled by a power of two and do not depend on it.
std::string underflow_warning();

struct GroupSummary {
  std::string level;
  Descriptives d;
};

struct OneWayResult {
  std::string factor;
  Effect effect;                      // sphericity fields NaN
  size_t n = 0;                       // observations used
  std::vector<GroupSummary> groups;   // first-appearance order
  std::vector<std::string> warnings;
};

// Groups are data.between[0]; exactly one between factor and no within factor.
Result<OneWayResult> one_way_anova(const LongData& data);

// The same from plain vectors: group label and value per observation (NaN = missing).
Result<OneWayResult> one_way_anova(const std::vector<std::string>& group, const std::vector<double>& y);

}  // namespace dtlab::stats

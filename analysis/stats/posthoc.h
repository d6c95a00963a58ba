// Holm-corrected pairwise post-hoc comparisons between the levels of one
// factor, as R's pairwise.t.test / pairwise.wilcox.test with
// p.adjust.method = "holm" (two-sided):
//   within factor, paired t:  pairwise.t.test(y, g, paired = TRUE)
//   within factor, Wilcoxon:  pairwise.wilcox.test(y, g, paired = TRUE) (R's exact/normal rule, correct = TRUE)
//   between factor, pooled t: pairwise.t.test(y, g) (pool.sd = TRUE: one SD
//     pooled over all groups, df = N - k)
//   within factor of a mixed design (between factors present), paired t:
//     pairs(emmeans(afex fit, ~ W), adjust = "holm") with afex's default
//     multivariate model (detail/multivariate.h): marginal means over the
//     between cells weighted equally (not over subjects), SE from the
//     residual covariance pooled over the groups, t on N - g df (g between
//     cells); test "emmeans t", d_z = estimate / pooled SD of the differences.
//     (A paired t over all subjects ignores the groups: mixed_posthoc.csv
//     gave p = .024 where emmeans gives .055, .111 after Holm.)
// With several within factors, each subject's values are first averaged over
// the other within factors (marginal means, on the decimal digits when the
// data came as text: detail/design.h). Holm (1979): sort the m p-values,
// p_(i) -> min(1, max_{j <= i} (m - j + 1) p_(j)); NaN p-values are kept and
// not counted in m (R's p.adjust).
// Every row describes the difference a - b whatever the test: n pairs (or
// n_a + n_b), mean difference, its SE and 95% CI (paired: t.test(paired =
// TRUE)$conf.int; pooled: mean +- t(.975, N - k) s_pooled sqrt(1/n_a + 1/n_b)),
// Cohen's d_z = mean difference / SD of the differences (within only; NaN
// for between). Missing data: the subject x cell rules of detail/design.h.
// Validated against: R 4.2 p.adjust(p, "holm") values, t.test(paired = TRUE)
// and pairwise.t.test(pool.sd = TRUE) on the sleep and PlantGrowth data
// (tests/analysis/stats/test_posthoc_descriptives.cpp); emmeans 1.8.4.1 on
// afex 1.2.1 fits of mixed_posthoc.csv and obk_long.csv (test_mixed_followups.cpp).
// Usage: auto rows = pairwise_within(data, "angle", PairwiseTest::paired_t);
#pragma once
#include <string>
#include <vector>

#include "analysis/stats/long_data.h"
#include "analysis/stats/paired.h"
#include "study/common/error.h"

namespace dtlab::stats {

std::vector<double> holm(const std::vector<double>& p);  // same order as p

struct Comparison {
  std::string a, b;     // levels compared; differences are a - b
  std::string test;     // "paired t", "wilcoxon", "pooled t", "emmeans t" (mixed designs)
  std::size_t n = 0;    // pairs (within) or observations in a and b (between)
  double estimate = 0;  // mean difference a - b
  double se = 0;        // its standard error
  double ci_low = 0, ci_high = 0;  // 95% CI of the mean difference
  double statistic = 0; // t or V
  double df = 0;        // NaN for Wilcoxon
  double p = 0, p_holm = 0;
  double dz = 0;        // Cohen's d_z (within; emmeans t: estimate / pooled SD of the subjects' scores); NaN pooled t
};

// A paired-t comparison row from two paired samples (x = level a, y = level b).
Comparison paired_comparison(const std::string& a, const std::string& b, const std::vector<double>& x,
                             const std::vector<double>& y);

// Sets p_holm of every row from the p of all rows (one family).
void adjust_holm(std::vector<Comparison>& family);

enum class PairwiseTest { paired_t, wilcoxon };

// All pairs of levels of within factor `factor` (level order of first appearance).
Result<std::vector<Comparison>> pairwise_within(const LongData& data, const std::string& factor, PairwiseTest test,
                                                const WilcoxonOptions& options = {});
// All pairs of levels of data.between[0], pooled-SD t tests (missing dv rows left out).
Result<std::vector<Comparison>> pairwise_between(const LongData& data);

}  // namespace dtlab::stats

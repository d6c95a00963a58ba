// Holm-corrected pairwise post-hoc comparisons between the levels of one
// factor, as R's pairwise.t.test / pairwise.wilcox.test with
// p.adjust.method = "holm" (two-sided):
//   within factor, paired t:  pairwise.t.test(y, g, paired = TRUE)
//   within factor, Wilcoxon:  pairwise.wilcox.test(y, g, paired = TRUE) (R's exact/normal rule, correct = TRUE)
//   between factor, pooled t: pairwise.t.test(y, g) (pool.sd = TRUE: one SD
//     pooled over all groups, df = N - k)
// With several within factors, each subject's values are first averaged over
// the other within factors (marginal means). Holm (1979): sort the m p-values,
// p_(i) -> min(1, max_{j <= i} (m - j + 1) p_(j)); NaN p-values are kept and
// not counted in m (R's p.adjust).
// Validated against: R 4.x p.adjust(method = "holm") definition, t.test and
// wilcox.test values (see paired.h).
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
  std::string test;     // "paired t", "wilcoxon", "pooled t"
  double estimate = 0;  // mean difference a - b
  double statistic = 0; // t or V
  double df = 0;        // NaN for Wilcoxon
  double p = 0, p_holm = 0;
};

enum class PairwiseTest { paired_t, wilcoxon };

// All pairs of levels of within factor `factor` (level order of first appearance).
Result<std::vector<Comparison>> pairwise_within(const LongData& data, const std::string& factor, PairwiseTest test,
                                                const WilcoxonOptions& options = {});
// All pairs of levels of data.between[0], pooled-SD t tests (missing dv rows left out).
Result<std::vector<Comparison>> pairwise_between(const LongData& data);

}  // namespace dtlab::stats

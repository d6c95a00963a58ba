// Following up a repeated-measures ANOVA: simple effects of an interaction
// and within-subject confidence intervals of the cell means.
//
// Simple effects of A x B (two within factors; each subject's values first
// averaged over the other within factors): for every level b of B the effect
// of A on the subset B = b, and for every level a of A the effect of B on A = a.
//   2 levels: paired t, as R's t.test(x, y, paired = TRUE) on the subset:
//     mean difference (first level - second), SE, 95% CI, t, df, p, d_z.
//   more levels: one-way repeated-measures ANOVA on the subset, as
//     aov(y ~ A + Error(id/A)) / afex (F, df, p, GG/HF, eta_p2 with its 90% CI).
//   Holm correction within each family ("A at each level of B" is one family
//   of |B| tests; "B at each level of A" another), as p.adjust(p, "holm").
// Within-subject CIs of the cell means (Cousineau 2005 with Morey's 2008
// correction): each subject's values are normalised, y'_sc = y_sc - mean_s +
// grand mean (within the subject's between group for mixed designs); per cell
//   SE = sd(y'_.c) / sqrt(N) * sqrt(C / (C - 1)), CI = mean +- t(1 - (1 - level)/2, N - 1) SE,
// with C the number of within cells. The mean is the ordinary cell mean.
// Mixed designs (any between factor): a and b may be any two factors,
//   between or within, and each row follows emmeans on the afex fit
//   (afex_options(emmeans_model = "multivariate"), detail/multivariate.h):
//   the effect of A at B = b averages every other factor with equal weights
//   (between cells too, whatever their sizes) and uses the residual
//   covariance pooled over the between cells, N - g df:
//     2 levels: pairs(emmeans(fit, ~ A | B)): estimate (first level - second,
//       levels in file order; emmeans sorts them), SE, 95% CI, t, p (test "emmeans t");
//     more levels: joint_tests(fit, by = "B")'s row for A: the Wald F of
//       the level contrasts on (levels - 1, N - g) df (test "emmeans F"; the
//       Effect carries name, df1, df2, F, p, log10_p, the rest NaN).
//   The contrast's dz is the estimate over the pooled SD of the subjects'
//   scores: d_z for a within factor, Cohen's d (SD pooled over the groups)
//   for a between factor (the text output labels it d).
//   Holm within each family as above. (joint_tests(fit, by = "B") also tests
//   interactions of the other factors at B = b; those are not computed.)
// Missing data: the subject x cell rules of rm_anova (listwise deletion,
// repeated rows only with an aggregation). The CIs are per between group.
// Validated against: R 4.2.2 t.test(paired = TRUE) and aov() on the subsets,
// p.adjust(p, "holm"), the Cousineau-Morey formula evaluated in R, and
// emmeans 1.8.4.1 joint_tests / pairs on afex 1.2.1 fits (tests).
// Usage: auto se = simple_effects(data, "angle", "noise");
#pragma once
#include <string>
#include <vector>

#include "analysis/stats/anova.h"
#include "analysis/stats/long_data.h"
#include "analysis/stats/posthoc.h"
#include "study/common/error.h"

namespace dtlab::stats {

struct SimpleEffect {
  std::string factor;                // the factor whose effect is tested (A)
  std::string at_factor, at_level;   // where it is tested (B = b)
  std::string test;                  // "paired t" (2 levels) or "rm-anova"; mixed designs: "emmeans t" or "emmeans F"
  std::size_t n = 0;                 // subjects
  Comparison contrast;               // paired t / emmeans t: first level - second level
  Effect anova;                      // rm-anova: the one row of the subset's ANOVA; emmeans F: the joint test
  double p = 0, p_holm = 0;          // the test's p and its Holm-adjusted p within the family
};

struct SimpleEffects {
  std::vector<SimpleEffect> rows;    // A at each level of B, then B at each level of A
  std::vector<std::string> dropped_subjects;
  std::vector<std::string> warnings;
};

// Simple effects of factors a and b (within factors; any two factors of a mixed design; see above).
Result<SimpleEffects> simple_effects(const LongData& data, const std::string& a, const std::string& b);

struct CellInterval {
  std::vector<std::pair<std::string, std::string>> levels;  // (factor, level), between factors first
  std::size_t n = 0;
  double mean = 0, se = 0, ci_low = 0, ci_high = 0;        // Cousineau-Morey SE and CI
};

// Within-subject CIs of every cell mean (see above); level in (0, 1).
Result<std::vector<CellInterval>> within_subject_intervals(const LongData& data, double level = 0.95);

}  // namespace dtlab::stats

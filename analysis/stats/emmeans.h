// Estimated marginal means and Holm-corrected pairwise contrasts of a mixed
// model, as R's emmeans 1.8 computes them for an lmerTest / glmer fit:
//   emmeans(m, pairwise ~ A, adjust = "holm", lmer.df = "satterthwaite",
//           lmerTest.limit = Inf[, type = "response"])
// Means: for each combination of the chosen factors' levels (first factor
// fastest, emmeans' grid order) the model's prediction averaged with equal
// weights over the levels of every other factor (L = mean of the cells' X
// rows), SE = sqrt(L V L'), df by Satterthwaite on that L (lmerTest
// contest1D; infinite for a binomial GLMM: z), 95% CI estimate +- t(.975,
// df) SE. Contrasts: every pair i < j in grid order, estimate_i - estimate_j,
// SE, Satterthwaite df of the difference, t (or z), two-sided p and Holm's
// adjustment over the family of all pairs; the 95% CI is not adjusted for
// multiplicity (emmeans would switch a Holm CI to Bonferroni).
// Back-transformed (type = "response"): for a log model, means exp(est) with
// the CI's ends exponentiated, contrasts as ratios exp(diff) with exp(CI);
// for a logit model, probabilities plogis(est) and odds ratios.
// Never refits; reads only the fit's beta, vcov and Satterthwaite pieces.
// Example: auto e = marginal_means(*fit, {"technique"}); e->contrasts[0].ratio
#pragma once
#include <string>
#include <vector>

#include "analysis/stats/lmm.h"
#include "study/common/error.h"

namespace dtlab::stats {

enum class EmmScale { identity, log, logit };

struct EmmRow {
  std::vector<std::string> levels;  // one per factor of the table
  double estimate = 0, se = 0, df = 0, ci_low = 0, ci_high = 0;  // model scale
  double response = 0, response_ci_low = 0, response_ci_high = 0;  // back-transformed (NaN on identity)
};

struct EmmContrast {
  std::string a, b;  // cell labels ("a1", or "a1 b2" for several factors); the contrast is a - b
  double estimate = 0, se = 0, df = 0, statistic = 0, p = 0, log10_p = 0, p_holm = 0;
  double ci_low = 0, ci_high = 0;               // 95% CI of a - b on the model scale
  double ratio = 0, ratio_ci_low = 0, ratio_ci_high = 0;  // exp(): ratio (log) or odds ratio (logit); NaN on identity
};

struct EmmTable {
  std::vector<std::string> factors;
  EmmScale scale = EmmScale::identity;
  std::vector<EmmRow> means;
  std::vector<EmmContrast> contrasts;
};

// The means and contrasts over `factors` (fixed factors of the fit).
Result<EmmTable> marginal_means(const LmmFit& fit, const std::vector<std::string>& factors);

// The same contrast the other way round (b - a): estimate, statistic and CI
// negated, ratios inverted; p, df and SE unchanged.
EmmContrast reversed(const EmmContrast& c);

// A copy-ready sentence for one contrast: for a log model of a time "a1
// trials took 0.74 times as long as a2 trials, 95% CI [0.70, 0.79], t(741.00)
// = -10.08, p < .001." (Holm's p, marked when the family has several
// contrasts); `measure` names the dv on the other scales ("the odds of a
// correct answer" for odds ratios, "relative error" for differences).
std::string apa_contrast_sentence(const EmmTable& table, const EmmContrast& c, bool time_measure,
                                  const std::string& measure);

}  // namespace dtlab::stats

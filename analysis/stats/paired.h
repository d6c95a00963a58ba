// Tests for two paired samples (x_i, y_i): Wilcoxon signed-rank, sign test
// and paired t-test, as R's wilcox.test(x, y, paired = TRUE),
// binom.test(#(x > y), #(x != y)) and t.test(x, y, paired = TRUE).
// Differences d = x - y are taken in double arithmetic on the values as read,
// exactly as R does, so ties and zeros are the ones R sees (R's own example:
// (4:2)/10 - (3:1)/10 has no ties in double). Pairs with a missing value are
// dropped (R's complete.cases).
//
// Wilcoxon signed-rank (Wilcoxon 1945; Hollander & Wolfe 1973, 3.1):
//   zeros dropped, n = nonzero pairs, r = average ranks of |d|, V = sum of r over d > 0.
//   Exact p: the permutation (sign-flip) distribution of V, computed by dynamic
//     programming over doubled ranks: R's psignrank when there are no ties,
//     the exact conditional distribution with ties. Two-sided:
//     min(1, 2 P(V' >= V)) if V > n(n+1)/4, else min(1, 2 P(V' <= V)) (as R).
//   Normal approximation: z = (V - n(n+1)/4 - c) / sqrt(n(n+1)(2n+1)/24 - sum(t^3 - t)/48),
//     c = sign(V - n(n+1)/4)/2 (two-sided) or +-1/2 (one-sided) when correct = true.
//   p: automatic = R's default: exact if n < 50 and no ties and no zeros, else normal;
//     always = exact (conditional with ties); never = normal; monte_carlo = sign-flip resampling.
//   p_exact is reported whenever the enumeration fits (n up to about 580 in automatic
//   mode) or is resampled, even if p is normal; never = not computed.
//   Defined results: all differences zero (n = 0) -> V = 0, p = NaN (R: NaN).
// Sign test: n+ = #(d > 0) of n = #(d != 0); p = P(Binomial(n, 1/2) as or more extreme), two-sided
//   min(1, 2 min(P(X <= n+), P(X >= n+))) (= binom.test at p = 1/2). n = 0 -> p = NaN.
// Paired t: t = mean(d) / (sd(d) / sqrt(m)), df = m - 1 over the m complete pairs (zeros kept),
//   95% CI of mean(d) as t.test: two-sided mean +- t(.975, df) SE; one-sided
//   (-Inf, mean + t(.95, df) SE) for "less", (mean - t(.95, df) SE, Inf) for "greater".
//   Cohen's d_z = mean(d) / sd(d). Differences are taken after scaling x and y
//   by a power of two, so values near the double maximum do not overflow t.
//   Degenerate data, each with a warning: SE < 10 eps |mean| (R's "data are
//   essentially constant", where t.test stops): t and p as computed, which for
//   SE = 0 is t = +-inf, p = 0; every difference zero: t = p = NaN (R: NaN);
//   m < 2 -> NaN; a mean or SD beyond the double range: those fields +-inf/NaN.
// Validated against: R 4.x stats-Ex.Rout.save (wilcox.test examples) and
//   t.test(extra ~ group, data = sleep, paired = TRUE); closed-form binomial tails.
#pragma once
#include <cstddef>
#include <string>
#include <vector>

#include "analysis/stats/friedman.h"  // ExactMode, ExactOptions
#include "analysis/stats/long_data.h"
#include "study/common/error.h"

namespace dtlab::stats {

enum class Alternative { two_sided, less, greater };  // hypotheses about x - y

struct WilcoxonOptions {
  ExactOptions exact;
  bool correct = true;  // continuity correction of the normal approximation
  Alternative alternative = Alternative::two_sided;
};

struct WilcoxonResult {
  std::size_t pairs = 0, zeros = 0, n = 0;  // complete pairs, zero differences, pairs used
  bool ties = false;
  double V = 0;
  double p = 0, log10_p = 0;
  std::string method;                       // "exact", "normal" or "monte-carlo": how p was computed
  double z = 0;                             // normal approximation (with the continuity correction if on)
  double p_normal = 0;
  double p_exact = 0;                       // NaN when not computed
  std::string exact_method = "none";        // "exact", "monte-carlo" or "none"
  std::string exact_note;                   // why p_exact was not computed (auto or always; "" otherwise)
  std::vector<std::string> warnings;
};

struct SignTestResult {
  std::size_t n = 0, positive = 0, negative = 0;
  double p = 0, log10_p = 0;
};

struct PairedTResult {
  std::size_t n = 0;
  double mean_difference = 0, sd = 0, se = 0, t = 0, df = 0, p = 0, log10_p = 0;
  double ci_low = 0, ci_high = 0;           // 95% CI of the mean difference (one-sided for less / greater)
  double dz = 0;                            // Cohen's d_z = mean_difference / sd
  std::vector<std::string> warnings;        // degenerate data (see above)
};

WilcoxonResult wilcoxon_signed_rank(const std::vector<double>& x, const std::vector<double>& y,
                                    const WilcoxonOptions& options = {});
SignTestResult sign_test(const std::vector<double>& x, const std::vector<double>& y,
                         Alternative alternative = Alternative::two_sided);
PairedTResult paired_t(const std::vector<double>& x, const std::vector<double>& y,
                       Alternative alternative = Alternative::two_sided);

// The three tests on long data for a within-subject factor of exactly two
// levels (x = first level in order of appearance, y = second): the design's
// only within factor, or `factor` of a larger all-within design, each
// subject's values then averaged over the other within factors (the
// robustness check of a two-level ANOVA effect).
struct PairedResult {
  std::string x_level, y_level;
  WilcoxonResult wilcoxon;
  SignTestResult sign;
  PairedTResult t;
  std::vector<std::string> dropped_subjects;
  std::vector<std::string> warnings;
};
Result<PairedResult> paired_tests(const LongData& data, const WilcoxonOptions& options = {},
                                  const std::string& factor = "");

}  // namespace dtlab::stats

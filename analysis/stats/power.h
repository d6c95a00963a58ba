// Statistical power: analytic (noncentral t and F) and by resampling
// participants, and the smallest sample size that reaches a target power.
//
// Paired t / any 1-df within effect, as R's power.t.test(n, delta, sd,
// sig.level, type = "paired", alternative, strict = FALSE):
//   df = n - 1, ncp = sqrt(n) delta / sd, q = t(1 - alpha / sides, df);
//   power = P(T'(df, ncp) > q) (the far tail is ignored, as strict = FALSE;
//   with strict = true P(T' < -q) is added for the two-sided test).
// Repeated-measures within effect, as G*Power 3's "ANOVA: Repeated measures,
//   within factors" (Faul, Erdfelder, Lang & Buchner 2007):
//   lambda = f^2 n m epsilon / (1 - rho), df1 = (m - 1) epsilon, df2 = (n - 1)(m - 1) epsilon,
//   power = P(F'(df1, df2, lambda) > F(1 - alpha; df1, df2)).
// From an observed effect (a pilot ANOVA row with N_pilot subjects, q between
//   cells): lambda grows linearly with n, lambda(n) = F df1 n / N_pilot, the
//   noncentrality the observed F estimates (SS_effect / MSE), times the observed
//   epsilon as G*Power does; df1 = df1_obs epsilon, df2 = (n - q) p epsilon with
//   p = df1_obs / df_between. For 1-df effects this is the paired t power with
//   delta / sd = d_z (F = t^2).
// Smallest n: the least integer n >= 2 whose power reaches the target (power
//   is increasing in n); NaN when even n = 10^7 does not.
// Resampling power: draw n participants with replacement from the pilot's
//   rows, run the test (a callback returning p), count p < alpha; R
//   replications give the estimate and a 95% Wilson interval (Monte Carlo error).
//   Seeded (SplitMix64, one stream per replication), reproducible whatever the
//   number of threads.
// Validated against: R 4.2.2 power.t.test and pf(ncp = ) (an independent
//   noncentral F), pingouin's power_rm_anova documentation examples (tested
//   there against G*Power), and convergence of the resampling power to the
//   analytic power on normal data (tests).
#pragma once
#include <cstdint>
#include <cstddef>
#include <functional>
#include <vector>

#include "analysis/stats/anova.h"
#include "analysis/stats/paired.h"

namespace dtlab::stats {

// Power of the paired t test (R's power.t.test, type = "paired").
double power_paired_t(double n, double delta, double sd, double alpha = 0.05,
                      Alternative alternative = Alternative::two_sided, bool strict = false);

// n (fractional) where power_paired_t reaches `power` (as power.t.test's uniroot); NaN if not below 1e7.
double n_for_power_paired_t(double delta, double sd, double power, double alpha = 0.05,
                            Alternative alternative = Alternative::two_sided);

// Power of an F test with noncentrality lambda: P(F'(df1, df2, lambda) > F(1 - alpha; df1, df2)).
double power_noncentral_f(double lambda, double df1, double df2, double alpha = 0.05);

// G*Power's repeated-measures within-factor power (formula above).
double power_rm_within(double f, double n, double m, double rho, double epsilon = 1.0, double alpha = 0.05);

// Power at n subjects of a pilot ANOVA effect (formula above). between_cells = q (1 without between factors).
double power_of_effect(const Effect& pilot, double n_pilot, double n, double alpha = 0.05, double between_cells = 1);

// Least integer n >= 2 with power(n) >= target; NaN if none up to 10^7.
double smallest_n(const std::function<double(double)>& power_at, double target);

struct ResampledPower {
  double power = 0;               // share of replications with p < alpha
  double ci_low = 0, ci_high = 0; // 95% Wilson interval of that share
  std::size_t replications = 0, rejections = 0, undefined = 0;  // undefined: replications whose p was NaN (not counted)
};

// Fills r.power, r.ci_low, r.ci_high from r.rejections, r.replications and r.undefined
// (the share of rejections among the defined replications, 95% Wilson interval).
void share_with_wilson_interval(ResampledPower& r);

// Power of `test` (participant rows -> p) at n participants drawn with replacement from `rows`.
ResampledPower power_by_resampling(const std::vector<std::vector<double>>& rows, std::size_t n,
                                   const std::function<double(const std::vector<std::vector<double>>&)>& test,
                                   std::size_t replications, std::uint64_t seed, double alpha = 0.05);

// A test run on one resample: `draw` holds n indices into the pilot's
// participants (with repeats); returns one p per hypothesis (NaN = undefined).
// Called from several threads at once: it must not touch shared mutable state.
using ResampleTest = std::function<std::vector<double>(const std::vector<std::size_t>& draw)>;

// The power of every hypothesis `test` returns (`hypotheses` of them) at n of
// `participants` drawn with replacement, from R replications on `threads`
// threads (0 = one per processor). Replication b draws from its own stream
// seeded by (seed, b), so the result depends on the seed, never on the
// thread count.
std::vector<ResampledPower> power_by_resampling(std::size_t participants, std::size_t n, std::size_t hypotheses,
                                                const ResampleTest& test, std::size_t replications,
                                                std::uint64_t seed, double alpha = 0.05, unsigned threads = 1);

}  // namespace dtlab::stats

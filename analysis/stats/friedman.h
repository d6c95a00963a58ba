// Friedman rank test for a complete block design (blocks = subjects,
// treatments = the cells of the within factor(s)), as R's friedman.test.
//   Ranks r_ij within each block (average ranks for ties), R_j = sum_i r_ij,
//   Q = 12 sum_j (R_j - n(k+1)/2)^2 / (n k (k+1) - sum_blocks sum_ties (t^3 - t) / (k - 1))
//   df = k - 1, p = P(X^2(df) >= Q)                      (chi-square approximation)
//   Kendall's W = Q / (n (k - 1))                        (tie-corrected, as pingouin)
//   Iman-Davenport F = (n - 1) Q / (n (k - 1) - Q), df1 = k - 1, df2 = (k - 1)(n - 1)
//   p_exact = P(Q' >= Q) under the permutation distribution that permutes the
//     (mid-)ranks within each block independently: exact for untied data
//     (the classical null distribution), the exact conditional distribution
//     with ties. Computed by dynamic programming over the blocks on the sorted
//     vector of rank sums (Kendall & Babington Smith; detail/friedman_exact.h:
//     dense lexicographic index, mirror symmetry without ties, the last block
//     summed directly, states settled early once the tail is decided), or by
//     Monte Carlo with a seed: p = (b + 1) / (N + 1) with b the resamples at
//     or above Q (Phipson & Smyth 2010).
// Exact modes: automatic = exact if the DP's work bound is at most 3e8 state
// updates (about a second of CPU at most; untied data: k = 3 up to n = 349,
// k = 4 up to 88, k = 5 up to 24, k = 6 up to 9, k = 7 up to 4, k = 8 up
// to 2), else none; always = up to 3e9 (k = 3 beyond 400, k = 4 up to 159,
// k = 5 up to 39, k = 6 up to 14, k = 7 up to 6, k = 8 up to 3; at most
// about 8 s of CPU; k = 6, n = 12 takes 2-4 s); ties cost more (a single tied
// block puts k = 6, n = 12 beyond); beyond that, or for k > 8, p_exact is NaN and
// exact_note says why and what applies instead (decided before any
// enumeration, so a refusal is instant; with `always` also a warning);
// never = no p_exact; monte_carlo = N resamples, only on request, reporting
// progress through the callback.
// Missing data: blocks with a missing cell are removed (R drops incomplete
// blocks; we warn and name them); several rows per cell are an error unless
// the data ask for an aggregation (LongData::aggregate).
// Ties are decided by exact double equality of the values read (as R).
// Defined results: every block fully tied -> Q = 0/0: Q, W, F and every p are
// NaN, with a warning (R gives NaN); Q = n(k-1) (perfect agreement) -> F = +inf,
// p_iman_davenport = 0, with a warning; one block (n = 1) -> Q, W and p
// defined, Iman-Davenport F NaN (df2 = 0). friedman_blocks: one treatment
// (k = 1) or no block -> NaN with a warning; friedman() on long data makes
// those two an Error (nothing to test). mean_ranks always has k entries.
// References: Friedman (1937); Iman & Davenport (1980); Kendall & Babington
// Smith (1939); Hollander & Wolfe (1973) 7.1.
// Validated against: R 4.x friedman.test examples (stats-Ex.Rout.save), scipy
// 1.x test values (Demsar, Bioestadistica, Zar 12.6), pingouin (wine),
// exact null tables computed with exact rational arithmetic (cross-checked
// with R package SuppDists).
#pragma once
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "analysis/stats/long_data.h"
#include "study/common/error.h"

namespace dtlab::stats {

enum class ExactMode { automatic, always, never, monte_carlo };

// Called now and then during a Monte Carlo run with (resamples done, total).
using Progress = std::function<void(std::size_t, std::size_t)>;

struct ExactOptions {
  ExactMode mode = ExactMode::automatic;
  std::size_t monte_carlo_samples = 100000;  // used by monte_carlo
  std::uint64_t seed = 1;                    // Monte Carlo seed (SplitMix64 stream)
  Progress progress;                         // optional; Monte Carlo only
};

struct FriedmanResult {
  std::vector<std::string> treatments;  // cell labels, first-appearance order
  std::vector<double> mean_ranks;       // R_j / n
  std::size_t n = 0, k = 0;             // blocks used, treatments
  bool ties = false;
  double Q = 0, df = 0, p = 0, log10_p = 0;
  double p_exact = 0;                   // NaN when not computed
  std::string exact_method = "none";    // "exact", "monte-carlo" or "none"
  std::string exact_note;               // why p_exact was not computed (auto or always; "" when it was, or never asked)
  std::size_t monte_carlo_samples = 0;
  std::uint64_t seed = 0;
  double kendall_W = 0;
  double iman_davenport_F = 0, id_df1 = 0, id_df2 = 0, p_iman_davenport = 0, log10_p_iman_davenport = 0;
  std::vector<std::string> dropped_blocks;
  std::vector<std::string> warnings;
};

// y[i][j]: block i, treatment j; every row the same length, no NaN.
FriedmanResult friedman_blocks(const std::vector<std::vector<double>>& y, const ExactOptions& exact = {});

// From long data: blocks = data.subject, treatments = cells of data.within.
Result<FriedmanResult> friedman(const LongData& data, const ExactOptions& exact = {});

}  // namespace dtlab::stats

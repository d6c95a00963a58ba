// The permutation distribution of the Friedman statistic: each block's
// (mid-)ranks permuted independently and uniformly. Ranks are passed doubled
// (2 r, integers even with mid-ranks) so every comparison is exact; the
// statistic is S = sum_j T_j^2 with T_j the column sums, which orders the
// permutations exactly as Friedman's Q does (its tie correction is constant
// under this distribution).
#pragma once
#include <cstddef>
#include <cstdint>
#include <functional>
#include <optional>
#include <utility>
#include <vector>

namespace dtlab::stats::detail {

// The whole distribution: (S, probability) pairs in increasing S; nullopt as below.
std::optional<std::vector<std::pair<std::int64_t, double>>> friedman_exact_distribution(
    const std::vector<std::vector<int>>& doubled_ranks, double budget);

// P(S >= s_obs) by dynamic programming over the sorted vector of column sums;
// nullopt when the work (states x permutations, summed over blocks) would
// exceed `budget` or k > 8.
std::optional<double> friedman_exact_tail(const std::vector<std::vector<int>>& doubled_ranks, std::int64_t s_obs,
                                          double budget);

// Monte Carlo estimate (b + 1) / (N + 1) with b the resamples with S >= s_obs;
// progress (if set) is called about 100 times.
double friedman_monte_carlo_tail(const std::vector<std::vector<int>>& doubled_ranks, std::int64_t s_obs,
                                 std::size_t samples, std::uint64_t seed,
                                 const std::function<void(std::size_t, std::size_t)>& progress = {});

// S for the given (doubled) ranks.
std::int64_t friedman_s(const std::vector<std::vector<int>>& doubled_ranks);

// Uniform integers from a SplitMix64 stream (dtlab::mix64); no global state.
class SplitMixStream {
 public:
  explicit SplitMixStream(std::uint64_t seed) : seed_(seed) {}
  std::uint64_t next();                     // the next 64 random bits
  std::uint64_t below(std::uint64_t bound);  // uniform in [0, bound), bound > 0 (Lemire 2019, unbiased)

 private:
  std::uint64_t seed_, counter_ = 0;
};

}  // namespace dtlab::stats::detail

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
#include <string>
#include <utility>
#include <vector>

namespace dtlab::stats::detail {

// The whole distribution: (S, probability) pairs in increasing S; nullopt as below.
std::optional<std::vector<std::pair<std::int64_t, double>>> friedman_exact_distribution(
    const std::vector<std::vector<int>>& doubled_ranks, double budget, std::string* why = nullptr);

// P(S >= s_obs) by dynamic programming over the sorted vector of column sums.
// nullopt, with the reason in *why, when the work bound (friedman_exact_work)
// exceeds `budget`, a step would hold more than 8.4e6 vectors or an index
// table of more than 4.2e6 entries (k = 2, 3 with large n), or k > 8;
// decided before any enumeration (the bound is counted only up to the
// budget), so a refusal costs little.
std::optional<double> friedman_exact_tail(const std::vector<std::vector<int>>& doubled_ranks, std::int64_t s_obs,
                                          double budget, std::string* why = nullptr);

// Upper bound on the DP's work: state updates (states reachable before each
// block x the block's distinct arrangements, summed) plus the entries of each
// step's index tables; infinity for k > 8 or beyond 1e15. About 1e8 take a
// third of a second on one core of the development machine.
double friedman_exact_work(const std::vector<std::vector<int>>& doubled_ranks);

// Monte Carlo estimate (b + 1) / (N + 1) with b the resamples with S >= s_obs;
// progress (if set) is called about 100 times.
double friedman_monte_carlo_tail(const std::vector<std::vector<int>>& doubled_ranks, std::int64_t s_obs,
                                 std::size_t samples, std::uint64_t seed,
                                 const std::function<void(std::size_t, std::size_t)>& progress = {});

// S for the given (doubled) ranks.
std::int64_t friedman_s(const std::vector<std::vector<int>>& doubled_ranks);

}  // namespace dtlab::stats::detail

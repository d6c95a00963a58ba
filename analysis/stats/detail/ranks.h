// Ranks as R's rank(x) computes them (ties.method = "average"): ties are
// decided by exact equality of the doubles given, so the caller decides what
// counts as tied (R compares the doubles it read, and so do we).
#pragma once
#include <cstddef>
#include <vector>

namespace dtlab::stats::detail {

// 1-based average ranks of x (no NaN allowed: the caller removes missing values).
std::vector<double> average_ranks(const std::vector<double>& x);

// Sizes of the groups of equal values in x, one entry per distinct value.
std::vector<size_t> tie_sizes(const std::vector<double>& x);

// Sum over tie groups of t^3 - t (0 when there are no ties).
double tie_sum(const std::vector<double>& x);

}  // namespace dtlab::stats::detail

// Counterbalancing designs: orders of n conditions (0..n-1) for successive
// participants, and property checks that say what a design guarantees.
// Guarantees: every constructor is a pure function of its arguments and gives
// the same table on every machine (a SplitMix64 stream from study/common/random.h, no std::rand,
// no std::random_device, no std:: distributions, whose outputs differ between
// standard libraries). Violated preconditions throw std::invalid_argument.
#pragma once
#include <cstdint>
#include <vector>

namespace dtlab::design {

using Order = std::vector<int>;         // one participant's sequence of condition indices
using OrderTable = std::vector<Order>;  // rows of a design; row k is the k-th order

// --- constructors ------------------------------------------------------------------

// Cyclic Latin square: n rows, row r = (r, r+1, ..., r+n-1) mod n. 1 <= n <= 4096.
OrderTable cyclic_latin_square(int n);

// Williams design (Williams 1949; Bradley 1958): row r = first row + r (mod n),
// first row 0, 1, n-1, 2, n-2, ... For even n the n rows are a Latin square in
// which every ordered pair of distinct conditions is adjacent exactly once; for
// odd n the n rows are followed by their mirror images (2n rows), and every
// ordered pair is adjacent exactly twice. 1 <= n <= 4096.
OrderTable williams_design(int n);

// All n! permutations in lexicographic order. 1 <= n <= 8 (8! = 40320 rows).
OrderTable all_permutations(int n);

// `rows` uniformly random permutations (Fisher-Yates over a SplitMix64 stream,
// bounded integers by rejection); row k depends only on (seed, k).
// 1 <= n <= 4096, 0 <= rows <= 1000000.
OrderTable random_orders(int n, int rows, std::uint64_t seed);
// Row `row` (>= 0) of random_orders(n, ., seed), computed alone.
Order random_order(int n, std::uint64_t seed, int row);

// Single rows, computed alone: row r of the corresponding table (0 <= r < its rows).
Order cyclic_latin_square_row(int n, int r);
Order williams_row(int n, int r);      // 0 <= r < n (even n) or 2n (odd n)
Order permutation_row(int n, int r);   // r-th permutation in lexicographic order, 0 <= r < n!

// --- property checks (n = number of columns of the first row) -------------------------

// Every row is a permutation of 0..n-1, and the table has at least one row.
bool is_permutation_table(const OrderTable& t);
// n x n, every condition once in every row and once in every column.
bool is_latin_square(const OrderTable& t);
// Every condition equally often at every position (column) over all rows.
bool positions_balanced(const OrderTable& t);
// Every ordered pair (a, b), a != b, appears as neighbours (a directly before b)
// equally often over all rows, and at least once (carry-over balance, first order).
bool williams_balanced(const OrderTable& t);
// A Latin square in which every ordered pair is adjacent exactly once (row-complete).
bool is_row_complete(const OrderTable& t);

}  // namespace dtlab::design

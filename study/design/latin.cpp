// Counterbalancing designs and their property checks; see latin.h.
// Constructors check their preconditions and throw std::invalid_argument;
// checks never throw and return false for malformed tables.
#include "study/design/latin.h"

#include <algorithm>
#include <numeric>
#include <stdexcept>
#include <string>

#include "study/common/random.h"

namespace dtlab::design {

namespace {

constexpr int kMaxSquare = 4096;

void require(bool ok, const std::string& what) {
  if (!ok) throw std::invalid_argument(what);
}

}  // namespace

Order cyclic_latin_square_row(int n, int r) {
  require(n >= 1 && n <= kMaxSquare, "cyclic_latin_square: n must be in [1, 4096], got " + std::to_string(n));
  require(r >= 0 && r < n, "cyclic_latin_square_row: row " + std::to_string(r) + " out of range for n = " +
                               std::to_string(n));
  Order row(n);
  for (int c = 0; c < n; ++c) row[c] = (r + c) % n;
  return row;
}

OrderTable cyclic_latin_square(int n) {
  require(n >= 1 && n <= kMaxSquare, "cyclic_latin_square: n must be in [1, 4096], got " + std::to_string(n));
  OrderTable t;
  for (int r = 0; r < n; ++r) t.push_back(cyclic_latin_square_row(n, r));
  return t;
}

Order williams_row(int n, int r) {
  require(n >= 1 && n <= kMaxSquare, "williams_design: n must be in [1, 4096], got " + std::to_string(n));
  const int rows = n % 2 == 0 ? n : 2 * n;
  require(r >= 0 && r < rows, "williams_row: row " + std::to_string(r) + " out of range for n = " + std::to_string(n));
  // First row 0, 1, n-1, 2, n-2, ...; row r adds r (mod n); for odd n, rows n..2n-1 mirror rows 0..n-1.
  const int shift = r % n;
  Order row(n);
  for (int j = 0; j < n; ++j) {
    const int first = j == 0 ? 0 : (j % 2 == 1 ? (j + 1) / 2 : n - j / 2);
    row[j] = (first + shift) % n;
  }
  if (r >= n) std::reverse(row.begin(), row.end());
  return row;
}

OrderTable williams_design(int n) {
  require(n >= 1 && n <= kMaxSquare, "williams_design: n must be in [1, 4096], got " + std::to_string(n));
  OrderTable t;
  const int rows = n % 2 == 0 ? n : 2 * n;
  for (int r = 0; r < rows; ++r) t.push_back(williams_row(n, r));
  return t;
}

Order permutation_row(int n, int r) {
  require(n >= 1 && n <= 8, "all_permutations: n must be in [1, 8], got " + std::to_string(n));
  int factorial = 1;
  for (int i = 2; i <= n; ++i) factorial *= i;
  require(r >= 0 && r < factorial,
          "permutation_row: row " + std::to_string(r) + " out of range for n = " + std::to_string(n));
  // Factorial number system: digit i picks among the items not used yet.
  Order pool(n);
  std::iota(pool.begin(), pool.end(), 0);
  Order row;
  for (int i = n; i >= 1; --i) {
    factorial /= i;
    const int pick = r / factorial;
    r %= factorial;
    row.push_back(pool[pick]);
    pool.erase(pool.begin() + pick);
  }
  return row;
}

OrderTable all_permutations(int n) {
  require(n >= 1 && n <= 8, "all_permutations: n must be in [1, 8], got " + std::to_string(n));
  Order row(n);
  std::iota(row.begin(), row.end(), 0);
  OrderTable t;
  do {
    t.push_back(row);
  } while (std::next_permutation(row.begin(), row.end()));
  return t;
}

Order random_order(int n, std::uint64_t seed, int row) {
  require(n >= 1 && n <= kMaxSquare, "random_order: n must be in [1, 4096], got " + std::to_string(n));
  require(row >= 0, "random_order: row must be >= 0, got " + std::to_string(row));
  Random<SplitMix64> rng(mix64(seed, static_cast<std::uint64_t>(row)));
  Order order(n);
  std::iota(order.begin(), order.end(), 0);
  rng.shuffle(order);  // Fisher-Yates
  return order;
}

OrderTable random_orders(int n, int rows, std::uint64_t seed) {
  require(n >= 1 && n <= kMaxSquare, "random_orders: n must be in [1, 4096], got " + std::to_string(n));
  require(rows >= 0 && rows <= 1000000, "random_orders: rows must be in [0, 1000000], got " + std::to_string(rows));
  OrderTable t;
  t.reserve(rows);
  for (int r = 0; r < rows; ++r) t.push_back(random_order(n, seed, r));
  return t;
}

bool is_permutation_table(const OrderTable& t) {
  if (t.empty() || t[0].empty()) return false;
  const std::size_t n = t[0].size();
  std::vector<char> seen(n);
  for (const Order& row : t) {
    if (row.size() != n) return false;
    std::fill(seen.begin(), seen.end(), 0);
    for (int c : row) {
      if (c < 0 || static_cast<std::size_t>(c) >= n || seen[c]) return false;
      seen[c] = 1;
    }
  }
  return true;
}

bool is_latin_square(const OrderTable& t) {
  if (!is_permutation_table(t) || t.size() != t[0].size()) return false;
  const std::size_t n = t.size();
  std::vector<char> seen(n);
  for (std::size_t col = 0; col < n; ++col) {
    std::fill(seen.begin(), seen.end(), 0);
    for (std::size_t r = 0; r < n; ++r) {
      if (seen[t[r][col]]) return false;
      seen[t[r][col]] = 1;
    }
  }
  return true;
}

bool positions_balanced(const OrderTable& t) {
  if (!is_permutation_table(t)) return false;
  const std::size_t n = t[0].size();
  if (t.size() % n != 0) return false;
  const std::size_t expected = t.size() / n;
  std::vector<std::size_t> count(n);
  for (std::size_t col = 0; col < n; ++col) {
    std::fill(count.begin(), count.end(), 0);
    for (const Order& row : t) ++count[row[col]];
    if (std::any_of(count.begin(), count.end(), [&](std::size_t c) { return c != expected; })) return false;
  }
  return true;
}

namespace {
// adjacency[a * n + b] = how often a directly precedes b, over all rows.
std::vector<std::size_t> adjacency(const OrderTable& t) {
  const std::size_t n = t[0].size();
  std::vector<std::size_t> adj(n * n);
  for (const Order& row : t)
    for (std::size_t j = 0; j + 1 < n; ++j) ++adj[row[j] * n + row[j + 1]];
  return adj;
}
}  // namespace

bool williams_balanced(const OrderTable& t) {
  if (!is_permutation_table(t)) return false;
  const std::size_t n = t[0].size();
  if (n < 2) return true;
  const auto adj = adjacency(t);
  const std::size_t expected = adj[0 * n + 1];
  if (expected == 0) return false;
  for (std::size_t a = 0; a < n; ++a)
    for (std::size_t b = 0; b < n; ++b)
      if (a != b && adj[a * n + b] != expected) return false;
  return true;
}

bool is_row_complete(const OrderTable& t) {
  if (!is_latin_square(t)) return false;
  const std::size_t n = t.size();
  if (n < 2) return true;
  const auto adj = adjacency(t);
  for (std::size_t a = 0; a < n; ++a)
    for (std::size_t b = 0; b < n; ++b)
      if (a != b && adj[a * n + b] != 1) return false;
  return true;
}

}  // namespace dtlab::design

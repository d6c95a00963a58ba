// Exact and Monte Carlo tails of the Friedman permutation distribution; see
// friedman_exact.h. The exact DP keeps, after each block, the probability of
// every sorted vector of column sums: the distribution is exchangeable over
// columns, so sorting loses nothing (Kendall & Babington Smith 1939). What
// makes k = 6, n = 12 take seconds instead of minutes (280 s before):
//  - one step's probabilities are a dense array indexed by the sorted
//    vector's lexicographic rank among the partitions in its box (Box): no
//    hashing, and neighbouring states write near each other;
//  - ranks are divided by their common divisor (2 for untied doubled ranks);
//  - untied data keep one of each mirrored pair of vectors (halves the work);
//  - a state with equal column sums needs only the arrangements of the
//    block's ranks that are non-decreasing along each run of equal sums,
//    each counted with the number of arrangements it stands for;
//  - the last block is never stored: each (state, arrangement) adds its S
//    to the tail (or histogram) directly, which saves the largest step;
//  - for a tail, states whose every continuation stays below (or reaches) the
//    observed S are settled at once (Settler).
// The work is bounded before it starts by counting the sorted vectors each
// step can reach (partitions in a box), so a design beyond the budget is
// refused at once with the reason. Never allocates more than two arrays of
// kMaxStates doubles.
#include "analysis/stats/detail/friedman_exact.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <numeric>
#include <optional>
#include <sstream>

#include "study/common/random.h"

namespace dtlab::stats::detail {
namespace {

constexpr std::size_t kMaxK = 8;  // treatments the enumeration handles

using Sums = std::array<int, kMaxK>;

// The sorted vectors of column sums after some blocks, as a dense index: the
// sums are w_j = lo + x_j with x ascending in [0, H] and summing to T; rank() numbers them in lexicographic
// order of x and first()/next() enumerate them in that order, so a step's
// probabilities are one array (no hashing; neighbouring states land near each
// other). N(j, m, s) counts the ascending sequences of length j in [m, H]
// summing to s; F(j, s, z) = sum_{y < z} N(j, y, s - y).
template <std::size_t K>
class Box {
 public:
  Box(int lo, int H, int T) : lo_(lo), H_(H), T_(T) {
    const std::size_t cols = static_cast<std::size_t>(H_) + 2, S = static_cast<std::size_t>(T_) + 1;
    std::vector<std::uint64_t> N(k_ * cols * S, 0);  // N[(j * cols + m) * S + s], j < k
    auto n_at = [&](std::size_t j, std::size_t m, int s) -> std::uint64_t {
      return s < 0 ? 0 : N[(j * cols + m) * S + static_cast<std::size_t>(s)];
    };
    for (std::size_t m = 0; m < cols; ++m) N[(0 * cols + m) * S + 0] = 1;
    for (std::size_t j = 1; j < k_; ++j)
      for (std::size_t m = cols - 1; m-- > 0;)  // N(j, m, s) = N(j, m + 1, s) + N(j - 1, m, s - m)
        for (int s = 0; s <= T_; ++s)
          N[(j * cols + m) * S + static_cast<std::size_t>(s)] =
              n_at(j, m + 1, s) + n_at(j - 1, m, s - static_cast<int>(m));
    F_.assign(k_ * S * cols, 0);
    for (std::size_t j = 0; j < k_; ++j)
      for (int s = 0; s <= T_; ++s)
        for (std::size_t z = 1; z < cols; ++z)
          F_[(j * S + static_cast<std::size_t>(s)) * cols + z] =
              F_[(j * S + static_cast<std::size_t>(s)) * cols + z - 1] + n_at(j, z - 1, s - static_cast<int>(z - 1));
    size_ = count_all();
  }
  std::size_t size() const { return size_; }
  std::size_t rank(const Sums& w) const {  // w: sorted sums of this box
    std::size_t r = 0;
    int rem = T_, prev = 0;
    for (std::size_t pos = 0; pos + 1 < k_; ++pos) {
      const int x = w[pos] - lo_;
      r += f(k_ - pos - 1, rem, x) - f(k_ - pos - 1, rem, prev);
      rem -= x;
      prev = x;
    }
    return r;
  }
  // rank(w) or, with `mirror`, the smaller of rank(w) and the rank of its
  // reflection x_j -> H - x_(k-1-j) (which holds the pair's probability).
  std::size_t canonical_rank(const Sums& w, bool mirror) const {
    if (!mirror) return rank(w);
    Sums m{};
    for (std::size_t j = 0; j < K; ++j) m[j] = 2 * lo_ + H_ - w[K - 1 - j];
    return std::lexicographical_compare(m.begin(), m.begin() + K, w.begin(), w.begin() + K) ? rank(m) : rank(w);
  }
  bool first(Sums& w) const { return fill(w, 0, 0, T_); }
  bool next(Sums& w) const {
    int before = 0;  // sum of x over positions < pos
    std::array<int, kMaxK> x{};
    for (std::size_t j = 0; j < k_; ++j) x[j] = w[j] - lo_;
    std::array<int, kMaxK> prefix{};
    for (std::size_t j = 0; j < k_; ++j) {
      prefix[j] = before;
      before += x[j];
    }
    for (std::size_t pos = k_ - 1; pos-- > 0;) {
      const int y = x[pos] + 1, rem = T_ - prefix[pos] - y, len = static_cast<int>(k_ - pos - 1);
      if (y <= H_ && len * y <= rem && rem <= len * H_) {
        w[pos] = lo_ + y;
        return fill(w, pos + 1, y, rem);
      }
    }
    return false;
  }

 private:
  std::uint64_t f(std::size_t j, int s, int z) const {
    const std::size_t cols = static_cast<std::size_t>(H_) + 2, S = static_cast<std::size_t>(T_) + 1;
    return F_[(j * S + static_cast<std::size_t>(s)) * cols + static_cast<std::size_t>(z)];
  }
  // The lexicographically smallest ascending completion of positions from.. with values >= prev summing to rem.
  bool fill(Sums& w, std::size_t from, int prev, int rem) const {
    for (std::size_t q = from; q < k_; ++q) {
      const int x = std::max(prev, rem - static_cast<int>(k_ - q - 1) * H_);
      if (x > H_ || (q + 1 == k_ && x != rem)) return false;
      w[q] = lo_ + x;
      prev = x;
      rem -= x;
    }
    return true;
  }
  // The number of vectors: the rank of the lexicographically last one (the front as large as the order allows) + 1.
  std::size_t count_all() const {
    Sums w{};
    if (!first(w)) return 0;
    int rem = T_, prev = 0;
    for (std::size_t q = 0; q < k_; ++q) {
      const int left = static_cast<int>(k_ - q);
      int x = std::min(H_, rem / left);  // ascending: x <= the mean of what is left
      x = std::max(x, prev);
      w[q] = lo_ + x;
      prev = x;
      rem -= x;
    }
    return rank(w) + 1;
  }
  static constexpr std::size_t k_ = K;
  int lo_, H_, T_;
  std::vector<std::uint64_t> F_;
  std::size_t size_ = 0;
};

// One block's ranks: its distinct arrangements, each of probability 1 / count,
// and per pattern of equal neighbours in a sorted state the canonical ones.
class Block {
 public:
  explicit Block(std::vector<int> ranks) : k_(ranks.size()) {
    std::sort(ranks.begin(), ranks.end());
    do {
      Sums p{};
      std::copy(ranks.begin(), ranks.end(), p.begin());
      perms_.push_back(p);
    } while (std::next_permutation(ranks.begin(), ranks.end()));
    by_pattern_.resize(std::size_t{1} << (k_ - 1));
  }
  std::size_t count() const { return perms_.size(); }
  int lowest() const { return perms_.front()[0]; }       // the first arrangement is sorted
  bool symmetric() const {  // the ranks are symmetric about their middle (always without ties)
    const Sums& p = perms_.front();
    for (std::size_t j = 0; j < k_; ++j)
      if (p[j] + p[k_ - 1 - j] != p[0] + p[k_ - 1]) return false;
    return true;
  }
  int highest() const { return perms_.front()[k_ - 1]; }
  int total() const {
    int t = 0;
    for (std::size_t j = 0; j < k_; ++j) t += perms_.front()[j];
    return t;
  }
  const Sums& perm(std::size_t i) const { return perms_[i]; }
  // Bit j of `pattern`: sums j and j+1 of the state are equal. Returns (arrangement, multiplicity).
  const std::vector<std::pair<std::uint32_t, double>>& canonical(unsigned pattern) {
    auto& list = by_pattern_[pattern];
    if (!list.empty()) return list;
    for (std::size_t i = 0; i < perms_.size(); ++i) {
      const Sums& p = perms_[i];
      double mult = 1;
      bool ok = true;
      std::size_t start = 0;
      for (std::size_t j = 0; j < k_ && ok; ++j) {
        const bool run_continues = j + 1 < k_ && ((pattern >> j) & 1u);
        if (run_continues) {
          ok = p[j] <= p[j + 1];
          continue;
        }
        mult *= arrangements(p, start, j + 1);  // distinct orders of the run's ranks
        start = j + 1;
      }
      if (ok) list.emplace_back(static_cast<std::uint32_t>(i), mult);
    }
    return list;
  }

 private:
  static double arrangements(const Sums& p, std::size_t from, std::size_t to) {
    double r = 1;
    std::size_t same = 1;
    for (std::size_t j = from; j < to; ++j) {
      r *= static_cast<double>(j - from + 1);
      if (j > from && p[j] == p[j - 1]) r /= static_cast<double>(++same);
      else same = 1;
    }
    return r;
  }
  std::size_t k_;
  std::vector<Sums> perms_;
  std::vector<std::vector<std::pair<std::uint32_t, double>>> by_pattern_;
};

unsigned tie_pattern(const Sums& s, std::size_t k) {
  unsigned pattern = 0;
  for (std::size_t j = 0; j + 1 < k; ++j)
    if (s[j] == s[j + 1]) pattern |= 1u << j;
  return pattern;
}

// Sorts s[0..K) ascending without branches (min/max compare-exchanges of an
// odd-even transposition network: k rounds; k <= 8, so at most 28 pairs).
template <std::size_t K>
void sort_small(Sums& s) {
  for (std::size_t round = 0; round < K; ++round)
    for (std::size_t j = round % 2; j + 1 < K; j += 2) {
      const int a = s[j], b = s[j + 1];
      s[j] = std::min(a, b);
      s[j + 1] = std::max(a, b);
    }
}

// Sorted vectors of k integers in [0, span] summing to total: partitions in a
// k x span box, the coefficient of q^total in the Gaussian binomial
// [span + k choose k]_q, built as prod_j (1 - q^(span + j)) / (1 - q^j) in
// O(k total) (each partial product is [span + j choose j]_q, nonnegative).
// A double: exact below 2^53, and only compared with limits above that.
double box_partitions(std::size_t k, int span, int total) {
  if (total < 0 || span < 0) return 0;
  const auto T = static_cast<std::size_t>(total), H = static_cast<std::size_t>(span);
  std::vector<double> c(T + 1, 0.0);
  c[0] = 1;
  for (std::size_t j = 1; j <= k; ++j) {
    for (std::size_t t = T; t >= H + j && t <= T; --t) c[t] -= c[t - H - j];  // times (1 - q^(H + j))
    for (std::size_t t = j; t <= T; ++t) c[t] += c[t - j];                    // over (1 - q^j)
  }
  return c[T];
}

// The common divisor of every rank (2 for untied doubled ranks): the DP runs
// on ranks / g, where the sums are g times closer together.
int rank_divisor(const std::vector<std::vector<int>>& r) {
  int g = 0;
  for (const auto& row : r)
    for (int v : row) g = std::gcd(g, v);
  return std::max(g, 1);
}

// The blocks, ranks divided by `g`, in the order the DP takes them: fewest
// arrangements first, so the largest one is the last, direct step.
std::vector<Block> blocks_of(const std::vector<std::vector<int>>& r, int g) {
  std::vector<std::vector<int>> sorted = r;
  for (auto& row : sorted) {
    for (int& v : row) v /= g;
    std::sort(row.begin(), row.end());
  }
  std::vector<Block> blocks;
  for (const auto& row : sorted) blocks.emplace_back(row);
  std::stable_sort(blocks.begin(), blocks.end(), [](const Block& a, const Block& b) { return a.count() < b.count(); });
  return blocks;
}

std::string number_text(double v) {
  std::ostringstream s;
  s.precision(2);
  s << v;
  return s.str();
}

// The geometry of the box after each block (lo, H, T; see Box), and the
// work: the sum over blocks of (states before it, at most the box's size and
// the product of the arrangements so far) x (its arrangements), plus the
// k (H + 2)(T + 1) entries of each stored step's Box tables. Sizes are
// counted only while the work stays within `limit`; beyond it `within` is
// false and `work` is a lower bound (so a refusal costs little even at
// n = 250000). `largest`: the most states and table entries of a stored step.
struct Geometry {
  std::vector<int> lo, H, T;
  double work = 0, largest_states = 0, largest_table = 0;
  bool within = true;
};

Geometry geometry(const std::vector<Block>& blocks, std::size_t k, double limit) {
  Geometry geo;
  double product = 1, before = 1;
  int lo = 0, hi = 0, total = 0;
  for (std::size_t b = 0; b < blocks.size(); ++b) {
    const Block& block = blocks[b];
    lo += block.lowest();
    hi += block.highest();
    total += block.total();
    product *= static_cast<double>(block.count());
    geo.lo.push_back(lo);
    geo.H.push_back(hi - lo);
    geo.T.push_back(total - static_cast<int>(k) * lo);
    if (!geo.within) continue;
    geo.work += before * static_cast<double>(block.count());
    if (b + 1 < blocks.size()) {  // a stored step: its Box and its states
      const double table = static_cast<double>(k) * (geo.H.back() + 2.0) * (geo.T.back() + 1.0);
      const double size = box_partitions(k, geo.H.back(), geo.T.back());
      geo.work += table;
      geo.largest_table = std::max(geo.largest_table, table);
      geo.largest_states = std::max(geo.largest_states, size);
      before = std::min(size, product);
    }
    geo.within = geo.work <= limit;
  }
  return geo;
}

constexpr double kMaxStates = 1 << 23;  // 8.4e6 probabilities (64 MB) per step
constexpr double kMaxTable = 1 << 22;   // 4.2e6 entries of a Box's two tables (64 MB)

// Runs the DP; `last` gets every (S, probability) of the final step. false
// (with *why) when the design is beyond the budget or the key's range.
// With a threshold (in the units of the scaled S) a state is settled early
// when every way the remaining blocks can go keeps the final S below it
// (dropped) or at or above it (its probability goes to the tail at once): the
// largest final S aligns every remaining block's ranks with the state's order
// (rearrangement inequality), and S is at least sum w^2 + 2 w . (remaining
// ranks anti-aligned) + (their total)^2 / k. Most states of a small or a
// large p settle long before the last block.
class Settler {
 public:
  Settler(const std::vector<Block>& blocks, std::size_t k, std::int64_t threshold)
      : k_(k), threshold_(threshold), rest_(blocks.size() + 1, Sums{}) {
    for (std::size_t b = blocks.size(); b-- > 0;)  // rest_[b]: ascending sum of the sorted ranks of blocks b..
      for (std::size_t j = 0; j < k; ++j) rest_[b][j] = rest_[b + 1][j] + blocks[b].perm(0)[j];
  }
  enum class Fate { open, below, reached };
  Fate fate(const Sums& w, std::size_t b) const {  // w: the sorted sums before block b
    const Sums& u = rest_[b];
    std::int64_t most = 0, sq = 0, anti = 0, total = 0;
    for (std::size_t j = 0; j < k_; ++j) {
      most += static_cast<std::int64_t>(w[j] + u[j]) * (w[j] + u[j]);
      sq += static_cast<std::int64_t>(w[j]) * w[j];
      anti += static_cast<std::int64_t>(w[j]) * u[k_ - 1 - j];
      total += u[j];
    }
    const auto k = static_cast<std::int64_t>(k_);
    if (most < threshold_) return Fate::below;
    return k * (sq + 2 * anti) + total * total >= k * threshold_ ? Fate::reached : Fate::open;
  }

 private:
  std::size_t k_;
  std::int64_t threshold_;
  std::vector<Sums> rest_;
};

// Refuses (false, the reason in *why) a design beyond the budget or the memory limits.
bool within_limits(const Geometry& geo, double budget, std::size_t n, std::size_t k, std::string* why) {
  const bool fits = geo.within && geo.largest_states <= kMaxStates && geo.largest_table <= kMaxTable;
  if (fits) return true;
  if (why) {
    const std::string design = " for n = " + std::to_string(n) + ", k = " + std::to_string(k);
    if (!geo.within)
      *why = "it needs more than " + number_text(budget) + " state updates" + design + " (the limit)";
    else if (geo.largest_states > kMaxStates)
      *why = "it needs a table of about " + number_text(geo.largest_states) + " rank-sum vectors" + design +
             ", above the limit of " + number_text(kMaxStates);
    else
      *why = "its index of rank-sum vectors needs about " + number_text(geo.largest_table) + " entries" + design +
             ", above the limit of " + number_text(kMaxTable);
  }
  return false;
}

// The DP for k = K (see the file comment); tail_at (S at or above which a
// state counts; nullptr: the whole distribution) lets states settle early.
template <std::size_t K, class Last>
bool run_dp_k(const std::vector<std::vector<int>>& r, double budget, std::string* why, const std::int64_t* tail_at,
              Last&& last) {
  constexpr std::size_t k = K;
  const int g = rank_divisor(r);
  std::vector<Block> blocks = blocks_of(r, g);
  const Geometry geo = geometry(blocks, k, budget);
  if (!within_limits(geo, budget, r.size(), k, why)) return false;
  // Step b reads the distribution after blocks 0..b-1 (`prob`, on box `from`)
  // and writes the one after block b; the last block feeds `last` directly.
  // When every block's ranks are symmetric, so is every distribution (and S
  // of a reflected final vector is S): one of each mirrored pair is kept,
  // with the pair's probability, which halves the work.
  const bool mirror = std::all_of(blocks.begin(), blocks.end(), [](const Block& b) { return b.symmetric(); });
  const std::optional<Settler> settler =
      tail_at ? std::optional<Settler>(std::in_place, blocks, k, (std::max<std::int64_t>(*tail_at, 0) + g * g - 1) / (g * g))
              : std::nullopt;
  std::vector<double> prob{1.0}, next;
  std::optional<Box<K>> from;
  Sums sums{}, moved{};
  for (std::size_t b = 0; b < blocks.size(); ++b) {
    Block& block = blocks[b];
    const double w = 1.0 / static_cast<double>(block.count());
    const bool final_step = b + 1 == blocks.size();
    std::optional<Box<K>> to;
    if (!final_step) {
      to.emplace(geo.lo[b], geo.H[b], geo.T[b]);
      next.assign(to->size(), 0.0);
    }
    std::size_t index = 0;
    bool more = from ? from->first(sums) : true;  // before any block: the zero vector
    for (; more; ++index, more = from && from->next(sums)) {
      const double p = prob[index];
      if (p == 0) continue;
      if (settler) {
        const Settler::Fate fate = settler->fate(sums, b);
        if (fate == Settler::Fate::reached) last(*tail_at, p);
        if (fate != Settler::Fate::open) continue;
      }
      for (const auto& [i, mult] : block.canonical(tie_pattern(sums, k))) {
        const Sums& perm = block.perm(i);
        for (std::size_t j = 0; j < k; ++j) moved[j] = sums[j] + perm[j];
        if (final_step) {
          std::int64_t s = 0;
          for (std::size_t j = 0; j < k; ++j) s += static_cast<std::int64_t>(moved[j]) * moved[j];
          last(s * g * g, p * w * mult);
        } else {
          sort_small<K>(moved);
          next[to->canonical_rank(moved, mirror)] += p * w * mult;
        }
      }
    }
    if (!final_step) {
      prob.swap(next);
      from = std::move(to);
    }
  }
  return true;
}

// run_dp_k for the k of r (2..8), unrolled per k.
template <class Last>
bool run_dp(const std::vector<std::vector<int>>& r, double budget, std::string* why, const std::int64_t* tail_at,
            Last&& last) {
  const std::size_t k = r.front().size();
  switch (k) {
    case 2: return run_dp_k<2>(r, budget, why, tail_at, last);
    case 3: return run_dp_k<3>(r, budget, why, tail_at, last);
    case 4: return run_dp_k<4>(r, budget, why, tail_at, last);
    case 5: return run_dp_k<5>(r, budget, why, tail_at, last);
    case 6: return run_dp_k<6>(r, budget, why, tail_at, last);
    case 7: return run_dp_k<7>(r, budget, why, tail_at, last);
    case 8: return run_dp_k<8>(r, budget, why, tail_at, last);
    default:
      if (why) *why = "k = " + std::to_string(k) + " treatments: the exact enumeration handles 2 <= k <= 8";
      return false;
  }
}

}  // namespace

std::int64_t friedman_s(const std::vector<std::vector<int>>& r) {
  if (r.empty()) return 0;
  std::vector<std::int64_t> t(r.front().size(), 0);
  for (const auto& row : r)
    for (std::size_t j = 0; j < row.size(); ++j) t[j] += row[j];
  std::int64_t s = 0;
  for (auto v : t) s += v * v;
  return s;
}

std::optional<std::vector<std::pair<std::int64_t, double>>> friedman_exact_distribution(
    const std::vector<std::vector<int>>& r, double budget, std::string* why) {
  using Out = std::vector<std::pair<std::int64_t, double>>;
  if (r.empty()) return Out{{0, 1.0}};
  // S <= k (sum of the blocks' largest ranks)^2: a histogram when that is small, else a map.
  double top = 0;
  for (const auto& row : r) top += *std::max_element(row.begin(), row.end());
  const double bound = static_cast<double>(r.front().size()) * top * top;
  Out out;
  if (bound < (1 << 24)) {
    std::vector<double> hist(static_cast<std::size_t>(bound) + 1, 0.0);
    if (!run_dp(r, budget, why, nullptr, [&](std::int64_t s, double p) { hist[static_cast<std::size_t>(s)] += p; }))
      return std::nullopt;
    for (std::size_t s = 0; s < hist.size(); ++s)
      if (hist[s] != 0) out.emplace_back(static_cast<std::int64_t>(s), hist[s]);
    return out;
  }
  std::map<std::int64_t, double> by_s;
  if (!run_dp(r, budget, why, nullptr, [&](std::int64_t s, double p) { by_s[s] += p; })) return std::nullopt;
  return Out(by_s.begin(), by_s.end());
}

std::optional<double> friedman_exact_tail(const std::vector<std::vector<int>>& r, std::int64_t s_obs, double budget,
                                          std::string* why) {
  if (r.empty()) return 1.0;
  double tail = 0.0;
  if (!run_dp(r, budget, why, &s_obs, [&](std::int64_t s, double p) {
        if (s >= s_obs) tail += p;
      }))
    return std::nullopt;
  return std::min(1.0, tail);
}

double friedman_exact_work(const std::vector<std::vector<int>>& r) {
  if (r.empty() || r.front().size() > kMaxK) return INFINITY;
  const Geometry geo = geometry(blocks_of(r, rank_divisor(r)), r.front().size(), 1e15);
  return geo.within ? geo.work : INFINITY;
}

double friedman_monte_carlo_tail(const std::vector<std::vector<int>>& r, std::int64_t s_obs, std::size_t samples,
                                 std::uint64_t seed, const std::function<void(std::size_t, std::size_t)>& progress) {
  Random<SplitMix64> rng(seed);
  const std::size_t k = r.empty() ? 0 : r.front().size();
  std::vector<std::int64_t> t(k);
  std::vector<int> row;
  std::size_t hits = 0;
  const std::size_t every = std::max<std::size_t>(1, samples / 100);
  for (std::size_t b = 0; b < samples; ++b) {
    if (progress && b % every == 0) progress(b, samples);
    std::fill(t.begin(), t.end(), 0);
    for (const auto& block : r) {
      row = block;
      rng.shuffle(row);  // Fisher-Yates
      for (std::size_t j = 0; j < k; ++j) t[j] += row[j];
    }
    std::int64_t s = 0;
    for (auto v : t) s += v * v;
    if (s >= s_obs) ++hits;
  }
  if (progress) progress(samples, samples);
  return (static_cast<double>(hits) + 1.0) / (static_cast<double>(samples) + 1.0);
}

}  // namespace dtlab::stats::detail

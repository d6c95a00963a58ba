// Exact and Monte Carlo tails of the Friedman permutation distribution; see
// friedman_exact.h. The exact DP keeps, after each block, the probability of
// every sorted vector of column sums: the distribution is exchangeable over
// columns, so sorting loses nothing (Kendall & Babington Smith 1939).
#include "analysis/stats/detail/friedman_exact.h"

#include <algorithm>
#include <array>
#include <map>
#include <unordered_map>

#include "study/common/hash.h"

namespace dtlab::stats::detail {
namespace {

using Key = std::array<std::uint64_t, 2>;  // up to 8 sums of 16 bits

struct KeyHash {
  std::size_t operator()(const Key& k) const { return static_cast<std::size_t>(dtlab::mix64(k[0], k[1])); }
};

Key pack(const std::vector<int>& sums) {
  Key key{0, 0};
  for (std::size_t j = 0; j < sums.size(); ++j)
    key[j / 4] |= static_cast<std::uint64_t>(sums[j]) << (16 * (j % 4));
  return key;
}

void unpack(const Key& key, std::size_t k, std::vector<int>& sums) {
  for (std::size_t j = 0; j < k; ++j) sums[j] = static_cast<int>((key[j / 4] >> (16 * (j % 4))) & 0xFFFF);
}

}  // namespace

std::uint64_t SplitMixStream::next() { return dtlab::mix64(seed_, counter_++); }

std::uint64_t SplitMixStream::below(std::uint64_t bound) {
  __extension__ typedef unsigned __int128 u128;
  u128 m = static_cast<u128>(next()) * bound;
  std::uint64_t low = static_cast<std::uint64_t>(m);
  if (low < bound) {
    const std::uint64_t threshold = (0 - bound) % bound;
    while (low < threshold) {
      m = static_cast<u128>(next()) * bound;
      low = static_cast<std::uint64_t>(m);
    }
  }
  return static_cast<std::uint64_t>(m >> 64);
}

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
    const std::vector<std::vector<int>>& r, double budget) {
  using Out = std::vector<std::pair<std::int64_t, double>>;
  if (r.empty()) return Out{{0, 1.0}};
  const std::size_t k = r.front().size();
  if (k > 8) return std::nullopt;
  int max_total = 0;
  for (const auto& row : r) max_total += *std::max_element(row.begin(), row.end());
  if (max_total > 0xFFFF) return std::nullopt;

  std::unordered_map<Key, double, KeyHash> states, next;
  states[pack(std::vector<int>(k, 0))] = 1.0;
  double work = 0.0;
  std::vector<int> sums(k), moved(k);
  for (const auto& row : r) {
    std::vector<int> perm = row;
    std::sort(perm.begin(), perm.end());
    std::vector<std::vector<int>> perms;
    do perms.push_back(perm);
    while (std::next_permutation(perm.begin(), perm.end()));
    work += static_cast<double>(states.size()) * static_cast<double>(perms.size());
    if (work > budget) return std::nullopt;
    const double w = 1.0 / static_cast<double>(perms.size());
    next.clear();
    next.reserve(states.size() * 4);
    for (const auto& [key, prob] : states) {
      unpack(key, k, sums);
      for (const auto& p : perms) {
        for (std::size_t j = 0; j < k; ++j) moved[j] = sums[j] + p[j];
        std::sort(moved.begin(), moved.end());
        next[pack(moved)] += prob * w;
      }
    }
    states.swap(next);
  }
  std::map<std::int64_t, double> by_s;
  for (const auto& [key, prob] : states) {
    unpack(key, k, sums);
    std::int64_t s = 0;
    for (int v : sums) s += static_cast<std::int64_t>(v) * v;
    by_s[s] += prob;
  }
  return Out(by_s.begin(), by_s.end());
}

std::optional<double> friedman_exact_tail(const std::vector<std::vector<int>>& r, std::int64_t s_obs, double budget) {
  const auto dist = friedman_exact_distribution(r, budget);
  if (!dist) return std::nullopt;
  double tail = 0.0;
  for (auto it = dist->rbegin(); it != dist->rend() && it->first >= s_obs; ++it) tail += it->second;  // small terms first
  return std::min(1.0, tail);
}

double friedman_monte_carlo_tail(const std::vector<std::vector<int>>& r, std::int64_t s_obs, std::size_t samples,
                                 std::uint64_t seed, const std::function<void(std::size_t, std::size_t)>& progress) {
  SplitMixStream rng(seed);
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
      for (std::size_t j = k; j > 1; --j) std::swap(row[j - 1], row[rng.below(j)]);  // Fisher-Yates
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

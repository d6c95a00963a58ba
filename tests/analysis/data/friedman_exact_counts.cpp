// Exact null distribution of the Friedman statistic for untied data, by
// integer counting (no floating point; written apart from analysis/stats so
// that it checks it independently): after each block, the number of ways (out
// of (k!)^blocks) to reach every sorted vector of rank sums, held in 128-bit
// integers; the last block is added without sorting and S = sum of squared
// rank sums counted. Prints one line per S: S Q count tail_count total, where
// tail_count = #{S' >= S} and Q = 12 S / (n k (k + 1)) - 3 n (k + 1).
// Build and run: g++ -O2 -std=c++17 friedman_exact_counts.cpp -o fec && ./fec 6 12 > out.txt
#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <string>
#include <unordered_map>
#include <vector>

typedef unsigned __int128 u128;

std::string text(u128 v) {
  if (v == 0) return "0";
  std::string s;
  while (v > 0) {
    s.insert(s.begin(), static_cast<char>('0' + static_cast<int>(v % 10)));
    v /= 10;
  }
  return s;
}

int main(int argc, char** argv) {
  if (argc != 3) return 2;
  const int k = std::atoi(argv[1]), n = std::atoi(argv[2]);
  if (k < 2 || k > 8 || n < 1) return 2;
  std::vector<std::vector<int>> perms;
  std::vector<int> p(k);
  for (int j = 0; j < k; ++j) p[j] = j + 1;
  do perms.push_back(p); while (std::next_permutation(p.begin(), p.end()));
  auto key = [&](const std::vector<int>& v) {  // rank sums <= 8 * 255: 8 bits each after sorting
    std::uint64_t x = 0;
    for (int j = 0; j < k; ++j) x = x * 256 + static_cast<std::uint64_t>(v[j]);
    return x;
  };
  auto unkey = [&](std::uint64_t x) {
    std::vector<int> v(k);
    for (int j = k - 1; j >= 0; --j, x /= 256) v[j] = static_cast<int>(x % 256);
    return v;
  };
  std::unordered_map<std::uint64_t, u128> states{{key(std::vector<int>(k, 0)), 1}};
  for (int b = 0; b + 1 < n; ++b) {
    std::unordered_map<std::uint64_t, u128> next;
    for (const auto& [x, count] : states) {
      const std::vector<int> v = unkey(x);
      for (const auto& q : perms) {
        std::vector<int> w(k);
        for (int j = 0; j < k; ++j) w[j] = v[j] + q[j];
        std::sort(w.begin(), w.end());
        next[key(w)] += count;
      }
    }
    states.swap(next);
  }
  std::map<long long, u128> dist;
  for (const auto& [x, count] : states) {
    const std::vector<int> v = unkey(x);
    for (const auto& q : perms) {
      long long s = 0;
      for (int j = 0; j < k; ++j) s += static_cast<long long>(v[j] + q[j]) * (v[j] + q[j]);
      dist[s] += count;
    }
  }
  u128 total = 1;
  for (int b = 0; b < n; ++b) total *= static_cast<u128>(perms.size());
  u128 tail = 0, sum = 0;
  std::vector<std::string> lines;
  for (auto it = dist.rbegin(); it != dist.rend(); ++it) {
    tail += it->second;
    sum += it->second;
    const double q = 12.0 * static_cast<double>(it->first) / (n * k * (k + 1.0)) - 3.0 * n * (k + 1.0);
    char b[64];
    std::snprintf(b, sizeof b, "%lld %.10g ", it->first, q);
    lines.push_back(b + text(it->second) + " " + text(tail) + " " + text(total));
  }
  if (sum != total) return 1;
  for (auto it = lines.rbegin(); it != lines.rend(); ++it) std::printf("%s\n", it->c_str());
  return 0;
}

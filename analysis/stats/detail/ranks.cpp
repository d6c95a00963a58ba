// Average ranks and tie groups; see ranks.h.
#include "analysis/stats/detail/ranks.h"

#include <algorithm>
#include <numeric>

namespace dtlab::stats::detail {

std::vector<double> average_ranks(const std::vector<double>& x) {
  const size_t n = x.size();
  std::vector<size_t> order(n);
  std::iota(order.begin(), order.end(), size_t{0});
  std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) { return x[a] < x[b]; });
  std::vector<double> r(n);
  for (size_t i = 0; i < n;) {
    size_t j = i;
    while (j + 1 < n && x[order[j + 1]] == x[order[i]]) ++j;
    const double avg = (static_cast<double>(i) + static_cast<double>(j)) / 2.0 + 1.0;
    for (size_t k = i; k <= j; ++k) r[order[k]] = avg;
    i = j + 1;
  }
  return r;
}

std::vector<size_t> tie_sizes(const std::vector<double>& x) {
  std::vector<double> s = x;
  std::sort(s.begin(), s.end());
  std::vector<size_t> sizes;
  for (size_t i = 0; i < s.size();) {
    size_t j = i;
    while (j + 1 < s.size() && s[j + 1] == s[i]) ++j;
    sizes.push_back(j - i + 1);
    i = j + 1;
  }
  return sizes;
}

double tie_sum(const std::vector<double>& x) {
  double t = 0.0;
  for (size_t s : tie_sizes(x)) {
    const double d = static_cast<double>(s);
    t += d * d * d - d;
  }
  return t;
}

}  // namespace dtlab::stats::detail

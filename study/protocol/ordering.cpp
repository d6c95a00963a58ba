// How many order rows and conditions a protocol declares (protocol.h,
// "scheme_rows", "declared_order_rows", "condition_index"): arithmetic over
// the parsed ordering and factors, apart from the loading and parsing of
// protocol.cpp. The parser checks the count against its limits and the design
// hash records it, so it lives in this stage, below study/design, which builds
// the rows themselves (design.cpp, latin.cpp). Exact: counts saturate at
// INT64_MAX, never overflow; reads nothing but the Protocol it is given.
#include <cstdint>
#include <limits>
#include <vector>

#include "study/protocol/protocol.h"

namespace dtlab::protocol {

std::int64_t scheme_rows(Scheme scheme, int n, int random_rows) {
  constexpr std::int64_t kMax = std::numeric_limits<std::int64_t>::max();
  switch (scheme) {
    case Scheme::latin_square: return n;
    case Scheme::williams: return n % 2 == 0 ? n : 2 * static_cast<std::int64_t>(n);
    case Scheme::full_permutation: {
      std::int64_t f = 1;
      for (int i = 2; i <= n; ++i) {
        if (f > kMax / i) return kMax;
        f *= i;
      }
      return f;
    }
    case Scheme::random: return random_rows;
    case Scheme::fixed: break;
  }
  return 1;
}

std::int64_t declared_order_rows(const Protocol& p) {
  constexpr std::int64_t kMax = std::numeric_limits<std::int64_t>::max();
  const Ordering& o = p.order;
  if (o.unit == OrderUnit::conditions) {
    int n = 1;
    for (const auto& f : p.factors) n *= static_cast<int>(f.levels.size());
    return scheme_rows(o.scheme, n, o.rows);
  }
  if (o.block_factor < 0 || o.block_factor >= static_cast<int>(p.factors.size())) return 0;
  int nested = 1;
  for (int f = 0; f < static_cast<int>(p.factors.size()); ++f)
    if (f != o.block_factor) nested *= static_cast<int>(p.factors[f].levels.size());
  const std::int64_t outer = scheme_rows(o.scheme, static_cast<int>(p.factors[o.block_factor].levels.size()), o.rows);
  const std::int64_t inner = scheme_rows(o.nested_scheme, nested, o.nested_rows);
  if (outer > 0 && inner > kMax / outer) return kMax;
  return outer * inner;
}

int condition_index(const Protocol& p, const std::vector<int>& levels) {
  if (levels.size() != p.factors.size()) return -1;
  int index = 0;
  for (std::size_t f = 0; f < levels.size(); ++f) {
    const int k = static_cast<int>(p.factors[f].levels.size());
    if (levels[f] < 0 || levels[f] >= k) return -1;
    index = index * k + levels[f];
  }
  return index;
}

}  // namespace dtlab::protocol

// Screen-door pixel masks (see pixel_masks.h; Poon 2000, chapter 4).
// One table serves both binary-partition methods: the pixel tree's leaves are
// the table's rows without the null nodes (a null node splits into two null
// nodes and changes no mask, so only its count is kept, for Table 2).
#include <algorithm>
#include <cmath>
#include <numeric>

#include "study/render/detail/pixel_masks.h"

namespace dtlab::render::detail {

int PixelMask::count() const {
  int c = 0;
  for (std::uint32_t w : words) c += __builtin_popcount(w);
  return c;
}

MaskTable::MaskTable(int n, Options options) : n_(n), opt_(options), rng_(options.seed) {
  Row root;  // 4.3.2: one row for the whole mask, empty, start 0, end 1
  root.pixels.resize(static_cast<std::size_t>(n));
  std::iota(root.pixels.begin(), root.pixels.end(), 0);
  rows_.push_back(std::move(root));
}

std::vector<int> splitting_order(int n, const std::vector<PixelMask>& filled_by_priority) {
  const std::size_t m = filled_by_priority.size();
  std::vector<std::vector<bool>> f(m, std::vector<bool>(static_cast<std::size_t>(n))), e = f;
  for (std::size_t i = 0; i < m; ++i)
    for (int b = 0; b < n; ++b) {
      const bool in = filled_by_priority[i].test(b);
      const bool prev_f = i == 0 || f[i - 1][static_cast<std::size_t>(b)];
      const bool prev_e = i == 0 || e[i - 1][static_cast<std::size_t>(b)];
      f[i][static_cast<std::size_t>(b)] = prev_f && in;
      e[i][static_cast<std::size_t>(b)] = prev_e && !in;
    }
  std::vector<int> order;
  std::vector<bool> seen(static_cast<std::size_t>(n), false);
  auto collect = [&](const std::vector<bool>& set) {
    for (int b = 0; b < n; ++b)
      if (set[static_cast<std::size_t>(b)] && !seen[static_cast<std::size_t>(b)]) {
        seen[static_cast<std::size_t>(b)] = true;
        order.push_back(b);
      }
  };
  for (std::size_t i = m; i-- > 0;) collect(f[i]);  // F^m first, down to F^0
  for (std::size_t i = m; i-- > 0;) collect(e[i]);
  collect(std::vector<bool>(static_cast<std::size_t>(n), true));  // the rest (none when m > 0)
  return order;
}

// The order in which the leaves [start, end) are split: table order, the pixel tree's random
// sequence, or (4.3.3) by the splitting-order rank of each row's pixels (a leaf lies wholly
// inside or outside every earlier mask, so its first pixel ranks it).
std::vector<int> MaskTable::row_order(const std::vector<int>& rank) const {
  std::vector<int> order(static_cast<std::size_t>(end() - start_));
  std::iota(order.begin(), order.end(), start_);
  if (!rank.empty())
    std::stable_sort(order.begin(), order.end(), [&](int a, int b) {
      return rank[static_cast<std::size_t>(rows_[static_cast<std::size_t>(a)].pixels.front())] <
             rank[static_cast<std::size_t>(rows_[static_cast<std::size_t>(b)].pixels.front())];
    });
  return order;
}

const PixelMask& MaskTable::add(float alpha_in, float depth) {
  const double alpha = std::clamp(static_cast<double>(alpha_in), 0.0, 1.0);
  errors_.clear();
  PixelMask mask(n_);
  if (opt_.generation == MaskGeneration::white_noise) {
    // round(alpha n) distinct pixels drawn uniformly (partial Fisher-Yates).
    std::vector<int> pixels(static_cast<std::size_t>(n_));
    std::iota(pixels.begin(), pixels.end(), 0);
    const int k = static_cast<int>(std::floor(alpha * n_ + 0.5));
    for (int i = 0; i < k; ++i) {
      const int j = i + static_cast<int>(rng_.below(static_cast<std::uint64_t>(n_ - i)));
      std::swap(pixels[static_cast<std::size_t>(i)], pixels[static_cast<std::size_t>(j)]);
      mask.set(pixels[static_cast<std::size_t>(i)]);
    }
  } else {
    std::vector<int> rank;
    if (opt_.generation == MaskGeneration::tabular && opt_.neighbourhood && !masks_.empty()) {
      std::vector<std::size_t> earlier(masks_.size());
      std::iota(earlier.begin(), earlier.end(), 0);
      std::stable_sort(earlier.begin(), earlier.end(), [&](std::size_t a, std::size_t b) { return depths_[a] < depths_[b]; });
      earlier.resize(std::min(earlier.size(), static_cast<std::size_t>(std::max(opt_.priorities, 0))));
      std::vector<PixelMask> filled;
      for (std::size_t i : earlier) filled.push_back(masks_[i]);
      const std::vector<int> order = splitting_order(n_, filled);
      rank.resize(order.size());
      for (std::size_t p = 0; p < order.size(); ++p) rank[static_cast<std::size_t>(order[p])] = static_cast<int>(p);
    }
    std::vector<int> order = row_order(rank);
    if (opt_.generation == MaskGeneration::pixel_tree)  // 4.2.2: a randomized splitting sequence
      rng_.shuffle(order);
    const int old_end = end();
    double error = 0.0;
    for (int r : order) {
      const std::vector<int> pixels = rows_[static_cast<std::size_t>(r)].pixels;  // copy: rows_ grows
      const int count = static_cast<int>(pixels.size());
      const double exact = alpha * count + error;
      const int k = std::clamp(static_cast<int>(std::floor(exact + 0.5)), 0, count);
      error = exact - k;
      errors_.push_back(error);
      if (k > 0) {  // a child with no pixel is abandoned (4.3.2)
        Row filled{true, std::vector<int>(pixels.begin(), pixels.begin() + k)};
        for (int b : filled.pixels) mask.set(b);
        rows_.push_back(std::move(filled));
      }
      if (k < count) rows_.push_back(Row{false, std::vector<int>(pixels.begin() + k, pixels.end())});
    }
    start_ = old_end;
    if (opt_.generation == MaskGeneration::pixel_tree) {
      tree_leaves_ *= 2.0;  // every leaf, null or not, splits in two
      operations_ += tree_leaves_;
    } else {
      operations_ += end() - old_end;
    }
  }
  masks_.push_back(std::move(mask));
  depths_.push_back(depth);
  return masks_.back();
}

std::vector<PixelMask> generate_masks(int n, const MaskTable::Options& options, const std::vector<float>& alpha,
                                      const std::vector<float>& depth) {
  MaskTable table(n, options);
  for (std::size_t i = 0; i < alpha.size(); ++i) table.add(alpha[i], i < depth.size() ? depth[i] : 0.0f);
  return table.masks();
}

StackResult stack_masks(const std::vector<PixelMask>& masks, const std::vector<float>& alpha,
                        const std::vector<float>& depth) {
  StackResult s;
  const std::size_t m = masks.size();
  const int n = m == 0 ? 0 : masks[0].size;
  std::vector<int> owner(static_cast<std::size_t>(n), -1);
  for (std::size_t j = 0; j < m; ++j)  // rendering order, z-buffered per mask pixel
    for (int b = 0; b < n; ++b) {
      int& o = owner[static_cast<std::size_t>(b)];
      if (masks[j].test(b) && (o < 0 || depth[j] < depth[static_cast<std::size_t>(o)])) o = static_cast<int>(j);
    }
  s.visible.assign(m, 0);
  for (int o : owner)
    if (o >= 0) ++s.visible[static_cast<std::size_t>(o)];
  for (std::size_t j = 0; j < m; ++j) {
    double e = n * static_cast<double>(alpha[j]);
    for (std::size_t i = 0; i < m; ++i)
      if (depth[i] < depth[j]) e *= 1.0 - static_cast<double>(alpha[i]);
    s.expected.push_back(e);
    s.faulty.push_back(std::abs(s.visible[j] - e));
    s.total_faulty += s.faulty.back();
  }
  return s;
}

const std::vector<PixelMask>& MaskCache::get(const std::vector<std::pair<float, int>>& sequence) {
  std::vector<std::int32_t> key;
  key.reserve(sequence.size() * 2);
  for (const auto& [a, rank] : sequence) {
    key.push_back(static_cast<std::int32_t>(std::lround(std::clamp(a, 0.0f, 1.0f) * 65536.0f)));
    key.push_back(rank);
  }
  auto it = cache_.find(key);
  if (it != cache_.end()) return it->second;
  MaskTable::Options o = opt_;
  for (std::int32_t k : key) o.seed = o.seed * 0x100000001b3ull + static_cast<std::uint64_t>(k);  // white noise, pixel tree
  MaskTable table(n_, o);
  for (std::size_t i = 0; i < sequence.size(); ++i)
    table.add(static_cast<float>(key[2 * i]) / 65536.0f, static_cast<float>(sequence[i].second));
  return cache_.emplace(std::move(key), table.masks()).first->second;
}

}  // namespace dtlab::render::detail

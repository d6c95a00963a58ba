// Internal: screen-door pixel masks on the CPU (Poon 2000, chapter 4): the
// pixel-tree masks (4.2.1), the tabular pixel masks by table rolling with the
// accumulated-error compensation (4.3.1-4.3.2) and the neighbourhood error
// compensation (4.3.3), white-noise masks for comparison, and the thesis's
// stacking test that counts faulty pixels (4.2.2). A mask of n pixels (n = s x s
// sub-pixels of one output pixel) says which sub-pixels an object covers.
// Guarantees: deterministic for a given seed (a SplitMix64 stream, study/common/random.h; no global RNG);
// a mask of alpha 1 is full, of alpha 0 empty. Pure C++; never touches GL.
#pragma once
#include <cstdint>
#include <map>
#include <utility>
#include <vector>

#include "study/common/random.h"

namespace dtlab::render::detail {

// How masks are made (ScreenDoorMasks in render.h maps onto it).
enum class MaskGeneration { tabular, pixel_tree, white_noise };

// n bits, bit i = mask pixel i (sub-pixel (i mod s, i / s) of an s x s block).
struct PixelMask {
  int size = 0;
  std::vector<std::uint32_t> words;  // ceil(size / 32) words, bit i in words[i / 32]
  explicit PixelMask(int n = 0) : size(n), words(static_cast<std::size_t>((n + 31) / 32), 0u) {}
  bool test(int i) const { return (words[static_cast<std::size_t>(i) / 32] >> (i % 32)) & 1u; }
  void set(int i) { words[static_cast<std::size_t>(i) / 32] |= 1u << (i % 32); }
  int count() const;
};

// The mask table of 4.3.1 (tabular) or the leaves of the pixel tree (4.2.1; null nodes are
// not stored, only counted). Masks are added in rendering order; add() returns the new mask.
class MaskTable {
 public:
  struct Options {
    MaskGeneration generation = MaskGeneration::tabular;
    bool neighbourhood = true;  // tabular only: 4.3.3's splitting order (off: rows in table order)
    int priorities = 6;         // how many nearest earlier objects the splitting order considers
    std::uint64_t seed = 1;     // pixel tree's randomized splitting sequence, white noise
  };
  struct Row {
    bool filled = false;
    std::vector<int> pixels;  // never empty (an empty child is abandoned)
  };
  MaskTable(int n, Options options);

  // Adds the next object's mask: alpha in [0, 1] (clamped), depth (smaller = nearer) for the
  // neighbourhood priorities. The filled child of each split row takes round(alpha count + e)
  // of its pixels (the first ones of its list), e the error accumulated over the rows split
  // before it for this mask (reset to 0 per mask).
  const PixelMask& add(float alpha, float depth);

  int size() const { return n_; }
  const std::vector<Row>& rows() const { return rows_; }  // the whole table, spawned rows appended
  int start() const { return start_; }                    // the leaves: rows [start, end)
  int end() const { return static_cast<int>(rows_.size()); }
  // The accumulated error after each row split by the last add(), in split order.
  const std::vector<double>& last_errors() const { return errors_; }
  // Atomic operations so far (Table 2): row entries (tabular) or tree nodes including null
  // nodes (pixel tree) created, the root included; white noise: 0.
  double operations() const { return operations_; }
  const std::vector<PixelMask>& masks() const { return masks_; }

 private:
  int n_;
  Options opt_;
  std::vector<Row> rows_;
  int start_ = 0;
  std::vector<double> errors_;
  double operations_ = 1.0;
  double tree_leaves_ = 1.0;  // pixel tree: leaves of the full tree, null ones included
  std::vector<PixelMask> masks_;
  std::vector<float> depths_;
  Random<SplitMix64> rng_;  // unbiased bounded draws (study/common/random.h)
  std::vector<int> row_order(const std::vector<int>& rank) const;
};

// 4.3.3: the splitting order of a new mask from the filled regions RF of the earlier objects
// by priority (nearest first): F^m, F^(m-1) \ F^m, ..., F^0 \ F^1, then E^m, ..., E^0 \ E^1,
// then any pixel in neither, each part in ascending pixel index. F^i = RF^(p0) ^ ... ^ RF^(pi),
// E^i the same with the empty regions.
std::vector<int> splitting_order(int n, const std::vector<PixelMask>& filled_by_priority);

// Masks for objects in rendering order (alphas and depths per object).
std::vector<PixelMask> generate_masks(int n, const MaskTable::Options& options, const std::vector<float>& alpha,
                                      const std::vector<float>& depth);

// The thesis's error comparison (4.2.2): stack the masks in rendering order with a per-pixel
// depth comparison (z-buffer, the nearer wins, ties the earlier); visible[j] = mask pixels
// object j finally owns; expected[j] = n alpha_j prod(1 - alpha_i) over objects i nearer than j;
// faulty[j] = |visible[j] - expected[j]|.
struct StackResult {
  std::vector<int> visible;
  std::vector<double> expected;
  std::vector<double> faulty;
  double total_faulty = 0.0;
};
StackResult stack_masks(const std::vector<PixelMask>& masks, const std::vector<float>& alpha,
                        const std::vector<float>& depth);

// The renderer's per-pixel generation, memoized: masks depend only on the alphas in rendering
// order (quantized to 1/65536) and the depth ranks, so pixels with equal sequences share them.
class MaskCache {
 public:
  MaskCache(int n, MaskTable::Options options) : n_(n), opt_(options) {}
  // Masks for the sequence (alpha, depth rank: 0 = nearest) in rendering order.
  const std::vector<PixelMask>& get(const std::vector<std::pair<float, int>>& sequence);
  std::size_t entries() const { return cache_.size(); }

 private:
  int n_;
  MaskTable::Options opt_;
  std::map<std::vector<std::int32_t>, std::vector<PixelMask>> cache_;
};

}  // namespace dtlab::render::detail

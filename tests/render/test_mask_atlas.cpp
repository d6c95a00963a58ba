// The mask atlas's shelf packing (study/render/detail/mask_atlas.h), without GL: every tile
// is its target's covered texels padded by n' + 1, inside its page, and no two tiles of a page
// overlap.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <vector>

#include "study/common/random.h"
#include "study/render/detail/mask_atlas.h"

namespace dtlab::render::detail {
namespace {

// A frame view with `n` targets whose covers are random rectangles of up to `side` texels (some
// cut by the grid's edges, every seventh empty) on a 128 x 128 grid with n' = 8. The stream is
// dtlab's own (study/common/random.h), the same with every standard library.
FrameView view_with_targets(int n, int side, std::uint64_t seed) {
  FrameView v;
  v.grid = MaskGrid{128, 128, 6.25f, 4.6875f, 8};
  Random<SplitMix64> rng(seed);
  for (int i = 0; i < n; ++i) {
    TargetView t;
    if (i % 7 != 6) {
      const int x = rng.between(-side / 2, 128);
      const int y = rng.between(-side / 2, 128);
      const int w = rng.between(1, side);
      const int h = rng.between(1, side);
      t.cover = PixelRect{x, y, x + w, y + h};
    }
    v.targets.push_back(t);
  }
  return v;
}

void expect_packed(const FrameView& v, const MaskAtlas& a) {
  ASSERT_EQ(a.tiles.size(), v.targets.size());
  ASSERT_FALSE(a.pages.empty());
  const int pad = v.grid.layers + 1;
  int largest = 0;
  for (std::size_t i = 0; i < a.tiles.size(); ++i) {
    const MaskTile& t = a.tiles[i];
    const PixelRect& c = v.targets[i].cover;
    if (c.empty()) {
      EXPECT_EQ(t.w, 0) << i;
      continue;
    }
    EXPECT_EQ(t.texels, c.expand(pad)) << i;
    EXPECT_EQ(t.w, c.x1 - c.x0 + 2 * pad) << i;
    EXPECT_EQ(t.h, c.y1 - c.y0 + 2 * pad) << i;
    EXPECT_EQ(t.inside, t.texels.intersect({0, 0, 128, 128})) << i;
    largest = std::max({largest, t.w, t.h});
    ASSERT_GE(t.page, 0);
    ASSERT_LT(t.page, static_cast<int>(a.pages.size()));
    const MaskAtlas::Page& p = a.pages[static_cast<std::size_t>(t.page)];
    EXPECT_GE(t.x, 0) << i;
    EXPECT_GE(t.y, 0) << i;
    EXPECT_LE(t.x + t.w, p.width) << i;
    EXPECT_LE(t.y + t.h, p.height) << i;
  }
  for (const MaskAtlas::Page& p : a.pages) {
    EXPECT_LE(std::max(p.width, p.height), std::max(4096, largest));
  }
  for (std::size_t i = 0; i < a.tiles.size(); ++i)
    for (std::size_t j = i + 1; j < a.tiles.size(); ++j) {
      const MaskTile &s = a.tiles[i], &t = a.tiles[j];
      if (s.w == 0 || t.w == 0 || s.page != t.page) continue;
      EXPECT_FALSE((PixelRect{s.x, s.y, s.x + s.w, s.y + s.h}.overlaps({t.x, t.y, t.x + t.w, t.y + t.h})))
          << "tiles " << i << " and " << j;
    }
}

TEST(MaskAtlas, TilesArePaddedCoversInsideTheirPagesWithoutOverlap) {
  for (std::uint64_t seed = 1; seed <= 5; ++seed) {
    const FrameView v = view_with_targets(40, 60, seed);
    expect_packed(v, plan_mask_atlas(v));
  }
}

// About 257 tiles of up to 618 texels a side (26 million texels) cannot share one 4096 x 4096 page.
TEST(MaskAtlas, ManyLargeTilesSpillOntoMorePages) {
  const FrameView v = view_with_targets(300, 600, 11);
  const MaskAtlas a = plan_mask_atlas(v);
  EXPECT_GT(a.pages.size(), 1u);
  expect_packed(v, a);
}

// A page measures powers of two around its tiles (one 21 x 23 tile: 32 x 32).
TEST(MaskAtlas, PageIsThePowerOfTwoAroundItsTiles) {
  FrameView v;
  v.grid = MaskGrid{128, 128, 6.25f, 6.25f, 8};
  TargetView t;
  t.cover = PixelRect{10, 20, 13, 25};  // 3 x 5 texels: a tile of 21 x 23
  v.targets = {t};
  const MaskAtlas a = plan_mask_atlas(v);
  ASSERT_EQ(a.pages.size(), 1u);
  EXPECT_EQ(a.tiles[0].w, 21);
  EXPECT_EQ(a.tiles[0].h, 23);
  EXPECT_EQ(a.pages[0].width, 32);
  EXPECT_EQ(a.pages[0].height, 32);
}

}  // namespace
}  // namespace dtlab::render::detail

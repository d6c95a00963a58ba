// Screen-door pixel masks (study/render/detail/pixel_masks.h) against the
// worked examples and tables of Poon (2000), chapter 4, and the random-data
// experiment of 5.1.2. Each expected value names the figure or table it comes
// from. Pure CPU; no GL context.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <string>
#include <vector>

#include "study/common/random.h"
#include "study/render/detail/pixel_masks.h"

namespace dtlab::render::detail {
namespace {

PixelMask mask_of(int n, std::initializer_list<int> pixels) {
  PixelMask m(n);
  for (int b : pixels) m.set(b);
  return m;
}

MaskTable::Options opts(MaskGeneration g, bool neighbourhood = true, std::uint64_t seed = 1) {
  MaskTable::Options o;
  o.generation = g;
  o.neighbourhood = neighbourhood;
  o.seed = seed;
  return o;
}

// Figure 9 (4.2.2): 16-pixel masks, alphas 0.5, 0.25, 0.5, depth order = rendering order (p0
// nearest). Exact visible pixels 8, 2, 3 (16 x 0.5; 16 x 0.5 x 0.25; 16 x 0.5 x 0.75 x 0.5); the
// pixel tree gives 8, 2, 3 with no faulty pixel. The tabular masks split the same way here.
TEST(PixelMasks, Figure9PixelTreeAndTabularAreExact) {
  const std::vector<float> alpha{0.5f, 0.25f, 0.5f}, depth{0.0f, 1.0f, 2.0f};
  for (MaskGeneration g : {MaskGeneration::pixel_tree, MaskGeneration::tabular}) {
    for (std::uint64_t seed = 1; seed <= 20; ++seed) {
      const auto masks = generate_masks(16, opts(g, true, seed), alpha, depth);
      EXPECT_EQ(masks[0].count(), 8);
      EXPECT_EQ(masks[1].count(), 4);
      EXPECT_EQ(masks[2].count(), 8);
      const StackResult s = stack_masks(masks, alpha, depth);
      EXPECT_EQ(s.visible, (std::vector<int>{8, 2, 3}));
      EXPECT_EQ(s.expected, (std::vector<double>{8.0, 2.0, 3.0}));
      EXPECT_EQ(s.total_faulty, 0.0);
    }
  }
}

// Figure 9: "the white noise masks give one or more faulty pixels at the second and higher
// opacities" (its example: 8, 0, 5 visible). The first mask is always exact; the later ones are
// not, for most seeds: P(p1 sees exactly 2 of its 4) = C(8,2) C(8,2) / C(16,4) = 784/1820
// (R: dhyper(2, 8, 8, 4) = 0.4308), so p1 alone is faulty with probability 0.57.
TEST(PixelMasks, Figure9WhiteNoiseIsFaultyAtHigherOpacities) {
  const std::vector<float> alpha{0.5f, 0.25f, 0.5f}, depth{0.0f, 1.0f, 2.0f};
  int faulty_seeds = 0, p1_exact = 0;
  for (std::uint64_t seed = 1; seed <= 400; ++seed) {
    const auto masks = generate_masks(16, opts(MaskGeneration::white_noise, true, seed), alpha, depth);
    EXPECT_EQ(masks[1].count(), 4);
    const StackResult s = stack_masks(masks, alpha, depth);
    EXPECT_EQ(s.faulty[0], 0.0);
    if (s.total_faulty > 0.0) ++faulty_seeds;
    if (s.visible[1] == 2) ++p1_exact;
  }
  EXPECT_GT(faulty_seeds, 400 * 6 / 10);
  // 0.4308 x 400 = 172.3; binomial sd 9.9: within 4 sd.
  EXPECT_NEAR(p1_exact, 172.3, 40.0);
}

// Figure 12 (4.3.2): 8 pixels; mask1 alpha 0.5 splits the root into a filled row {0,1,2,3} and
// an empty row {4,5,6,7}, no error; mask2 alpha 0.125: the first row gives 4 x 0.125 = 0.5 ->
// one pixel {0}, accumulated error -0.5 (4 x 0.125 - 1); the second row gets 0.5 - 0.5 = 0
// pixels, so its filled child is abandoned and its 4 pixels go to the next (empty) row entry.
TEST(PixelMasks, Figure12TableRolling) {
  MaskTable t(8, opts(MaskGeneration::tabular));
  t.add(0.5f, 1.0f);
  ASSERT_EQ(t.rows().size(), 3u);
  EXPECT_EQ(t.start(), 1);
  EXPECT_EQ(t.end(), 3);
  EXPECT_TRUE(t.rows()[1].filled);
  EXPECT_EQ(t.rows()[1].pixels, (std::vector<int>{0, 1, 2, 3}));
  EXPECT_FALSE(t.rows()[2].filled);
  EXPECT_EQ(t.rows()[2].pixels, (std::vector<int>{4, 5, 6, 7}));
  EXPECT_EQ(t.last_errors(), (std::vector<double>{0.0}));
  const PixelMask& m2 = t.add(0.125f, 0.0f);
  EXPECT_EQ(t.start(), 3);
  ASSERT_EQ(t.end(), 6);
  EXPECT_TRUE(t.rows()[3].filled);
  EXPECT_EQ(t.rows()[3].pixels, (std::vector<int>{0}));
  EXPECT_EQ(t.last_errors()[0], -0.5);
  EXPECT_FALSE(t.rows()[4].filled);
  EXPECT_EQ(t.rows()[4].pixels, (std::vector<int>{1, 2, 3}));
  EXPECT_FALSE(t.rows()[5].filled);
  EXPECT_EQ(t.rows()[5].pixels, (std::vector<int>{4, 5, 6, 7}));
  EXPECT_EQ(m2.count(), 1);
  EXPECT_TRUE(m2.test(0));
}

// Table 1 (4.3.3): RF^2, RF^1, RF^4 as printed (priorities: mask2, mask1, mask4); the splitting
// order of the new mask is {13, 15, 12, 14, 4, 5, 6, 7, 0, 2, 1, 3, 8, 9, 10, 11}.
TEST(PixelMasks, Table1NeighbourhoodSplittingOrder) {
  const std::vector<PixelMask> rf{mask_of(16, {4, 5, 6, 7, 12, 13, 14, 15}), mask_of(16, {8, 9, 10, 11, 12, 13, 14, 15}),
                                  mask_of(16, {1, 3, 5, 7, 9, 11, 13, 15})};
  EXPECT_EQ(splitting_order(16, rf), (std::vector<int>{13, 15, 12, 14, 4, 5, 6, 7, 0, 2, 1, 3, 8, 9, 10, 11}));
}

// Table 2 (4.3.4): atomic operations (node / row-entry creations, the root included) for m masks
// of size n with alpha 0.5 (every split non-trivial until a row holds one pixel): pixel tree
// 2^(m+1) - 1; tabular 2^(m+1) - 1 while 2^m <= n, else n (m - log2 n + 2) - 1.
TEST(PixelMasks, Table2OperationCounts) {
  struct Case {
    int n, m;
    double pixel_tree, tabular;
  };
  for (const Case& c : {Case{1024, 24, 33554431.0, 16383.0}, Case{1024, 10, 2047.0, 2047.0}, Case{64, 16, 131071.0, 767.0},
                        Case{64, 6, 127.0, 127.0}}) {
    MaskTable tree(c.n, opts(MaskGeneration::pixel_tree)), tab(c.n, opts(MaskGeneration::tabular));
    for (int i = 0; i < c.m; ++i) {
      tree.add(0.5f, static_cast<float>(i));
      tab.add(0.5f, static_cast<float>(i));
    }
    EXPECT_EQ(tree.operations(), c.pixel_tree) << "n=" << c.n << " m=" << c.m;
    EXPECT_EQ(tab.operations(), c.tabular) << "n=" << c.n << " m=" << c.m;
  }
}

TEST(PixelMasks, AlphaOneIsFullAndZeroIsEmpty) {
  for (MaskGeneration g : {MaskGeneration::tabular, MaskGeneration::pixel_tree, MaskGeneration::white_noise}) {
    const auto masks = generate_masks(64, opts(g), {0.3f, 1.0f, 0.0f, 0.7f}, {3.0f, 2.0f, 1.0f, 0.0f});
    EXPECT_EQ(masks[1].count(), 64);
    EXPECT_EQ(masks[2].count(), 0);
    EXPECT_EQ(masks[0].count(), 19);  // round(0.3 x 64 = 19.2)
  }
}

// The masks' random streams as they stood before the generators became one family
// (study/common/random.h): white noise draws pixels (a partial Fisher-Yates), the pixel tree
// shuffles its splitting sequence. A screen-door image made from a seed stays the same only
// while these hold; never regenerate them to make a change pass. The pixel tree's masks for the
// first alphas come out the same for seeds 1 to 4 and 99 (the error carried from leaf to leaf
// rounds each leaf alike in any splitting order); for the second alphas seeds 1 and 2 differ.
TEST(PixelMasks, SeededMasksArePinned) {
  struct Pin {
    MaskGeneration generation;
    std::uint64_t seed;
    std::vector<std::vector<std::uint32_t>> words;
  };
  const Pin pins[] = {
      {MaskGeneration::white_noise, 1,
       {{0x660981c2u, 0x40101a70u}, {0xf8340d32u, 0x17458d65u}, {0xa6bae155u, 0xfb0bbb9du}, {0xc0010240u, 0x43068014u}}},
      {MaskGeneration::white_noise, 99,
       {{0x041408c0u, 0x604cc38eu}, {0x40333e45u, 0x52b7291bu}, {0x4fb44d4au, 0xfdafe4cdu}, {0x44404a10u, 0x49140004u}}},
      {MaskGeneration::pixel_tree, 1,
       {{0x0007ffffu, 0x00000000u}, {0xfff801ffu, 0x0000007fu}, {0x7ff87e1fu, 0x003fff80u}, {0x80188221u, 0x00c00381u}}},
  };
  for (const Pin& p : pins) {
    const auto masks = generate_masks(64, opts(p.generation, true, p.seed), {0.3f, 0.45f, 0.6f, 0.2f}, {0.f, 1.f, 2.f, 3.f});
    ASSERT_EQ(masks.size(), p.words.size());
    for (std::size_t i = 0; i < masks.size(); ++i)
      EXPECT_EQ(masks[i].words, p.words[i]) << "generation " << static_cast<int>(p.generation) << " seed " << p.seed << " mask " << i;
  }
  const Pin tree[] = {
      {MaskGeneration::pixel_tree, 1,
       {{0x0007ffffu, 0x00000000u}, {0xfff81fffu, 0x0007ffffu}, {0xfff8e07fu, 0x03f8001fu}, {0x00382081u, 0x04080060u},
        {0xffdbefbfu, 0x7cf8ffe3u}}},
      {MaskGeneration::pixel_tree, 2,
       {{0x0007ffffu, 0x00000000u}, {0xfff83fffu, 0x0003ffffu}, {0xfff8c07fu, 0x03fc001fu}, {0x00384081u, 0x04040060u},
        {0xffffdfbfu, 0x7cf87fa3u}}},
  };
  for (const Pin& p : tree) {
    const auto masks = generate_masks(64, opts(p.generation, true, p.seed), {0.3f, 0.7f, 0.55f, 0.15f, 0.8f},
                                      {2.f, 0.f, 3.f, 1.f, 4.f});
    ASSERT_EQ(masks.size(), p.words.size());
    for (std::size_t i = 0; i < masks.size(); ++i)
      EXPECT_EQ(masks[i].words, p.words[i]) << "pixel tree seed " << p.seed << " mask " << i;
  }
}

// 5.1.2, Figures 19-20: random alphas and depths, random order, 16 objects on 16 x 16 masks and
// 32 on 32 x 32; faulty pixels per level. The thesis reports at most 1 to 2 faulty pixels for
// the tabular masks with neighbourhood compensation, about 7 (16 x 16) and 27 (32 x 32) in the
// worst case for white noise and for tabular masks without the compensation. The data come from
// the one generator (study/common/random.h), 100 trials per stream.
struct RandomRun {
  double worst = 0.0, mean = 0.0, p99 = 0.0;  // faulty pixels per level: max, mean, 99th percentile
};
RandomRun random_run(int side, MaskTable::Options o, int trials, std::uint64_t stream_seed) {
  dtlab::Stream stream(stream_seed);
  const int n = side * side, m = side;
  std::vector<double> faulty;
  for (int t = 0; t < trials; ++t) {
    std::vector<float> alpha, depth;
    for (int i = 0; i < m; ++i) {
      alpha.push_back(static_cast<float>(stream.uniform()));
      depth.push_back(static_cast<float>(stream.uniform()));
    }
    o.seed = static_cast<std::uint64_t>(t) + 1;
    const StackResult s = stack_masks(generate_masks(n, o, alpha, depth), alpha, depth);
    faulty.insert(faulty.end(), s.faulty.begin(), s.faulty.end());
  }
  std::sort(faulty.begin(), faulty.end());
  RandomRun r;
  r.worst = faulty.back();
  for (double f : faulty) r.mean += f;
  r.mean /= static_cast<double>(faulty.size());
  r.p99 = faulty[faulty.size() * 99 / 100];
  return r;
}

// The thesis's "only 1 to 2 faulty pixels" holds for 99 levels in 100, not for every level: on
// eight streams of 100 trials the compensated masks' 99th percentile was 1.10-1.34 (16 x 16) and
// 1.27-1.59 (32 x 32), their worst level 1.82-3.13 and 3.47-6.13; white noise's 99th percentile
// 6.1-6.2 and 9.6-10.3, plain tabular's 3.8-4.4 and 6.9-7.6. (An earlier version of this test
// asserted the worst level <= 2.0 at 16 x 16 on one hand-rolled LCG's data; other streams break
// that, so it was a property of that data, not of the masks.)
TEST(PixelMasks, RandomDataNeighbourhoodCompensationBeatsWhiteNoise) {
  for (int side : {16, 32})
    for (std::uint64_t stream_seed : {1u, 2u, 3u}) {
      SCOPED_TRACE("side " + std::to_string(side) + ", stream " + std::to_string(stream_seed));
      const RandomRun noise = random_run(side, opts(MaskGeneration::white_noise), 100, stream_seed);
      const RandomRun plain = random_run(side, opts(MaskGeneration::tabular, false), 100, stream_seed);
      const RandomRun comp = random_run(side, opts(MaskGeneration::tabular, true), 100, stream_seed);
      EXPECT_LT(comp.mean, noise.mean);
      EXPECT_LT(comp.mean, plain.mean);
      EXPECT_LT(comp.p99, plain.p99);
      EXPECT_LT(comp.p99, noise.p99);
      EXPECT_LT(comp.worst, noise.worst);
      EXPECT_LT(comp.worst, plain.worst);
      EXPECT_LE(comp.p99, 2.0) << "the thesis's 1 to 2 faulty pixels, for 99 levels in 100";
      EXPECT_LE(comp.worst, side == 16 ? 4.0 : 8.0);
      EXPECT_GT(noise.worst, 5.0);
      EXPECT_GT(noise.p99, 4.0);
    }
}

}  // namespace
}  // namespace dtlab::render::detail

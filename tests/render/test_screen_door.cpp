// The screen-door method (docs/render.md, "screen-door"; Poon 2000, chapter 4)
// on hand-built scenes with flat colours and a float colour buffer, so every
// expected pixel is a count of mask pixels over the mask size:
//   nothing occluded: the standard frame, byte for byte;
//   an impenetrable wall (alpha 1) stays opaque;
//   one wall (alpha aT) over a target: (k wall + (n - k) target) / n with k = round(aT n), the
//   mask's filled count (4.3.2: the first split of the whole mask);
//   two walls over a target drawn in either order: the same image (the z-buffer, not the
//   order, decides what shows: "order invariant", 4.2);
//   the mean error against `reference` does not grow from 8 x 8 to 32 x 32 masks.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "tests/render/scenes.h"
#include "tests/common/must.h"

using dtlab::test::must;

namespace dtlab::render {
namespace {

using testing::add_object;
using testing::front_camera;
using testing::headless_context;
using testing::project;
using testing::quad_mesh;

constexpr int kW = 128, kH = 96;
const glm::vec3 kBack(0.0f, 1.0f, 0.0f), kTarget(1.0f, 0.0f, 0.0f), kWall(0.0f, 0.0f, 1.0f), kWall2(1.0f, 1.0f, 1.0f);

struct Built {
  scene::Scene scene;
  std::vector<glm::vec3> flat;
};

// Back plane z = -20, target box around (0, 0, -12), a wall at z = -8 (optionally a second at
// -5; `group`: both walls in one sort group, drawn far-to-near or, `swapped`, near-to-far).
Built scene_of(bool wall_in_front, bool impenetrable = false, bool two_walls = false, bool swapped = false) {
  Built b;
  auto add = [&](scene::Mesh m, glm::vec3 c, bool target = false, bool imp = false) {
    const std::uint32_t i = add_object(b.scene, std::move(m), c, target, imp);
    b.flat.push_back(c);
    return i;
  };
  add(quad_mesh(-40, -40, 40, 40, -20), kBack);
  add(testing::box_mesh({-1.5f, -1.5f, -13.0f}, {1.5f, 1.5f, -11.0f}), kTarget, true);
  const float x = wall_in_front ? 0.0f : 9.0f;  // off to the side: nothing hides the target
  const std::uint32_t w1 = add(quad_mesh(x - 4, -3, x + 4, 3, -8), kWall, false, impenetrable);
  if (two_walls) {
    const std::uint32_t w2 = add(quad_mesh(-2.5f, -2, 2.5f, 2, -5), kWall2);
    for (std::uint32_t i : {w1, w2}) b.scene.objects[i].group = 100;
    b.scene.objects[w1].order_in_group = swapped ? 1 : 0;  // 0 first
    b.scene.objects[w2].order_in_group = swapped ? 0 : 1;
  }
  return b;
}

FrameSettings settings(Method m, int side, const Built& b) {
  FrameSettings f;
  f.method = m;
  f.screen_door.mask_side = side;
  f.flat_colors = b.flat;
  f.float_color = true;
  f.dt.gradient_px = 6.0f;
  return f;
}

std::vector<float> render_float(const Built& b, const FrameSettings& f) {
  auto r = Renderer::create(b.scene);
  EXPECT_TRUE(r.ok()) << (r.ok() ? "" : r.error().to_string());
  const FrameReport rep = must(r.value()->render_offscreen(front_camera(kW, kH), f, kW, kH));
  EXPECT_TRUE(rep.gl_errors.empty()) << rep.gl_errors.front();
  return must(r.value()->read_color_float());
}

glm::vec3 at(const std::vector<float>& px, glm::ivec2 p) {
  const std::size_t k = (static_cast<std::size_t>(p.y) * kW + static_cast<std::size_t>(p.x)) * 4;
  return {px[k], px[k + 1], px[k + 2]};
}

glm::ivec2 pixel_of(glm::vec3 world) { return glm::ivec2(project(front_camera(kW, kH), world, kW, kH)); }

class ScreenDoor : public ::testing::TestWithParam<int> {
 protected:
  void SetUp() override { headless_context(); }
};

TEST_P(ScreenDoor, NothingOccludedIsTheStandardFrame) {
  const Built b = scene_of(false);
  FrameSettings f = settings(Method::screen_door, GetParam(), b);
  f.flat_colors.clear();
  f.float_color = false;
  auto r = Renderer::create(b.scene);
  ASSERT_TRUE(r.ok());
  must(r.value()->render_offscreen(front_camera(kW, kH), f, kW, kH));
  const Image sd = must(r.value()->read_color());
  f.method = Method::standard;
  must(r.value()->render_offscreen(front_camera(kW, kH), f, kW, kH));
  EXPECT_EQ(sd.rgba, must(r.value()->read_color()).rgba);
}

TEST_P(ScreenDoor, AnImpenetrableWallStaysOpaque) {
  const Built b = scene_of(true, true);
  const std::vector<float> px = render_float(b, settings(Method::screen_door, GetParam(), b));
  const glm::vec3 c = at(px, pixel_of({0.0f, 0.0f, -8.0f}));
  EXPECT_EQ(c, kWall);
}

// One wall at alpha aT over the target's centre: the wall keeps k = round(aT n) of the n
// sub-pixels (the tabular mask's first split, Figure 12), the target the rest.
TEST_P(ScreenDoor, OneWallIsItsMaskCountOverTheTarget) {
  const int side = GetParam(), n = side * side;
  const Built b = scene_of(true);
  const FrameSettings f = settings(Method::screen_door, side, b);
  const std::vector<float> px = render_float(b, f);
  const double k = std::floor(static_cast<double>(f.dt.alpha_target) * n + 0.5);  // 19 of 64, 77 of 256, 307 of 1024
  const glm::vec3 expect = (static_cast<float>(k) * kWall + static_cast<float>(n - k) * kTarget) / static_cast<float>(n);
  const glm::vec3 c = at(px, pixel_of({0.0f, 0.0f, -8.0f}));
  EXPECT_NEAR(c.r, expect.r, 1e-3);
  EXPECT_NEAR(c.g, expect.g, 1e-3);
  EXPECT_NEAR(c.b, expect.b, 1e-3);
  // Far from the target (beyond the gradient) the wall is opaque.
  EXPECT_EQ(at(px, pixel_of({3.8f, 2.8f, -8.0f})), kWall);
}

// Two walls, both at aT (both drawn after the target): drawn far-to-near or near-to-far, the same
// image; the target's centre shows the nearer wall's 19.2 of 64 (alpha blending: 0.3 x 64), the
// farther's 13.44 and the target's 31.36 within one sub-pixel each.
TEST_P(ScreenDoor, TwoWallsInEitherOrderGiveOneImage) {
  const int side = GetParam(), n = side * side;
  const Built a = scene_of(true, false, true, false), b = scene_of(true, false, true, true);
  const std::vector<float> pa = render_float(a, settings(Method::screen_door, side, a));
  const std::vector<float> pb = render_float(b, settings(Method::screen_door, side, b));
  EXPECT_EQ(pa, pb);
  const glm::vec3 c = at(pa, pixel_of({0.0f, 0.0f, -5.0f}));
  // Channels: r = target + near wall (white), g = near wall, b = near + far wall (blue).
  const double near = c.g * n, target = c.r * n - near, far = c.b * n - near;
  EXPECT_NEAR(near, 0.3 * n, 1.0);
  EXPECT_NEAR(far, 0.3 * 0.7 * n, 1.0);
  EXPECT_NEAR(target, 0.7 * 0.7 * n, 1.0);
}

INSTANTIATE_TEST_SUITE_P(MaskSides, ScreenDoor, ::testing::Values(8, 16, 32),
                         [](const ::testing::TestParamInfo<int>& i) { return "s" + std::to_string(i.param); });

// Mean absolute error against `reference` over the frame (flat colours, two walls and the
// gradient): finer masks quantize alpha more finely, so it does not grow from 8 to 32.
TEST(ScreenDoorError, DoesNotGrowWithTheMaskSide) {
  headless_context();
  const Built b = scene_of(true, false, true, false);
  const std::vector<float> ref = render_float(b, settings(Method::reference, 8, b));
  std::vector<double> err;
  for (int side : {8, 16, 32}) {
    const std::vector<float> px = render_float(b, settings(Method::screen_door, side, b));
    double sum = 0.0;
    for (std::size_t i = 0; i < px.size(); ++i)
      if (i % 4 != 3) sum += std::abs(px[i] - ref[i]);
    err.push_back(sum / (kW * kH * 3));
    std::printf("mask %dx%d: mean |error| %.6f\n", side, side, err.back());
  }
  EXPECT_LE(err[1], err[0] * 1.05);
  EXPECT_LE(err[2], err[1] * 1.05);
  EXPECT_GT(err[0], 0.0);  // 8 x 8 quantizes alpha: not exact
}

}  // namespace
}  // namespace dtlab::render

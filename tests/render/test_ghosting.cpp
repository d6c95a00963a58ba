// The ghosting method (docs/render.md, "ghosting") on hand-built scenes: which
// objects become ghosts, the blend of a ghost over what it hides, its edges,
// and the standard frame when nothing stands in front of a target. Expected
// pixels come from the blend equation C = a C_ghost + (1 - a) C_behind with
// flat colours (exact; the background is black in that mode), 160 x 120.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>

#include "tests/common/must.h"
#include "tests/render/scenes.h"

namespace dtlab::render {
namespace {

using dtlab::test::must;
using testing::add_object;
using testing::front_camera;
using testing::headless_context;
using testing::rgb_at;

constexpr int kW = 160, kH = 120;
const glm::vec3 kTarget(0.0f, 0.8f, 0.0f), kInFront(0.8f, 0.0f, 0.0f), kAside(0.0f, 0.0f, 0.8f), kWall(0.6f, 0.6f, 0.0f);

// T: a target box x, y in [-1, 1], z in [-18, -16]. F: a distractor quad at z = -10 in front of
// it, x, y in [-2, 2]. A: a distractor quad at z = -10 beside it, x in [3, 5] (its rectangle
// misses T's). Seen from the origin down -z.
scene::Scene scene_with(bool wall_in_front = false) {
  scene::Scene s;
  add_object(s, testing::box_mesh({-1.0f, -1.0f, -18.0f}, {1.0f, 1.0f, -16.0f}), kTarget, true);
  add_object(s, testing::quad_mesh(-2.0f, -2.0f, 2.0f, 2.0f, -10.0f), kInFront);
  add_object(s, testing::quad_mesh(3.0f, -1.0f, 5.0f, 1.0f, -10.0f), kAside);
  if (wall_in_front) add_object(s, testing::quad_mesh(-2.0f, -2.0f, 2.0f, 2.0f, -8.0f), kWall, false, true);
  return s;
}

FrameSettings settings(const scene::Scene& s, Method m, bool flat, bool edges = false) {
  FrameSettings f;
  f.method = m;
  f.ghosting.alpha = 0.25f;
  f.ghosting.edges = edges;
  if (flat)
    for (const auto& o : s.objects) f.flat_colors.push_back(o.color);
  return f;
}

Image render(const scene::Scene& s, const FrameSettings& f, FrameReport* report = nullptr) {
  auto r = Renderer::create(s);
  EXPECT_TRUE(r.ok()) << (r.ok() ? "" : r.error().to_string());
  const FrameReport rep = must(r.value()->render_offscreen(front_camera(kW, kH), f, kW, kH));
  EXPECT_TRUE(rep.gl_errors.empty()) << rep.gl_errors.front();
  if (report != nullptr) *report = rep;
  Image img = must(r.value()->read_color());
  testing::maybe_dump(img, std::string(to_string(f.method)));
  return img;
}

glm::ivec2 pixel_of(glm::vec3 p) {
  const glm::vec2 w = testing::project(front_camera(kW, kH), p, kW, kH);
  return {static_cast<int>(std::floor(w.x)), static_cast<int>(std::floor(w.y))};
}

void expect_near(glm::ivec3 got, glm::vec3 want, const char* what) {
  const glm::ivec3 w(glm::round(glm::clamp(want, 0.0f, 1.0f) * 255.0f));
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(got[i], w[i], 2) << what << " channel " << i;
}

class GhostingTest : public ::testing::Test {
 protected:
  void SetUp() override { headless_context(); }
};

TEST_F(GhostingTest, TheDistractorInFrontOfATargetIsAGhostTheOneBesideItStaysOpaque) {
  const scene::Scene s = scene_with();
  FrameReport rep;
  const Image img = render(s, settings(s, Method::ghosting, true), &rep);
  EXPECT_EQ(rep.passes_run(), (std::vector<std::string>{"ghost-opaque", "ghost-blend", "present"}));
  const glm::ivec2 t = pixel_of({0.0f, 0.0f, -10.0f});  // F over T
  expect_near(rgb_at(img, t.x, t.y), 0.25f * kInFront + 0.75f * kTarget, "ghost over the target");
  const glm::ivec2 f = pixel_of({1.8f, 1.8f, -10.0f});  // F's corner: over the (black) background
  expect_near(rgb_at(img, f.x, f.y), 0.25f * kInFront, "ghost over the background");
  const glm::ivec2 a = pixel_of({4.0f, 0.0f, -10.0f});
  expect_near(rgb_at(img, a.x, a.y), kAside, "the distractor beside the target");
  // Under standard, F hides the target.
  const Image standard = render(s, settings(s, Method::standard, true));
  expect_near(rgb_at(standard, t.x, t.y), kInFront, "standard");
}

TEST_F(GhostingTest, AnImpenetrableSurfaceIsNeverAGhost) {
  const scene::Scene s = scene_with(true);
  const Image img = render(s, settings(s, Method::ghosting, true));
  const glm::ivec2 t = pixel_of({0.0f, 0.0f, -8.0f});
  expect_near(rgb_at(img, t.x, t.y), kWall, "the impenetrable wall stays opaque in front of the ghost");
}

TEST_F(GhostingTest, EdgesAreOpaqueLinesOnTheGhostsOutline) {
  const scene::Scene s = scene_with();
  const Image plain = render(s, settings(s, Method::ghosting, false, false));
  const Image edged = render(s, settings(s, Method::ghosting, false, true));
  // Along F's top border (y = 2 at z = -10), some pixel of the 3-pixel column is the edge colour
  // (0.08, 0.08, 0.1) x 255 = (20, 20, 26); without edges none is.
  int edge_pixels = 0, plain_edge_pixels = 0;
  for (float x : {-1.5f, -0.5f, 0.5f, 1.5f}) {
    const glm::ivec2 p = pixel_of({x, 2.0f, -10.0f});
    for (int dy = -1; dy <= 1; ++dy) {
      const auto is_edge = [](glm::ivec3 c) { return std::abs(c.r - 20) <= 2 && std::abs(c.g - 20) <= 2 && std::abs(c.b - 26) <= 2; };
      edge_pixels += is_edge(rgb_at(edged, p.x, p.y + dy));
      plain_edge_pixels += is_edge(rgb_at(plain, p.x, p.y + dy));
    }
  }
  EXPECT_GE(edge_pixels, 4) << "one per sampled column at least";
  EXPECT_EQ(plain_edge_pixels, 0);
  // Inside F, away from its border, the edges change nothing.
  const glm::ivec2 in = pixel_of({0.0f, 0.0f, -10.0f});
  EXPECT_EQ(rgb_at(edged, in.x, in.y), rgb_at(plain, in.x, in.y));
}

TEST_F(GhostingTest, WithNothingInFrontOfATargetTheFrameIsStandards) {
  scene::Scene s;
  add_object(s, testing::box_mesh({-1.0f, -1.0f, -18.0f}, {1.0f, 1.0f, -16.0f}), kTarget, true);
  add_object(s, testing::quad_mesh(3.0f, -1.0f, 5.0f, 1.0f, -10.0f), kAside);
  FrameReport rep;
  const Image ghosting = render(s, settings(s, Method::ghosting, false, true), &rep);
  const Image standard = render(s, settings(s, Method::standard, false));
  EXPECT_EQ(ghosting.rgba, standard.rgba);
  EXPECT_EQ(rep.passes_run(), (std::vector<std::string>{"opaque", "present"}));
}

// Visible pixels (docs/render.md): the target seen through a ghost at 0.75 of the final colour
// counts, as under dynamic transparency; under standard it is hidden.
TEST_F(GhostingTest, TheHiddenTargetBecomesVisible) {
  const scene::Scene s = scene_with();
  auto r = Renderer::create(s);
  ASSERT_TRUE(r.ok());
  const auto ghost = must(r.value()->visibility(front_camera(kW, kH), settings(s, Method::ghosting, false), kW, kH));
  const auto standard = must(r.value()->visibility(front_camera(kW, kH), settings(s, Method::standard, false), kW, kH));
  ASSERT_EQ(ghost.size(), 1u);
  EXPECT_GT(ghost[0].silhouette_pixels, 100);
  EXPECT_EQ(ghost[0].visible_pixels, ghost[0].silhouette_pixels);
  EXPECT_EQ(standard[0].visible_pixels, 0);
}

}  // namespace
}  // namespace dtlab::render

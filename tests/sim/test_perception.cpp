// What the simulated participant sees (study/sim/perception.h) against the
// renderer's own measure: look()'s packed weight frames must give exactly
// Renderer::visibility()'s visible pixel counts, for standard and dt-seed,
// ABSTRACT and WALKTHROUGH, at several cameras; the CPU silhouettes must agree
// with the renderer's occlusion-query silhouettes up to rasterisation rules;
// and packing must actually save frames (the reason it exists).
#include <gtest/gtest.h>

#include <cmath>
#include <map>

#include "app/platform/gl_context.h"
#include "study/render/render.h"
#include "study/scene/generate.h"
#include "study/sim/perception.h"
#include "tests/common/must.h"

using dtlab::test::must;

namespace dtlab::sim {
namespace {

constexpr int kW = 160, kH = 120;

class Perception : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    auto c = platform::create_headless(kW, kH);
    ASSERT_TRUE(c.ok()) << c.error().to_string();
    ctx_ = std::move(c.value()).release();
  }
  static void TearDownTestSuite() {
    delete ctx_;
    ctx_ = nullptr;
  }
  static platform::GlContext* ctx_;
};
platform::GlContext* Perception::ctx_ = nullptr;

render::FrameSettings settings(render::Method m) {
  render::FrameSettings f;
  f.method = m;
  f.dt.gradient_px = render::gradient_px_from_mask_pixels(8.0f, 128, kW, kH);
  return f;
}

struct Case {
  scene::Kind kind;
  scene::Task task;
  std::uint64_t seed;
  render::Method method;
  float yaw, pitch;  // added to the start camera
};

TEST_F(Perception, VisiblePixelsEqualTheRenderersVisibility) {
  const Case cases[] = {
      {scene::Kind::abstract, scene::Task::T1, 11, render::Method::standard, 0.0f, 0.0f},
      {scene::Kind::abstract, scene::Task::T1, 11, render::Method::dt_seed, 0.0f, 0.0f},
      {scene::Kind::abstract, scene::Task::T1, 12, render::Method::standard, 1.3f, 0.5f},
      {scene::Kind::abstract, scene::Task::T1, 12, render::Method::dt_seed, 1.3f, 0.5f},
      {scene::Kind::abstract, scene::Task::T2, 13, render::Method::dt_seed, 2.0f, 0.7f},
      {scene::Kind::walkthrough, scene::Task::T3, 14, render::Method::standard, 0.0f, 0.0f},
      {scene::Kind::walkthrough, scene::Task::T3, 14, render::Method::dt_seed, 2.4f, 0.0f},
      // The lens (an eraser cone through the view's centre): seen through like any method.
      {scene::Kind::abstract, scene::Task::T1, 11, render::Method::lens, 0.0f, 0.0f},
      {scene::Kind::walkthrough, scene::Task::T3, 14, render::Method::lens, 2.4f, 0.0f},
      // Screen-door (8 x 8 tabular masks): the weight frames box-filtered like its colour frames.
      {scene::Kind::abstract, scene::Task::T1, 11, render::Method::screen_door, 0.0f, 0.0f},
      {scene::Kind::walkthrough, scene::Task::T3, 14, render::Method::screen_door, 2.4f, 0.0f},
      // vdt (distractors transparent, the nearest one blended): likewise.
      {scene::Kind::abstract, scene::Task::T1, 11, render::Method::vdt, 0.0f, 0.0f},
      {scene::Kind::walkthrough, scene::Task::T3, 14, render::Method::vdt, 2.4f, 0.0f},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(std::string(scene::kind_name(c.kind)) + " seed " + std::to_string(c.seed) + " " +
                 std::string(render::to_string(c.method)));
    auto sc = scene::generate(c.kind, c.task, c.seed);
    ASSERT_TRUE(sc.ok());
    auto r = render::Renderer::create(sc.value());
    ASSERT_TRUE(r.ok()) << r.error().to_string();
    scene::CameraStart start = sc->camera;
    start.yaw += c.yaw;
    start.pitch += c.pitch;
    const render::Camera cam = render::camera_from_start(start, static_cast<float>(kW) / kH);
    render::FrameSettings fs = settings(c.method);
    fs.lens = render::scene_lens(sc.value(), kW, kH);
    fs.lens.shape = render::LensShape::cone;
    fs.lens.length = 4.0f * fs.lens.radius;
    const auto reference = must(r.value()->visibility(cam, fs, kW, kH));

    std::vector<std::uint32_t> targets;
    std::map<std::uint32_t, render::TargetVisibility> by_index;
    for (const auto& v : reference) {
      targets.push_back(v.id - 1);  // Object::id is index + 1
      by_index[v.id - 1] = v;
    }
    ASSERT_FALSE(targets.empty());
    const View view = must(look(*r.value(), cam, fs, kW, kH, targets, object_bounds(sc.value())));
    ASSERT_EQ(view.seen.size(), targets.size());
    long visible_sum = 0;
    for (const Seen& s : view.seen) {
      const render::TargetVisibility& ref = by_index.at(s.index);
      EXPECT_EQ(s.visible_px, ref.visible_pixels) << "object " << s.index;
      EXPECT_LE(s.clear_px, s.visible_px);
      // CPU rasterisation (pixel centres) against the GPU's occlusion query: edges may differ by a pixel.
      EXPECT_NEAR(static_cast<double>(s.silhouette_px), static_cast<double>(ref.silhouette_pixels),
                  3.0 + 0.15 * static_cast<double>(ref.silhouette_pixels))
          << "object " << s.index;
      visible_sum += s.visible_px;
    }
    EXPECT_GT(visible_sum, 0) << "the view shows some target";
    for (double ms : view.frame_ms) EXPECT_GE(ms, 0.0);
  }
}

// The reason look() packs: a view of ~20-40 spread-out targets needs far fewer frames than the
// three-per-frame of Renderer::visibility.
TEST_F(Perception, PackingSavesFrames) {
  for (std::uint64_t seed : {21u, 22u, 23u}) {
    auto sc = scene::generate(scene::Kind::abstract, scene::Task::T1, seed);
    ASSERT_TRUE(sc.ok());
    auto r = render::Renderer::create(sc.value());
    ASSERT_TRUE(r.ok());
    std::vector<std::uint32_t> targets;
    for (std::uint32_t i = 0; i < sc->objects.size(); ++i)
      if (sc->objects[i].target) targets.push_back(i);
    const render::Camera cam = render::camera_from_start(sc->camera, static_cast<float>(kW) / kH);
    const View v =
        must(look(*r.value(), cam, settings(render::Method::standard), kW, kH, targets, object_bounds(sc.value())));
    const std::size_t unpacked = (targets.size() + 2) / 3;
    EXPECT_LT(v.frame_ms.size() * 2, unpacked) << targets.size() << " targets in " << v.frame_ms.size() << " frames";
  }
}

// Objects behind the eye or outside the view cost nothing and are seen as nothing; a view with
// nothing of interest in it is still rendered once (the participant looks at it).
TEST_F(Perception, ObjectsOutOfViewAreNotSeen) {
  auto sc = scene::generate(scene::Kind::walkthrough, scene::Task::T3, 5);
  ASSERT_TRUE(sc.ok());
  auto r = render::Renderer::create(sc.value());
  ASSERT_TRUE(r.ok());
  const auto bounds = object_bounds(sc.value());
  std::uint32_t target = 0;
  for (std::uint32_t i = 0; i < sc->objects.size(); ++i)
    if (sc->objects[i].kind == sc->answer.target_kind) target = i;
  // Look straight away from the object.
  const glm::vec3 eye = sc->camera.position;
  const glm::vec3 at(sc->objects[target].transform[3]);
  const float yaw_to = std::atan2(-(at.x - eye.x), -(at.z - eye.z));
  scene::CameraStart away = sc->camera;
  away.yaw = yaw_to + 3.14159265f;
  const std::uint32_t one[] = {target};
  const View v = must(look(*r.value(), render::camera_from_start(away, static_cast<float>(kW) / kH),
                           settings(render::Method::dt_seed), kW, kH, one, bounds));
  ASSERT_EQ(v.seen.size(), 1u);
  EXPECT_EQ(v.seen[0].rect_px, 0);
  EXPECT_EQ(v.seen[0].visible_px, 0);
  EXPECT_EQ(v.frame_ms.size(), 1u);
}

// An aid that follows the cursor is swept over the view: cells one aid diameter wide, row by row,
// alternating direction. Pure geometry: the expected spots are worked out by hand below.
TEST(AidSpots, ASearchlightTilesTheViewRowByRowAlternating) {
  render::FrameSettings f = settings(render::Method::dt_seed);
  const render::Camera cam = render::orbit_camera(glm::vec3(0.0f), 100.0f, 0.0f, 0.3f, 0.785398f, 4.0f / 3.0f, 1.0f, 500.0f);
  EXPECT_TRUE(aid_spots(f, cam, false, kW, kH).empty()) << "passive: nothing follows the cursor";
  f.dt.mode = render::DtMode::active;
  f.dt.searchlight_radius = 24.0f;  // 0.2 of 120 rows, the protocol's default share
  // 160 / 48 -> 4 columns of 40 pixels, 120 / 48 -> 3 rows of 40: centres 20, 60, 100, 140 and 20, 60, 100.
  const std::vector<glm::vec2> expected = {{20, 20},  {60, 20},  {100, 20}, {140, 20}, {140, 60}, {100, 60},
                                           {60, 60},  {20, 60},  {20, 100}, {60, 100}, {100, 100}, {140, 100}};
  const std::vector<glm::vec2> got = aid_spots(f, cam, false, kW, kH);
  ASSERT_EQ(got.size(), expected.size());
  for (std::size_t i = 0; i < got.size(); ++i) {
    EXPECT_FLOAT_EQ(got[i].x, expected[i].x) << i;
    EXPECT_FLOAT_EQ(got[i].y, expected[i].y) << i;
  }
  // Every pixel of the view is within sqrt(2) radii of a spot (the cells are at most 2r wide).
  for (int y = 0; y < kH; y += 7)
    for (int x = 0; x < kW; x += 7) {
      float d = 1e9f;
      for (const glm::vec2& c : got) d = std::min(d, glm::length(glm::vec2(x + 0.5f, y + 0.5f) - c));
      EXPECT_LE(d, 24.0f * std::sqrt(2.0f) + 1e-3f) << x << "," << y;
    }
  // Radius 60: 160 / 120 -> 2 columns, 120 / 120 -> 1 row.
  f.dt.searchlight_radius = 60.0f;
  const auto two = aid_spots(f, cam, false, kW, kH);
  ASSERT_EQ(two.size(), 2u);
  EXPECT_FLOAT_EQ(two[0].x, 40.0f);
  EXPECT_FLOAT_EQ(two[1].x, 120.0f);
  EXPECT_FLOAT_EQ(two[1].y, 60.0f);
  // Larger than the view: one spot at the centre.
  f.dt.searchlight_radius = 1000.0f;
  const auto one = aid_spots(f, cam, false, kW, kH);
  ASSERT_EQ(one.size(), 1u);
  EXPECT_FLOAT_EQ(one[0].x, 80.0f);
  EXPECT_FLOAT_EQ(one[0].y, 60.0f);
  // WALKTHROUGH: the mouse turns the head; the aid stays at the centre, nothing is swept.
  EXPECT_TRUE(aid_spots(f, cam, true, kW, kH).empty());
}

TEST(AidSpots, AnActiveLensIsSweptAtItsProjectedSize) {
  render::FrameSettings f;
  f.method = render::Method::lens;
  f.lens.radius = 20.0f;
  f.lens.distance = 237.6f;
  const render::Camera cam =
      render::orbit_camera(glm::vec3(0.0f), 237.6f, 0.0f, 0.3f, 0.785398f, 4.0f / 3.0f, 1.0f, 1000.0f);
  EXPECT_EQ(aid_radius_px(f, cam, kH), 0.0f) << "a fixed lens does not follow the cursor";
  f.lens.follows_cursor = true;
  // 20 / 237.6 / tan(22.5 deg) x 60 rows = 0.0841751 x 2.4142136 x 60 = 12.19299 pixels.
  EXPECT_NEAR(aid_radius_px(f, cam, kH), 12.19299f, 1e-3f);
  // Cells of 24.386 pixels would make 7 x 5 = 35 spots; at most 12: cells of sqrt(160 x 120 / 12) = 40
  // pixels, 4 x 3 spots (gaps between the lens's circles).
  EXPECT_EQ(aid_spots(f, cam, false, kW, kH).size(), 12u);
  // The eye inside the lens: the lens covers the view, one spot.
  f.lens.radius = 300.0f;
  EXPECT_EQ(aid_spots(f, cam, false, kW, kH).size(), 1u);
}

}  // namespace
}  // namespace dtlab::sim

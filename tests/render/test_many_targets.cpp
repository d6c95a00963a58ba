// Any number of targets. The target query tells "a target is hidden by
// another object" from "by its own back faces" with a stencil code per
// target; codes used to be k mod 63 + 1, so the 1st and 64th targets shared
// one and a target hidden only by the other went unseen: the effect did not
// run and the target stayed hidden (regression test below, 300 targets).
// Codes now come from colouring the targets' screen rectangles (1..255), and
// when more than 255 targets overlap one another the effect runs without a
// query (the article's behaviour).
#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

#include "tests/render/scenes.h"
#include "tests/common/must.h"

using dtlab::test::must;

namespace dtlab::render {
namespace {

using testing::add_object;
using testing::box_mesh;

constexpr int kW = 256, kH = 192;

bool ran(const FrameReport& r, const std::string& pass) {
  const auto v = r.passes_run();
  return std::find(v.begin(), v.end(), pass) != v.end();
}

// 300 small target boxes on a 20 x 15 grid at z = -20, none in front of another, except that
// the 64th (slot 63) is moved in front of the 1st (slot 0), which it hides completely.
scene::Scene grid_scene() {
  scene::Scene s;
  for (int k = 0; k < 300; ++k) {
    const float x = -11.4f + 1.2f * static_cast<float>(k % 20), y = -8.4f + 1.2f * static_cast<float>(k / 20);
    if (k == 63) {
      const float cx = -11.4f * 0.75f, cy = -8.4f * 0.75f;  // on the line from the eye to the 1st, at z = -15
      add_object(s, box_mesh({cx - 0.45f, cy - 0.45f, -15.0f}, {cx + 0.45f, cy + 0.45f, -14.5f}), {1, 0, 0}, true);
    } else {
      add_object(s, box_mesh({x - 0.3f, y - 0.3f, -20.3f}, {x + 0.3f, y + 0.3f, -19.7f}), {1, 0, 0}, true);
    }
  }
  return s;
}

TEST(ManyTargets, ATargetHiddenByTheTargetSixtyThreeLaterIsUncovered) {
  testing::headless_context();
  const scene::Scene s = grid_scene();
  auto r = Renderer::create(s);
  ASSERT_TRUE(r.ok());
  const Camera cam = testing::front_camera(kW, kH);
  for (Method m : {Method::standard, Method::dt_seed, Method::dt_fast}) {
    SCOPED_TRACE(std::string(to_string(m)));
    FrameSettings settings;
    settings.method = m;
    settings.dt.gradient_px = 3.0f;
    settings.timed = true;
    const FrameReport rep = must((*r)->render_offscreen(cam, settings, kW, kH));
    EXPECT_TRUE(rep.gl_errors.empty()) << rep.gl_errors.front();
    if (m != Method::standard) {
      EXPECT_TRUE(ran(rep, m == Method::dt_seed ? "dt-clear" : "dt-composite"));
    }
    const auto vis = must((*r)->visibility(cam, settings, kW, kH));
    ASSERT_EQ(vis.size(), 300u);
    EXPECT_GT(vis[0].silhouette_pixels, 0);
    if (m == Method::standard) {
      EXPECT_EQ(vis[0].visible_pixels, 0) << "the scene must hide target 1 for the test to mean anything";
    } else {
      EXPECT_GT(vis[0].visible_pixels, vis[0].silhouette_pixels / 2) << "target 1 behind target 64";
    }
  }
}

// 300 targets one behind another, all on the same pixels: 255 codes cannot tell them apart, so
// there is no query and the effect runs; with the R1 guard (without it, each target's weight is
// aT times the one behind it) the second nearest shows through the nearest with weight
// aT (1 - aT): floored to aT, then the nearest, floored to aT too, in front of it.
TEST(ManyTargets, MoreThan255OverlappingTargetsRunTheEffectWithoutAQuery) {
  testing::headless_context();
  scene::Scene s;
  std::vector<glm::vec3> flat;
  for (int k = 0; k < 300; ++k) {  // farthest first; the nearest is the last
    const float z = -40.0f + 0.1f * static_cast<float>(k);
    add_object(s, box_mesh({-2.0f, -2.0f, z - 0.05f}, {2.0f, 2.0f, z}), {1, 0, 0}, true);
    flat.push_back(k == 298 ? glm::vec3(1, 0, 0) : glm::vec3(0.0f));  // the second nearest, red
  }
  auto r = Renderer::create(s);
  ASSERT_TRUE(r.ok());
  const Camera cam = testing::front_camera(kW, kH);
  for (Method m : {Method::dt_seed, Method::dt_fast}) {
    SCOPED_TRACE(std::string(to_string(m)));
    FrameSettings settings;
    settings.method = m;
    settings.dt.gradient_px = 2.0f;
    settings.dt.r1_guard = true;
    settings.flat_colors = flat;
    settings.timed = true;
    for (int frame = 0; frame < 2; ++frame) {
      const FrameReport rep = must((*r)->render_offscreen(cam, settings, kW, kH));
      EXPECT_TRUE(rep.gl_errors.empty()) << rep.gl_errors.front();
      EXPECT_FALSE(ran(rep, "target-query"));
      EXPECT_TRUE(ran(rep, m == Method::dt_seed ? "dt-clear" : "dt-composite"));
      // Weight mode: the red channel is the second target's share.
      const int red = testing::rgb_at(must((*r)->read_color()), kW / 2, kH / 2).r;
      const float aT = settings.dt.alpha_target;
      EXPECT_NEAR(red, aT * (1.0f - aT) * 255.0f, 2.0f);
    }
  }
}

}  // namespace
}  // namespace dtlab::render

// Pixel tests on hand-built scenes whose answers follow from the blending
// equations of docs/render.md (never from earlier output). Flat colours
// (weight mode: unlit, exact) make every expected value a closed formula:
//   one wall w in front of target t:  c = w aT + t (1 - aT)
//   two walls w1 (far), w2 (near):    c = w2 aT + (w1 aT + t (1 - aT)) (1 - aT)
// Each case runs under dt-seed, dt-fast and reference; tolerance 2/255.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "tests/render/scenes.h"

namespace dtlab::render {
namespace {

using testing::add_object;
using testing::front_camera;
using testing::headless_context;
using testing::project;
using testing::quad_mesh;
using testing::rgb_at;

constexpr int kW = 256, kH = 192;

const glm::vec3 kBack(0.0f, 1.0f, 0.0f);     // green back plane
const glm::vec3 kTarget(1.0f, 0.0f, 0.0f);   // red target
const glm::vec3 kWall(0.0f, 0.0f, 1.0f);     // blue wall
const glm::vec3 kWall2(1.0f, 1.0f, 1.0f);    // white second wall

struct Built {
  scene::Scene scene;
  std::vector<glm::vec3> flat;  // per object
};

// Back plane at z = -20, a target box around (0, 0, -12), one wall at z = -8 (and one at -5).
Built wall_scene(bool two_walls, bool impenetrable_wall = false) {
  Built b;
  add_object(b.scene, quad_mesh(-40, -40, 40, 40, -20), kBack);
  b.flat.push_back(kBack);
  add_object(b.scene, testing::box_mesh({-1.5f, -1.5f, -13.0f}, {1.5f, 1.5f, -11.0f}), kTarget, true);
  b.flat.push_back(kTarget);
  add_object(b.scene, quad_mesh(-5, -4, 5, 4, -8), kWall, false, impenetrable_wall);
  b.flat.push_back(kWall);
  if (two_walls) {
    add_object(b.scene, quad_mesh(-3, -2.5f, 3, 2.5f, -5), kWall2);
    b.flat.push_back(kWall2);
  }
  return b;
}

struct Case {
  Method method;
  int mask_resolution;
};
std::string name_of(const ::testing::TestParamInfo<Case>& info) {
  std::string n(to_string(info.param.method));
  for (auto& c : n)
    if (c == '-') c = '_';
  return n + "_mask" + std::to_string(info.param.mask_resolution);
}

class BlendTest : public ::testing::TestWithParam<Case> {
 protected:
  void SetUp() override { headless_context(); }
  Image render(const Built& b, DtSettings dt, FrameReport* report = nullptr) {
    auto r = Renderer::create(b.scene);
    EXPECT_TRUE(r.ok()) << (r.ok() ? "" : r.error().to_string());
    FrameSettings s;
    s.method = GetParam().method;
    s.dt = dt;
    s.dt.mask_resolution = GetParam().mask_resolution;
    s.flat_colors = b.flat;
    const FrameReport rep = (*r)->render_offscreen(front_camera(kW, kH), s, kW, kH);
    EXPECT_TRUE(rep.gl_errors.empty()) << rep.gl_errors.front();
    if (report) *report = rep;
    Image img = (*r)->read_color();
    testing::maybe_dump(img);
    return img;
  }
};

glm::ivec3 expect255(glm::vec3 c) { return glm::ivec3(glm::round(c * 255.0f)); }

void expect_near(glm::ivec3 got, glm::vec3 want, const std::string& what) {
  const glm::ivec3 w = expect255(want);
  for (int k = 0; k < 3; ++k)
    EXPECT_LE(std::abs(got[k] - w[k]), 2) << what << ": channel " << k << " is " << got[k] << ", expected " << w[k];
}

TEST_P(BlendTest, TargetBehindOneWallShowsBlendOfWallAndTarget) {
  DtSettings dt;
  const Image img = render(wall_scene(false), dt);
  const glm::vec2 c = project(front_camera(kW, kH), {0, 0, -11}, kW, kH);
  const float aT = dt.alpha_target;
  expect_near(rgb_at(img, static_cast<int>(c.x), static_cast<int>(c.y)), kWall * aT + kTarget * (1.0f - aT),
              "target centre");
  EXPECT_NEAR(testing::alpha_at(img, static_cast<int>(c.x), static_cast<int>(c.y)), aT * 255.0f, 2.0f);
}

TEST_P(BlendTest, TwoWallsCompoundAsTheArticleSays) {
  DtSettings dt;
  const Image img = render(wall_scene(true), dt);
  const glm::vec2 c = project(front_camera(kW, kH), {0, 0, -11}, kW, kH);
  const float aT = dt.alpha_target;
  const glm::vec3 want = kWall2 * aT + (kWall * aT + kTarget * (1.0f - aT)) * (1.0f - aT);
  expect_near(rgb_at(img, static_cast<int>(c.x), static_cast<int>(c.y)), want, "target centre");
}

INSTANTIATE_TEST_SUITE_P(Methods, BlendTest,
                         ::testing::Values(Case{Method::dt_seed, 128}, Case{Method::dt_seed, 0}, Case{Method::dt_fast, 128},
                                           Case{Method::dt_fast, 0}, Case{Method::reference, 0}),
                         name_of);

}  // namespace
}  // namespace dtlab::render

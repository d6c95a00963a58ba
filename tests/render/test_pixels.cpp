// Pixel tests on hand-built scenes whose answers follow from the blending
// equations of docs/render.md (never from earlier output). Flat colours
// (weight mode: unlit, exact) make every expected value a closed formula:
//   one wall w in front of target t:  c = w aT + t (1 - aT)
//   two walls w1 (far), w2 (near):    c = w2 aT + (w1 aT + t (1 - aT)) (1 - aT)
//   a target standing in a farther target's gradient (R1 guard on):  weight >= aT
//   a target drawn after an object in front of it (sort error, R1 guard on):
//                                     c = o aT + t (1 - aT); guard off (the article): c = o
// Each case runs under dt-seed (128 and full-resolution masks), dt-fast (both)
// and reference; tolerance 2/255 unless a mask edge is involved.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <string>
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
void PrintTo(const Case& c, std::ostream* os) {  // readable ctest names
  *os << to_string(c.method) << " mask " << c.mask_resolution;
}
std::string name_of(const ::testing::TestParamInfo<Case>& info) {
  std::string n(to_string(info.param.method));
  for (auto& c : n)
    if (c == '-') c = '_';
  return n + "_mask" + std::to_string(info.param.mask_resolution);
}

class BlendTest : public ::testing::TestWithParam<Case> {
 protected:
  void SetUp() override { headless_context(); }
  // Renders `b` with the test's method (or `method` if given); flat colours, front camera.
  Image render(const Built& b, DtSettings dt, FrameReport* report = nullptr, std::optional<Method> method = {},
               int frames = 1) {
    auto r = Renderer::create(b.scene);
    EXPECT_TRUE(r.ok()) << (r.ok() ? "" : r.error().to_string());
    FrameSettings s;
    s.method = method.value_or(GetParam().method);
    s.dt = dt;
    s.dt.mask_resolution = GetParam().mask_resolution;
    s.flat_colors = b.flat;
    s.timed = true;  // query answers known at once (dt-fast picks its next frame plan from them)
    FrameReport rep;
    for (int f = 0; f < frames; ++f) {
      rep = must((*r)->render_offscreen(front_camera(kW, kH), s, kW, kH));
      EXPECT_TRUE(rep.gl_errors.empty()) << rep.gl_errors.front();
    }
    if (report) *report = rep;
    Image img = must((*r)->read_color());
    testing::maybe_dump(img, method ? "-" + std::string(to_string(*method)) : "");
    return img;
  }
  glm::vec2 target_centre() const { return project(front_camera(kW, kH), {0, 0, -11}, kW, kH); }
};

std::vector<std::string> effect_passes(const FrameReport& r) {
  std::vector<std::string> out;
  for (const auto& p : r.passes_run())
    if (p != "opaque" && p != "target-query" && p != "present") out.push_back(p);
  return out;
}

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

TEST_P(BlendTest, WallFartherThanTheGradientFromAnyTargetIsUnchanged) {
  DtSettings dt;
  const Image img = render(wall_scene(false), dt);
  // x = 30 is on the wall, about 75 pixels left of the target (gradient 24 pixels).
  EXPECT_EQ(rgb_at(img, 30, kH / 2), glm::ivec3(0, 0, 255));
  EXPECT_EQ(testing::alpha_at(img, 30, kH / 2), 255);
}

TEST_P(BlendTest, GradientRisesMonotonicallyFromA0ToOne) {
  DtSettings dt;
  const Image img = render(wall_scene(false), dt);
  // Right of the target's silhouette, behind the wall is the green back plane:
  // c = blue a(d) + green (1 - a(d)), so the blue channel is 255 a(d).
  const glm::vec2 edge = project(front_camera(kW, kH), {1.5f, 0, -11}, kW, kH);
  const int y = static_cast<int>(edge.y);
  const int x0 = static_cast<int>(std::ceil(edge.x)) + 3, x1 = x0 + static_cast<int>(dt.gradient_px) + 6;
  int prev = -1;
  for (int x = x0; x <= x1; ++x) {
    const glm::ivec3 c = rgb_at(img, x, y);
    EXPECT_NEAR(c.b + c.g, 255, 2) << "x " << x << ": a blend of blue and green only";
    EXPECT_GE(c.b, prev - 1) << "x " << x << ": the gradient must not fall";
    prev = std::max(prev, c.b);
  }
  EXPECT_LT(rgb_at(img, x0, y).b, 255 * 0.5) << "starts low (a0 = " << dt.alpha_start << ")";
  EXPECT_GE(rgb_at(img, x1, y).b, 253) << "reaches 1 within n pixels";
}

TEST_P(BlendTest, ImpenetrableWallNeverTurnsTransparent) {
  DtSettings dt;
  const Built b = wall_scene(false, true);
  const Image dt_img = render(b, dt);
  const Image std_img = render(b, dt, nullptr, Method::standard);
  const glm::vec2 c = target_centre();
  EXPECT_EQ(rgb_at(dt_img, static_cast<int>(c.x), static_cast<int>(c.y)), glm::ivec3(0, 0, 255));
  EXPECT_LE(must(compare(dt_img, std_img)).max_abs, 1) << "nothing may differ from the standard frame";
}

TEST_P(BlendTest, LayerLimitOneLeavesTheSecondWallOpaque) {
  DtSettings dt;
  dt.layer_limit = 1;
  const Image img = render(wall_scene(true), dt);
  const glm::vec2 c = target_centre();
  expect_near(rgb_at(img, static_cast<int>(c.x), static_cast<int>(c.y)), kWall2, "limit 1: the front wall is opaque");
  dt.layer_limit = 2;
  const Image two = render(wall_scene(true), dt);
  const float aT = dt.alpha_target;
  expect_near(rgb_at(two, static_cast<int>(c.x), static_cast<int>(c.y)),
              kWall2 * aT + (kWall * aT + kTarget * (1.0f - aT)) * (1.0f - aT), "limit 2: both walls transparent");
}

TEST_P(BlendTest, ActiveModeActsOnlyInsideTheSearchlight) {
  DtSettings dt;
  dt.mode = DtMode::active;
  const glm::vec2 c = target_centre();
  // Searchlight far from the target: nothing to uncover; the effect runs no pass.
  dt.searchlight_center = {20.0f, 20.0f};
  dt.searchlight_radius = 10.0f;
  FrameReport rep;
  const Image off = render(wall_scene(false), dt, &rep);
  const Image std_img = render(wall_scene(false), dt, nullptr, Method::standard);
  EXPECT_LE(must(compare(off, std_img)).max_abs, 1);
  if (GetParam().method != Method::reference) {
    EXPECT_TRUE(effect_passes(rep).empty()) << effect_passes(rep).front();
  }
  // Searchlight on the target (radius 40): blended inside, untouched outside.
  dt.searchlight_center = {c.x, static_cast<float>(kH) - c.y};
  dt.searchlight_radius = 40.0f;
  const Image on = render(wall_scene(false), dt);
  const float aT = dt.alpha_target;
  expect_near(rgb_at(on, static_cast<int>(c.x), static_cast<int>(c.y)), kWall * aT + kTarget * (1.0f - aT),
              "inside the searchlight");
  EXPECT_EQ(rgb_at(on, static_cast<int>(c.x) + 45, static_cast<int>(c.y)), glm::ivec3(0, 0, 255))
      << "outside the searchlight (45 px from its centre) the wall stays opaque";
}

TEST_P(BlendTest, CircleMaskTurnsTheWholeCircleToAT) {
  DtSettings dt;
  dt.shape = MaskShape::circle;
  const Image img = render(wall_scene(false), dt);
  // The target's silhouette is a 46-pixel square; the circle around it has radius ~32.5 px.
  // 28 px right of the centre: outside the square, inside the circle, the back plane behind.
  const glm::vec2 c = target_centre();
  const float aT = dt.alpha_target;
  expect_near(rgb_at(img, static_cast<int>(c.x) + 28, static_cast<int>(c.y)), kWall * aT + kBack * (1.0f - aT),
              "inside the circle, off the target");
}

TEST_P(BlendTest, NothingOccludedRunsNoEffectPassAndGivesTheStandardFrame) {
  Built b;
  add_object(b.scene, quad_mesh(-40, -40, 40, 40, -20), kBack);
  add_object(b.scene, testing::box_mesh({-1.5f, -1.5f, -7.0f}, {1.5f, 1.5f, -6.0f}), kTarget, true);  // in front
  add_object(b.scene, quad_mesh(-5, -4, 5, 4, -8), kWall);
  b.flat = {kBack, kTarget, kWall};
  DtSettings dt;
  FrameReport rep;
  const Image img = render(b, dt, &rep, std::nullopt, 2);
  const Image std_img = render(b, dt, nullptr, Method::standard);
  EXPECT_LE(must(compare(img, std_img)).max_abs, 1);
  if (GetParam().method != Method::reference) {
    EXPECT_TRUE(effect_passes(rep).empty()) << effect_passes(rep).front();
    EXPECT_EQ(rep.passes_run(), (std::vector<std::string>{"opaque", "target-query", "present"}));
  }
}

TEST_P(BlendTest, NoTargetsRunsNoEffectPass) {
  Built b = wall_scene(false);
  for (auto& o : b.scene.objects) o.target = false;
  FrameReport rep;
  render(b, DtSettings{}, &rep);
  if (GetParam().method != Method::reference) {
    EXPECT_EQ(rep.passes_run(), (std::vector<std::string>{"opaque", "present"}));
  }
}

TEST_P(BlendTest, TargetInAFartherTargetsGradientKeepsAtLeastATWeight) {
  // Target A far behind on the left, target B in front of A's gradient, no walls.
  Built b;
  add_object(b.scene, quad_mesh(-40, -40, 40, 40, -20), glm::vec3(0.0f));
  add_object(b.scene, testing::box_mesh({-4.0f, -1.0f, -16.0f}, {-2.0f, 1.0f, -15.0f}), glm::vec3(0.0f), true);
  add_object(b.scene, testing::box_mesh({-1.6f, -0.5f, -9.0f}, {-0.6f, 0.5f, -8.5f}), kTarget, true);
  b.flat = {glm::vec3(0.0f), glm::vec3(0.0f), kTarget};
  DtSettings dt;
  dt.r1_guard = true;
  const Image img = render(b, dt);
  const glm::vec2 p = project(front_camera(kW, kH), {-1.1f, 0.0f, -8.5f}, kW, kH);
  // Weight mode: B's red channel is its weight. A's gradient (a0 = 0.1) would leave it 0.1 or less.
  EXPECT_GE(rgb_at(img, static_cast<int>(p.x), static_cast<int>(p.y)).r, static_cast<int>(dt.alpha_target * 255.0f) - 2);
}

TEST_P(BlendTest, SortErrorDoesNotHideATarget) {
  // O: a deep box whose front face (z = -7) hides the target but whose centre (z = -23.5)
  // is farther than the target's (z = -12): back to front by centres draws O first.
  Built b;
  add_object(b.scene, testing::box_mesh({-3.0f, -3.0f, -40.0f}, {3.0f, 3.0f, -7.0f}), kWall);
  add_object(b.scene, testing::box_mesh({-1.0f, -1.0f, -13.0f}, {1.0f, 1.0f, -11.0f}), kTarget, true);
  b.flat = {kWall, kTarget};
  DtSettings dt;
  dt.r1_guard = true;
  const Image img = render(b, dt);
  const glm::vec2 c = target_centre();
  const float aT = dt.alpha_target;
  expect_near(rgb_at(img, static_cast<int>(c.x), static_cast<int>(c.y)), kWall * aT + kTarget * (1.0f - aT),
              "the object in front shows the target through with weight aT");
  if (GetParam().method == Method::reference) return;  // exact order: no sort error to guard against
  dt.r1_guard = false;  // the article as printed: the target stays hidden
  const Image article = render(b, dt);
  expect_near(rgb_at(article, static_cast<int>(c.x), static_cast<int>(c.y)), kWall, "without the R1 guard");
}

INSTANTIATE_TEST_SUITE_P(Methods, BlendTest,
                         ::testing::Values(Case{Method::dt_seed, 128}, Case{Method::dt_seed, 0}, Case{Method::dt_fast, 128},
                                           Case{Method::dt_fast, 0}, Case{Method::reference, 0}),
                         name_of);

}  // namespace
}  // namespace dtlab::render

namespace dtlab::render {
namespace {

// dt-seed and dt-fast have two frame plans (standard-first, effect-first) chosen by whether the
// previous frame needed the effect; they must give the same image, also when the guess is wrong
// (effect-first, then no target occluded: standard-fallback must restore the standard frame).
class FramePlans : public ::testing::TestWithParam<Method> {};

TEST_P(FramePlans, BothPlansGiveTheSameImage) {
  testing::headless_context();
  const auto ran = [](const FrameReport& f, const std::string& n) {
    const auto v = f.passes_run();
    return std::find(v.begin(), v.end(), n) != v.end();
  };
  const std::string effect_pass = GetParam() == Method::dt_seed ? "dt-clear" : "dt-composite";
  const auto settings_for = [this](const Built& b) {
    FrameSettings s;
    s.method = GetParam();
    s.flat_colors = b.flat;
    s.timed = true;  // query answers known at once: the next frame's plan follows them
    return s;
  };
  for (bool two : {false, true}) {
    const Built b = wall_scene(two);
    auto r = Renderer::create(b.scene);
    ASSERT_TRUE(r.ok());
    const FrameSettings s = settings_for(b);
    const FrameReport first = must((*r)->render_offscreen(front_camera(kW, kH), s, kW, kH));
    const Image a = must((*r)->read_color());
    const FrameReport second = must((*r)->render_offscreen(front_camera(kW, kH), s, kW, kH));
    const Image c = must((*r)->read_color());
    EXPECT_TRUE(ran(first, "opaque"));
    EXPECT_TRUE(ran(first, effect_pass));
    EXPECT_FALSE(ran(second, "opaque")) << "the second frame must take the effect-first plan";
    EXPECT_TRUE(ran(second, "query-invert"));
    EXPECT_FALSE(ran(second, "standard-fallback"));
    EXPECT_EQ(must(compare(a, c)).max_abs, 0);
  }
  // A wrong guess: the searchlight leaves the target, so after a frame that needed the effect,
  // the next one has nothing to uncover.
  const Built b = wall_scene(false);
  auto r = Renderer::create(b.scene);
  ASSERT_TRUE(r.ok());
  FrameSettings s = settings_for(b);
  s.dt.mode = DtMode::active;
  const glm::vec2 c = project(front_camera(kW, kH), {0, 0, -11}, kW, kH);
  s.dt.searchlight_center = {c.x, static_cast<float>(kH) - c.y};
  s.dt.searchlight_radius = 40.0f;
  const FrameReport on = must((*r)->render_offscreen(front_camera(kW, kH), s, kW, kH));
  EXPECT_TRUE(ran(on, effect_pass));
  s.dt.searchlight_center = {20.0f, 20.0f};
  s.dt.searchlight_radius = 10.0f;
  const FrameReport away = must((*r)->render_offscreen(front_camera(kW, kH), s, kW, kH));
  const Image fell_back = must((*r)->read_color());
  EXPECT_FALSE(ran(away, "opaque"));
  EXPECT_TRUE(ran(away, "standard-fallback"));
  s.method = Method::standard;
  must((*r)->render_offscreen(front_camera(kW, kH), s, kW, kH));
  EXPECT_EQ(must(compare(fell_back, must((*r)->read_color()))).max_abs, 0);
}

INSTANTIATE_TEST_SUITE_P(Methods, FramePlans, ::testing::Values(Method::dt_seed, Method::dt_fast),
                         [](const ::testing::TestParamInfo<Method>& info) {
                           std::string n(to_string(info.param));
                           for (auto& ch : n)
                             if (ch == '-') ch = '_';
                           return n;
                         });

}  // namespace
}  // namespace dtlab::render

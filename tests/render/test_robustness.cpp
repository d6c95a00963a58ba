// Robustness of every method on hostile geometry: degenerate triangles, the
// camera inside an object, geometry crossing the near plane, zero targets,
// every object a target, a target straddling the viewport edge. For each:
// no GL error after any pass (the frame graph checks glGetError after every
// pass), no NaN or infinity in a float colour buffer, every value inside
// what the scene can produce ([0, 1]; alpha 1 where no mask applies), and in
// flat-black weight mode every pixel exactly black (garbage would show).
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "tests/render/scenes.h"
#include "tests/common/must.h"

using dtlab::test::must;

namespace dtlab::render {
namespace {

using testing::add_object;
using testing::box_mesh;
using testing::quad_mesh;
using testing::sphere_mesh;

constexpr int kW = 160, kH = 120;

struct Hostile {
  std::string name;
  scene::Scene scene;
  Camera camera;
};

// A few objects in front of the default camera, `targets` deciding which are targets.
scene::Scene base(bool all_targets, bool no_targets) {
  scene::Scene s;
  add_object(s, quad_mesh(-30, -30, 30, 30, -25), {0.2f, 0.8f, 0.3f}, all_targets);
  add_object(s, sphere_mesh({0, 0, -12}, 2.0f), {1, 0, 0}, !no_targets);
  add_object(s, box_mesh({-4, -3, -9}, {4, 3, -8}), {0.1f, 0.3f, 0.9f}, all_targets);
  add_object(s, sphere_mesh({3, 2, -15}, 1.5f), {1, 0, 0}, !no_targets);
  return s;
}

std::vector<Hostile> cases() {
  std::vector<Hostile> out;
  const Camera front = testing::front_camera(kW, kH);
  {
    Hostile h{"degenerate_triangles", base(false, false), front};
    scene::Mesh m = box_mesh({-1, -1, -7}, {1, 1, -6});
    // Zero-area triangles: repeated indices, collinear points, a point triangle, zero normals.
    const auto n = static_cast<std::uint32_t>(m.vertices.size());
    m.vertices.push_back({{0, 0, -6.5f}, {0, 0, 0}, {1, 1, 1}});
    m.vertices.push_back({{1, 0, -6.5f}, {0, 0, 0}, {1, 1, 1}});
    m.vertices.push_back({{2, 0, -6.5f}, {0, 0, 0}, {1, 1, 1}});
    m.indices.insert(m.indices.end(), {0, 0, 0, n, n + 1, n + 2, 1, 1, 2, n, n, n});
    add_object(h.scene, m, {0.9f, 0.9f, 0.1f}, true);
    out.push_back(std::move(h));
  }
  {
    Hostile h{"camera_inside_an_object", base(false, false), front};
    add_object(h.scene, box_mesh({-1, -1, -1}, {1, 1, 1}), {0.5f, 0.5f, 0.5f});       // around the eye
    add_object(h.scene, sphere_mesh({0, 0, 0}, 0.5f), {1, 0, 0}, true);               // a target around it too
    out.push_back(std::move(h));
  }
  {
    Hostile h{"geometry_crossing_the_near_plane", base(false, false), front};
    add_object(h.scene, quad_mesh(-5, -5, 5, 5, -0.1f), {0.7f, 0.2f, 0.7f});          // at the near plane
    add_object(h.scene, box_mesh({-0.5f, -0.5f, -3}, {0.5f, 0.5f, 2}), {0.3f, 0.3f, 0.3f}, true);  // through the eye plane
    scene::Mesh slab = quad_mesh(-3, -3, 3, 3, 0);
    for (auto& v : slab.vertices) v.position.z = v.position.x;  // a plane tilted through the eye
    add_object(h.scene, slab, {0.1f, 0.9f, 0.9f});
    out.push_back(std::move(h));
  }
  out.push_back({"zero_targets", base(false, true), front});
  out.push_back({"all_targets", base(true, false), front});
  {
    Hostile h{"target_across_the_viewport_edge", base(false, false), front};
    add_object(h.scene, sphere_mesh({7.5f, 0, -10}, 3.0f), {1, 0, 0}, true);
    add_object(h.scene, quad_mesh(4, -4, 12, 4, -6), {0.2f, 0.2f, 0.9f});
    out.push_back(std::move(h));
  }
  {
    Hostile h{"looking_straight_down", base(false, false), front};
    h.camera = walk_camera({0, 20, -12}, 0.0f, -1.5707963f, glm::radians(60.0f), static_cast<float>(kW) / kH, 0.1f, 100.0f);
    out.push_back(std::move(h));
  }
  return out;
}

struct Case {
  Method method;
  MaskShape shape;
  int layer_limit;
  bool active;
};
void PrintTo(const Case& c, std::ostream* os) {  // readable ctest names
  *os << to_string(c.method) << ' ' << to_string(c.shape) << " layers " << c.layer_limit
      << (c.active ? " active" : " passive");
}

class Robustness : public ::testing::TestWithParam<Case> {
 protected:
  void SetUp() override { testing::headless_context(); }
  FrameSettings settings() const {
    FrameSettings s;
    s.method = GetParam().method;
    s.dt.shape = GetParam().shape;
    s.dt.layer_limit = GetParam().layer_limit;
    s.dt.gradient_px = 12.0f;
    if (GetParam().active) {
      s.dt.mode = DtMode::active;
      s.dt.searchlight_center = {kW * 0.5f, kH * 0.5f};
      s.dt.searchlight_radius = 40.0f;
    }
    return s;
  }
};

TEST_P(Robustness, NoGlErrorNoNanNoGarbage) {
  for (const Hostile& h : cases()) {
    SCOPED_TRACE(h.name);
    auto made = Renderer::create(h.scene);
    ASSERT_TRUE(made.ok()) << made.error().to_string();
    Renderer& r = **made;
    // Two frames: dt-fast takes its other frame plan on the second.
    for (int frame = 0; frame < 2; ++frame) {
      FrameSettings s = settings();
      s.float_color = true;
      const FrameReport rep = must(r.render_offscreen(h.camera, s, kW, kH));
      EXPECT_TRUE(rep.gl_errors.empty()) << rep.gl_errors.front();
      const std::vector<float> px = must(r.read_color_float());
      ASSERT_EQ(px.size(), static_cast<std::size_t>(kW * kH * 4));
      int bad = 0;
      for (float v : px)
        if (!std::isfinite(v) || v < -1e-3f || v > 1.0f + 1e-3f) ++bad;
      EXPECT_EQ(bad, 0) << "values outside [0, 1] or not finite";
      if (s.method == Method::standard) {
        for (std::size_t i = 3; i < px.size(); i += 4) ASSERT_NEAR(px[i], 1.0f, 1e-3f) << "standard leaves alpha 1";
      }
    }
    // Weight mode with every object flat black: every pixel of every method is exactly black.
    FrameSettings s = settings();
    s.flat_colors.assign(h.scene.objects.size(), glm::vec3(0.0f));
    const FrameReport rep = must(r.render_offscreen(h.camera, s, kW, kH));
    EXPECT_TRUE(rep.gl_errors.empty()) << rep.gl_errors.front();
    const Image img = must(r.read_color());
    int nonblack = 0;
    for (std::size_t i = 0; i < img.rgba.size(); i += 4)
      nonblack += img.rgba[i] != 0 || img.rgba[i + 1] != 0 || img.rgba[i + 2] != 0;
    EXPECT_EQ(nonblack, 0);
    testing::maybe_dump(img, "-" + h.name);
  }
}

std::string name_of(const ::testing::TestParamInfo<Case>& info) {
  std::string n(to_string(info.param.method));
  for (auto& c : n)
    if (c == '-') c = '_';
  return n + "_" + std::string(to_string(info.param.shape)) + (info.param.layer_limit ? "_limit" : "") +
         (info.param.active ? "_active" : "");
}

INSTANTIATE_TEST_SUITE_P(
    Methods, Robustness,
    ::testing::Values(Case{Method::standard, MaskShape::outline, 0, false},
                      Case{Method::dt_seed, MaskShape::outline, 0, false},
                      Case{Method::dt_seed, MaskShape::ellipse, 2, true},
                      Case{Method::dt_fast, MaskShape::outline, 0, false},
                      Case{Method::dt_fast, MaskShape::circle, 1, false},
                      Case{Method::dt_fast, MaskShape::outline, 0, true},
                      Case{Method::reference, MaskShape::outline, 0, false},
                      Case{Method::reference, MaskShape::circle, 2, true}),
    name_of);

TEST(RobustnessScene, BadMeshIndexIsAnErrorNamingTheMesh) {
  testing::headless_context();
  scene::Scene s = base(false, false);
  s.meshes[1].indices.push_back(100000);
  s.meshes[1].indices.push_back(0);
  s.meshes[1].indices.push_back(1);
  auto r = Renderer::create(s);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.error().to_string().find("meshes[1]"), std::string::npos) << r.error().to_string();
}

TEST(RobustnessScene, ObjectWithMissingMeshIsAnError) {
  testing::headless_context();
  scene::Scene s = base(false, false);
  s.objects[2].mesh = 99;
  auto r = Renderer::create(s);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.error().to_string().find("objects[2]"), std::string::npos) << r.error().to_string();
}

// validate() is check() as a Status (render.h): an invalid_input Error naming the member.
TEST(RobustnessScene, OutOfRangeSettingsAreRejected) {
  struct Case {
    const char* field;
    DtSettings dt;
  };
  std::vector<Case> cases(3);
  cases[0] = {"DtSettings.alpha_target", {}};
  cases[0].dt.alpha_target = 1.0f;
  cases[1] = {"DtSettings.layer_limit", {}};
  cases[1].dt.layer_limit = 101;
  cases[2] = {"DtSettings.gradient_px", {}};
  cases[2].dt.gradient_px = -1.0f;
  for (const Case& c : cases) {
    const Status st = validate(c.dt);
    ASSERT_FALSE(st.ok()) << c.field;
    EXPECT_EQ(st.error().kind, ErrorKind::invalid_input) << c.field;
    EXPECT_EQ(st.error().field, c.field);
  }
  EXPECT_TRUE(validate(DtSettings{}).ok());
}

}  // namespace
}  // namespace dtlab::render

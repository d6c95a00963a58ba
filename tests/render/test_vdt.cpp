// The vdt method (Diepstraten, Weiskopf & Ertl 2002; docs/render.md, "vdt") on
// hand-built scenes. Every expected pixel comes from the paper's blending
// equation C = alpha C_t + a_dst C_dst (GL_SRC_ALPHA, GL_DST_ALPHA) with alpha
// derived here by hand from eq. (2), alpha = 1 - (d_min / d_object,max)^k, and
// the silhouette edges of eq. (1) worked out for each view; never from earlier
// output. Flat colours (exact; the background is black in that mode), 160 x 120.
#include <gtest/gtest.h>

#include <glad/gl.h>

#include <cmath>
#include <optional>
#include <vector>

#include "study/render/detail/vdt_alpha.h"
#include "study/scene/primitives.h"
#include "tests/render/scenes.h"
#include "tests/common/must.h"

using dtlab::test::must;

namespace dtlab::render {
namespace {

using testing::add_object;
using testing::front_camera;
using testing::headless_context;
using testing::rgb_at;

constexpr int kW = 160, kH = 120;

// A square of half-side h around `c` in the plane z = c.z facing +z, split into an inner square
// of half-side g (two triangles) and a frame (eight): only the outer border is a silhouette
// (an open surface's border), so the four inner vertices all lie h - g from the nearest
// silhouette line and alpha is constant over the inner square.
scene::Mesh framed_quad(glm::vec3 c, float h, float g) {
  scene::Mesh m;
  m.name = "framed_quad";
  const glm::vec3 n(0.0f, 0.0f, 1.0f);
  for (float s : {h, g})
    for (glm::vec2 d : {glm::vec2(-1, -1), glm::vec2(1, -1), glm::vec2(1, 1), glm::vec2(-1, 1)})
      m.vertices.push_back({c + glm::vec3(d * s, 0.0f), n, glm::vec3(1.0f)});
  m.indices = {4, 5, 6, 4, 6, 7};  // inner square
  for (std::uint32_t e = 0; e < 4; ++e) {
    const std::uint32_t o0 = e, o1 = (e + 1) % 4, i0 = 4 + e, i1 = 4 + (e + 1) % 4;
    m.indices.insert(m.indices.end(), {o0, o1, i1, o0, i1, i0});
  }
  return m;
}

// A flat octahedron around `c`: vertices (+-a, 0, 0), (0, +-a, 0), (0, 0, +-cz), outward CCW faces.
scene::Mesh diamond(glm::vec3 c, float a, float cz) {
  scene::Mesh m;
  m.name = "diamond";
  for (int sz : {1, -1})
    for (int sy : {1, -1})
      for (int sx : {1, -1}) {
        const glm::vec3 x(sx * a, 0, 0), y(0, sy * a, 0), z(0, 0, sz * cz);
        const glm::vec3 n = glm::normalize(glm::vec3(sx / a, sy / a, sz / cz));
        const auto base = static_cast<std::uint32_t>(m.vertices.size());
        for (const glm::vec3& p : {x, y, z}) m.vertices.push_back({c + p, n, glm::vec3(1.0f)});
        if (sx * sy * sz > 0) m.indices.insert(m.indices.end(), {base, base + 1, base + 2});
        else m.indices.insert(m.indices.end(), {base, base + 2, base + 1});
      }
  return m;
}

FrameSettings flat(const scene::Scene& s, Method m = Method::vdt, float k = 1.0f) {
  FrameSettings f;
  f.method = m;
  f.vdt.falloff = k;
  f.vdt.opaque_alpha = 0.5f;
  f.vdt.background_alpha = 0.5f;
  for (const auto& o : s.objects) f.flat_colors.push_back(o.color);
  return f;
}

Image render(const scene::Scene& s, const FrameSettings& f, const Camera& cam = front_camera(kW, kH),
             FrameReport* report = nullptr) {
  auto r = Renderer::create(s);
  EXPECT_TRUE(r.ok()) << (r.ok() ? "" : r.error().to_string());
  const FrameReport rep = must(r.value()->render_offscreen(cam, f, kW, kH));
  EXPECT_TRUE(rep.gl_errors.empty()) << rep.gl_errors.front();
  if (report != nullptr) *report = rep;
  Image img = must(r.value()->read_color());
  testing::maybe_dump(img, std::string(to_string(f.method)));
  return img;
}

// The pixel a world point projects into (bottom-left origin).
glm::ivec2 pixel_of(const Camera& cam, glm::vec3 p) {
  const glm::vec2 w = testing::project(cam, p, kW, kH);
  return {static_cast<int>(std::floor(w.x)), static_cast<int>(std::floor(w.y))};
}

glm::ivec3 levels(glm::vec3 c) { return glm::ivec3(glm::round(glm::clamp(c, 0.0f, 1.0f) * 255.0f)); }

void expect_near(glm::ivec3 got, glm::vec3 want, const char* what) {
  const glm::ivec3 w = levels(want);
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(got[i], w[i], 2) << what << " channel " << i;
}

// Framed quads with h = 3, g = 1.5 (or any g / h = 1/2): d_min = h - g, d_object,max = h sqrt 2
// (centre to a corner), so with k = 1: alpha = 1 - (1.5 / 4.2426) = 1 - 0.353553 = 0.646447.
const float kInnerAlpha = 1.0f - 1.5f / (3.0f * std::sqrt(2.0f));
const glm::vec3 kNear(0.6f, 0.0f, 0.0f), kFar(0.0f, 0.0f, 0.6f), kOpaque(0.0f, 0.8f, 0.0f);

// N: transparent framed quad at z = -10, x in [-4.5, 1.5] (inner [-3, 0]); F: transparent framed
// quad at z = -14, x in [-1.5, 4.5] (inner [0, 3]); O: an opaque target box, x in [-4, 4],
// y in [-1, 1], z in [-18, -16].
scene::Scene layered_scene() {
  scene::Scene s;
  add_object(s, framed_quad({-1.5f, 0.0f, -10.0f}, 3.0f, 1.5f), kNear);
  add_object(s, framed_quad({1.5f, 0.0f, -14.0f}, 3.0f, 1.5f), kFar);
  add_object(s, testing::box_mesh({-4.0f, -1.0f, -18.0f}, {4.0f, 1.0f, -16.0f}), kOpaque, true);
  return s;
}

class VdtTest : public ::testing::Test {
 protected:
  void SetUp() override { headless_context(); }
};

// Rule: only the nearest transparent layer is blended over the first opaque layer behind it.
// Through F's inner square onto O (N does not reach there): alpha C_F + a_opaque C_O.
TEST_F(VdtTest, NearestTransparentLayerBlendsOverTheFirstOpaqueLayer) {
  const scene::Scene s = layered_scene();
  const Camera cam = front_camera(kW, kH);
  const Image img = render(s, flat(s));
  const glm::ivec2 p = pixel_of(cam, {2.52f, 0.0f, -14.0f});  // x / |z| = 0.18: F inner, O front face
  expect_near(rgb_at(img, p.x, p.y), kInnerAlpha * kFar + 0.5f * kOpaque, "F over O");
}

// Rule: two transparent objects never shine through each other. Where N covers F with nothing
// opaque behind, the pixel is N blended over the (black) background: alpha C_N + a_bg 0.
TEST_F(VdtTest, TransparentFacesNeverShineThroughEachOther) {
  const scene::Scene s = layered_scene();
  const Camera cam = front_camera(kW, kH);
  const Image img = render(s, flat(s));
  const glm::ivec2 p = pixel_of(cam, {-0.5f, 1.0f, -10.0f});  // (-0.05, 0.1): N inner, F behind, not O
  expect_near(rgb_at(img, p.x, p.y), kInnerAlpha * kNear, "N over F");
  // F alone over the background (no N): F's own blend shows, so F is drawn where it is nearest.
  const glm::ivec2 f = pixel_of(cam, {2.52f, 1.2f, -14.0f});  // (0.18, 0.086): F inner, above O (0.0625)
  expect_near(rgb_at(img, f.x, f.y), kInnerAlpha * kFar, "F over background");
}

// Rule: an opaque object behind two transparent ones is hidden (it does not shine through to the
// nearer one): N over F over O shows N over the background, not over O.
TEST_F(VdtTest, OpaqueBehindTwoTransparentObjectsIsHidden) {
  const scene::Scene s = layered_scene();
  const Camera cam = front_camera(kW, kH);
  const Image img = render(s, flat(s));
  const glm::ivec2 p = pixel_of(cam, {-0.5f, 0.0f, -10.0f});  // (-0.05, 0): N inner, F frame, O
  expect_near(rgb_at(img, p.x, p.y), kInnerAlpha * kNear, "N over F over O");
  // Without F the same pixel shows O through N: alpha C_N + a_opaque C_O.
  scene::Scene one = s;
  one.objects.erase(one.objects.begin() + 1);
  const Image img1 = render(one, flat(one));
  expect_near(rgb_at(img1, p.x, p.y), kInnerAlpha * kNear + 0.5f * kOpaque, "N over O");
}

// Rule: faces of the same transparent object never shine through: a transparent box in front of
// O blends only its front face. Seen head-on its front face's rim is the whole silhouette (the side
// faces face away), so every front-face vertex has d_min = 0, alpha = 1: C_box + a_opaque C_O.
TEST_F(VdtTest, BackFacesOfATransparentObjectNeverShineThrough) {
  scene::Scene s;
  const glm::vec3 box(0.3f, 0.0f, 0.0f);
  add_object(s, testing::box_mesh({-1.0f, -0.5f, -12.0f}, {1.0f, 0.5f, -10.0f}), box);
  add_object(s, testing::box_mesh({-4.0f, -1.0f, -18.0f}, {4.0f, 1.0f, -16.0f}), kOpaque, true);
  const Camera cam = front_camera(kW, kH);
  const Image img = render(s, flat(s));
  const glm::ivec2 p = pixel_of(cam, {0.3f, 0.1f, -10.0f});
  expect_near(rgb_at(img, p.x, p.y), box + 0.5f * kOpaque, "box over O");
}

// The alpha of the transparent surface hit by the ray through pixel `px`: eq. (2) at the vertices
// (`vertex_alpha` of mesh vertex k), interpolated at the hit point (perspective-correct = 3D
// barycentric). nullopt where the ray misses every front face.
std::optional<float> alpha_at_pixel(const Camera& cam, const scene::Mesh& m, const std::vector<float>& vertex_alpha,
                                    glm::ivec2 px) {
  const glm::mat4 inv = glm::inverse(cam.view_proj());
  const glm::vec4 f = inv * glm::vec4((px.x + 0.5f) / kW * 2.0f - 1.0f, (px.y + 0.5f) / kH * 2.0f - 1.0f, 1.0f, 1.0f);
  const glm::vec3 o = cam.eye, d = glm::normalize(glm::vec3(f) / f.w - cam.eye);
  float best = INFINITY;
  std::optional<float> out;
  for (std::size_t t = 0; t + 2 < m.indices.size(); t += 3) {
    const std::uint32_t i0 = m.indices[t], i1 = m.indices[t + 1], i2 = m.indices[t + 2];
    const glm::vec3 a = m.vertices[i0].position, e1 = m.vertices[i1].position - a, e2 = m.vertices[i2].position - a;
    if (glm::dot(glm::cross(e1, e2), d) >= 0.0f) continue;  // back face
    const glm::vec3 pv = glm::cross(d, e2);
    const float det = glm::dot(e1, pv);
    const glm::vec3 tv = o - a;
    const float u = glm::dot(tv, pv) / det;
    const glm::vec3 qv = glm::cross(tv, e1);
    const float v = glm::dot(d, qv) / det, dist = glm::dot(e2, qv) / det;
    if (u < 0 || v < 0 || u + v > 1 || dist <= 0 || dist >= best) continue;
    best = dist;
    out = (1 - u - v) * vertex_alpha[i0] + u * vertex_alpha[i1] + v * vertex_alpha[i2];
  }
  return out;
}

// View dependence: a flat octahedron (a = 2, c = 0.5, centre (0, 0, -10); d_object,max = a = 2).
// View A, from +z on its axis: the four upper faces face the eye, the silhouette is the equator
// (eq. 1), the front vertex (0, 0, c) is sqrt(c^2 + a^2 / 2) = 1.5 from each equator edge's
// line: alpha = 1 - (1.5 / 2)^k = 0.25 (k = 1); equator vertices 1. View B, from +x on the x axis:
// the four +x faces face the eye, the silhouette is the edges in the plane x = 0, on which the
// front vertex now lies: alpha = 1; the vertex (a, 0, 0) is sqrt(a^2 + (a c / sqrt(a^2 + c^2))^2)
// = 2.05798 from the nearest of them: 1 - 2.05798 / 2 < 0, clamped to 0.
TEST_F(VdtTest, ViewDependentAlphaFollowsEquationTwo) {
  scene::Scene s;
  const glm::vec3 c(0.0f, 0.0f, -10.0f), grey(0.8f);
  add_object(s, diamond(c, 2.0f, 0.5f), grey);
  const scene::Mesh& m = s.meshes[0];
  auto alphas = [&](float front, float plus_x) {  // per mesh vertex by its position; the others 1
    std::vector<float> a;
    for (const auto& v : m.vertices) {
      const glm::vec3 r = v.position - c;
      a.push_back(r.z > 0.1f ? front : (r.x > 1.0f ? plus_x : 1.0f));
    }
    return a;
  };
  const float aspect = static_cast<float>(kW) / kH;
  const Camera view_a = orbit_camera(c, 10.0f, 0.0f, 0.0f, glm::radians(60.0f), aspect, 0.1f, 100.0f);
  const Camera view_b = orbit_camera(c, 10.0f, glm::radians(90.0f), 0.0f, glm::radians(60.0f), aspect, 0.1f, 100.0f);
  struct Case {
    const Camera& cam;
    std::vector<float> vertex_alpha;
    const char* name;
  };
  // View A: front 0.25, every equator vertex 1 (the back vertex is on back faces only).
  // View B: front 1, (a, 0, 0) 0, every other vertex 1.
  const Case cases[] = {{view_a, alphas(0.25f, 1.0f), "view A"}, {view_b, alphas(1.0f, 0.0f), "view B"}};
  for (const Case& k : cases) {
    SCOPED_TRACE(k.name);
    const Image img = render(s, flat(s), k.cam);
    int checked = 0;
    for (int y = kH / 2 - 20; y <= kH / 2 + 20; y += 2)
      for (int x = kW / 2 - 20; x <= kW / 2 + 20; x += 2) {
        const auto a = alpha_at_pixel(k.cam, m, k.vertex_alpha, {x, y});
        if (!a) continue;
        ++checked;
        expect_near(rgb_at(img, x, y), *a * grey, "diamond");  // + a_bg x black
      }
    EXPECT_GT(checked, 30);  // view B sees the thin diamond edge-on: fewer pixels
  }
  // The pure function agrees at the front vertex (index 2 is (0, 0, +c) of the first face).
  const detail::VdtTopology topo = detail::vdt_topology(m);
  EXPECT_NEAR(detail::vdt_vertex_alpha(topo, glm::mat4(1.0f), view_a.eye, 1.0f)[2], 0.25f, 1e-5f);
  EXPECT_NEAR(detail::vdt_vertex_alpha(topo, glm::mat4(1.0f), view_a.eye, 0.5f)[2], 1.0f - std::sqrt(0.75f), 1e-5f);
  EXPECT_NEAR(detail::vdt_vertex_alpha(topo, glm::mat4(1.0f), view_b.eye, 1.0f)[2], 1.0f, 1e-5f);
  EXPECT_NEAR(detail::vdt_vertex_alpha(topo, glm::mat4(1.0f), view_b.eye, 1.0f)[0], 0.0f, 1e-6f);  // (a, 0, 0)
}

// No transparent object in view (targets and impenetrable surfaces only): standard's frame, bit for
// bit, lit, with standard's passes.
TEST_F(VdtTest, NoTransparentObjectIsStandardBitForBit) {
  scene::Scene s;
  add_object(s, testing::box_mesh({-1.0f, -1.0f, -12.0f}, {1.0f, 1.0f, -10.0f}), {0.9f, 0.2f, 0.2f}, true);
  add_object(s, testing::quad_mesh(-20, -20, 20, 20, -30), {0.2f, 0.6f, 0.3f}, false, true);
  FrameSettings f;
  FrameReport sr, vr;
  const Image standard = render(s, f, front_camera(kW, kH), &sr);
  f.method = Method::vdt;
  const Image vdt = render(s, f, front_camera(kW, kH), &vr);
  EXPECT_EQ(vdt.rgba, standard.rgba);
  EXPECT_EQ(vr.passes_run(), sr.passes_run());
}

// The passes of section 6.2 in the paper's order.
TEST_F(VdtTest, PassesInThePapersOrder) {
  const scene::Scene s = layered_scene();
  FrameReport rep;
  render(s, flat(s), front_camera(kW, kH), &rep);
  EXPECT_EQ(rep.passes_run(), (std::vector<std::string>{"vdt-nearest", "vdt-second", "vdt-opaque", "vdt-blend",
                                                        "vdt-foreground", "present"}));
}

// The caller's GL state survives a vdt frame (the alpha attribute and buffer, culling, blending,
// depth function, program, bindings), and the frame after it is not changed by it.
TEST_F(VdtTest, RestoresTheCallersGlState) {
  const scene::Scene s = layered_scene();
  auto r = Renderer::create(s);
  ASSERT_TRUE(r.ok());
  FrameSettings standard;
  must(r.value()->render_offscreen(front_camera(kW, kH), standard, kW, kH));
  const Image before = must(r.value()->read_color());
  GLuint buffer = 0;
  glGenBuffers(1, &buffer);
  glBindBuffer(GL_ARRAY_BUFFER, buffer);
  glEnable(GL_CULL_FACE);
  glCullFace(GL_FRONT);
  glFrontFace(GL_CW);
  glEnable(GL_BLEND);
  glBlendFuncSeparate(GL_ONE, GL_ONE, GL_ZERO, GL_ONE);
  glDepthFunc(GL_GEQUAL);
  glDepthMask(GL_FALSE);
  glClearColor(0.25f, 0.5f, 0.75f, 1.0f);
  glActiveTexture(GL_TEXTURE2);
  FrameSettings f = flat(s);
  f.flat_colors.clear();
  must(r.value()->render_offscreen(front_camera(kW, kH), f, kW, kH));
  GLint v = 0;
  glGetIntegerv(GL_ARRAY_BUFFER_BINDING, &v);
  EXPECT_EQ(static_cast<GLuint>(v), buffer);
  EXPECT_TRUE(glIsEnabled(GL_CULL_FACE));
  glGetIntegerv(GL_CULL_FACE_MODE, &v);
  EXPECT_EQ(v, GL_FRONT);
  glGetIntegerv(GL_FRONT_FACE, &v);
  EXPECT_EQ(v, GL_CW);
  EXPECT_TRUE(glIsEnabled(GL_BLEND));
  glGetIntegerv(GL_BLEND_DST_RGB, &v);
  EXPECT_EQ(v, GL_ONE);
  glGetIntegerv(GL_DEPTH_FUNC, &v);
  EXPECT_EQ(v, GL_GEQUAL);
  GLboolean mask = GL_TRUE;
  glGetBooleanv(GL_DEPTH_WRITEMASK, &mask);
  EXPECT_EQ(mask, GL_FALSE);
  GLfloat clear[4] = {};
  glGetFloatv(GL_COLOR_CLEAR_VALUE, clear);
  EXPECT_EQ(clear[2], 0.75f);
  glGetIntegerv(GL_ACTIVE_TEXTURE, &v);
  EXPECT_EQ(v, GL_TEXTURE2);
  glActiveTexture(GL_TEXTURE0);
  glDisable(GL_CULL_FACE);
  glDisable(GL_BLEND);
  glDepthMask(GL_TRUE);
  glBindBuffer(GL_ARRAY_BUFFER, 0);
  glDeleteBuffers(1, &buffer);
  must(r.value()->render_offscreen(front_camera(kW, kH), standard, kW, kH));
  EXPECT_EQ(must(r.value()->read_color()).rgba, before.rgba);
}

// The edge lists eq. (1) runs on: split vertices welded, degenerate triangles left out, so a
// closed mesh becomes a closed 2-manifold: every edge has two faces and V - E + F = 2 (Euler).
// A box: 8 corners, 12 edges + 6 face diagonals, 12 triangles. A UV sphere (its pole rows and
// seam split): the same two properties.
TEST(VdtTopology, ClosedMeshesWeldToClosedSurfaces) {
  const detail::VdtTopology box = detail::vdt_topology(testing::box_mesh({-1, -1, -1}, {1, 2, 3}));
  EXPECT_EQ(box.points.size(), 8u);
  EXPECT_EQ(box.edges.size(), 18u);
  EXPECT_EQ(box.planes.size(), 12u);
  const detail::VdtTopology sphere = detail::vdt_topology(testing::sphere_mesh({0, 0, -5}, 2.0f));
  for (const detail::VdtTopology* t : {&box, &sphere}) {
    for (const auto& e : t->edges) EXPECT_EQ(e.faces.size(), 2u);
    EXPECT_EQ(static_cast<long>(t->points.size()) - static_cast<long>(t->edges.size()) +
                  static_cast<long>(t->planes.size()),
              2);
  }
  // ABSTRACT's own primitives (their seams and poles are placed with sin(2 pi), sin(pi) a few 1e-16
  // off zero: welded within tolerance, no edge is a border). Euler characteristic: 2, a torus 0.
  for (scene::Primitive p : {scene::Primitive::sphere, scene::Primitive::cone, scene::Primitive::box,
                             scene::Primitive::torus}) {
    SCOPED_TRACE(std::string(scene::primitive_name(p)));
    const detail::VdtTopology t = detail::vdt_topology(scene::primitive_mesh(p));
    int not_two = 0;
    for (const auto& e : t.edges) not_two += e.faces.size() != 2;
    EXPECT_EQ(not_two, 0);
    EXPECT_EQ(static_cast<long>(t.points.size()) - static_cast<long>(t.edges.size()) +
                  static_cast<long>(t.planes.size()),
              p == scene::Primitive::torus ? 0 : 2);
  }
  // An open quad: its 4 border edges have one face each, the diagonal two.
  const detail::VdtTopology quad = detail::vdt_topology(testing::quad_mesh(0, 0, 1, 1, 0));
  int border = 0;
  for (const auto& e : quad.edges) border += e.faces.size() == 1;
  EXPECT_EQ(border, 4);
  EXPECT_EQ(quad.edges.size(), 5u);
}

TEST(VdtSettingsCheck, NamesTheMember) {
  VdtSettings v;
  EXPECT_FALSE(check(v).has_value());
  v.falloff = 1.5f;
  ASSERT_TRUE(check(v).has_value());
  EXPECT_EQ(check(v)->rfind("falloff ", 0), 0u) << *check(v);
  v = {};
  v.opaque_alpha = -0.1f;
  EXPECT_EQ(check(v)->rfind("opaque_alpha ", 0), 0u);
  v = {};
  v.background_alpha = NAN;
  EXPECT_EQ(check(v)->rfind("background_alpha ", 0), 0u);
  EXPECT_EQ(parse_method("vdt"), Method::vdt);
  EXPECT_EQ(to_string(Method::vdt), "vdt");
  EXPECT_FALSE(uses_transparency(Method::vdt));
}

}  // namespace
}  // namespace dtlab::render

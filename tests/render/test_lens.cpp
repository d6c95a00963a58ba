// The lens method (Ropinski & Hinrichs 2004; docs/render.md, "lens") on hand-built
// scenes, each expectation from the classification rule, never from earlier output:
// a fragment at depth z is behind the lens (z > back), inside (front <= z <= back) or
// in front (z < front); behind and in front are drawn normally, inside in the lens
// style (eraser: non-targets removed; wireframe: lines; tint: mixed with the tint).
// Which pixels the lens covers and where the wall meets it are computed here by ray
// casting against the lens mesh and the wall plane. Flat colours (exact) unless
// the test is about shading; 160 x 120 frames.
#include <gtest/gtest.h>

#include <cmath>
#include <optional>
#include <vector>

#include "study/render/detail/lens_volume.h"
#include "tests/render/scenes.h"
#include "tests/common/must.h"

using dtlab::test::must;

namespace dtlab::render {
namespace {

using testing::add_object;
using testing::front_camera;
using testing::headless_context;
using testing::quad_mesh;
using testing::rgb_at;

constexpr int kW = 160, kH = 120;
const glm::vec3 kBack(0.0f, 1.0f, 0.0f), kTarget(1.0f, 0.0f, 0.0f), kWall(0.0f, 0.0f, 1.0f);
constexpr float kWallZ = -8.0f;

// Back plane at z = -20, a target box around (0, 0, -12), a wall at z = -8 hiding it (optional).
scene::Scene wall_scene(bool wall = true) {
  scene::Scene s;
  add_object(s, quad_mesh(-40, -40, 40, 40, -20), kBack);
  add_object(s, testing::box_mesh({-1.5f, -1.5f, -13.0f}, {1.5f, 1.5f, -11.0f}), kTarget, true);
  if (wall) add_object(s, quad_mesh(-5, -4, 5, 4, kWallZ), kWall);
  return s;
}

FrameSettings settings(Method m, bool flat, const scene::Scene& s) {
  FrameSettings f;
  f.method = m;
  if (flat)
    for (const auto& o : s.objects) f.flat_colors.push_back(o.color);
  return f;
}

LensSettings lens(LensShape shape, LensStyle style, float distance, float radius, float length = 4.0f) {
  LensSettings l;
  l.shape = shape;
  l.style = style;
  l.center = {kW / 2.0f, kH / 2.0f};
  l.distance = distance;
  l.radius = radius;
  l.length = length;
  return l;
}

Image render(const scene::Scene& s, const FrameSettings& f, const Camera& cam = front_camera(kW, kH)) {
  auto r = Renderer::create(s);
  EXPECT_TRUE(r.ok()) << (r.ok() ? "" : r.error().to_string());
  const FrameReport report = must(r.value()->render_offscreen(cam, f, kW, kH));
  EXPECT_TRUE(report.gl_errors.empty()) << report.gl_errors.front();
  Image img = must(r.value()->read_color());
  testing::maybe_dump(img, std::string(to_string(f.method)) + "-" + std::string(to_string(f.lens.shape)) + "-" +
                               std::string(to_string(f.lens.style)));
  return img;
}

// The ray from the eye through the centre of window pixel (x, y) (bottom-left origin).
glm::vec3 ray(const Camera& cam, int x, int y) {
  const glm::mat4 inv = glm::inverse(cam.view_proj());
  const glm::vec4 p = inv * glm::vec4((x + 0.5f) / kW * 2.0f - 1.0f, (y + 0.5f) / kH * 2.0f - 1.0f, 1.0f, 1.0f);
  return glm::normalize(glm::vec3(p) / p.w - cam.eye);
}

// Where ray o + t d enters and leaves the convex mesh (t0 <= t1), if it meets it.
std::optional<std::pair<float, float>> hit(const std::vector<glm::vec3>& tris, glm::vec3 o, glm::vec3 d) {
  float t0 = INFINITY, t1 = -INFINITY;
  for (std::size_t i = 0; i + 2 < tris.size(); i += 3) {  // Moller-Trumbore, both sides
    const glm::vec3 e1 = tris[i + 1] - tris[i], e2 = tris[i + 2] - tris[i];
    const glm::vec3 p = glm::cross(d, e2);
    const float det = glm::dot(e1, p);
    if (std::fabs(det) < 1e-12f) continue;
    const glm::vec3 s = o - tris[i];
    const float u = glm::dot(s, p) / det;
    const glm::vec3 q = glm::cross(s, e1);
    const float v = glm::dot(d, q) / det;
    if (u < 0 || v < 0 || u + v > 1) continue;
    const float t = glm::dot(e2, q) / det;
    t0 = std::min(t0, t);
    t1 = std::max(t1, t);
  }
  if (t0 > t1) return std::nullopt;
  return std::pair{t0, t1};
}

// Per pixel: -1 the lens misses it and its 8 neighbours in the view; +1 the wall's surface along the ray is
// inside the lens by a margin of `eps` (distance along the ray); 0 anything else (near an edge).
std::vector<int> classify_wall(const LensSettings& l, const Camera& cam, float eps) {
  const detail::LensVolume v = detail::make_lens_volume(l, cam, kW, kH);
  std::vector<int> covered(kW * kH, 0), out(kW * kH, 0);
  std::vector<float> wall_t(kW * kH, INFINITY);
  std::vector<std::pair<float, float>> span(kW * kH);
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      const glm::vec3 d = ray(cam, x, y);
      // Covered: the ray is still inside the lens past the near plane (a cone's rays all start
      // inside it, but those leaving through its side before the near plane see nothing of it).
      const auto h = hit(v.triangles, cam.eye, d);
      if (h && h->second * glm::dot(d, cam.forward) > cam.near_plane) {
        covered[y * kW + x] = 1;
        span[y * kW + x] = {std::max(h->first, 0.0f), h->second};
      }
      const float t = (kWallZ - cam.eye.z) / d.z;
      const glm::vec3 p = cam.eye + t * d;
      if (t > 0 && std::fabs(p.x) < 5 && std::fabs(p.y) < 4) wall_t[y * kW + x] = t;
    }
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      bool near = false;
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          const int xx = std::clamp(x + dx, 0, kW - 1), yy = std::clamp(y + dy, 0, kH - 1);
          near = near || covered[yy * kW + xx];
        }
      const int i = y * kW + x;
      if (!near) out[i] = -1;
      else if (covered[i] && wall_t[i] > span[i].first + eps && wall_t[i] < span[i].second - eps) out[i] = 1;
    }
  return out;
}

bool same_pixel(const Image& a, const Image& b, int x, int y) {
  return rgb_at(a, x, y) == rgb_at(b, x, y);
}

class LensTest : public ::testing::Test {
 protected:
  void SetUp() override { headless_context(); }
};

// A lens holding no geometry: every pixel equals standard's, bit for bit, lit, for every shape and style.
TEST_F(LensTest, EmptyLensIsStandardBitForBit) {
  const scene::Scene s = wall_scene();
  const Image standard = render(s, settings(Method::standard, false, s));
  for (LensShape shape : {LensShape::sphere, LensShape::box, LensShape::cylinder, LensShape::cone})
    for (LensStyle style : {LensStyle::eraser, LensStyle::wireframe, LensStyle::tint}) {
      FrameSettings f = settings(Method::lens, false, s);
      f.lens = lens(shape, style, 4.0f, 1.0f, 2.0f);  // z in -3 .. -5: nothing there (wall at -8)
      const Image img = render(s, f);
      EXPECT_EQ(img.rgba, standard.rgba) << to_string(shape) << " " << to_string(style);
    }
}

// The paper's pass order and count: two lens-only depth passes, three scene passes.
TEST_F(LensTest, PassesInThePapersOrder) {
  const scene::Scene s = wall_scene();
  auto r = Renderer::create(s);
  ASSERT_TRUE(r.ok());
  FrameSettings f = settings(Method::lens, false, s);
  f.lens = lens(LensShape::box, LensStyle::eraser, 8.0f, 2.0f);
  const FrameReport report = must(r.value()->render_offscreen(front_camera(kW, kH), f, kW, kH));
  EXPECT_EQ(report.passes_run(),
            (std::vector<std::string>{"lens-back", "lens-front", "lens-behind", "lens-inside", "lens-in-front", "present"}));
}

// A target behind a wall shows through an eraser lens around the wall; standard shows the wall.
TEST_F(LensTest, EraserRevealsTargetBehindWall) {
  const scene::Scene s = wall_scene();
  FrameSettings f = settings(Method::lens, true, s);
  f.lens = lens(LensShape::sphere, LensStyle::eraser, 8.0f, 2.5f);
  const Image standard = render(s, settings(Method::standard, true, s));
  const Image img = render(s, f);
  EXPECT_EQ(rgb_at(standard, kW / 2, kH / 2), glm::ivec3(0, 0, 255));
  EXPECT_EQ(rgb_at(img, kW / 2, kH / 2), glm::ivec3(255, 0, 0));
  auto r = Renderer::create(s);
  ASSERT_TRUE(r.ok());
  const auto seen_std = must(r.value()->visibility(front_camera(kW, kH), settings(Method::standard, false, s), kW, kH));
  const auto seen_lens = must(r.value()->visibility(front_camera(kW, kH), f, kW, kH));
  ASSERT_EQ(seen_lens.size(), 1u);
  EXPECT_EQ(seen_std[0].visible_pixels, 0);
  EXPECT_GT(seen_lens[0].visible_pixels, 50);
}

// Targets are never erased: an eraser lens around the target leaves it exactly as standard draws it.
TEST_F(LensTest, EraserKeepsTargets) {
  const scene::Scene s = wall_scene(false);
  FrameSettings f = settings(Method::lens, true, s);
  f.lens = lens(LensShape::sphere, LensStyle::eraser, 12.0f, 3.0f);
  EXPECT_EQ(render(s, f).rgba, render(s, settings(Method::standard, true, s)).rgba);
}

// Nor are impenetrable surfaces (rule R3: a WALKTHROUGH's floor, ceiling, outer walls): an eraser
// lens around an impenetrable wall leaves the frame as standard draws it.
TEST_F(LensTest, EraserKeepsImpenetrableSurfaces) {
  scene::Scene s = wall_scene();
  s.objects.back().impenetrable = true;  // the wall
  FrameSettings f = settings(Method::lens, true, s);
  f.lens = lens(LensShape::sphere, LensStyle::eraser, 8.0f, 2.5f);
  EXPECT_EQ(render(s, f).rgba, render(s, settings(Method::standard, true, s)).rgba);
}

// Each style, pixel by pixel, for each shape: outside the footprint = standard; where the wall is
// inside the lens: eraser = the scene without the wall, tint = wall (1 - s) (weight mode: the
// tint is black), wireframe = the wall on its edges, the scene without the wall elsewhere.
TEST_F(LensTest, StylesFollowTheClassification) {
  const scene::Scene s = wall_scene(), no_wall = wall_scene(false);
  const Camera cam = front_camera(kW, kH);
  const Image standard = render(s, settings(Method::standard, true, s));
  const Image behind = render(no_wall, settings(Method::standard, true, no_wall));
  for (LensShape shape : {LensShape::sphere, LensShape::box, LensShape::cylinder, LensShape::cone}) {
    const LensSettings base = lens(shape, LensStyle::eraser, 8.0f, 2.0f, 3.0f);
    const std::vector<int> cls = classify_wall(base, cam, 0.05f);
    for (LensStyle style : {LensStyle::eraser, LensStyle::wireframe, LensStyle::tint}) {
      FrameSettings f = settings(Method::lens, true, s);
      f.lens = base;
      f.lens.style = style;
      const Image img = render(s, f);
      int inside = 0, outside = 0, wrong = 0, lines = 0;
      for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x) {
          const int c = cls[y * kW + x];
          if (c < 0) {
            ++outside;
            wrong += !same_pixel(img, standard, x, y);
          } else if (c > 0) {
            ++inside;
            const glm::ivec3 got = rgb_at(img, x, y);
            if (style == LensStyle::eraser) {
              wrong += !same_pixel(img, behind, x, y);
            } else if (style == LensStyle::tint) {
              const int want = static_cast<int>(std::lround(255.0 * 0.5));
              wrong += !(got.r == 0 && got.g == 0 && std::abs(got.b - want) <= 1);
            } else {
              const bool line = got == glm::ivec3(0, 0, 255);
              lines += line;
              wrong += !line && !same_pixel(img, behind, x, y);
            }
          }
        }
      EXPECT_GT(inside, 100) << to_string(shape);
      EXPECT_GT(outside, 1000) << to_string(shape);
      EXPECT_EQ(wrong, 0) << to_string(shape) << " " << to_string(style);
      if (style == LensStyle::wireframe) {
        EXPECT_GT(lines, 5) << to_string(shape);            // the wall's diagonal crosses the lens
        EXPECT_LT(lines, inside / 4) << to_string(shape);  // lines, not the filled wall
      }
    }
  }
}

// The eye inside the lens (a sphere around the camera): every ray starts inside, so the wall
// (inside) is tinted and the back plane (behind the sphere) is not.
TEST_F(LensTest, CameraInsideTheLens) {
  const scene::Scene s = wall_scene();
  FrameSettings f = settings(Method::lens, true, s);
  f.lens = lens(LensShape::sphere, LensStyle::tint, 0.5f, 11.0f);
  ASSERT_TRUE(detail::make_lens_volume(f.lens, front_camera(kW, kH), kW, kH).eye_inside);
  const Image img = render(s, f);
  EXPECT_NEAR(rgb_at(img, kW / 2, kH / 2).b, 128, 1);               // the wall, tinted
  EXPECT_EQ(rgb_at(img, 2, 2), glm::ivec3(0, 255, 0));              // the back plane, behind the lens
  f.lens.style = LensStyle::eraser;
  EXPECT_EQ(rgb_at(render(s, f), kW / 2, kH / 2), glm::ivec3(255, 0, 0));  // the wall erased: the target
}

// A lens crossing the near plane (eye outside it, its front surface nearer than the near plane)
// stays closed: a quad just beyond the near plane on the axis is inside and tinted.
TEST_F(LensTest, LensCrossingTheNearPlane) {
  scene::Scene s = wall_scene();
  add_object(s, quad_mesh(-0.2f, -0.2f, 0.2f, 0.2f, -0.5f), glm::vec3(1.0f, 1.0f, 1.0f));
  FrameSettings f = settings(Method::lens, true, s);
  f.lens = lens(LensShape::sphere, LensStyle::tint, 2.05f, 2.0f);  // nearest point at 0.05 < near 0.1
  ASSERT_FALSE(detail::make_lens_volume(f.lens, front_camera(kW, kH), kW, kH).eye_inside);
  const Image img = render(s, f);
  const glm::ivec3 c = rgb_at(img, kW / 2, kH / 2);
  EXPECT_NEAR(c.r, 128, 1);
  EXPECT_NEAR(c.g, 128, 1);
  EXPECT_NEAR(c.b, 128, 1);
}

TEST(LensSettingsCheck, RejectsBadValues) {
  LensSettings l;
  EXPECT_FALSE(check(l).has_value());
  l.radius = 0.0f;
  EXPECT_EQ(check(l).value_or(""), "radius must be finite and > 0 (got 0)");
  l = LensSettings{};
  l.distance = NAN;
  EXPECT_TRUE(check(l).has_value());
  l = LensSettings{};
  l.tint_strength = 1.5f;
  EXPECT_TRUE(check(l).has_value());
  EXPECT_EQ(parse_method("lens"), Method::lens);
  EXPECT_EQ(parse_lens_shape("cone"), LensShape::cone);
  EXPECT_EQ(parse_lens_style("wireframe"), LensStyle::wireframe);
  EXPECT_FALSE(parse_lens_style("glass").has_value());
}

}  // namespace
}  // namespace dtlab::render

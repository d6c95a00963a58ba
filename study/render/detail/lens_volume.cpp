// The lens volume on the CPU (see lens_volume.h).
#include "study/render/detail/lens_volume.h"

#include <algorithm>
#include <cmath>

namespace dtlab::render::detail {

namespace {

constexpr int kSegments = 32;  // around the axis (cylinder, cone, sphere slices)
constexpr int kStacks = 16;    // sphere

struct Frame {  // the lens's local frame: u, v across the ray, w along it
  glm::vec3 origin, u, v, w;
  glm::vec3 at(float x, float y, float z) const { return origin + x * u + y * v + z * w; }
};

void tri(std::vector<glm::vec3>& out, glm::vec3 a, glm::vec3 b, glm::vec3 c) {
  out.push_back(a);
  out.push_back(b);
  out.push_back(c);
}

void quad(std::vector<glm::vec3>& out, glm::vec3 a, glm::vec3 b, glm::vec3 c, glm::vec3 d) {
  tri(out, a, b, c);
  tri(out, a, c, d);
}

float angle(int k) { return 2.0f * 3.14159265358979f * static_cast<float>(k) / kSegments; }

// A prism over a circle (cylinder) or a frustum/cone: radius r0 at z0, r1 at z1, closed at both ends
// (a zero radius degenerates its cap to nothing).
void lathe(std::vector<glm::vec3>& out, const Frame& f, float r0, float z0, float r1, float z1) {
  for (int k = 0; k < kSegments; ++k) {
    const float a = angle(k), b = angle(k + 1);
    const glm::vec3 p0 = f.at(r0 * std::cos(a), r0 * std::sin(a), z0), p1 = f.at(r0 * std::cos(b), r0 * std::sin(b), z0);
    const glm::vec3 q0 = f.at(r1 * std::cos(a), r1 * std::sin(a), z1), q1 = f.at(r1 * std::cos(b), r1 * std::sin(b), z1);
    if (r0 > 0.0f) {
      tri(out, f.at(0, 0, z0), p1, p0);
      quad(out, p0, p1, q1, q0);
    } else {
      tri(out, p0, q1, q0);  // p0 == p1: the apex
    }
    tri(out, f.at(0, 0, z1), q0, q1);
  }
}

void sphere(std::vector<glm::vec3>& out, const Frame& f, float r) {
  auto point = [&](int i, int k) {
    const float polar = 3.14159265358979f * static_cast<float>(i) / kStacks;
    return f.at(r * std::sin(polar) * std::cos(angle(k)), r * std::sin(polar) * std::sin(angle(k)), r * std::cos(polar));
  };
  for (int i = 0; i < kStacks; ++i)
    for (int k = 0; k < kSegments; ++k) {
      if (i > 0) tri(out, point(i, k), point(i, k + 1), point(i + 1, k + 1));
      if (i + 1 < kStacks) tri(out, point(i, k), point(i + 1, k + 1), point(i + 1, k));
    }
}

void box(std::vector<glm::vec3>& out, const Frame& f, float r, float h) {
  glm::vec3 c[8];
  for (int i = 0; i < 8; ++i) c[i] = f.at(i & 1 ? r : -r, i & 2 ? r : -r, i & 4 ? h : -h);
  quad(out, c[0], c[1], c[3], c[2]);
  quad(out, c[4], c[6], c[7], c[5]);
  quad(out, c[0], c[4], c[5], c[1]);
  quad(out, c[2], c[3], c[7], c[6]);
  quad(out, c[0], c[2], c[6], c[4]);
  quad(out, c[1], c[5], c[7], c[3]);
}

}  // namespace

bool inside_convex(const std::vector<glm::vec3>& t, glm::vec3 p) {
  if (t.size() < 12) return false;
  glm::vec3 centroid(0.0f);
  for (const glm::vec3& v : t) centroid += v;
  centroid /= static_cast<float>(t.size());
  for (std::size_t i = 0; i + 2 < t.size(); i += 3) {
    glm::vec3 n = glm::cross(t[i + 1] - t[i], t[i + 2] - t[i]);
    const float len = glm::length(n);
    if (!(len > 0.0f)) continue;  // degenerate (a sphere's pole, a cone's apex)
    n /= len;
    if (glm::dot(n, centroid - t[i]) > 0.0f) n = -n;  // outward
    if (glm::dot(n, p - t[i]) >= 0.0f) return false;
  }
  return true;
}

PixelRect lens_footprint(const LensVolume& v, const Camera& camera, int width, int height) {
  if (v.eye_inside || v.triangles.empty()) return PixelRect{0, 0, width, height};
  return screen_rect(v.triangles, camera.proj * camera.view, width, height);
}

LensVolume make_lens_volume(const LensSettings& lens, const Camera& camera, int width, int height) {
  LensVolume out;
  // The view ray through the centre pixel: unproject the pixel at the far plane.
  const glm::mat4 inv = glm::inverse(camera.proj * camera.view);
  const glm::vec2 ndc(2.0f * lens.center.x / static_cast<float>(width) - 1.0f,
                      1.0f - 2.0f * lens.center.y / static_cast<float>(height));
  const glm::vec4 far = inv * glm::vec4(ndc, 1.0f, 1.0f);
  glm::vec3 dir = glm::vec3(far) / far.w - camera.eye;
  dir = glm::length(dir) > 0.0f ? glm::normalize(dir) : camera.forward;
  const glm::vec3 up_view(camera.view[0][1], camera.view[1][1], camera.view[2][1]);  // the camera's up in world space
  glm::vec3 u = glm::cross(dir, up_view);
  if (!(glm::length(u) > 1e-6f)) u = glm::cross(dir, glm::vec3(1.0f, 0.0f, 0.0f));
  if (!(glm::length(u) > 1e-6f)) u = glm::cross(dir, glm::vec3(0.0f, 0.0f, 1.0f));
  u = glm::normalize(u);
  const glm::vec3 v = glm::cross(u, dir);
  out.axis = dir;
  out.center = camera.eye + lens.distance * dir;
  const Frame f{out.center, u, v, dir};
  const float h = 0.5f * lens.length;
  switch (lens.shape) {
    case LensShape::sphere: sphere(out.triangles, f, lens.radius); break;
    case LensShape::box: box(out.triangles, f, lens.radius, h); break;
    case LensShape::cylinder: lathe(out.triangles, f, lens.radius, -h, lens.radius, h); break;
    case LensShape::cone: {
      // The paper's flat lens as a volume: the apex a near-plane distance behind the eye (so the
      // eye is strictly inside and every ray through the lens disc starts inside), the slope
      // giving `radius` at the centre, closed by a disc at distance + length / 2.
      const float behind = camera.near_plane;
      const float slope = lens.radius / (lens.distance + behind);
      const float z1 = h, z0 = -(lens.distance + behind);
      lathe(out.triangles, f, 0.0f, z0, slope * (z1 - z0), z1);
      break;
    }
  }
  out.eye_inside = inside_convex(out.triangles, camera.eye);
  return out;
}

}  // namespace dtlab::render::detail

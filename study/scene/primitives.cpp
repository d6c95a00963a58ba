// Tessellation of the primitives in primitives.h. Seams duplicate vertices so
// each vertex has one normal; degenerate pole triangles are left out.
#include "study/scene/primitives.h"

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

namespace dtlab::scene {
namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;

std::uint32_t add_vertex(Mesh& m, glm::vec3 p, glm::vec3 n) {
  m.vertices.push_back(Vertex{p, glm::normalize(n), glm::vec3(1.0f)});
  return static_cast<std::uint32_t>(m.vertices.size() - 1);
}

void add_triangle(Mesh& m, std::uint32_t a, std::uint32_t b, std::uint32_t c) {
  m.indices.insert(m.indices.end(), {a, b, c});
}

void require(bool ok, const char* what) {
  if (!ok) throw std::invalid_argument(what);
}

}  // namespace

Mesh sphere_mesh(int slices, int stacks) {
  require(slices >= 3 && stacks >= 2, "sphere_mesh: needs slices >= 3 and stacks >= 2");
  Mesh m;
  m.name = "sphere";
  const auto row = static_cast<std::uint32_t>(slices + 1);
  for (int i = 0; i <= stacks; ++i) {
    const double theta = std::numbers::pi * i / stacks;
    for (int j = 0; j <= slices; ++j) {
      const double phi = kTwoPi * j / slices;
      const glm::vec3 p(static_cast<float>(std::sin(theta) * std::cos(phi)), static_cast<float>(std::cos(theta)),
                        static_cast<float>(std::sin(theta) * std::sin(phi)));
      add_vertex(m, p, p);
    }
  }
  for (int i = 0; i < stacks; ++i) {
    for (int j = 0; j < slices; ++j) {
      const auto a = static_cast<std::uint32_t>(i) * row + static_cast<std::uint32_t>(j);
      const auto b = a + row, c = b + 1, d = a + 1;
      if (i != 0) add_triangle(m, b, a, d);
      if (i != stacks - 1) add_triangle(m, b, d, c);
    }
  }
  return m;
}

Mesh box_mesh(glm::vec3 h) {
  require(h.x > 0 && h.y > 0 && h.z > 0, "box_mesh: half extents must be positive");
  Mesh m;
  m.name = "box";
  // Per face: normal n and in-plane axes u, v with u x v = n.
  const glm::vec3 axes[6][3] = {
      {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}},  {{-1, 0, 0}, {0, 0, 1}, {0, 1, 0}}, {{0, 1, 0}, {0, 0, 1}, {1, 0, 0}},
      {{0, -1, 0}, {1, 0, 0}, {0, 0, 1}}, {{0, 0, 1}, {1, 0, 0}, {0, 1, 0}},  {{0, 0, -1}, {0, 1, 0}, {1, 0, 0}},
  };
  for (const auto& f : axes) {
    const glm::vec3 n = f[0] * h, u = f[1] * h, v = f[2] * h;
    const auto base = static_cast<std::uint32_t>(m.vertices.size());
    add_vertex(m, n - u - v, f[0]);
    add_vertex(m, n + u - v, f[0]);
    add_vertex(m, n + u + v, f[0]);
    add_vertex(m, n - u + v, f[0]);
    add_triangle(m, base, base + 1, base + 2);
    add_triangle(m, base, base + 2, base + 3);
  }
  return m;
}

Mesh frustum_mesh(int slices, float r_bottom, float r_top, float height, bool cap_bottom, bool cap_top) {
  require(slices >= 3, "frustum_mesh: needs slices >= 3");
  require(r_bottom >= 0 && r_top >= 0 && (r_bottom > 0 || r_top > 0) && height > 0,
          "frustum_mesh: radii must be >= 0 (not both 0) and height > 0");
  Mesh m;
  m.name = r_top == 0.0f ? "cone" : "frustum";
  const float slope = (r_bottom - r_top) / height;  // outward normal is (cos, slope, sin), normalized
  auto ring = [&](double phi, float r, float y) {
    const auto c = static_cast<float>(std::cos(phi)), s = static_cast<float>(std::sin(phi));
    return add_vertex(m, {r * c, y, r * s}, {c, slope, s});
  };
  for (int j = 0; j < slices; ++j) {
    const double p0 = kTwoPi * j / slices, p1 = kTwoPi * (j + 1) / slices, pm = 0.5 * (p0 + p1);
    const auto b0 = ring(p0, r_bottom, 0.0f), b1 = ring(p1, r_bottom, 0.0f);
    if (r_top == 0.0f) {
      add_triangle(m, b0, ring(pm, 0.0f, height), b1);  // one apex vertex per slice, normal at mid-angle
    } else if (r_bottom == 0.0f) {
      add_triangle(m, ring(pm, 0.0f, 0.0f), ring(p0, r_top, height), ring(p1, r_top, height));
    } else {
      const auto t0 = ring(p0, r_top, height), t1 = ring(p1, r_top, height);
      add_triangle(m, b0, t0, t1);
      add_triangle(m, b0, t1, b1);
    }
  }
  auto cap = [&](float r, float y, bool up) {
    const glm::vec3 n(0.0f, up ? 1.0f : -1.0f, 0.0f);
    const auto c = add_vertex(m, {0.0f, y, 0.0f}, n);
    const auto first = static_cast<std::uint32_t>(m.vertices.size());
    for (int j = 0; j < slices; ++j) {
      const double phi = kTwoPi * j / slices;
      add_vertex(m, {r * static_cast<float>(std::cos(phi)), y, r * static_cast<float>(std::sin(phi))}, n);
    }
    for (int j = 0; j < slices; ++j) {
      const auto a = first + static_cast<std::uint32_t>(j);
      const auto b = first + static_cast<std::uint32_t>((j + 1) % slices);
      if (up) add_triangle(m, c, b, a); else add_triangle(m, c, a, b);
    }
  };
  if (cap_bottom && r_bottom > 0) cap(r_bottom, 0.0f, false);
  if (cap_top && r_top > 0) cap(r_top, height, true);
  return m;
}

Mesh torus_mesh(int major_segments, int minor_segments, float major_radius, float minor_radius) {
  require(major_segments >= 3 && minor_segments >= 3, "torus_mesh: needs >= 3 segments each way");
  require(major_radius > minor_radius && minor_radius > 0, "torus_mesh: needs major > minor > 0");
  Mesh m;
  m.name = "torus";
  const auto row = static_cast<std::uint32_t>(minor_segments + 1);
  for (int i = 0; i <= major_segments; ++i) {
    const double u = kTwoPi * i / major_segments;
    const auto cu = static_cast<float>(std::cos(u)), su = static_cast<float>(std::sin(u));
    for (int j = 0; j <= minor_segments; ++j) {
      const double v = kTwoPi * j / minor_segments;
      const auto cv = static_cast<float>(std::cos(v)), sv = static_cast<float>(std::sin(v));
      const float ring = major_radius + minor_radius * cv;
      add_vertex(m, {ring * cu, minor_radius * sv, ring * su}, {cv * cu, sv, cv * su});
    }
  }
  for (int i = 0; i < major_segments; ++i) {
    for (int j = 0; j < minor_segments; ++j) {
      const auto a = static_cast<std::uint32_t>(i) * row + static_cast<std::uint32_t>(j);
      const auto b = a + row;  // next around the major circle
      add_triangle(m, a, a + 1, b + 1);
      add_triangle(m, a, b + 1, b);
    }
  }
  return m;
}

std::string_view primitive_name(Primitive p) {
  switch (p) {
    case Primitive::sphere: return "sphere";
    case Primitive::cone: return "cone";
    case Primitive::box: return "box";
    case Primitive::torus: return "torus";
  }
  return "?";
}

namespace {
constexpr float kCubeHalf = 0.57735026918962576f;  // 1/sqrt(3): the cube's corners lie on the unit sphere
}

Mesh primitive_mesh(Primitive p) {
  Mesh m;
  switch (p) {
    case Primitive::sphere: m = sphere_mesh(12, 6); break;           // 120 triangles
    case Primitive::cone:                                            // 32 triangles
      m = frustum_mesh(16, 0.8f, 0.0f, 1.6f, true, false);
      for (auto& v : m.vertices) v.position.y -= 0.6f;
      break;
    case Primitive::box: m = box_mesh(glm::vec3(kCubeHalf)); break;  // 12 triangles
    case Primitive::torus: m = torus_mesh(10, 6, 0.7f, 0.3f); break; // 120 triangles
  }
  m.name = std::string(primitive_name(p));
  return m;
}

Chord primitive_chord(Primitive p) {
  switch (p) {
    case Primitive::sphere: return {{0, 1, 0}, {0, -1, 0}};
    case Primitive::cone: return {{0, 1, 0}, {0.8f, -0.6f, 0}};
    case Primitive::box: return {glm::vec3(kCubeHalf), glm::vec3(-kCubeHalf)};
    case Primitive::torus: return {{1, 0, 0}, {-1, 0, 0}};
  }
  return {};
}

}  // namespace dtlab::scene

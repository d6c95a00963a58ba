// MeshBuilder: appends transformed primitives; see mesh_builder.h.
#include "study/scene/detail/mesh_builder.h"

#include <cmath>
#include <stdexcept>

#include "study/scene/primitives.h"

namespace dtlab::scene::detail {

void MeshBuilder::add(const Mesh& part, const glm::mat4& transform, glm::vec3 color) {
  const glm::mat3 normal_matrix = glm::transpose(glm::inverse(glm::mat3(transform)));
  const bool mirrored = glm::determinant(glm::mat3(transform)) < 0.0f;
  const auto base = static_cast<std::uint32_t>(mesh_.vertices.size());
  for (const Vertex& v : part.vertices) {
    mesh_.vertices.push_back(Vertex{glm::vec3(transform * glm::vec4(v.position, 1.0f)),
                                    glm::normalize(normal_matrix * v.normal), color});
  }
  for (std::size_t i = 0; i + 2 < part.indices.size(); i += 3) {
    const std::uint32_t a = base + part.indices[i], b = base + part.indices[i + 1], c = base + part.indices[i + 2];
    if (mirrored) mesh_.indices.insert(mesh_.indices.end(), {a, c, b});
    else mesh_.indices.insert(mesh_.indices.end(), {a, b, c});
  }
}

glm::mat4 rotation_from_y(glm::vec3 dir) {
  const glm::vec3 y = glm::normalize(dir);
  const glm::vec3 helper = std::abs(y.x) < 0.9f ? glm::vec3(1, 0, 0) : glm::vec3(0, 0, 1);
  const glm::vec3 z = glm::normalize(glm::cross(helper, y));
  const glm::vec3 x = glm::cross(y, z);
  glm::mat4 r(1.0f);
  r[0] = glm::vec4(x, 0.0f);
  r[1] = glm::vec4(y, 0.0f);
  r[2] = glm::vec4(z, 0.0f);
  return r;
}

namespace {

glm::mat4 translate(glm::vec3 t) {
  glm::mat4 m(1.0f);
  m[3] = glm::vec4(t, 1.0f);
  return m;
}

glm::mat4 scale(glm::vec3 s) {
  glm::mat4 m(1.0f);
  m[0][0] = s.x;
  m[1][1] = s.y;
  m[2][2] = s.z;
  return m;
}

glm::mat4 yaw_matrix(float yaw) {
  glm::mat4 m(1.0f);
  const float c = std::cos(yaw), s = std::sin(yaw);
  m[0][0] = c;
  m[0][2] = -s;
  m[2][0] = s;
  m[2][2] = c;
  return m;
}

// Unit meshes shared by all shorthands (built once, immutable afterwards).
const Mesh& unit_sphere() { static const Mesh m = sphere_mesh(18, 10); return m; }
const Mesh& unit_box() { static const Mesh m = box_mesh(glm::vec3(0.5f)); return m; }

}  // namespace

void MeshBuilder::box(glm::vec3 center, glm::vec3 size, glm::vec3 color, float yaw) {
  add(unit_box(), translate(center) * yaw_matrix(yaw) * scale(size), color);
}

void MeshBuilder::ellipsoid(glm::vec3 center, glm::vec3 radii, glm::vec3 color, const glm::mat4& rotation) {
  add(unit_sphere(), translate(center) * rotation * scale(radii), color);
}

void MeshBuilder::cylinder(glm::vec3 from, glm::vec3 to, float radius, glm::vec3 color, int slices) {
  frustum(from, to, radius, radius, color, slices);
}

void MeshBuilder::frustum(glm::vec3 from, glm::vec3 to, float r_from, float r_to, glm::vec3 color, int slices) {
  const glm::vec3 d = to - from;
  const float len = glm::length(d);
  if (len <= 0.0f) throw std::invalid_argument("MeshBuilder::frustum: from and to coincide");
  add(frustum_mesh(slices, r_from, r_to, len, true, true), translate(from) * rotation_from_y(d / len), color);
}

void MeshBuilder::cone(glm::vec3 base, glm::vec3 apex, float radius, glm::vec3 color, int slices) {
  frustum(base, apex, radius, 0.0f, color, slices);
}

void MeshBuilder::fin(glm::vec3 base, glm::vec3 apex, float radius, glm::vec3 flat_axis, float thickness,
                      glm::vec3 color) {
  const glm::vec3 d = apex - base;
  const float len = glm::length(d);
  if (len <= 0.0f) throw std::invalid_argument("MeshBuilder::fin: base and apex coincide");
  // Frame: y along the cone axis, z along flat_axis (made orthogonal), x = y x z.
  const glm::vec3 y = d / len;
  const glm::vec3 z = glm::normalize(flat_axis - glm::dot(flat_axis, y) * y);
  const glm::vec3 x = glm::cross(y, z);
  glm::mat4 frame(1.0f);
  frame[0] = glm::vec4(x, 0.0f);
  frame[1] = glm::vec4(y, 0.0f);
  frame[2] = glm::vec4(z, 0.0f);
  const float squash = thickness / (2.0f * radius);
  add(frustum_mesh(16, radius, 0.0f, len, true, false), translate(base) * frame * scale({1.0f, 1.0f, squash}), color);
}

void MeshBuilder::torus(glm::vec3 center, glm::vec3 axis, float major, float minor, glm::vec3 color,
                        int major_segments, int minor_segments) {
  add(torus_mesh(major_segments, minor_segments, major, minor), translate(center) * rotation_from_y(axis), color);
}

}  // namespace dtlab::scene::detail

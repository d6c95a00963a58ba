// Checks shared by the scene tests: a mesh is a valid indexed triangle list
// (indices in range, unit normals, counter-clockwise front faces agreeing
// with the vertex normals) and world-space helpers.
#pragma once
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "study/scene/scene.h"

namespace dtlab::scene::testing {

// Valid triangle list whose faces point the same way as their vertex normals.
// `min_agree` is the fraction of faces whose geometric normal must agree with
// the mean vertex normal (1.0 for convex primitives; compound models may have
// a few slivers where smooth normals and flat faces disagree slightly).
inline ::testing::AssertionResult valid_mesh(const Mesh& m, double min_agree = 1.0) {
  if (m.vertices.empty() || m.indices.empty() || m.indices.size() % 3 != 0)
    return ::testing::AssertionFailure() << m.name << ": empty or not a triangle list";
  for (std::uint32_t i : m.indices)
    if (i >= m.vertices.size()) return ::testing::AssertionFailure() << m.name << ": index " << i << " out of range";
  for (const Vertex& v : m.vertices) {
    if (std::abs(glm::length(v.normal) - 1.0f) > 1e-4f)
      return ::testing::AssertionFailure() << m.name << ": normal of length " << glm::length(v.normal);
    for (int k = 0; k < 3; ++k)
      if (!(v.color[k] >= 0.0f && v.color[k] <= 1.0f)) return ::testing::AssertionFailure() << m.name << ": colour out of [0,1]";
  }
  std::size_t agree = 0, faces = 0;
  for (std::size_t t = 0; t < m.indices.size(); t += 3) {
    const Vertex &a = m.vertices[m.indices[t]], &b = m.vertices[m.indices[t + 1]], &c = m.vertices[m.indices[t + 2]];
    const glm::vec3 n = glm::cross(b.position - a.position, c.position - a.position);
    if (glm::length(n) < 1e-9f) return ::testing::AssertionFailure() << m.name << ": degenerate triangle " << t / 3;
    ++faces;
    if (glm::dot(n, a.normal + b.normal + c.normal) > 0.0f) ++agree;
  }
  if (static_cast<double>(agree) < min_agree * static_cast<double>(faces))
    return ::testing::AssertionFailure() << m.name << ": only " << agree << " of " << faces
                                         << " faces are counter-clockwise as seen from their normals";
  return ::testing::AssertionSuccess();
}

inline glm::vec3 world(const Object& o, const Vertex& v) { return glm::vec3(o.transform * glm::vec4(v.position, 1.0f)); }

struct Aabb {
  glm::vec3 lo{1e30f}, hi{-1e30f};
  void add(glm::vec3 p) {
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  }
  bool overlaps(const Aabb& o) const {
    return lo.x < o.hi.x && o.lo.x < hi.x && lo.y < o.hi.y && o.lo.y < hi.y && lo.z < o.hi.z && o.lo.z < hi.z;
  }
};

inline Aabb world_aabb(const Scene& s, const Object& o) {
  Aabb box;
  for (const Vertex& v : s.meshes[o.mesh].vertices) box.add(world(o, v));
  return box;
}

inline std::size_t scene_triangles(const Scene& s) {
  std::size_t n = 0;
  for (const Object& o : s.objects) n += s.meshes[o.mesh].triangle_count();
  return n;
}

}  // namespace dtlab::scene::testing

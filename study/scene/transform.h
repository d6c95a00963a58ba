// m * vec4(p, 1), for the per-vertex loops that project meshes every frame
// (frame_view's target bounds, the simulated participant's silhouettes).
// The same operations in the same order as glm's mat4 * vec4 ((m0 x + m1 y) +
// (m2 z + m3 w), w = 1), so the same floats as glm gives; written out because
// GCC at -O2 keeps glm's operator* out of line, and a call per vertex was 5% of
// a simulation's CPU time.
#pragma once
#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

namespace dtlab::scene {

inline glm::vec4 transform_point(const glm::mat4& m, const glm::vec3& p) {
  glm::vec4 r;
  for (int i = 0; i < 4; ++i) r[i] = (m[0][i] * p.x + m[1][i] * p.y) + (m[2][i] * p.z + m[3][i] * 1.0f);
  return r;
}

}  // namespace dtlab::scene

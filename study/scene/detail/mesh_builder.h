// Building compound meshes (the WALKTHROUGH models) from primitives: each part
// is a primitive mesh, a model transform and one colour. Parts are appended
// in call order, so a model's mesh is a pure function of its build code.
// Normals go through the inverse transpose; mirrored parts flip their winding
// so front faces stay counter-clockwise. Never used for hashed data.
#pragma once
#include <string>

#include <glm/glm.hpp>

#include "study/scene/scene.h"

namespace dtlab::scene::detail {

class MeshBuilder {
 public:
  explicit MeshBuilder(std::string name) { mesh_.name = std::move(name); }

  // Append `part` transformed by `transform`, every vertex coloured `color`.
  void add(const Mesh& part, const glm::mat4& transform, glm::vec3 color);

  // --- shorthands in model space (y up, +x forward, floor at y = 0) --------
  void box(glm::vec3 center, glm::vec3 size, glm::vec3 color, float yaw = 0.0f);  // size = full edge lengths
  void ellipsoid(glm::vec3 center, glm::vec3 radii, glm::vec3 color, const glm::mat4& rotation = glm::mat4(1.0f));
  void sphere(glm::vec3 center, float radius, glm::vec3 color) { ellipsoid(center, glm::vec3(radius), color); }
  void cylinder(glm::vec3 from, glm::vec3 to, float radius, glm::vec3 color, int slices = 16);  // capped
  void frustum(glm::vec3 from, glm::vec3 to, float r_from, float r_to, glm::vec3 color, int slices = 20);  // capped
  void cone(glm::vec3 base, glm::vec3 apex, float radius, glm::vec3 color, int slices = 16);  // base capped
  // Flattened cone: like cone() but squashed to `thickness` across `flat_axis` (fins, ears).
  void fin(glm::vec3 base, glm::vec3 apex, float radius, glm::vec3 flat_axis, float thickness, glm::vec3 color);
  void torus(glm::vec3 center, glm::vec3 axis, float major, float minor, glm::vec3 color, int major_segments = 28,
             int minor_segments = 8);

  Mesh finish() && { return std::move(mesh_); }

 private:
  Mesh mesh_;
};

// A rotation taking +y to `dir` (unit), with a deterministic choice of the
// remaining axes.
glm::mat4 rotation_from_y(glm::vec3 dir);

}  // namespace dtlab::scene::detail

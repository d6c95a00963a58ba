// Internal: a scene's meshes in GPU buffers (one vertex and one index buffer
// for all meshes, one VAO) and per-object draw records with world bounds.
// Guarantees: every object's draw stays inside its mesh's index range (the
// scene is checked at upload; a bad mesh or index is an Error naming the
// object). Never: changes GL state other than the bindings it restores.
#pragma once
#include <cstdint>
#include <memory>
#include <vector>

#include <glm/glm.hpp>

#include "study/common/error.h"
#include "study/render/frame_report.h"
#include "study/scene/scene.h"

namespace dtlab::render::detail {

struct ObjectRecord {
  std::uint32_t id = 0;
  bool target = false;
  bool impenetrable = false;
  std::uint32_t group = 0;
  std::uint32_t order_in_group = 0;
  glm::mat4 model{1.0f};
  glm::mat3 normal_matrix{1.0f};
  glm::vec3 tint{1.0f};
  std::int32_t index_count = 0;
  std::size_t first_index = 0;
  std::int32_t base_vertex = 0;
  std::uint32_t mesh = 0;
  glm::vec3 world_min{0.0f}, world_max{0.0f};  // world-space AABB of the transformed mesh
  glm::vec3 mesh_min{0.0f}, mesh_max{0.0f};    // the mesh's own box (model space): `model` maps it to a
                                               // box around the object tighter than the world AABB
  bool convex = false;    // every vertex lies behind every triangle's plane: seen from outside, at most one
                          // front-facing fragment per pixel (so one culled pass selects the frontmost surface)
  bool mirrored = false;  // det(model) < 0: the winding of front faces flips
  bool drawable() const { return index_count > 0; }
};

class SceneGpu {
 public:
  static Result<std::unique_ptr<SceneGpu>> create(const scene::Scene& scene);  // checks and uploads
  ~SceneGpu();
  SceneGpu(const SceneGpu&) = delete;
  SceneGpu& operator=(const SceneGpu&) = delete;

  unsigned vao() const { return vao_; }
  void draw(const ObjectRecord& o) const;  // glDrawElementsBaseVertex; the VAO must be bound (counted)
  const DrawCounts& counts() const { return counts_; }  // since creation
  const std::vector<ObjectRecord>& objects() const { return objects_; }

 private:
  SceneGpu() = default;
  unsigned vao_ = 0, vbo_ = 0, ibo_ = 0;
  std::vector<ObjectRecord> objects_;
  mutable DrawCounts counts_;
};

}  // namespace dtlab::render::detail

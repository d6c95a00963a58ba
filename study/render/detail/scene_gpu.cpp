// Upload of a scene's meshes (see scene_gpu.h).
#include <glad/gl.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "study/render/detail/scene_gpu.h"

namespace dtlab::render::detail {

namespace {
Error scene_error(const std::string& field, std::string message) {
  Error e;
  e.field = field;
  e.message = std::move(message);
  return e;
}
// True if no vertex lies in front of any triangle's plane (tolerance relative to the mesh
// size) and the front faces are wound counter-clockwise seen from outside. Meshes past
// 20000 triangles are not checked (treated as not convex: always drawn with two passes).
bool is_convex(const scene::Mesh& mesh, float size) {
  if (mesh.indices.empty() || mesh.indices.size() > 60000) return false;
  const float eps = 1e-4f * std::max(size, 1e-6f);
  for (std::size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
    const glm::vec3 a = mesh.vertices[mesh.indices[t]].position;
    const glm::vec3 b = mesh.vertices[mesh.indices[t + 1]].position;
    const glm::vec3 c = mesh.vertices[mesh.indices[t + 2]].position;
    const glm::vec3 n = glm::cross(b - a, c - a);
    const float len = glm::length(n);
    if (len <= 1e-12f) continue;  // degenerate: no plane
    const glm::vec3 u = n / len;
    for (const auto& v : mesh.vertices)
      if (glm::dot(v.position - a, u) > eps) return false;
  }
  return true;
}

bool finite(const glm::mat4& m) {
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r)
      if (!std::isfinite(m[c][r])) return false;
  return true;
}
}  // namespace

Result<std::unique_ptr<SceneGpu>> SceneGpu::create(const scene::Scene& scene) {
  struct Packed {
    float p[3], n[3], c[3];
  };
  std::vector<Packed> vertices;
  std::vector<std::uint32_t> indices;
  std::vector<std::size_t> first_index(scene.meshes.size()), first_vertex(scene.meshes.size());
  std::vector<glm::vec3> mesh_min(scene.meshes.size()), mesh_max(scene.meshes.size());
  std::vector<char> mesh_convex(scene.meshes.size(), 0);
  for (std::size_t m = 0; m < scene.meshes.size(); ++m) {
    const auto& mesh = scene.meshes[m];
    const std::string field = "meshes[" + std::to_string(m) + "] (" + mesh.name + ")";
    if (mesh.indices.size() % 3 != 0) return scene_error(field, "index count is not a multiple of 3");
    for (auto i : mesh.indices)
      if (i >= mesh.vertices.size())
        return scene_error(field, "index " + std::to_string(i) + " is past the " +
                                      std::to_string(mesh.vertices.size()) + " vertices");
    first_index[m] = indices.size();
    first_vertex[m] = vertices.size();
    glm::vec3 lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());
    for (const auto& v : mesh.vertices) {
      if (!std::isfinite(v.position.x) || !std::isfinite(v.position.y) || !std::isfinite(v.position.z))
        return scene_error(field, "a vertex position is not finite");
      vertices.push_back({{v.position.x, v.position.y, v.position.z},
                          {v.normal.x, v.normal.y, v.normal.z},
                          {v.color.r, v.color.g, v.color.b}});
      lo = glm::min(lo, v.position);
      hi = glm::max(hi, v.position);
    }
    if (mesh.vertices.empty()) lo = hi = glm::vec3(0.0f);
    mesh_min[m] = lo;
    mesh_max[m] = hi;
    mesh_convex[m] = is_convex(mesh, glm::length(hi - lo)) ? 1 : 0;
    indices.insert(indices.end(), mesh.indices.begin(), mesh.indices.end());
  }

  std::unique_ptr<SceneGpu> gpu(new SceneGpu());
  for (std::size_t i = 0; i < scene.objects.size(); ++i) {
    const auto& o = scene.objects[i];
    const std::string field = "objects[" + std::to_string(i) + "] (id " + std::to_string(o.id) + ")";
    if (o.mesh >= scene.meshes.size())
      return scene_error(field, "mesh " + std::to_string(o.mesh) + " does not exist (" +
                                    std::to_string(scene.meshes.size()) + " meshes)");
    if (!finite(o.transform)) return scene_error(field, "transform is not finite");
    ObjectRecord r;
    r.id = o.id;
    r.target = o.target;
    r.impenetrable = o.impenetrable;
    r.group = o.group;
    r.order_in_group = o.order_in_group;
    r.model = o.transform;
    const glm::mat3 m3(o.transform);
    const float det = glm::determinant(m3);
    r.normal_matrix = std::abs(det) > 1e-20f ? glm::transpose(glm::inverse(m3)) : m3;
    r.mirrored = det < 0.0f;
    r.convex = mesh_convex[o.mesh] != 0 && std::abs(det) > 1e-20f;
    r.tint = o.color;
    r.mesh = o.mesh;
    r.index_count = static_cast<std::int32_t>(scene.meshes[o.mesh].indices.size());
    r.first_index = first_index[o.mesh];
    r.base_vertex = static_cast<std::int32_t>(first_vertex[o.mesh]);
    glm::vec3 lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());
    for (int c = 0; c < 8; ++c) {
      const glm::vec3 corner((c & 1) ? mesh_max[o.mesh].x : mesh_min[o.mesh].x,
                             (c & 2) ? mesh_max[o.mesh].y : mesh_min[o.mesh].y,
                             (c & 4) ? mesh_max[o.mesh].z : mesh_min[o.mesh].z);
      const glm::vec3 w = glm::vec3(o.transform * glm::vec4(corner, 1.0f));
      lo = glm::min(lo, w);
      hi = glm::max(hi, w);
    }
    r.world_min = lo;
    r.world_max = hi;
    r.mesh_min = mesh_min[o.mesh];
    r.mesh_max = mesh_max[o.mesh];
    gpu->objects_.push_back(r);
  }

  GLint prev_vao = 0, prev_buf = 0;
  glGetIntegerv(GL_VERTEX_ARRAY_BINDING, &prev_vao);
  glGetIntegerv(GL_ARRAY_BUFFER_BINDING, &prev_buf);
  glGenVertexArrays(1, &gpu->vao_);
  glBindVertexArray(gpu->vao_);
  glGenBuffers(1, &gpu->vbo_);
  glBindBuffer(GL_ARRAY_BUFFER, gpu->vbo_);
  glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(vertices.size() * sizeof(Packed)),
               vertices.empty() ? nullptr : vertices.data(), GL_STATIC_DRAW);
  glGenBuffers(1, &gpu->ibo_);
  glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, gpu->ibo_);
  glBufferData(GL_ELEMENT_ARRAY_BUFFER, static_cast<GLsizeiptr>(indices.size() * sizeof(std::uint32_t)),
               indices.empty() ? nullptr : indices.data(), GL_STATIC_DRAW);
  for (GLuint a = 0; a < 3; ++a) {
    glEnableVertexAttribArray(a);
    glVertexAttribPointer(a, 3, GL_FLOAT, GL_FALSE, sizeof(Packed),
                          reinterpret_cast<const void*>(static_cast<std::uintptr_t>(a * 3 * sizeof(float))));
  }
  glBindVertexArray(static_cast<GLuint>(prev_vao));
  glBindBuffer(GL_ARRAY_BUFFER, static_cast<GLuint>(prev_buf));
  return gpu;
}

SceneGpu::~SceneGpu() {
  if (ibo_ != 0) glDeleteBuffers(1, &ibo_);
  if (vbo_ != 0) glDeleteBuffers(1, &vbo_);
  if (vao_ != 0) glDeleteVertexArrays(1, &vao_);
}

void SceneGpu::draw(const ObjectRecord& o) const {
  if (!o.drawable()) return;
  ++counts_.draws;
  counts_.triangles += o.index_count / 3;
  glDrawElementsBaseVertex(GL_TRIANGLES, o.index_count, GL_UNSIGNED_INT,
                           reinterpret_cast<const void*>(o.first_index * sizeof(std::uint32_t)), o.base_vertex);
}

}  // namespace dtlab::render::detail

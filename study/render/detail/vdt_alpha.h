// Internal: the view-dependent alpha of Diepstraten, Weiskopf & Ertl (2002),
// section 5 (docs/render.md, "vdt"): per frame and per transparent object,
// its silhouette edges by Appel's test (eq. 1: the two faces sharing an edge
// face opposite ways from the eye; an edge with one face is on the outline
// too), then per vertex the distance d_min to the nearest silhouette edge's
// line and alpha = 1 - (d_min / d_object,max)^k (eq. 2), clamped to [0, 1].
// Pure maths on the CPU, as in the paper; no GL. Guarantees: a vertex on a
// silhouette edge gets alpha 1; an object seen with no silhouette gets alpha 0
// everywhere (nothing to fall off from). Never: reads or writes GL state.
#pragma once
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "study/scene/scene.h"

namespace dtlab::render::detail {

// A mesh's edges with the faces that share them, its vertices welded by position within 1e-5 of
// the mesh's size (the scene's meshes split vertices at sharp edges for their normals and at
// seams; a silhouette is an edge of the surface).
struct VdtTopology {
  std::vector<glm::vec3> points;      // welded positions, model space
  std::vector<std::uint32_t> weld;    // per mesh vertex: its index in `points`
  std::vector<glm::vec4> planes;      // per non-degenerate triangle: outward unit normal n, d = -n.p
  struct Edge {
    std::uint32_t a = 0, b = 0;       // welded endpoints
    std::vector<std::uint32_t> faces; // indices into `planes` (2 on a closed manifold surface)
  };
  std::vector<Edge> edges;
};
VdtTopology vdt_topology(const scene::Mesh& mesh);  // degenerate triangles (zero area) are left out

// Equation (2) per mesh vertex of an object with `model` seen from `eye` (world space), in the
// mesh's vertex order; `k` the falling-off term in [0, 1]. d_object,max is the largest distance
// from the centre of the object's world-space bounding box to its vertices.
std::vector<float> vdt_vertex_alpha(const VdtTopology& topo, const glm::mat4& model, glm::vec3 eye, float k);

}  // namespace dtlab::render::detail

// The view-dependent alpha of vdt (see vdt_alpha.h): Appel's silhouette test
// and equation (2) of Diepstraten, Weiskopf & Ertl (2002), per vertex.
#include "study/render/detail/vdt_alpha.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <optional>
#include <utility>

namespace dtlab::render::detail {

namespace {

// Welds positions closer than `eps` (a hash grid of cell eps; a point is looked up in its cell and
// the 26 around it). Exact equality is not enough: generators place seam and pole vertices with
// sin(2 pi) or sin(pi) in floating point, a few 1e-16 off zero, and an unwelded seam would be a
// border, so a silhouette edge across the middle of the object.
void weld(const scene::Mesh& mesh, VdtTopology& t) {
  glm::vec3 lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());
  for (const scene::Vertex& v : mesh.vertices) {
    lo = glm::min(lo, v.position);
    hi = glm::max(hi, v.position);
  }
  const float eps = mesh.vertices.empty() ? 1.0f : std::max(1e-5f * glm::length(hi - lo), 1e-12f);
  using Cell = std::array<long long, 3>;
  std::map<Cell, std::vector<std::uint32_t>> grid;
  auto cell_of = [&](glm::vec3 p) {
    return Cell{static_cast<long long>(std::floor(p.x / eps)), static_cast<long long>(std::floor(p.y / eps)),
                static_cast<long long>(std::floor(p.z / eps))};
  };
  t.weld.reserve(mesh.vertices.size());
  for (const scene::Vertex& v : mesh.vertices) {
    const Cell c = cell_of(v.position);
    std::optional<std::uint32_t> found;
    for (long long dx = -1; dx <= 1 && !found; ++dx)
      for (long long dy = -1; dy <= 1 && !found; ++dy)
        for (long long dz = -1; dz <= 1 && !found; ++dz) {
          const auto it = grid.find({c[0] + dx, c[1] + dy, c[2] + dz});
          if (it == grid.end()) continue;
          for (std::uint32_t k : it->second)
            if (glm::length(t.points[k] - v.position) <= eps) {
              found = k;
              break;
            }
        }
    if (!found) {
      found = static_cast<std::uint32_t>(t.points.size());
      t.points.push_back(v.position);
      grid[c].push_back(*found);
    }
    t.weld.push_back(*found);
  }
}

}  // namespace

VdtTopology vdt_topology(const scene::Mesh& mesh) {
  VdtTopology t;
  weld(mesh, t);
  std::map<std::pair<std::uint32_t, std::uint32_t>, std::size_t> edge_of;
  for (std::size_t i = 0; i + 2 < mesh.indices.size(); i += 3) {
    const std::uint32_t w[3] = {t.weld[mesh.indices[i]], t.weld[mesh.indices[i + 1]], t.weld[mesh.indices[i + 2]]};
    const glm::vec3 a = t.points[w[0]], b = t.points[w[1]], c = t.points[w[2]];
    const glm::vec3 n = glm::cross(b - a, c - a);
    const float len = glm::length(n);
    if (w[0] == w[1] || w[1] == w[2] || w[0] == w[2] || !(len > 1e-12f)) continue;  // no plane, no facing
    const glm::vec3 u = n / len;
    const auto face = static_cast<std::uint32_t>(t.planes.size());
    t.planes.emplace_back(u, -glm::dot(u, a));
    for (int e = 0; e < 3; ++e) {
      const auto key = std::minmax(w[e], w[(e + 1) % 3]);
      const auto [it, added] = edge_of.emplace(key, t.edges.size());
      if (added) t.edges.push_back({key.first, key.second, {}});
      t.edges[it->second].faces.push_back(face);
    }
  }
  return t;
}

std::vector<float> vdt_vertex_alpha(const VdtTopology& topo, const glm::mat4& model, glm::vec3 eye, float k) {
  // Equation (1) in model space: the sign of n . (p - o) is that of the face's plane evaluated at
  // the eye, and an affine map keeps every plane's sides (a mirroring flips all of them, which
  // leaves the product's sign alone). The eye goes to model space once per object.
  const glm::vec3 o = glm::vec3(glm::inverse(model) * glm::vec4(eye, 1.0f));
  std::vector<char> front(topo.planes.size());
  for (std::size_t f = 0; f < topo.planes.size(); ++f)
    front[f] = glm::dot(glm::vec3(topo.planes[f]), o) + topo.planes[f].w > 0.0f ? 1 : 0;

  // Distances are measured in world space (the paper's \vec v, \vec p, \vec e).
  std::vector<glm::vec3> world(topo.points.size());
  glm::vec3 lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());
  for (std::size_t i = 0; i < world.size(); ++i) {
    world[i] = glm::vec3(model * glm::vec4(topo.points[i], 1.0f));
    lo = glm::min(lo, world[i]);
    hi = glm::max(hi, world[i]);
  }
  const glm::vec3 center = 0.5f * (lo + hi);
  float d_max = 0.0f;
  for (const glm::vec3& w : world) d_max = std::max(d_max, glm::length(w - center));

  // Silhouette edges: faces on both sides of the eye (two-face edges: eq. 1; an edge of more faces
  // counts when they disagree), or a border of the surface (one face).
  struct Line {
    glm::vec3 p, e;
    float ee;
  };
  std::vector<Line> silhouette;
  for (const VdtTopology::Edge& e : topo.edges) {
    bool any_front = false, any_back = false;
    for (std::uint32_t f : e.faces) (front[f] ? any_front : any_back) = true;
    if (e.faces.size() == 1 || (any_front && any_back)) {
      const glm::vec3 p = world[e.a], d = world[e.b] - world[e.a];
      silhouette.push_back({p, d, glm::dot(d, d)});
    }
  }

  std::vector<float> welded(topo.points.size(), 0.0f);
  if (!silhouette.empty() && d_max > 0.0f) {
    for (std::size_t i = 0; i < world.size(); ++i) {
      const glm::vec3 v = world[i];
      float d_min = std::numeric_limits<float>::max();
      for (const Line& l : silhouette) {
        // d = || v - (p + ((v - p) . e / ||e||^2) e) ||: the distance to the edge's line.
        const glm::vec3 foot = l.ee > 0.0f ? l.p + (glm::dot(v - l.p, l.e) / l.ee) * l.e : l.p;
        d_min = std::min(d_min, glm::length(v - foot));
      }
      const float alpha = 1.0f - std::pow(d_min / d_max, k);
      welded[i] = std::clamp(alpha, 0.0f, 1.0f);
    }
  }
  std::vector<float> out(topo.weld.size());
  for (std::size_t i = 0; i < out.size(); ++i) out[i] = welded[topo.weld[i]];
  return out;
}

}  // namespace dtlab::render::detail

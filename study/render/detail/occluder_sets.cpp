// Poon's minimum occluder sets (see occluder_sets.h; thesis 3.2).
#include <algorithm>
#include <cmath>
#include <iterator>
#include <limits>
#include <map>
#include <utility>

#include "study/render/detail/occluder_sets.h"

namespace dtlab::render::detail {

std::vector<IdSet> combination_table(const std::vector<IdSet>& stacks) {
  std::vector<IdSet> slots;
  for (const IdSet& s : stacks) {
    if (s.empty()) return {};  // an uncovered pixel: the occludee is visible
    slots.push_back(s);
  }
  std::sort(slots.begin(), slots.end(), [](const IdSet& a, const IdSet& b) {
    return a.size() != b.size() ? a.size() < b.size() : a < b;
  });
  slots.erase(std::unique(slots.begin(), slots.end()), slots.end());
  return slots;
}

namespace {

// The search state of 3.2.2: slots cancelled by the intermediate MOS, the kept sets.
struct MosSearch {
  const std::vector<IdSet>& table;
  const std::vector<double>& cost;
  int keep;
  long budget;
  std::vector<int> hits;  // per slot: members of the intermediate MOS it contains (0: still open)
  IdSet chosen;
  double chosen_cost = 0.0;
  std::vector<std::pair<double, IdSet>> kept;  // ascending cost
  long steps = 0;

  void pick(std::uint32_t id, int delta) {
    for (std::size_t s = 0; s < table.size(); ++s)
      if (std::binary_search(table[s].begin(), table[s].end(), id)) hits[s] += delta;
  }
  // Every member has a slot only it cancels (else a member is redundant, Figure 3 right).
  bool minimal() const {
    for (std::uint32_t id : chosen) {
      bool needed = false;
      for (std::size_t s = 0; s < table.size() && !needed; ++s)
        needed = hits[s] == 1 && std::binary_search(table[s].begin(), table[s].end(), id);
      if (!needed) return false;
    }
    return true;
  }
  void record() {
    IdSet set = chosen;
    std::sort(set.begin(), set.end());
    for (const auto& k : kept)
      if (k.second == set) return;
    const auto at = std::upper_bound(kept.begin(), kept.end(), chosen_cost,
                                     [](double c, const auto& k) { return c < k.first; });
    kept.insert(at, {chosen_cost, std::move(set)});
    if (static_cast<int>(kept.size()) > keep) kept.pop_back();
  }
  void run() {
    if (++steps > budget) return;
    // Pruning: already no cheaper than the dearest set kept.
    if (static_cast<int>(kept.size()) >= keep && chosen_cost >= kept.back().first) return;
    std::size_t open = 0;
    while (open < table.size() && hits[open] > 0) ++open;
    if (open == table.size()) {
      if (minimal()) record();
      return;
    }
    // Left to right: the first open slot's IDs in turn (a one-ID slot forces its ID).
    for (std::uint32_t id : table[open]) {
      chosen.push_back(id);
      chosen_cost += cost[id];
      pick(id, +1);
      run();
      pick(id, -1);
      chosen_cost -= cost[id];
      chosen.pop_back();
    }
  }
};

}  // namespace

std::vector<IdSet> minimum_occluder_sets(const std::vector<IdSet>& table, const std::vector<double>& cost, int keep,
                                         long budget) {
  if (table.empty() || keep <= 0) return {};
  MosSearch s{table, cost, keep, budget, std::vector<int>(table.size(), 0), {}, 0.0, {}, 0};
  s.run();
  std::vector<IdSet> out;
  for (auto& k : s.kept) out.push_back(std::move(k.second));
  return out;
}

namespace {

constexpr float kNear = 0.05f;

// A square 90-degree view: pixel (x, y) looks along forward + u right + v up, u, v in [-1, 1],
// so the ray parameter is the view depth.
struct RayView {
  glm::vec3 eye, forward, right, up;
  int res;
  glm::vec3 dir(int x, int y) const {
    const float u = (static_cast<float>(x) + 0.5f) / static_cast<float>(res) * 2.0f - 1.0f;
    const float v = (static_cast<float>(y) + 0.5f) / static_cast<float>(res) * 2.0f - 1.0f;
    return forward + u * right + v * up;
  }
};

// Entry depth of the ray into the box, or a negative value if it misses or starts inside.
float entry(glm::vec3 o, glm::vec3 d, glm::vec3 lo, glm::vec3 hi) {
  float t0 = -std::numeric_limits<float>::max(), t1 = std::numeric_limits<float>::max();
  for (int a = 0; a < 3; ++a) {
    if (std::abs(d[a]) < 1e-12f) {
      if (o[a] < lo[a] || o[a] > hi[a]) return -1.0f;
      continue;
    }
    float ta = (lo[a] - o[a]) / d[a], tb = (hi[a] - o[a]) / d[a];
    if (ta > tb) std::swap(ta, tb);
    t0 = std::max(t0, ta);
    t1 = std::min(t1, tb);
  }
  return t0 <= t1 && t0 > kNear ? t0 : -1.0f;
}

// Pixels [x0, x1) x [y0, y1) a box projects onto (one pixel of margin), and its nearest depth;
// empty when outside the view or when it reaches the eye plane (never an occludee then).
struct Image {
  int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
  float near = 0.0f;
  bool empty() const { return x1 <= x0 || y1 <= y0; }
};
Image project_box(const ObjectRecord& o, const RayView& v) {
  Image im;
  float u0 = 1e30f, v0 = 1e30f, u1 = -1e30f, v1 = -1e30f, near = 1e30f;
  for (int c = 0; c < 8; ++c) {
    const glm::vec3 p(o.model * glm::vec4((c & 1) ? o.mesh_max.x : o.mesh_min.x, (c & 2) ? o.mesh_max.y : o.mesh_min.y,
                                          (c & 4) ? o.mesh_max.z : o.mesh_min.z, 1.0f));
    const glm::vec3 r = p - v.eye;
    const float z = glm::dot(r, v.forward);
    if (z <= kNear) return im;
    near = std::min(near, z);
    const float u = glm::dot(r, v.right) / z, w = glm::dot(r, v.up) / z;
    u0 = std::min(u0, u), u1 = std::max(u1, u), v0 = std::min(v0, w), v1 = std::max(v1, w);
  }
  const float s = 0.5f * static_cast<float>(v.res);
  im.x0 = std::max(0, static_cast<int>(std::floor((u0 + 1.0f) * s)) - 1);
  im.y0 = std::max(0, static_cast<int>(std::floor((v0 + 1.0f) * s)) - 1);
  im.x1 = std::min(v.res, static_cast<int>(std::ceil((u1 + 1.0f) * s)) + 1);
  im.y1 = std::min(v.res, static_cast<int>(std::ceil((v1 + 1.0f) * s)) + 1);
  im.near = near;
  return im;
}

}  // namespace

namespace {

// Per pixel of a view, every candidate its ray enters, nearest first (local ids = positions in
// `candidates`), and each candidate's cost: 1 plus its projected share of the view.
struct RayHits {
  std::vector<std::vector<std::pair<float, std::uint32_t>>> pixels;
  std::vector<double> cost;
};
RayHits cast_rays(const std::vector<ObjectRecord>& objects, const std::vector<std::uint32_t>& candidates,
                  const RayView& view) {
  const int R = view.res;
  RayHits out{std::vector<std::vector<std::pair<float, std::uint32_t>>>(static_cast<std::size_t>(R * R)),
              std::vector<double>(candidates.size(), 1.0)};
  // Only candidates the view's pyramid can see: no ray enters a box wholly outside one of its planes.
  std::vector<std::uint32_t> seen;
  for (std::uint32_t c = 0; c < candidates.size(); ++c) {
    const ObjectRecord& o = objects[candidates[c]];
    int outside = 0x1f;
    for (int k = 0; k < 8; ++k) {
      const glm::vec3 r = glm::vec3((k & 1) ? o.world_max.x : o.world_min.x, (k & 2) ? o.world_max.y : o.world_min.y,
                                    (k & 4) ? o.world_max.z : o.world_min.z) - view.eye;
      const float z = glm::dot(r, view.forward), u = glm::dot(r, view.right), v = glm::dot(r, view.up);
      outside &= (z <= kNear ? 1 : 0) | (u > z ? 2 : 0) | (-u > z ? 4 : 0) | (v > z ? 8 : 0) | (-v > z ? 16 : 0);
    }
    if (outside == 0) seen.push_back(c);
  }
  for (int y = 0; y < R; ++y)
    for (int x = 0; x < R; ++x) {
      auto& h = out.pixels[static_cast<std::size_t>(y * R + x)];
      const glm::vec3 d = view.dir(x, y);
      for (std::uint32_t c : seen) {
        const ObjectRecord& o = objects[candidates[c]];
        const float t = entry(view.eye, d, o.world_min, o.world_max);
        if (t > 0.0f) {
          h.emplace_back(t, c);
          out.cost[c] += 1.0 / static_cast<double>(R * R);
        }
      }
      std::sort(h.begin(), h.end());
    }
  return out;
}

// 3.2.1-3.2.2: per occludee, its occluder stacks, combination table and cheapest MOSs; identical
// sets of different occludees grouped (their gains add).
std::map<IdSet, int> occluder_sets(const std::vector<ObjectRecord>& objects, const std::vector<std::uint32_t>& candidates,
                                   const RayView& view, const RayHits& hits, const MosParams& p) {
  std::vector<bool> is_candidate(objects.size(), false);
  for (auto c : candidates) is_candidate[c] = true;
  std::map<IdSet, int> gain;
  for (std::uint32_t i = 0; i < objects.size(); ++i) {
    const ObjectRecord& o = objects[i];
    if (is_candidate[i] || !o.drawable() || o.index_count / 3 <= p.min_triangles) continue;
    const Image im = project_box(o, view);
    if (im.empty()) continue;
    std::vector<IdSet> stacks;
    for (int y = im.y0; y < im.y1; ++y)
      for (int x = im.x0; x < im.x1; ++x) {
        IdSet s;
        for (const auto& [t, c] : hits.pixels[static_cast<std::size_t>(y * view.res + x)]) {
          if (t >= im.near) break;
          s.push_back(c);
        }
        std::sort(s.begin(), s.end());
        stacks.push_back(std::move(s));
      }
    for (const IdSet& m : minimum_occluder_sets(combination_table(stacks), hits.cost, p.keep)) ++gain[m];
  }
  return gain;
}

// 3.2.3: score = (gain + gains of its subsets) / cost; sets in score order overlaid in the ID
// buffer (first chosen occluder per ray) until `limit` occluders are visible in it.
IdSet select_by_score(const std::map<IdSet, int>& gain, const RayHits& hits, std::size_t candidates, int limit) {
  struct Scored {
    double score;
    IdSet set;
  };
  std::vector<Scored> scored;
  for (const auto& [set, g] : gain) {
    double total = g, c = 0.0;
    for (const auto& [other, og] : gain)
      if (other.size() < set.size() && std::includes(set.begin(), set.end(), other.begin(), other.end())) total += og;
    for (auto id : set) c += hits.cost[id];
    scored.push_back({total / c, set});
  }
  std::stable_sort(scored.begin(), scored.end(), [](const Scored& a, const Scored& b) { return a.score > b.score; });
  IdSet selected;
  for (const Scored& s : scored) {
    if (static_cast<int>(selected.size()) >= limit) break;
    IdSet with;
    std::set_union(selected.begin(), selected.end(), s.set.begin(), s.set.end(), std::back_inserter(with));
    if (static_cast<int>(with.size()) > limit) continue;
    std::vector<bool> seen(candidates, false);
    for (const auto& h : hits.pixels)
      for (const auto& [t, c] : h)
        if (std::binary_search(with.begin(), with.end(), c)) {
          seen[c] = true;
          break;
        }
    selected.clear();
    for (std::uint32_t c = 0; c < candidates; ++c)
      if (seen[c]) selected.push_back(c);
  }
  return selected;
}

}  // namespace

IdSet select_occluders(const std::vector<ObjectRecord>& objects, const std::vector<std::uint32_t>& candidates,
                       glm::vec3 eye, glm::vec3 forward, const MosParams& p) {
  RayView view{eye, glm::normalize(forward), {}, {}, p.resolution};
  view.right = glm::normalize(glm::cross(view.forward, glm::vec3(0.0f, 1.0f, 0.0f)));
  view.up = glm::cross(view.right, view.forward);
  const RayHits hits = cast_rays(objects, candidates, view);
  const IdSet local = select_by_score(occluder_sets(objects, candidates, view, hits, p), hits, candidates.size(), p.limit);
  IdSet out;
  for (auto c : local) out.push_back(candidates[c]);
  return out;
}

const IdSet& OccluderDatabase::nearest(glm::vec3 eye) const {
  const int x = std::clamp(static_cast<int>(std::floor(eye.x / cell_size)), 0, width - 1);
  const int z = std::clamp(static_cast<int>(std::floor(eye.z / cell_size)), 0, height - 1);
  return cells[static_cast<std::size_t>(z * width + x)];
}

OccluderDatabase build_occluder_database(const scene::Scene& scene, const std::vector<ObjectRecord>& objects,
                                         const MosParams& p) {
  OccluderDatabase db;
  if (!scene.plan) return db;
  db.width = scene.plan->width;
  db.height = scene.plan->height;
  db.cell_size = scene.plan->cell_size;
  std::vector<std::uint32_t> walls;
  for (std::uint32_t i = 0; i < scene.objects.size() && i < objects.size(); ++i)
    if (scene.objects[i].kind == "wall" && objects[i].drawable()) walls.push_back(i);
  const glm::vec3 dirs[4] = {{0, 0, -1}, {-1, 0, 0}, {0, 0, 1}, {1, 0, 0}};
  for (int z = 0; z < db.height; ++z)
    for (int x = 0; x < db.width; ++x) {
      const glm::vec3 eye((static_cast<float>(x) + 0.5f) * db.cell_size, scene.camera.position.y,
                          (static_cast<float>(z) + 0.5f) * db.cell_size);
      IdSet all;
      for (const glm::vec3& d : dirs) {
        const IdSet s = select_occluders(objects, walls, eye, d, p);
        IdSet merged;
        std::set_union(all.begin(), all.end(), s.begin(), s.end(), std::back_inserter(merged));
        all = std::move(merged);
      }
      db.cells.push_back(std::move(all));
    }
  return db;
}

}  // namespace dtlab::render::detail

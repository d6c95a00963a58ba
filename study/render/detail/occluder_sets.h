// Internal: Poon's minimum occluder set (MOS) preprocessing (thesis 3.2) for
// WALKTHROUGH scenes: per grid point of the floor plan and four view
// directions, an occluder stack per occludee, its combination table, an
// exhaustive search with cost pruning, gain / cost scoring and selection with
// an ID buffer. CPU only and deterministic (rays at pixel centres against the
// wall boxes; no GL, no hashing, ordered containers only).
// Guarantees: a selected occluder is a wall object (an axis-aligned box that
// fills its world AABB), so the run-time render of it is exact. Never: decides
// what is culled (occlusion_culling.h does, conservatively, for any list).
#pragma once
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "study/render/detail/scene_gpu.h"
#include "study/scene/scene.h"

namespace dtlab::render::detail {

// One occluder set; members are occluder ids (any integers), ascending.
using IdSet = std::vector<std::uint32_t>;

// The combination table of one occludee (thesis Figure 4): each slot is the set of occluders
// stacked at some of its pixels, slots in ascending order of size (ties: lexicographic).
// Empty when some pixel has no occluder: the occludee is visible and has no MOS.
std::vector<IdSet> combination_table(const std::vector<IdSet>& stacks);

// The exhaustive search of 3.2.2: the minimal sets that cancel every slot, the `keep` cheapest
// (by `cost`, one value per id, summed; ties in the order found) with pruning of any branch that
// is already no cheaper than the dearest kept set once `keep` are kept. `budget` caps the search
// steps (a table of n ids costs O(n!) at worst). Sets ascending by cost.
std::vector<IdSet> minimum_occluder_sets(const std::vector<IdSet>& table, const std::vector<double>& cost,
                                         int keep = 4, long budget = 200000);

// Parameters of the preprocessing (docs/render.md, "Occlusion culling").
struct MosParams {
  int resolution = 32;        // rays per side of each representative view (square, 90 degrees)
  int min_triangles = 20;     // occludees: objects with more triangles (thesis: "more than 20 primitives")
  int keep = 4;               // cheapest MOSs kept per occludee
  int limit = 16;             // occluders selected per view direction (4 directions: at most 64 per point)
};

// The occluders chosen for one view from `eye` along `forward` (square 90-degree view):
// occluder stacks per occludee, MOS search, grouping of identical sets, superset gains, score
// gain / cost (cost per occluder: 1 + its projected share of the view), then sets in score
// order overlaid in an ID buffer until `limit` occluders are visible in it. Object indices.
IdSet select_occluders(const std::vector<ObjectRecord>& objects, const std::vector<std::uint32_t>& candidates,
                       glm::vec3 eye, glm::vec3 forward, const MosParams& p);

// The occluder database of a WALKTHROUGH scene: per floor-plan cell (row-major, as
// FloorPlan::room), the union of select_occluders at the cell's centre, eye height, for the four
// axis directions, from the eye height the scene starts at. Candidates: the scene's "wall" objects.
struct OccluderDatabase {
  int width = 0, height = 0;  // cells
  float cell_size = 1.0f;
  std::vector<IdSet> cells;
  // The list of the grid point nearest to `eye` (its cell, clamped to the plan).
  const IdSet& nearest(glm::vec3 eye) const;
};
OccluderDatabase build_occluder_database(const scene::Scene& scene, const std::vector<ObjectRecord>& objects,
                                         const MosParams& p = {});

}  // namespace dtlab::render::detail

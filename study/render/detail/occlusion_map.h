// Internal: the CPU half of Poon's run-time occlusion culling (thesis 3.1,
// 3.3): the opacity map (a summed-area table of the occluders' coverage
// bitmap; the overlap test is two additions and one subtraction), the sparse
// depth map (per pixel, the jump to the nearest local depth peak to its
// right), and the bounding-volume hierarchy tested recursively against them.
// Guarantees: a node is reported hidden only if every map texel its screen
// rectangle touches is covered and holds occluder depth strictly nearer than
// the node's nearest point. Never: touches GL (occlusion_culling.cpp feeds it).
#pragma once
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "study/render/detail/frame_view.h"
#include "study/render/detail/scene_gpu.h"

namespace dtlab::render::detail {

// A width x height map over a view, texel (x, y) covering output pixels [x b, (x + 1) b) x
// [y b, (y + 1) b) (origin bottom-left), b = `block`.
struct OcclusionMap {
  int width = 0, height = 0, block = 1;
  std::vector<float> depth;          // farthest occluder depth per texel, window depth; 1: not covered
  std::vector<int> opacity;          // (width + 1) x (height + 1): Op(s, t), row 0 and column 0 zeros
  std::vector<std::uint16_t> steps;  // sparse depth map: texels from here to the next peak, inclusive
  int op(int s, int t) const { return opacity[static_cast<std::size_t>(t * (width + 1) + s)]; }
  // Covered texels in (x1, x2] x (y1, y2] in the opacity map's 1-based coordinates (the OPF).
  int opf(int x1, int x2, int y1, int y2) const { return op(x1, y1) - op(x1, y2) - op(x2, y1) + op(x2, y2); }
  // Texels [x0, x1) x [y0, y1) all hold depth below `near` (walks the sparse depth map per row).
  bool behind(int x0, int y0, int x1, int y1, float near) const;
};

// Builds both maps from the per-texel depth; texels inside any of `holes` (output pixels) count
// as not covered (pixels a transparency method may change).
OcclusionMap make_occlusion_map(std::vector<float> depth, int width, int height, int block,
                                const std::vector<PixelRect>& holes = {});

// A bounding-volume tree over the objects: median splits along the longest axis of the
// centroids; a leaf holds at most `leaf_triangles` triangles or a single object (dtlab draws
// objects whole, so an object is never split). nodes[0] is the root.
struct Hierarchy {
  struct Node {
    glm::vec3 lo{0.0f}, hi{0.0f};
    int left = -1, right = -1;                // children; -1 in a leaf
    std::vector<std::uint32_t> objects;       // leaf only
  };
  std::vector<Node> nodes;
};
Hierarchy build_hierarchy(const std::vector<ObjectRecord>& objects, long leaf_triangles = 256);

struct CullCounts {
  int nodes_tested = 0, nodes_culled = 0;
};
// Recursive test from the root (view-frustum culling first, then the overlap test, the adaptive
// stop below coverage `min_coverage`, and the depth comparison); sets culled[i] for each object of
// a hidden node, never for an object in `keep`.
CullCounts cull_hierarchy(const Hierarchy& h, const std::vector<ObjectRecord>& objects, const OcclusionMap& map,
                          const glm::mat4& view_proj, int width, int height, const std::vector<bool>& keep,
                          std::vector<bool>& culled, float min_coverage = 0.2f);

}  // namespace dtlab::render::detail

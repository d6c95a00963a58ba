// Internal: what the CPU knows about one frame before any GL call: each
// object's conservative screen rectangle (empty when outside the view
// frustum), the mask texel grid, the targets in view with their stencil
// codes, mask supports and circle/ellipse parameters, and the draw order
// (impenetrable first, then the sorted groups). Pure maths; no GL.
// Guarantees: a rectangle never misses a pixel the object covers (geometry
// crossing the near plane gets the whole viewport); a support never misses a
// pixel whose alpha the target's mask (grid or exact) can lower; two targets
// whose rectangles overlap never share a code. Never: reads GL state.
#pragma once
#include <algorithm>
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "study/render/camera.h"
#include "study/render/detail/scene_gpu.h"
#include "study/render/detail/sort.h"

namespace dtlab::technique {
struct DtSettings;
}
namespace dtlab::render {
using technique::DtSettings;
}

namespace dtlab::render::detail {

// Window pixels [x0, x1) x [y0, y1), origin bottom-left (GL's convention).
struct PixelRect {
  int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
  bool empty() const { return x1 <= x0 || y1 <= y0; }
  long area() const { return empty() ? 0 : static_cast<long>(x1 - x0) * (y1 - y0); }
  PixelRect intersect(const PixelRect& o) const {
    return {std::max(x0, o.x0), std::max(y0, o.y0), std::min(x1, o.x1), std::min(y1, o.y1)};
  }
  PixelRect expand(int d) const { return {x0 - d, y0 - d, x1 + d, y1 + d}; }
  bool overlaps(const PixelRect& o) const { return !intersect(o).empty(); }
  bool operator==(const PixelRect&) const = default;
};

// The conservative window rectangle of `points` seen through `view_proj` (one pixel of margin,
// clipped to the viewport; empty when they project outside it); the whole viewport when a point
// lies behind the near plane, where the projection is unbounded. The rule object rectangles use.
PixelRect screen_rect(const std::vector<glm::vec3>& points, const glm::mat4& view_proj, int width, int height);

// The texel grid of the masks (docs/render.md, "Mask"), the same for dt-seed and dt-fast: R x R
// texels over the whole view (the article's 128 x 128: texels of W/R x H/R pixels), or one
// texel per pixel for R = 0; the gradient is `layers` texels wide (Algorithm 2's n).
struct MaskGrid {
  int width = 1, height = 1;             // texels
  float texel_x = 1.0f, texel_y = 1.0f;  // output pixels per texel
  int layers = 0;                        // n' = round(n / sqrt(texel_x texel_y)), at least 1 if n > 0
};
MaskGrid mask_grid(const DtSettings& dt, int width, int height);

struct TargetView {
  std::uint32_t object = 0;       // index into the scene's objects
  int code = 1;                   // stencil code of the frontmost-object test, 1..255 (0: none left)
  glm::vec4 bounds{0.0f};         // tight bounds of the projected vertices (x0, y0, x1, y1), window pixels, unclipped
  PixelRect rect;                 // silhouette bounds, clipped to the viewport
  PixelRect support;              // pixels whose alpha its mask can change, clipped to the viewport
  PixelRect cover;                // mask texels its silhouette (or shape) can cover, grid units
  glm::vec2 shape_center{0.0f};   // circle / ellipse centre, window pixels
  glm::vec2 shape_radii{0.0f};    // semi-axes, window pixels (equal for a circle)
  // Some object sorted before it overlaps it on screen, reaches nearer than its farthest point,
  // and no face plane of that object's box has the eye and the target's box on its outer side: a
  // sort error could hide it (the R1 guard's repair is needed only then).
  bool may_be_drawn_late = false;
};

struct FrameView {
  int width = 0, height = 0;
  MaskGrid grid;
  int max_code = 0;                         // largest target code; 0: no targets
  // More than 255 targets overlap one another's rectangles: some target has code 0, so the target
  // query cannot decide and the effect runs unconditionally (the article's behaviour).
  bool codes_exhausted = false;
  Camera camera;
  glm::mat4 view_proj{1.0f};
  std::vector<PixelRect> rects;             // per object
  std::vector<TargetView> targets;          // targets in view, scene order
  std::vector<int> target_slot;             // per object: index into targets, or -1
  std::vector<bool> single_pass;            // per object: one back-face-culled pass selects its frontmost surface
  std::vector<std::uint32_t> impenetrable;  // impenetrable objects in view, scene order
  std::vector<std::uint32_t> sorted;        // other objects in view, back to front
  glm::vec3 searchlight{0.0f, 0.0f, -1.0f}; // (x, y, radius) window pixels; radius < 0: passive mode
  PixelRect viewport() const { return {0, 0, width, height}; }
};

// `scene` supplies target vertices for tight bounds; `sorter` keeps the order between frames.
FrameView make_frame_view(const std::vector<ObjectRecord>& objects, const scene::Scene& scene,
                          const Camera& camera, int width, int height, const DtSettings& dt, GroupSorter& sorter);

}  // namespace dtlab::render::detail

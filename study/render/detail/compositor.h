// Internal: the exact per-pixel compositor behind the `reference` method. It
// takes, for every object in view, the object's own frontmost surface (colour
// and depth per pixel, rendered alone on the GPU) and composites, per pixel,
// all surfaces back to front in exact depth order with the alpha rule of
// docs/render.md: alpha starts at 1; a surface blends as c*A + C*(1-A); a
// target's mask event multiplies A by M_T(p) at the target's depth (its own
// depth where it covers p, its nearest depth elsewhere);
// impenetrable surfaces are the base, never transparent; the layer limit
// restarts its count where a mask drops A below 1; with the R1 guard a
// target's surface blends with max(A, aT) and leaves that as A. Masks are exact at full
// resolution (chessboard distance transform, two raster passes).
// Pure C++ (no GL); rows are bottom-up like GL's.
#pragma once
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "study/render/detail/frame_view.h"
#include "study/render/render.h"

namespace dtlab::render::detail {

struct ObjectLayer {
  std::uint32_t object = 0;       // scene object index
  PixelRect rect;                 // window pixels covered by `depth` and `color`
  std::vector<float> depth;       // rect.w * rect.h, row-major bottom-up; >= 1: not covered
  std::vector<glm::vec4> color;   // same layout
  float depth_at(int x, int y) const {
    return depth[static_cast<std::size_t>(y - rect.y0) * static_cast<std::size_t>(rect.x1 - rect.x0) +
                 static_cast<std::size_t>(x - rect.x0)];
  }
};

struct CompositeInput {
  int width = 0, height = 0;
  glm::vec3 background{0.0f};
  DtSettings dt;
  bool transparency = false;                 // false: standard (frontmost surface only)
  glm::vec3 searchlight{0.0f, 0.0f, -1.0f};  // (x, y, radius) window pixels; radius < 0: off
  std::vector<ObjectLayer> layers;           // scene order
  std::vector<bool> impenetrable;            // per scene object index
  std::vector<bool> is_target;               // per scene object index
  std::vector<TargetView> targets;           // targets in view
};

struct CompositeOutput {
  std::vector<glm::vec4> rgba;  // width * height, bottom-up; a = the cumulative alpha
  bool effect = false;          // transparency was on and some target was occluded
};

// One target's exact mask over its support rectangle (the rule of the file comment), shared with
// screen-door, which picks each surface's mask from the product of these.
struct MaskField {
  PixelRect rect;
  std::vector<float> alpha;  // M_T(p) in rect (row-major, bottom-up), 1 where the mask does not apply
  std::vector<float> depth;  // depth of the mask event
  float at(int x, int y) const {  // 1 outside rect
    if (x < rect.x0 || x >= rect.x1 || y < rect.y0 || y >= rect.y1) return 1.0f;
    return alpha[static_cast<std::size_t>(y - rect.y0) * static_cast<std::size_t>(rect.x1 - rect.x0) +
                 static_cast<std::size_t>(x - rect.x0)];
  }
};
// Target t's mask from its own layer (coverage: depth < 1; null: no pixel covered); `searchlight`
// (x, y, radius), radius < 0: passive mode.
MaskField exact_mask(const DtSettings& dt, glm::vec3 searchlight, const TargetView& t, const ObjectLayer* layer);

// Composites the layers; see the file comment for the rules.
CompositeOutput composite(const CompositeInput& in);

// Chessboard (Chebyshev) distance, in pixels, from each pixel of a w x h grid to the nearest
// covered pixel, capped at `cap`. Exact (Rosenfeld & Pfaltz two-pass transform).
std::vector<int> chessboard_distance(const std::vector<bool>& covered, int w, int h, int cap);

// The gradient of the visual model: alpha at Chebyshev distance d >= 1 pixels from the mask.
float gradient_alpha(float d, float alpha_start, float gradient_px);

}  // namespace dtlab::render::detail

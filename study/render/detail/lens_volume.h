// Internal: the lens method's volume on the CPU (render.h LensSettings): a
// closed convex triangle mesh in world space around the view ray through the
// lens centre pixel, and whether the eye is inside it. Pure maths; no GL.
// Guarantees: the mesh is convex and closed (every shape is the convex hull
// of its vertices), so along any ray the depth test finds exactly one entry
// (nearest) and one exit (farthest) surface; `eye_inside` is decided against
// the mesh's own face planes, so it agrees with what is rasterized.
// Never: depends on the scene or reads GL state.
#pragma once
#include <vector>

#include <glm/glm.hpp>

#include "study/render/camera.h"
#include "study/render/detail/frame_view.h"
#include "study/render/render.h"

namespace dtlab::render::detail {

struct LensVolume {
  std::vector<glm::vec3> triangles;  // world space, 3 per triangle
  glm::vec3 center{0.0f};            // world space
  glm::vec3 axis{0.0f, 0.0f, -1.0f}; // unit view ray through the centre pixel
  bool eye_inside = false;           // the eye is inside the volume: no entry surface (front map = 0)
};

// The volume of `lens` for `camera` and a width x height view (lens.center in output pixels,
// origin top-left). `lens` must pass check().
LensVolume make_lens_volume(const LensSettings& lens, const Camera& camera, int width, int height);

// The window pixels (bottom-left origin) the volume can cover: the bounds of its projected
// vertices grown by a pixel (a convex volume projects inside the hull of its vertices), or the
// whole view when the eye is inside it or a vertex lies behind the near plane (screen_rect, the
// rule object rectangles use).
PixelRect lens_footprint(const LensVolume& v, const Camera& camera, int width, int height);

// Whether world point `p` lies strictly inside the closed convex mesh `triangles`.
bool inside_convex(const std::vector<glm::vec3>& triangles, glm::vec3 p);

}  // namespace dtlab::render::detail

// What a simulated participant sees in one view: per object of interest, how
// many pixels of the rendered frame it covers with at least kVisibleShare of
// the final colour, computed with the trial's rendering method's own passes
// (the renderer's weight mode, render.h FrameSettings::flat_colors), exactly
// as Renderer::visibility counts them but with fewer frames: objects whose
// screen rectangles (their projected vertices' bounds) do not overlap share a colour channel, so a
// view of 30 spread-out targets costs one or two frames instead of ten.
// Guarantees: the counts equal Renderer::visibility's visible_pixels for the
// same camera and settings (tested); every frame rendered is timed and
// reported. Never: changes the scene's target flags or the method's settings
// other than the flat colours (so the frame shows what the condition shows).
#pragma once
#include <cstdint>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "study/render/render.h"
#include "study/scene/scene.h"

namespace dtlab::sim {

// World-space vertices of every object (its mesh's distinct positions, transformed), computed once
// per scene: their projection bounds the object's silhouette exactly (the silhouette is the
// projection of its triangles, whose corners these are).
struct ObjectBounds {
  const scene::Mesh* mesh = nullptr;  // the object's mesh (for its silhouette)
  glm::mat4 transform{1.0f};          // model -> world
  std::vector<glm::vec3> points;  // world space
  glm::vec3 min{0.0f}, max{0.0f};  // their box
  glm::vec3 center() const { return 0.5f * (min + max); }
};
std::vector<ObjectBounds> object_bounds(const scene::Scene& scene);

struct Seen {
  std::uint32_t index = 0;  // index into Scene::objects
  long visible_px = 0;      // pixels where the object's share of the colour is >= kVisibleShare
  long clear_px = 0;        // of those, pixels where its share is >= 0.9 (nothing, or nearly nothing, in front)
  long rect_px = 0;         // area of its screen rectangle (0 when behind the eye or outside the view)
  long silhouette_px = 0;   // pixels it would cover with nothing in front (CPU rasterisation, pixel centres)
};

struct View {
  std::vector<Seen> seen;         // one per requested object, in request order
  std::vector<double> frame_ms;   // measured time of every frame rendered for this view
};

// Renders the view (camera, settings, width x height) in weight mode and counts each requested
// object's visible pixels. Needs the renderer's GL context current. `objects` are indices
// into the scene's objects; `bounds` = object_bounds(scene). Errors: the renderer's.
Result<View> look(render::Renderer& renderer, const render::Camera& camera, const render::FrameSettings& settings, int width,
          int height, std::span<const std::uint32_t> objects, const std::vector<ObjectBounds>& bounds);

// The on-screen radius in pixels of an aid that follows the cursor: the active searchlight's radius,
// or an active lens's radius as seen at its distance; 0 when nothing follows the cursor (passive
// transparency, a fixed lens, no aid).
float aid_radius_px(const render::FrameSettings& settings, const render::Camera& camera, int height);
// Where a participant puts such an aid while looking over one view (docs/sim.md, "Active aids"): the
// centres of a grid of cells one aid diameter wide covering the view (wider when that would make more
// than kMaxAidSpots), row by row, alternating direction (the shortest sweep); one spot at the view's
// centre when the aid covers the whole view.
inline constexpr int kMaxAidSpots = 12;
// Empty when nothing follows the cursor or `mouse_turns_view` (WALKTHROUGH: the mouse turns the
// head and the aid stays at the view's centre, as `dtlab run` draws it).
std::vector<glm::vec2> aid_spots(const render::FrameSettings& settings, const render::Camera& camera,
                                 bool mouse_turns_view, int width, int height);

}  // namespace dtlab::sim

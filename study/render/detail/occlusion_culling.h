// Internal: Poon's occlusion culling at run time (thesis 3.1 steps 1-5) for
// a walkthrough scene, as the first stage of the frame graph: the occluder
// list of the grid point nearest the eye drawn depth-only ("cull-occluders"),
// reduced to a small map ("cull-map"), read back, made the opacity and sparse
// depth maps and tested against the hierarchy ("cull-test"); the renderer
// flushes that stage, and hidden objects leave the frame's object lists
// before the method's passes are declared over them.
// Guarantees: conservative for every method: a culled object has no fragment
// that could reach the image (under standard, each pixel of its rectangle is
// covered by a drawn occluder nearer than it; under a transparency method or
// the lens, pixels a mask or the lens may change never count as covered and
// targets are never culled). Never: changes the picture, or GL state that the
// frame's GlStateGuard does not restore.
#pragma once
#include <chrono>
#include <memory>
#include <optional>

#include "study/render/detail/frame_view.h"
#include "study/render/detail/occluder_sets.h"
#include "study/render/detail/occlusion_map.h"
#include "study/render/detail/passes.h"
#include "study/render/detail/programs.h"

namespace dtlab::render::detail {

class OcclusionCuller {
 public:
  // The hierarchy now; the occluder database on prepare() or else on the first frame (timed in
  // that frame's report).
  OcclusionCuller(const scene::Scene& scene, const std::vector<ObjectRecord>& objects);
  ~OcclusionCuller();  // needs the renderer's context current (deletes its program)
  OcclusionCuller(const OcclusionCuller&) = delete;
  OcclusionCuller& operator=(const OcclusionCuller&) = delete;

  // Builds the occluder database if it is not built yet; returns the milliseconds it took (0 if
  // it was built before). CPU only.
  double prepare();

  // Declares the culling of `view` for a frame drawn with `fc` (built on `view`) as passes of
  // `fg`; `report` (which must outlive the graph's execution) gets the counts at once and the
  // rest as the passes run, and `view`'s rects and draw lists lose the hidden objects when the
  // caller flush()es the stage. Returns whether it declared any pass: none when the method culls
  // nothing or no occluder is in view. `footprint`: pixels the method may change beyond the
  // targets' masks (a lens's; detail/method.h), nullopt for none. A shader that does not link
  // throws GlFailure (an environment Error at render.h).
  bool add_passes(FrameGraph& fg, FrameView& view, const FrameContext& fc, std::optional<PixelRect> footprint,
                  CullingReport& report);

 private:
  const scene::Scene& scene_;
  const std::vector<ObjectRecord>& objects_;
  Hierarchy hierarchy_;
  std::unique_ptr<OccluderDatabase> database_;
  Program reduce_;
  std::chrono::steady_clock::time_point started_;  // when this frame's first culling pass ran (CullingReport::ms)

  // Steps 4-5: the hierarchy tested against `map`; hidden objects leave `view`'s rects and lists.
  void cull(FrameView& view, const OcclusionMap& map, bool transparency, CullingReport& report) const;
};

}  // namespace dtlab::render::detail

// Internal: Poon's occlusion culling at run time (thesis 3.1 steps 1-5) for
// a walkthrough scene: the occluder list of the grid point nearest the eye,
// those occluders drawn depth-only, reduced on the GPU to a small map read
// back, the opacity and sparse depth maps, and the hierarchy test; hidden
// objects are taken out of the frame's object lists before any pass is built.
// Guarantees: conservative for every method: a culled object has no fragment
// that could reach the image (under standard, each pixel of its rectangle is
// covered by a drawn occluder nearer than it; under a transparency method or
// the lens, pixels a mask or the lens may change never count as covered and
// targets are never culled). Never: changes the picture, or GL state that the
// frame's GlStateGuard does not restore.
#pragma once
#include <memory>

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
  ~OcclusionCuller();  // needs the renderer's context current
  OcclusionCuller(const OcclusionCuller&) = delete;
  OcclusionCuller& operator=(const OcclusionCuller&) = delete;

  // Builds the occluder database if it is not built yet; returns the milliseconds it took (0 if
  // it was built before). CPU only.
  double prepare();

  // Culls `view` in place (its rects and draw lists) for a frame drawn with `fc` (built on `view`).
  // `footprint`: pixels the method may change beyond the targets' masks (a lens's; detail/method.h),
  // nullptr for none.
  Result<CullingReport> run(FrameView& view, const FrameContext& fc, const PixelRect* footprint);

 private:
  void ensure_targets(int width, int height);
  // Steps 2-3 on the GPU: the occluders' depth, reduced to the map's texels, read back.
  std::vector<float> occluder_map(const FrameView& view, const FrameContext& fc, CullingReport& report);
  const scene::Scene& scene_;
  const std::vector<ObjectRecord>& objects_;
  Hierarchy hierarchy_;
  std::unique_ptr<OccluderDatabase> database_;
  Program reduce_;
  unsigned depth_fbo_ = 0, depth_tex_ = 0, map_fbo_ = 0, map_tex_ = 0;
  int width_ = 0, height_ = 0, map_w_ = 0, map_h_ = 0, block_ = 1;
};

}  // namespace dtlab::render::detail

// Internal: the vdt method (docs/render.md, "vdt"): Diepstraten, Weiskopf &
// Ertl (2002), "Transparency in Interactive Technical Illustrations", its
// model of section 4 with the view-dependent alpha of section 5 (computed on
// the CPU per vertex, vdt_alpha.h) and the depth sorting of section 6.2 as
// frame-graph passes over depth textures (no read-back to the CPU).
// Transparent: every object that is neither a target nor impenetrable.
// Guarantees: a frame with no transparent object in view is standard's frame.
// Never: draws a transparent surface behind the nearest one, or an opaque
// surface behind the second-nearest transparent front face.
#pragma once
#include <cstddef>
#include <cstdint>
#include <optional>
#include <vector>

#include "study/render/detail/frame_graph.h"
#include "study/render/detail/programs.h"
#include "study/render/detail/vdt_alpha.h"

namespace dtlab::render::detail {

struct FrameContext;

// The vdt method's own programs (shaders/vdt_peel.frag, shaders/vdt.frag).
struct VdtPrograms {
  Program peel;   // object.vert + vdt_peel.frag: vdt-second, discarding at or in front of D1
  Program blend;  // object.vert with VERTEX_ALPHA + vdt.frag: vdt-blend, alpha from attribute 3
};

// What one vdt frame draws: the objects in view by class, where each transparent object's alphas
// start in the alpha buffer (attribute 3 is pointed there before its draw), the programs.
struct VdtFrame {
  std::vector<std::uint32_t> transparent, opaque;  // scene object indices, in view
  unsigned alpha_buffer = 0;
  std::vector<std::ptrdiff_t> alpha_offset;        // per transparent entry: bytes (see VdtState::prepare)
  const VdtPrograms* programs = nullptr;
};

// The vdt method's state between frames: its programs, one GL buffer of per-vertex alphas, re-filled
// every vdt frame, and the meshes' edge lists. Lives in the method's MethodSlot (method_vdt.cpp);
// destroy() needs the context current.
class VdtState {
 public:
  // Sorts the objects in view into `frame` and, if some are transparent, computes their alphas
  // (eq. 2 for this eye) and uploads them, linking the programs on the first such frame (throws
  // GlFailure if the driver refuses one: programs.h). False when nothing in view is
  // transparent (the frame is then standard's). Inside the frame's GlStateGuard (binds the array
  // buffer).
  bool prepare(const FrameContext& fc, VdtFrame& frame);
  void destroy();

 private:
  VdtPrograms programs_;
  unsigned buffer_ = 0;
  std::vector<std::optional<VdtTopology>> topology_;  // per mesh
  std::vector<float> alphas_;                         // staging, kept to avoid reallocation
};

// The passes of section 6.2 (Figure 7) in the paper's order; returns the final colour:
//   vdt-nearest     transparent front faces -> depth map D1 (the nearest transparent surface);
//   vdt-second      the same, peeling off what is at or in front of D1 -> D2 (the second);
//   vdt-opaque      opaque objects into colour (alpha: their fixed weight; background cleared with
//                   its weight) against D2: only what lies in front of the second layer survives;
//   vdt-blend       the transparent front faces at exactly D1, blended C = a C_t + a_dst C_dst;
//   vdt-foreground  opaque objects in front of D1 drawn again over the blend.
Handle add_vdt_passes(FrameGraph& fg, const FrameContext& fc, const VdtFrame& frame);

}  // namespace dtlab::render::detail

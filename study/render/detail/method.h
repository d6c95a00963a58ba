// Internal: the renderer's side of the technique registry. Each method of
// technique/settings.h's list registers its passes here as `k_passes_<id>`,
// in the file that implements it (method_<name>.cpp); Renderer::render() asks
// the entry of the frame's method for its passes and knows no method by name.
// Guarantees: a method's GL state between frames lives in its MethodSlot,
// destroyed with the renderer. Never: a method's passes read another's slot.
#pragma once
#include <functional>
#include <memory>
#include <optional>

#include "study/render/detail/passes.h"

namespace dtlab::render::detail {

// What a method keeps between frames (GL buffers, topology); made by the method on its first
// frame, destroyed with the renderer (context current).
class MethodState {
 public:
  virtual ~MethodState() = default;
};

struct MethodSlot {
  std::unique_ptr<MethodState> state;
  // A frame-coherent method's plan: did its last frame need the effect (some target occluded)?
  // Effect-first when it did, standard-first otherwise (passes.h EffectFirst).
  bool effect_hint = false;
};

// What a method's passes hand back to the renderer.
struct MethodFrame {
  Handle color;     // the final colour
  Handle occluded;  // "some target is occluded" (the target query); invalid: no query this frame
};

struct MethodPasses {
  // Before occlusion culling, from the settings and camera alone: pixels beyond the targets'
  // masks the method may change (a lens's footprint); culling hides nothing that shows there.
  // nullptr: none.
  std::optional<PixelRect> (*footprint)(MethodSlot& slot, const FrameSettings& s, const Camera& camera, int width,
                                        int height) = nullptr;
  // Declares the frame's passes up to the final colour (the renderer adds `present`).
  MethodFrame (*add)(FrameGraph& fg, const FrameContext& fc, MethodSlot& slot) = nullptr;
  // The renderer sets slot.effect_hint from the frame's target query (frame coherence).
  bool frame_coherent = false;
};

// The passes of every method, by technique::Method.
const MethodPasses& passes_of(Method m);

// An effect after the standard frame: its passes, conditional on `query` (passes.h). A function or a
// lambda that captures the method's state (its programs), called before add_standard_first returns.
using Effect = std::function<MainTargets(FrameGraph& fg, const FrameContext& fc, MainTargets main, Handle query)>;
// The standard-first plan: `opaque` (with the targets' codes in the stencil when an effect
// follows), the target query when a target is in view (culled if nothing reads it), then
// `effect` when given and a target is in view.
MethodFrame add_standard_first(FrameGraph& fg, const FrameContext& fc, const Effect& effect);

// A frame-coherent method's frame (dt-seed, dt-fast): `direct` (effect-first) when the last frame
// needed the effect and it can serve this one (effect_first_possible), else the standard-first
// plan with `effect`.
MethodFrame add_coherent(FrameGraph& fg, const FrameContext& fc, const MethodSlot& slot,
                         EffectFirst (*direct)(FrameGraph& fg, const FrameContext& fc), const Effect& effect);

}  // namespace dtlab::render::detail

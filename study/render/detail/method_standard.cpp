// The standard method (opaque z-buffered rendering with a headlight) and the
// standard-first plan the dynamic transparency methods share (method.h), and
// the table of every method's passes, generated from technique/settings.h's
// list. Guarantees: with no effect, the frame is the standard frame exactly.
#include <array>

#include "study/render/detail/method.h"

namespace dtlab::render::detail {

MethodFrame add_standard_first(FrameGraph& fg, const FrameContext& fc, const Effect& effect) {
  const bool targets = !fc.view.targets.empty();
  MainTargets main = add_opaque_pass(fg, fc, effect != nullptr && targets);
  MethodFrame out;
  // Declared whenever a target is in view; only the effect's passes read it, so for `standard`
  // compile() culls it. Without exact codes (more than 255 targets overlapping one another)
  // there is no query and the effect runs unconditionally.
  if (targets && !fc.view.codes_exhausted) out.occluded = add_target_query_pass(fg, fc, main.depth, 0xFF);
  if (effect != nullptr && targets) main = effect(fg, fc, main, out.occluded);
  out.color = main.color;
  return out;
}

MethodFrame add_coherent(FrameGraph& fg, const FrameContext& fc, const MethodSlot& slot,
                         EffectFirst (*direct)(FrameGraph& fg, const FrameContext& fc), const Effect& effect) {
  if (slot.effect_hint && !fc.view.targets.empty() && effect_first_possible(fc)) {
    const EffectFirst d = direct(fg, fc);
    return {d.color, d.occluded};
  }
  return add_standard_first(fg, fc, effect);
}

namespace {
MethodFrame add_standard(FrameGraph& fg, const FrameContext& fc, MethodSlot&) {
  return add_standard_first(fg, fc, nullptr);
}
}  // namespace

extern const MethodPasses k_passes_standard{nullptr, add_standard};

#define DTLAB_RENDER_DECLARE_PASSES(id) extern const MethodPasses k_passes_##id;
DTLAB_TECHNIQUE_METHODS(DTLAB_RENDER_DECLARE_PASSES)
#undef DTLAB_RENDER_DECLARE_PASSES

const MethodPasses& passes_of(Method m) {
#define DTLAB_RENDER_PASSES_ADDRESS(id) &k_passes_##id,
  static constexpr std::array kPasses{DTLAB_TECHNIQUE_METHODS(DTLAB_RENDER_PASSES_ADDRESS)};
#undef DTLAB_RENDER_PASSES_ADDRESS
  return *kPasses[static_cast<std::size_t>(m)];
}

}  // namespace dtlab::render::detail

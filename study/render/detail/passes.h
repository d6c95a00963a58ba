// Internal: the render passes each method adds to the frame graph, and the
// per-frame context they draw with. Each add_*() declares one or more passes
// (XxxPassData struct + setup that only declares + execute that only uses
// what was declared) and returns the handles later passes need.
// Guarantees: every execute sets all the GL state it relies on (no pass
// inherits state from another). Never: a pass draws to a resource it did not
// declare.
#pragma once
#include <memory>
#include <vector>

#include <glm/glm.hpp>

#include "study/render/detail/frame_view.h"
#include "study/render/detail/programs.h"
#include "study/render/detail/scene_gpu.h"
#include "study/render/detail/frame_graph.h"
#include "study/render/render.h"

namespace dtlab::render::detail {

struct FrameContext {
  const SceneGpu& gpu;
  const Programs& programs;
  const FrameView& view;
  const FrameSettings& settings;
  const scene::Scene& scene;
  TextureFormat color_format = TextureFormat::rgba8;

  int width() const { return view.width; }
  int height() const { return view.height; }
  glm::vec4 flat_color(std::uint32_t object) const;  // a > 0.5: flat colour in use
  glm::vec3 background() const;                     // black in weight mode

  // Scene geometry, lit (or flat in weight mode). With `searchlight` in active mode, fragments
  // outside the circle are discarded (the R1 guard's repair only; that variant may discard).
  void use_lit(const glm::mat4& view_proj, bool searchlight = false) const;
  void draw_lit(std::uint32_t object) const;
  // Scene geometry writing `alpha` to every channel (depth-only passes, silhouettes, queries).
  // With `searchlight` in active mode it is cut to the circle (`outside_one`: alpha 1 outside).
  void use_alpha(const glm::mat4& view_proj, float alpha, bool searchlight, bool outside_one = false) const;
  void draw_alpha(std::uint32_t object) const;
  // Binds `p` unless it is bound (every program change in a frame goes through here).
  void use_program(const Program& p) const;
  // A screen-aligned rectangle in window pixels of a w x h target, with `p` already in use.
  void quad(const Program& p, float x0, float y0, float x1, float y1, int w, int h) const;
  // The same over `r`, window pixels of this frame's view.
  void quad(const Program& p, const PixelRect& r) const;
  glm::vec3 searchlight_uniform(bool on) const;  // (x, y, r) or r = -1
  bool active() const { return view.searchlight.z >= 0.0f; }  // active mode (a searchlight)
  bool guard() const { return settings.dt.r1_guard; }

  // What this frame last set, per program (state changes cost llvmpipe far more than draws;
  // redundant glUniform calls are not filtered by Mesa). A FrameContext lives one frame.
  struct Uniforms {
    const Program* program = nullptr;
    glm::mat4 vp{0.0f};
    glm::vec3 searchlight{0.0f};
    float alpha = -1.0f;
    int outside_one = -1;
    bool valid = false;
  };
  struct Bound {
    unsigned program = 0;
    const Program* lit = nullptr;    // the lit program in use (object, object_sl, their FLAT variants, a method's)
    const Program* alpha = nullptr;  // the alpha program in use (object_alpha, object_alpha_sl, or a method's own)
    Uniforms uniforms[4];            // object or object_flat, their _sl, object_alpha, object_alpha_sl
  };
  mutable Bound bound;
  Uniforms& uniforms_of(const Program& p) const;
  bool track_impenetrable() const { return settings.dt.r1_guard && !view.impenetrable.empty(); }
};

struct MainTargets {
  Handle color;
  Handle depth;  // depth 24 + stencil 8
};

// `opaque`: clears and draws every object in view with a z-buffer (the standard frame).
// With `stencil_codes`, each target writes its code into the stencil (for the target query).
MainTargets add_opaque_pass(FrameGraph& fg, const FrameContext& fc, bool stencil_codes);
// `target-query`: one occlusion query counting target fragments hidden behind another object.
// `code_bits`: the stencil bits that hold the frontmost object's code (0xFF after `opaque`, 0x3F
// after dt-fast's `dt-direct`).
Handle add_target_query_pass(FrameGraph& fg, const FrameContext& fc, Handle depth, int code_bits);
// `present`: blits the final colour into the imported output.
void add_present_pass(FrameGraph& fg, const FrameContext& fc, Handle color, Handle output);

// dt-seed, dt-fast: the effect's passes, all conditional on `query` (unconditional if it is not
// valid: more than 255 targets overlap one another, so no query can decide).
MainTargets add_seed_passes(FrameGraph& fg, const FrameContext& fc, MainTargets main, Handle query);
MainTargets add_fast_passes(FrameGraph& fg, const FrameContext& fc, MainTargets main, Handle query);
// dt-seed, dt-fast when the previous frame needed the effect: the effect drawn directly (no
// standard frame first), each object writing its frontmost code (stencil bits 0-5) as it goes, then
// the target query on its depth; if no target turns out occluded, the pixels the effect could
// change are re-rendered the standard way (conditional on the inverted query).
struct EffectFirst {
  Handle color;     // the final colour
  Handle occluded;  // the target query ("some target is occluded")
};
EffectFirst add_seed_direct_passes(FrameGraph& fg, const FrameContext& fc);
EffectFirst add_fast_direct_passes(FrameGraph& fg, const FrameContext& fc);
// Whether the effect-first plan can serve this frame (no layer limit: bits 0-5 hold codes, and
// the target codes fit in them).
bool effect_first_possible(const FrameContext& fc);
// The effect-first plan's tail after the effect: `target-query` on `effect.depth` (codes in bits
// 0-5), `query-invert` ("no target occluded" as a query of its own, on the GPU), and
// `standard-fallback`, conditional on that, which clears each of `regions` and draws every object
// overlapping it exactly as `opaque` does.
EffectFirst add_effect_first_tail(FrameGraph& fg, const FrameContext& fc, MainTargets effect,
                                  std::shared_ptr<const std::vector<PixelRect>> regions);
// reference: per-object layers rendered on the GPU, composited exactly on the CPU.
Handle add_reference_pass(FrameGraph& fg, const FrameContext& fc);

// Shared GL sequences of the two GPU methods.
//
// Stencil layout while the effect is drawn (docs/render.md, "Stencil"):
//   bit 7     a target's mark: its silhouette during its mask steps; before that, "this target
//             is frontmost here" (for the R1 guard's repair, which also sets it once per pixel);
//   bit 6     "the frontmost surface is impenetrable" (kept only when the R1 guard is on and an
//             impenetrable object is in view);
//   bits 0-5  the frontmost object's code (target query), or the layer-limit counter.
struct StencilWrite {  // written where an object's draw passes the depth test
  int ref = 0;
  int mask = 0;       // 0: no stencil writes
  bool mark = false;  // also set bit 7 (a target's mark: where it is frontmost when drawn)
};
// What object `i`'s draw writes: with `codes`, its code (0 for non-targets); bit 6 when tracked;
// bit 7 for a target under the R1 guard.
StencilWrite object_stencil(const FrameContext& fc, std::uint32_t i, bool codes);

// Clears colour (to the background, alpha 1), depth (1) and stencil (0) of the bound framebuffer
// within the scissor, if enabled; leaves every write mask on.
void clear_to_background(const FrameContext& fc);
// Sets the scissor box to `r` (window pixels; the caller enables the test).
void scissor(const PixelRect& r);
// clear_to_background over `region` only (scissor set to it; the caller enables the test).
void clear_region(const FrameContext& fc, const PixelRect& region);

// Draws object `i` of a back-to-front sequence so that only its frontmost surfaces blend with
// the destination alpha (article V.3): a depth pass, then a colour pass with depth EQUAL; or,
// with `single_pass` and a convex object seen from outside, one back-face-culled pass (the same
// surfaces). Applies the layer limit's stencil logic and, for a target, the R1 guard's floor.
void draw_transparent_object(const FrameContext& fc, std::uint32_t i, bool single_pass, StencilWrite sw);
// Draws object `i` with a plain z-buffer and no blending: where no mask can apply (alpha is 1).
// `depth_func` GL_LEQUAL gives ties to the later object, as a depth-EQUAL colour pass does.
void draw_opaque_object(const FrameContext& fc, std::uint32_t i, StencilWrite sw = {}, unsigned depth_func = 0x0201);
// R1 guard, step 2: target `i`'s fragments hidden by something drawn before it (a sort error),
// except behind impenetrable surfaces, blended once per pixel as c (1 - aT) + C aT.
void repair_target(const FrameContext& fc, std::uint32_t i);
// The same repair fused with mark_target, for a target drawn in one culled pass (convex, seen
// from outside, outline mask): each of its front-face fragments sets bit 7 whatever the tests
// say, and blends only where hidden by something drawn earlier and not impenetrable.
void repair_and_mark_target(const FrameContext& fc, std::uint32_t i);
// Target `slot`'s silhouette (outline: its mesh through `view_proj`) or shape (circle /
// ellipse: window pixel p maps to p * px_map.xy + px_map.zw of the bound framebuffer), with
// whatever colour/stencil state the caller set (the program is chosen here). With
// `searchlight`, active mode cuts it to the circle (`outside_one`: alpha 1 outside instead).
void draw_target_seed(const FrameContext& fc, int slot, float alpha, const glm::mat4& view_proj,
                      glm::vec4 px_map, bool searchlight, bool outside_one = false);
// The three framebuffer steps of a target's mask (Algorithm 2, lines 10-11): mark_target sets
// bit 7 on its whole full-resolution silhouette; between begin_apply and the caller's quad, the
// mask multiplies into alpha outside the mark; finish_target multiplies aT into the marked
// silhouette (inside the searchlight) and clears the mark. With `keep_codes` bits 0-5 are left
// alone; otherwise they are the layer-limit counter, restarted at 1 where alpha drops.
void mark_target(const FrameContext& fc, int slot, bool keep_codes);
// State for drawing into a plain buffer (a mask page): no depth, stencil, blending or culling,
// every colour channel written.
void buffer_state();
// State for multiplying into the framebuffer's alpha only (blend dst.a *= src.a): no depth test or
// writes, no culling, the stencil test on (the caller sets its function and operations).
void alpha_multiply_state();
void begin_apply(const FrameContext& fc, bool keep_codes);
void finish_target(const FrameContext& fc, int slot);
// Binds the quad program that multiplies aT into alpha inside the searchlight (1, no change,
// outside it): a marked silhouette's step, for FrameContext::quad under the caller's stencil test.
const Program& use_target_alpha_quad(const FrameContext& fc);

}  // namespace dtlab::render::detail

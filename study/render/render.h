// The dtlab renderer: draws a scene::Scene with one of seven methods through
// a frame graph (detail/frame_graph.h), into a caller-owned target (a window's
// default framebuffer or an offscreen framebuffer), in any GL 3.3 core
// context (the platform layer makes one). Methods (docs/render.md):
//   standard   opaque z-buffered rendering with a headlight;
//   dt-seed    the article's image-space dynamic transparency, faithfully
//              (object-level back-to-front order, per-target 128x128 masks
//              grown by ping-pong border passes);
//   dt-fast    the same visual model at close to standard's cost (all masks
//              at once in a reduced-resolution atlas, scissored regions);
//   reference  exact per-pixel compositing on the CPU (the error yardstick);
//   lens       Ropinski & Hinrichs's volumetric 3D magic lens (a convex lens volume, a second
//              depth test against its back- and front-face depth maps, three scene passes);
//   screen-door  dt-seed's picture by Poon's (2000) sub-pixel screen-door transparency: each
//              surface's alpha picks an n-pixel mask, z-buffered on an enlarged buffer, box-filtered;
//   vdt        Diepstraten, Weiskopf & Ertl's view-dependent transparency (distractors transparent,
//              targets and impenetrable surfaces opaque; image-space depth peeling of two layers).
// Guarantees: the GL state of the caller is restored after every call that
// draws; an effect the frame does not call for (transparency off, no target
// in view) runs no pass; with no target occluded the picture is standard's:
// dt-seed and dt-fast decide on the GPU, and run no effect pass when the
// previous frame needed none (standard-first plan), else draw the effect and
// then standard's frame again (effect-first plan, docs/render.md). Never:
// creates a GL context, reads files, or includes GL headers in this public
// header.
#pragma once
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <glm/glm.hpp>

#include "study/common/error.h"
#include "study/render/camera.h"
#include "study/render/frame_report.h"
#include "study/render/image.h"
#include "study/scene/scene.h"

namespace dtlab::render {

enum class Method { standard, dt_seed, dt_fast, reference, lens, screen_door, vdt };
// "standard", "dt-seed", "dt-fast", "reference", "lens", "screen-door", "vdt"
std::string_view to_string(Method m);
std::optional<Method> parse_method(std::string_view s);  // inverse of to_string; nullopt if unknown
// Dynamic transparency (target-driven masks): dt-seed, dt-fast, reference, screen-door. Not vdt: its
// transparency is per object class and the same whether or not a target is occluded (no masks, no
// target query).
bool uses_transparency(Method m);

enum class MaskShape { outline, circle, ellipse };
std::string_view to_string(MaskShape s);
std::optional<MaskShape> parse_mask_shape(std::string_view s);

enum class DtMode { passive, active };  // passive: whole view; active: searchlight circle only

// Parameters of dynamic transparency (docs/render.md, "The visual model").
struct DtSettings {
  float alpha_target = 0.3f;    // aT in [0, 1): weight of a surface in front of a target
  float alpha_start = 0.1f;     // a0 in [0,1): weight of a surface next to the target's outline
  float gradient_px = 24.0f;    // n >= 0: the weight rises from a0 to 1 over n output pixels (Chebyshev)
  int mask_resolution = 128;    // mask buffer side R (R x R as in the article); 0 = full resolution;
                                // at most max_mask_resolution() of the view
  MaskShape shape = MaskShape::outline;
  DtMode mode = DtMode::passive;
  glm::vec2 searchlight_center{0.0f};  // active mode: output pixels, origin top-left (a cursor position)
  float searchlight_radius = 120.0f;   // active mode: output pixels
  int layer_limit = 0;          // at most this many transparent surfaces in front of a target; 0 = no limit (max 60)
  // R1 guard, off by default (the article's algorithm as printed; docs/render.md, "R1 guard"): on,
  // (1) a target is never blended with less than aT weight (the alpha at its own frontmost pixels
  // is raised to at least aT before it is drawn); (2) where an object the back-to-front sort drew
  // too early hides a target, the target is blended over it with weight 1 - aT (never behind
  // impenetrable surfaces). Off, a target standing in the gradient of a farther target fades to
  // a0 or below, and a sort error hides a target completely (both measured).
  bool r1_guard = false;
};
// The settings a DtSettings value is checked on; callers map them to what their user wrote (a
// command-line option, a protocol key).
enum class DtField { alpha_target, alpha_start, gradient, mask_resolution, layer_limit, searchlight };
std::string_view to_string(DtField f);  // the DtSettings member: "alpha_target", ...
struct SettingsProblem {
  DtField field;
  std::string message;  // what was expected, e.g. "must be below 1 (got 1)"
};
// The finest mask a width x height view can use: its longer side (a finer buffer than the view
// changes nothing but the cost: dt-seed draws R x R n' times per target), or the article's 128.
int max_mask_resolution(int width, int height);
// Checks every range, and with a view (width, height > 0) that mask_resolution is at most
// max_mask_resolution(width, height). nullopt when the settings are fine. aT and a0 must be below
// 1: Algorithm 3 finds the target by its alpha differing from 1, and rule R2 makes occluders
// transparent (aT = 1 would leave them opaque).
std::optional<SettingsProblem> check(const DtSettings& s, int width = 0, int height = 0);
// Throws std::invalid_argument "DtSettings.<field>: <message>" if check() finds a problem.
void validate(const DtSettings& s, int width = 0, int height = 0);
// The article's unit: `mask_pixels` of a `mask_resolution`-square mask over a width x height
// view, in output pixels (the protocol's gradient_width is in mask pixels).
float gradient_px_from_mask_pixels(float mask_pixels, int mask_resolution, int width, int height);

// The lens method (docs/render.md, "lens"): a convex lens volume on the view ray through `center`.
enum class LensShape { sphere, box, cylinder, cone };
std::string_view to_string(LensShape s);  // "sphere", "box", "cylinder", "cone"
std::optional<LensShape> parse_lens_shape(std::string_view s);
// What the lens does to the geometry inside it: eraser removes every distractor inside (targets and
// impenetrable surfaces stay, drawn normally); wireframe draws it as lines; tint mixes in a colour.
enum class LensStyle { eraser, wireframe, tint };
std::string_view to_string(LensStyle s);  // "eraser", "wireframe", "tint"
std::optional<LensStyle> parse_lens_style(std::string_view s);

// The lens volume in the camera's frame: its axis is the view ray through `center`; sizes are in
// world units. sphere: `radius` around the centre; box: a cube of half-side `radius` whose faces
// are square to the ray (depth `length`); cylinder: `radius`, `length` along the ray; cone: apex
// just behind the eye, radius `radius` at the centre, closed by a disc `length` / 2 beyond it.
struct LensSettings {
  LensShape shape = LensShape::sphere;
  LensStyle style = LensStyle::eraser;
  glm::vec2 center{0.0f};    // output pixels, origin top-left (a cursor position)
  bool follows_cursor = false;  // active mode: a session moves `center` to the cursor every frame
  float distance = 10.0f;    // eye to the lens centre along the ray, > 0
  float radius = 2.0f;       // > 0
  float length = 4.0f;       // box, cylinder, cone: extent along the ray (> 0); sphere: unused
  glm::vec3 tint{1.0f, 0.55f, 0.1f};  // tint style: the colour mixed in
  float tint_strength = 0.5f;         // tint style: its weight, [0, 1]
};
// nullopt when fine; else what is wrong, naming the member ("radius must be > 0 (got -1)").
std::optional<std::string> check(const LensSettings& s);
// A lens sized to `scene` at the centre of a width x height view: distance = the orbit distance
// (ABSTRACT: centred on the orbit centre) or two floor-plan cells (WALKTHROUGH); radius = a
// quarter of the view's half-height at that distance; length = 2 x radius.
LensSettings scene_lens(const scene::Scene& scene, int width, int height);

// The screen-door method (docs/render.md, "screen-door"; Poon 2000, chapter 4): each output pixel is
// an s x s block of sub-pixels of an enlarged buffer, each surface keeps the sub-pixels of its mask.
enum class ScreenDoorMasks { tabular, pixel_tree, white_noise };  // tabular: with neighbourhood compensation
std::string_view to_string(ScreenDoorMasks m);  // "tabular", "pixel-tree", "white-noise"
std::optional<ScreenDoorMasks> parse_screen_door_masks(std::string_view s);
struct ScreenDoorSettings {
  int mask_side = 8;  // s: 8 (the thesis's practical size), 16 or 32; a mask has s x s pixels
  ScreenDoorMasks masks = ScreenDoorMasks::tabular;
};
// nullopt when fine; else what is wrong ("mask_side must be 8, 16 or 32 (got 5)").
std::optional<std::string> check(const ScreenDoorSettings& s);
// The vdt method (docs/render.md, "vdt"): Diepstraten, Weiskopf & Ertl (2002). Distractors are
// transparent; targets and impenetrable surfaces opaque. A transparent surface's alpha is eq. (2),
// 1 - (d_min / d_object,max)^k per vertex (d_min: distance to its nearest silhouette edge); the final
// colour is alpha C_transparent + a_dst C_behind (GL_SRC_ALPHA, GL_DST_ALPHA), where a_dst is the
// fixed alpha of the opaque object behind, or of the background.
struct VdtSettings {
  float falloff = 0.5f;           // k in [0, 1]: the paper's "falling off term"
  float opaque_alpha = 0.5f;      // [0, 1]: weight of an opaque object seen through a transparent one
  float background_alpha = 0.5f;  // [0, 1]: weight of the background (the paper suggests 0.5)
};
// nullopt when fine; else what is wrong, naming the member ("falloff must be 0..1 (got 2)").
std::optional<std::string> check(const VdtSettings& s);

struct FrameSettings {
  Method method = Method::standard;
  DtSettings dt;
  LensSettings lens;  // method lens only
  ScreenDoorSettings screen_door;  // method screen-door only
  VdtSettings vdt;    // method vdt only
  glm::vec3 background{0.80f, 0.82f, 0.86f};  // linear RGB of pixels no object covers
  bool float_color = false;   // RGBA16F colour buffer instead of RGBA8 (tests scan it for NaN)
  bool timed = false;         // glFinish at the end and report frame_ms (benchmarks, --frames)
  bool profile_passes = false;  // glFinish after every pass; PassRecord::ms (slows the frame; debugging)
  // Poon's occlusion culling (WALKTHROUGH only; docs/render.md): objects hidden behind the nearest
  // grid point's occluders are not drawn. The picture is unchanged under every method.
  bool occlusion_culling = false;
  // Flat colours per object index (unlit, exact): the weight mode used to count visible pixels.
  // Empty: normal shading. Objects beyond the vector's size are black.
  std::vector<glm::vec3> flat_colors;
};

struct TargetVisibility {
  std::uint32_t id = 0;            // Object::id
  long silhouette_pixels = 0;      // pixels the target covers in the viewport, ignoring every other object
  long visible_pixels = 0;         // pixels where the target contributes >= kVisibleShare of the final colour
};
inline constexpr float kVisibleShare = 0.10f;  // docs/render.md, "Visible pixels"

// A renderer bound to one scene and to the GL context current at create().
class Renderer {
 public:
  // Compiles the shaders and uploads the meshes. Needs a current GL 3.3 core context.
  // Fails (Error with the shader's name and the compiler's log) if a shader does not compile.
  static Result<std::unique_ptr<Renderer>> create(const scene::Scene& scene);
  ~Renderer();
  Renderer(const Renderer&) = delete;
  Renderer& operator=(const Renderer&) = delete;

  // Renders one frame of target.width x target.height pixels and presents it into `target`
  // (blit). Keeps the context's GL state as it was. The report names the passes that ran.
  FrameReport render(const Camera& camera, const FrameSettings& settings, const ImportedTarget& target);
  // Renders into an internal offscreen target of width x height (no caller framebuffer needed).
  FrameReport render_offscreen(const Camera& camera, const FrameSettings& settings, int width, int height);

  // The last frame's final colour, RGBA8, top row first (alpha: the cumulative alpha buffer).
  Image read_color() const;
  // The last frame's final colour as RGBA floats, bottom row first (exact when rendered with float_color).
  std::vector<float> read_color_float() const;

  // Per-target silhouette and visible pixel counts under `settings.method`, computed with the
  // method's own passes (flat weight colours, 3 targets per frame). Targets in scene order.
  std::vector<TargetVisibility> visibility(const Camera& camera, FrameSettings settings, int width, int height);

  // The effect region: pixels where some target in view has an exact mask below 1 (its
  // silhouette or shape grown by the gradient, at full resolution as `reference` draws it; in
  // active mode cut to the searchlight), one byte per pixel (1 = in), top row first as Image.
  std::vector<std::uint8_t> effect_region(const Camera& camera, const DtSettings& dt, int width, int height);

  // Builds now what the first frame drawn with `settings` would otherwise build inside it: the
  // occluder database of occlusion culling (FrameSettings::occlusion_culling on a scene with a
  // floor plan; 0.3-0.8 s for a WALKTHROUGH). A session calls it before a trial's first frame so
  // that the frame is not late. Returns the milliseconds it took (0: nothing to build). CPU only.
  double prepare(const FrameSettings& settings);

  // The last frame's graph in Graphviz dot syntax (culled passes grey).
  const std::string& last_graphviz() const;
  const scene::Scene& scene() const;

 private:
  struct Impl;
  explicit Renderer(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

}  // namespace dtlab::render

// The settings of every rendering method, in one table: the typed settings
// each method draws with (the renderer's units: output pixels, world units)
// and the protocol keys each method reads (the author's units: mask pixels,
// shares of the view), with the lists that generate the registry's tables
// (technique.h). Guarantees: GL-free and scene-free (the protocol stage reads
// it); every range check of a method's settings is the method's own, here.
// Never: parses text or knows a file format (technique.h's KeyReader does).
#pragma once
#include <cstddef>
#include <optional>
#include <string>
#include <string_view>

#include <glm/glm.hpp>

namespace dtlab::technique {

// Every rendering method, in Method order; each X(id) has a registration `k_method_<id>` in the
// file that implements it (technique.h). A new method adds one line here.
#define DTLAB_TECHNIQUE_METHODS(X) \
  X(standard) X(dt_seed) X(dt_fast) X(reference) X(lens) X(screen_door) X(vdt) X(ghosting)

enum class Method {
#define DTLAB_TECHNIQUE_ENUM(id) id,
  DTLAB_TECHNIQUE_METHODS(DTLAB_TECHNIQUE_ENUM)
#undef DTLAB_TECHNIQUE_ENUM
};
#define DTLAB_TECHNIQUE_ONE(id) +1
inline constexpr std::size_t kMethodCount = 0 DTLAB_TECHNIQUE_METHODS(DTLAB_TECHNIQUE_ONE);
#undef DTLAB_TECHNIQUE_ONE

// --- dynamic transparency (dt-seed, dt-fast, reference, screen-door) -------------------------

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
  // R1 guard, off in a bare DtSettings (the article's algorithm as printed; docs/render.md, "R1
  // guard"); a protocol's r1_guard key and `dtlab render` turn it on by default. On, (1) a target
  // is never blended with less than aT weight (the alpha at its own frontmost pixels is raised to
  // at least aT before it is drawn); (2) where an object the back-to-front sort drew too early
  // hides a target, the target is blended over it with weight 1 - aT (never behind impenetrable
  // surfaces). Off, a target standing in the gradient of a farther target fades to a0 or below,
  // and a sort error hides a target completely (both measured).
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
// The article's unit: `mask_pixels` of a `mask_resolution`-square mask over a width x height
// view, in output pixels (the protocol's gradient_width is in mask pixels).
float gradient_px_from_mask_pixels(float mask_pixels, int mask_resolution, int width, int height);

// --- lens (Ropinski & Hinrichs 2004) ----------------------------------------------------------

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

// --- screen-door (Poon 2000, chapter 4) -------------------------------------------------------

// Each output pixel is an s x s block of sub-pixels of an enlarged buffer, each surface keeps the
// sub-pixels of its mask.
enum class ScreenDoorMasks { tabular, pixel_tree, white_noise };  // tabular: with neighbourhood compensation
std::string_view to_string(ScreenDoorMasks m);  // "tabular", "pixel-tree", "white-noise"
std::optional<ScreenDoorMasks> parse_screen_door_masks(std::string_view s);
struct ScreenDoorSettings {
  int mask_side = 8;  // s: 8 (the thesis's practical size), 16 or 32; a mask has s x s pixels
  ScreenDoorMasks masks = ScreenDoorMasks::tabular;
};
// nullopt when fine; else what is wrong ("mask_side must be 8, 16 or 32 (got 5)").
std::optional<std::string> check(const ScreenDoorSettings& s);

// --- vdt (Diepstraten, Weiskopf & Ertl 2002) --------------------------------------------------

// Distractors are transparent; targets and impenetrable surfaces opaque. A transparent surface's
// alpha is eq. (2), 1 - (d_min / d_object,max)^k per vertex (d_min: distance to its nearest
// silhouette edge); the final colour is alpha C_transparent + a_dst C_behind (GL_SRC_ALPHA,
// GL_DST_ALPHA), where a_dst is the fixed alpha of the opaque object behind, or of the background.
struct VdtSettings {
  float falloff = 0.5f;           // k in [0, 1]: the paper's "falling off term"
  float opaque_alpha = 0.5f;      // [0, 1]: weight of an opaque object seen through a transparent one
  float background_alpha = 0.5f;  // [0, 1]: weight of the background (the paper suggests 0.5)
};
// nullopt when fine; else what is wrong, naming the member ("falloff must be 0..1 (got 2)").
std::optional<std::string> check(const VdtSettings& s);

// --- ghosting ---------------------------------------------------------------------------------

// Every distractor in front of a target in view is drawn as a ghost: at a fixed weight over what it
// hides, with its edges (silhouettes, creases) drawn as opaque lines (docs/render.md, "ghosting").
struct GhostingSettings {
  float alpha = 0.25f;  // [0, 1): weight of a ghost's surface
  bool edges = true;    // draw the ghosts' edges as dark opaque lines
};
// nullopt when fine; else what is wrong, naming the member.
std::optional<std::string> check(const GhostingSettings& s);

// --- what a frame draws with, what a protocol holds -------------------------------------------

// The settings of every method a frame can draw (render::FrameSettings is one); a method reads
// only its own. A new method with settings adds one line here.
#define DTLAB_TECHNIQUE_FRAME_GROUPS(X) \
  X(dt, DtSettings) X(lens, LensSettings) X(screen_door, ScreenDoorSettings) X(vdt, VdtSettings) \
  X(ghosting, GhostingSettings)
struct MethodSettings {
  Method method = Method::standard;
#define DTLAB_TECHNIQUE_MEMBER(member, Type) Type member;
  DTLAB_TECHNIQUE_FRAME_GROUPS(DTLAB_TECHNIQUE_MEMBER)
};

// The protocol keys of [rendering.*] in the author's units, one struct per key group (a group is
// read by every method that lists it; technique.h). Defaults are the protocol's.
struct DtKeys {                       // dt-seed, dt-fast, reference, screen-door
  double a0 = 0.1;                    // alpha where the mask gradient starts (next to the target)
  double aT = 0.3;                    // alpha of surfaces directly in front of a target
  int gradient_width = 8;             // n: gradient width in mask pixels
  int mask_resolution = 128;          // mask buffer is mask_resolution x mask_resolution
  std::string mask_shape = "outline"; // "outline" | "circle" | "ellipse"
  std::string mode = "passive";       // "passive" (whole view) | "active" (searchlight; a lens: follows the
                                      // cursor) | "fixed" (a lens at the view's centre; the lens's default)
  int layer_limit = 0;                // most surfaces made transparent in front of a target; 0 = no limit
  double searchlight_radius = 0.2;    // mode = "active": the searchlight's radius as a share of the view's
                                      // height (0.2 = 120 pixels at the article's 800 x 600)
};
struct CullingKeys {                  // every method
  bool occlusion_culling = false;     // Poon's occlusion culling in WALKTHROUGH scenes (the picture is unchanged)
};
struct GuardKeys {                    // the dynamic transparency methods: the R1 guard (docs/render.md)
  bool r1_guard = true;               // false: the article's algorithm as printed
};
struct LensKeys {                     // lens; sizes in world units (the scene's own scale)
  std::string shape = "sphere";       // "sphere" | "box" | "cylinder" | "cone"
  std::string style = "eraser";       // "eraser" | "wireframe" | "tint"
  double radius = 0.0;                // required with lens
  double distance = 0.0;              // eye to lens centre along the cursor's ray; required with lens
  double length = 0.0;                // box, cylinder, cone: extent along the ray; 0 = 2 x radius
};
struct ScreenDoorKeys {               // screen-door
  int screen_door_mask = 8;                        // mask side in sub-pixels: 8, 16 or 32
  std::string screen_door_generation = "tabular";  // "tabular" | "pixel-tree" | "white-noise"
};
struct VdtKeys {                      // vdt: eq. (2)'s k and the fixed blend weights, each in [0, 1]
  double falloff = 0.5;
  double opaque_alpha = 0.5;
  double background_alpha = 0.5;
};

// Every key group, in the order of the design hash; each X(member, Type) has a registration
// `k_keys_<member>` in the file that reads it (technique.h). A new method with protocol keys adds
// one line here (its keys may be its frame settings, as ghosting's are).
#define DTLAB_TECHNIQUE_KEY_GROUPS(X) \
  X(dt, DtKeys) X(culling, CullingKeys) X(guard, GuardKeys) X(lens, LensKeys) X(screen_door, ScreenDoorKeys) \
  X(vdt, VdtKeys) X(ghosting, GhostingSettings)
struct Keys {
  DTLAB_TECHNIQUE_KEY_GROUPS(DTLAB_TECHNIQUE_MEMBER)
};
#undef DTLAB_TECHNIQUE_MEMBER

}  // namespace dtlab::technique

// The dtlab renderer: draws a scene::Scene with one of the methods of the
// technique registry (study/technique/settings.h lists them, docs/render.md
// describes each) through a frame graph
// (detail/frame_graph.h), into a caller-owned target (a window's default
// framebuffer or an offscreen framebuffer), in any GL 3.3 core context (the
// platform layer makes one). Each method registers its passes in
// detail/method_<name>.cpp (detail/method.h); no code here names one.
// Guarantees: the GL state of the caller is restored after every call that
// draws; an effect the frame does not call for (transparency off, no target
// in view) runs no pass; with no target occluded the picture is standard's:
// dt-seed and dt-fast decide on the GPU, and run no effect pass when the
// previous frame needed none (standard-first plan), else draw the effect and
// then standard's frame again (effect-first plan, docs/render.md). Errors:
// every public function returns Result/Status, never throws: settings out of
// range or a bad size -> invalid_input; the GL out of memory, a lost context,
// a framebuffer the driver calls incomplete, a failed allocation ->
// environment; a broken internal promise -> internal (docs/render.md,
// "Errors"). Never: creates a GL context, reads files, or includes GL headers
// in this public header.
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
#include "study/technique/technique.h"

namespace dtlab::render {

// What a method is and the settings it draws with live in the technique registry
// (study/technique: GL-free, read by the protocol and the session too); the renderer uses them
// under these names.
using technique::check;
using technique::DtField;
using technique::DtMode;
using technique::DtSettings;
using technique::gradient_px_from_mask_pixels;
using technique::LensSettings;
using technique::LensShape;
using technique::LensStyle;
using technique::MaskShape;
using technique::max_mask_resolution;
using technique::Method;
using technique::parse_lens_shape;
using technique::parse_lens_style;
using technique::parse_mask_shape;
using technique::parse_method;
using technique::parse_screen_door_masks;
using technique::ScreenDoorMasks;
using technique::ScreenDoorSettings;
using technique::SettingsProblem;
using technique::to_string;
using technique::uses_transparency;
using technique::VdtSettings;

// check() as a Status: an invalid_input Error, field "DtSettings.<field>", when it finds a problem.
Status validate(const DtSettings& s, int width = 0, int height = 0);
// A lens sized to `scene` at the centre of a width x height view: distance = the orbit distance
// (ABSTRACT: centred on the orbit centre) or two floor-plan cells (WALKTHROUGH); radius = a
// quarter of the view's half-height at that distance; length = 2 x radius.
LensSettings scene_lens(const scene::Scene& scene, int width, int height);

// A frame's method and its settings (technique::MethodSettings: method, dt, lens, screen_door,
// vdt, ghosting; a method reads only its own), and how the frame is drawn.
struct FrameSettings : technique::MethodSettings {
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

// A renderer bound to one scene and to the GL context current at create(). No member throws: a
// failure is an Error (field "render", the message starting with the function's name). After an
// environment Error the renderer may be called again (the next frame starts from scratch) or
// destroyed; the failed frame's picture is undefined.
class Renderer {
 public:
  // Compiles the shaders and uploads the meshes. Needs a current GL 3.3 core context.
  // Fails (Error with the shader's name and the compiler's log) if a shader does not compile,
  // (environment) if an allocation fails.
  static Result<std::unique_ptr<Renderer>> create(const scene::Scene& scene);
  ~Renderer();
  Renderer(const Renderer&) = delete;
  Renderer& operator=(const Renderer&) = delete;

  // Renders one frame of target.width x target.height pixels and presents it into `target`
  // (blit). Keeps the context's GL state as it was. The report names the passes that ran.
  // Errors: invalid_input for a non-positive size or settings out of range (check()); environment
  // when the GL runs out of memory, loses its context or calls a framebuffer incomplete (e.g. a
  // size beyond GL_MAX_TEXTURE_SIZE); other GL errors stay in FrameReport::gl_errors.
  [[nodiscard]] Result<FrameReport> render(const Camera& camera, const FrameSettings& settings,
                                           const ImportedTarget& target);
  // Renders into an internal offscreen target of width x height, each 1..16384 (no caller
  // framebuffer needed). Errors as render().
  [[nodiscard]] Result<FrameReport> render_offscreen(const Camera& camera, const FrameSettings& settings, int width,
                                                     int height);

  // The last frame's final colour, RGBA8, top row first (alpha: the cumulative alpha buffer);
  // empty before the first frame. Errors: environment (GL out of memory, context lost).
  [[nodiscard]] Result<Image> read_color() const;
  // The last frame's final colour as RGBA floats, bottom row first (exact when rendered with
  // float_color); empty before the first frame. Errors as read_color().
  [[nodiscard]] Result<std::vector<float>> read_color_float() const;

  // Per-target silhouette and visible pixel counts under `settings.method`, computed with the
  // method's own passes (flat weight colours, 3 targets per frame). Targets in scene order.
  // Errors as render().
  [[nodiscard]] Result<std::vector<TargetVisibility>> visibility(const Camera& camera, FrameSettings settings,
                                                                 int width, int height);

  // The effect region: pixels where some target in view has an exact mask below 1 (its
  // silhouette or shape grown by the gradient, at full resolution as `reference` draws it; in
  // active mode cut to the searchlight), one byte per pixel (1 = in), top row first as Image.
  // Sizes 1..16384. Errors as render().
  [[nodiscard]] Result<std::vector<std::uint8_t>> effect_region(const Camera& camera, const DtSettings& dt, int width,
                                                                int height);

  // Builds now what the first frame drawn with `settings` would otherwise build inside it: the
  // occluder database of occlusion culling (FrameSettings::occlusion_culling on a scene with a
  // floor plan; 0.3-0.8 s for a WALKTHROUGH). A session calls it before a trial's first frame so
  // that the frame is not late. Returns the milliseconds it took (0: nothing to build). CPU only.
  // Errors: environment when an allocation fails.
  [[nodiscard]] Result<double> prepare(const FrameSettings& settings);

  // The last frame's graph in Graphviz dot syntax (culled passes grey).
  const std::string& last_graphviz() const;
  const scene::Scene& scene() const;

 private:
  struct Impl;
  explicit Renderer(std::unique_ptr<Impl> impl);
  // The bodies of render(), visibility() and effect_region() after their argument checks; they
  // may throw (detail/boundary.h), the public functions turn that into an Error.
  FrameReport draw_frame(const Camera& camera, const FrameSettings& settings, const ImportedTarget& target);
  std::vector<TargetVisibility> count_visibility(const Camera& camera, FrameSettings settings, int width, int height);
  std::vector<std::uint8_t> region_mask(const Camera& camera, const DtSettings& dt, int width, int height);
  std::unique_ptr<Impl> impl_;
};

}  // namespace dtlab::render

// The Renderer (see render.h): owns the scene's GPU data, the programs, the
// frame graph backend and the group order; builds one frame graph per frame
// from the method and what the frame calls for.
#include <glad/gl.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "study/render/detail/gl_state.h"
#include "study/render/detail/lens_volume.h"
#include "study/render/detail/passes.h"
#include "study/render/detail/renderer_impl.h"
#include "study/render/render.h"

namespace dtlab::render {

std::string_view to_string(Method m) {
  switch (m) {
    case Method::standard: return "standard";
    case Method::dt_seed: return "dt-seed";
    case Method::dt_fast: return "dt-fast";
    case Method::reference: return "reference";
    case Method::lens: return "lens";
    case Method::screen_door: return "screen-door";
    case Method::vdt: return "vdt";
  }
  return "?";
}

std::optional<Method> parse_method(std::string_view s) {
  for (Method m : {Method::standard, Method::dt_seed, Method::dt_fast, Method::reference, Method::lens,
                   Method::screen_door, Method::vdt})
    if (to_string(m) == s) return m;
  return std::nullopt;
}

bool uses_transparency(Method m) {
  return m == Method::dt_seed || m == Method::dt_fast || m == Method::reference || m == Method::screen_door;
}

std::string_view to_string(ScreenDoorMasks m) {
  switch (m) {
    case ScreenDoorMasks::tabular: return "tabular";
    case ScreenDoorMasks::pixel_tree: return "pixel-tree";
    case ScreenDoorMasks::white_noise: return "white-noise";
  }
  return "?";
}

std::optional<ScreenDoorMasks> parse_screen_door_masks(std::string_view s) {
  for (ScreenDoorMasks m : {ScreenDoorMasks::tabular, ScreenDoorMasks::pixel_tree, ScreenDoorMasks::white_noise})
    if (to_string(m) == s) return m;
  return std::nullopt;
}

std::optional<std::string> check(const ScreenDoorSettings& s) {
  if (s.mask_side == 8 || s.mask_side == 16 || s.mask_side == 32) return std::nullopt;
  return "mask_side must be 8, 16 or 32 (got " + std::to_string(s.mask_side) + ")";
}

std::string_view to_string(LensShape s) {
  switch (s) {
    case LensShape::sphere: return "sphere";
    case LensShape::box: return "box";
    case LensShape::cylinder: return "cylinder";
    case LensShape::cone: return "cone";
  }
  return "?";
}

std::optional<LensShape> parse_lens_shape(std::string_view s) {
  for (LensShape v : {LensShape::sphere, LensShape::box, LensShape::cylinder, LensShape::cone})
    if (to_string(v) == s) return v;
  return std::nullopt;
}

std::string_view to_string(LensStyle s) {
  switch (s) {
    case LensStyle::eraser: return "eraser";
    case LensStyle::wireframe: return "wireframe";
    case LensStyle::tint: return "tint";
  }
  return "?";
}

std::optional<LensStyle> parse_lens_style(std::string_view s) {
  for (LensStyle v : {LensStyle::eraser, LensStyle::wireframe, LensStyle::tint})
    if (to_string(v) == s) return v;
  return std::nullopt;
}

std::optional<std::string> check(const LensSettings& s) {
  auto positive = [](const char* name, float v) -> std::optional<std::string> {
    if (v > 0.0f && std::isfinite(v)) return std::nullopt;
    std::ostringstream o;
    o << name << " must be finite and > 0 (got " << v << ")";
    return o.str();
  };
  if (auto p = positive("distance", s.distance)) return p;
  if (auto p = positive("radius", s.radius)) return p;
  if (auto p = positive("length", s.length)) return p;
  if (!std::isfinite(s.center.x) || !std::isfinite(s.center.y)) return std::string("center must be finite");
  if (!(s.tint_strength >= 0.0f && s.tint_strength <= 1.0f)) {
    std::ostringstream o;
    o << "tint_strength must be 0..1 (got " << s.tint_strength << ")";
    return o.str();
  }
  if (!(glm::all(glm::greaterThanEqual(s.tint, glm::vec3(0.0f))) && glm::all(glm::lessThanEqual(s.tint, glm::vec3(1.0f)))))
    return std::string("tint must be an RGB colour in 0..1");
  return std::nullopt;
}

std::string_view to_string(MaskShape s) {
  switch (s) {
    case MaskShape::outline: return "outline";
    case MaskShape::circle: return "circle";
    case MaskShape::ellipse: return "ellipse";
  }
  return "?";
}

std::optional<MaskShape> parse_mask_shape(std::string_view s) {
  for (MaskShape m : {MaskShape::outline, MaskShape::circle, MaskShape::ellipse})
    if (to_string(m) == s) return m;
  return std::nullopt;
}

std::string_view to_string(DtField f) {
  switch (f) {
    case DtField::alpha_target: return "alpha_target";
    case DtField::alpha_start: return "alpha_start";
    case DtField::gradient: return "gradient_px";
    case DtField::mask_resolution: return "mask_resolution";
    case DtField::layer_limit: return "layer_limit";
    case DtField::searchlight: return "searchlight";
  }
  return "?";
}

int max_mask_resolution(int width, int height) { return std::max({128, width, height}); }

std::optional<SettingsProblem> check(const DtSettings& s, int width, int height) {
  auto got = [](double v) {
    std::ostringstream o;
    o << " (got " << v << ")";
    return o.str();
  };
  if (!(s.alpha_target >= 0.0f && s.alpha_target < 1.0f))
    return SettingsProblem{DtField::alpha_target, "must be at least 0 and below 1" + got(s.alpha_target)};
  if (!(s.alpha_start >= 0.0f && s.alpha_start < 1.0f))
    return SettingsProblem{DtField::alpha_start, "must be at least 0 and below 1" + got(s.alpha_start)};
  if (!(s.gradient_px >= 0.0f && s.gradient_px <= 4096.0f))
    return SettingsProblem{DtField::gradient, "must be 0..4096 output pixels" + got(s.gradient_px)};
  if (s.mask_resolution < 0)
    return SettingsProblem{DtField::mask_resolution, "must be 0 (full resolution) or positive" + got(s.mask_resolution)};
  if (width > 0 && height > 0 && s.mask_resolution > max_mask_resolution(width, height))
    return SettingsProblem{DtField::mask_resolution,
                           "must be at most " + std::to_string(max_mask_resolution(width, height)) + " for a " +
                               std::to_string(width) + " x " + std::to_string(height) +
                               " view (a mask finer than the view changes nothing but the cost; 0 = full "
                               "resolution)" + got(s.mask_resolution)};
  if (s.layer_limit < 0 || s.layer_limit > 60)
    return SettingsProblem{DtField::layer_limit, "must be 0 (no limit) or 1..60" + got(s.layer_limit)};
  if (!(s.searchlight_radius >= 0.0f) || !std::isfinite(s.searchlight_radius) || !std::isfinite(s.searchlight_center.x) ||
      !std::isfinite(s.searchlight_center.y))
    return SettingsProblem{DtField::searchlight, "radius must be finite and >= 0 and the centre finite"};
  return std::nullopt;
}

void validate(const DtSettings& s, int width, int height) {
  if (const auto p = check(s, width, height))
    throw std::invalid_argument("DtSettings." + std::string(to_string(p->field)) + ": " + p->message);
}

float gradient_px_from_mask_pixels(float mask_pixels, int mask_resolution, int width, int height) {
  if (mask_resolution <= 0) return mask_pixels;
  return mask_pixels * std::sqrt(static_cast<float>(width) * static_cast<float>(height)) / static_cast<float>(mask_resolution);
}

LensSettings scene_lens(const scene::Scene& sc, int width, int height) {
  LensSettings l;
  l.center = {0.5f * static_cast<float>(width), 0.5f * static_cast<float>(height)};
  const bool orbit = sc.camera.mode == scene::CameraStart::Mode::orbit;
  const float cell = sc.plan ? sc.plan->cell_size : 4.0f;
  l.distance = orbit ? sc.camera.distance : 2.0f * cell;
  l.radius = 0.25f * l.distance * std::tan(0.5f * sc.camera.fov_y);
  l.length = 2.0f * l.radius;
  return l;
}

Renderer::Renderer(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
Renderer::~Renderer() = default;

Result<std::unique_ptr<Renderer>> Renderer::create(const scene::Scene& scene) {
  auto impl = std::make_unique<Impl>();
  impl->scene = scene;
  auto gpu = detail::SceneGpu::create(impl->scene);
  if (!gpu) return gpu.error();
  impl->gpu = std::move(gpu.value());
  auto programs = detail::compile_programs();
  if (!programs) return programs.error();
  impl->programs = std::move(programs.value());
  impl->sorter = std::make_unique<detail::GroupSorter>(impl->gpu->objects());
  return std::unique_ptr<Renderer>(new Renderer(std::move(impl)));
}

const scene::Scene& Renderer::scene() const { return impl_->scene; }
const std::string& Renderer::last_graphviz() const { return impl_->graphviz; }

double Renderer::prepare(const FrameSettings& settings) {
  if (settings.method == Method::vdt) return 0.0;  // vdt culls nothing (OcclusionCuller::run)
  detail::OcclusionCuller* culler = impl_->culler_for(settings);
  return culler != nullptr ? culler->prepare() : 0.0;
}

FrameReport Renderer::render(const Camera& camera, const FrameSettings& settings, const ImportedTarget& target) {
  if (target.width <= 0 || target.height <= 0)
    throw std::invalid_argument("Renderer::render: target size must be positive, got " + std::to_string(target.width) +
                                "x" + std::to_string(target.height));
  validate(settings.dt, target.width, target.height);
  if (settings.method == Method::lens)
    if (const auto problem = check(settings.lens)) throw std::invalid_argument("LensSettings." + *problem);
  if (settings.method == Method::screen_door)
    if (const auto problem = check(settings.screen_door)) throw std::invalid_argument("ScreenDoorSettings." + *problem);
  if (settings.method == Method::vdt)
    if (const auto problem = check(settings.vdt)) throw std::invalid_argument("VdtSettings." + *problem);
  if (settings.flat_colors.size() > impl_->gpu->objects().size())
    throw std::invalid_argument("Renderer::render: more flat colours than objects");
  using Clock = std::chrono::steady_clock;
  const auto t0 = Clock::now();
  detail::GlStateGuard guard;
  detail::FrameView view = detail::make_frame_view(impl_->gpu->objects(), impl_->scene, camera, target.width,
                                                   target.height, settings.dt, *impl_->sorter);
  detail::LensVolume volume;
  detail::PixelRect lens_footprint;
  if (settings.method == Method::lens) {
    volume = detail::make_lens_volume(settings.lens, camera, target.width, target.height);
    lens_footprint = detail::lens_footprint(volume, camera, target.width, target.height);
  }
  const CullingReport culling = impl_->cull(view, settings, lens_footprint);
  const detail::FrameContext fc{*impl_->gpu, impl_->programs, view, settings, impl_->scene,
                                settings.float_color ? TextureFormat::rgba16f : TextureFormat::rgba8, {}};
  FrameGraph fg;
  const Handle output = fg.import_target("output", target);
  const bool transparency = uses_transparency(settings.method);
  const bool targets = !view.targets.empty();
  Handle color;
  Handle occluded;  // "some target is occluded": the effect was called for (none: no query this frame)
  // dt-seed and dt-fast pick the frame plan from whether the last frame of the method needed the
  // effect (frame coherence): effect-first when it did, standard-first otherwise.
  bool* effect_hint = settings.method == Method::dt_fast   ? &impl_->fast_effect_hint
                      : settings.method == Method::dt_seed ? &impl_->seed_effect_hint
                                                           : nullptr;
  const bool direct = effect_hint && *effect_hint && targets && detail::effect_first_possible(fc);
  detail::LensGpu lens;
  detail::VdtFrame vdt_frame;
  if (settings.method == Method::lens) {
    lens = impl_->upload_lens(volume);
    lens.footprint = lens_footprint;
    color = detail::add_lens_passes(fg, fc, lens);
  } else if (settings.method == Method::vdt && impl_->vdt.prepare(fc, vdt_frame)) {
    color = detail::add_vdt_passes(fg, fc, vdt_frame);  // else no transparent object in view: standard's frame
  } else if (settings.method == Method::reference) {
    color = detail::add_reference_pass(fg, fc);
  } else if (direct) {
    const detail::EffectFirst d = settings.method == Method::dt_seed ? detail::add_seed_direct_passes(fg, fc)
                                                                     : detail::add_fast_direct_passes(fg, fc);
    color = d.color;
    occluded = d.occluded;
  } else {
    detail::MainTargets main = detail::add_opaque_pass(fg, fc, transparency && targets);
    // Declared whenever a target is in view; only the effect's passes read it, so for
    // `standard` compile() culls it. Without exact codes (more than 255 targets overlapping one
    // another) there is no query and the effect runs unconditionally.
    if (targets && !view.codes_exhausted) occluded = detail::add_target_query_pass(fg, fc, main.depth, 0xFF);
    if (transparency && targets) {
      main = settings.method == Method::dt_seed       ? detail::add_seed_passes(fg, fc, main, occluded)
             : settings.method == Method::screen_door ? detail::add_screen_door_passes(fg, fc, main, occluded)
                                                      : detail::add_fast_passes(fg, fc, main, occluded);
    }
    color = main.color;
  }
  detail::add_present_pass(fg, fc, color, output);
  fg.compile();
  detail::set_frame_baseline(impl_->gpu->vao());
  fg.execute(impl_->backend, settings.profile_passes, &impl_->gpu->counts());
  if (settings.timed) glFinish();
  const auto t1 = Clock::now();
  // The next frame's plan follows whether this one needed the effect; an answer not ready yet
  // (untimed frame) leaves the guess as it was.
  if (effect_hint) {
    if (!targets) *effect_hint = false;
    else if (!occluded.valid()) *effect_hint = true;
    else if (const auto a = fg.answer(occluded, impl_->backend, settings.timed)) *effect_hint = *a;
  }
  FrameReport report = fg.report(impl_->backend, settings.timed);
  report.culling = culling;
  if (settings.timed) report.frame_ms = std::chrono::duration<double, std::milli>(t1 - t0).count();
  impl_->backend.end_frame();
  impl_->graphviz = fg.graphviz();
  impl_->last_target = target;
  impl_->last_float = settings.float_color;
  return report;
}

FrameReport Renderer::render_offscreen(const Camera& camera, const FrameSettings& settings, int width, int height) {
  if (width <= 0 || height <= 0 || width > 16384 || height > 16384)
    throw std::invalid_argument("Renderer::render_offscreen: size must be 1..16384, got " + std::to_string(width) + "x" +
                                std::to_string(height));
  impl_->ensure_offscreen(width, height, settings.float_color);
  return render(camera, settings, ImportedTarget{impl_->out_fbo, width, height});
}

namespace {
// glReadPixels of the whole of `t` into `out`, leaving the read framebuffer, its read buffer,
// the pixel pack buffer and the pack parameters as the caller had them.
void read_target(const ImportedTarget& t, GLenum type, void* out) {
  GLint fbo = 0, buffer = 0, pack_buffer = 0, alignment = 4, row_length = 0, skip_rows = 0, skip_pixels = 0;
  glGetIntegerv(GL_READ_FRAMEBUFFER_BINDING, &fbo);
  glGetIntegerv(GL_PIXEL_PACK_BUFFER_BINDING, &pack_buffer);
  glGetIntegerv(GL_PACK_ALIGNMENT, &alignment);
  glGetIntegerv(GL_PACK_ROW_LENGTH, &row_length);
  glGetIntegerv(GL_PACK_SKIP_ROWS, &skip_rows);
  glGetIntegerv(GL_PACK_SKIP_PIXELS, &skip_pixels);
  glBindFramebuffer(GL_READ_FRAMEBUFFER, t.framebuffer);
  glGetIntegerv(GL_READ_BUFFER, &buffer);
  if (t.framebuffer == 0) glReadBuffer(GL_BACK);  // where present blitted the frame
  glBindBuffer(GL_PIXEL_PACK_BUFFER, 0);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glPixelStorei(GL_PACK_ROW_LENGTH, 0);
  glPixelStorei(GL_PACK_SKIP_ROWS, 0);
  glPixelStorei(GL_PACK_SKIP_PIXELS, 0);
  glReadPixels(0, 0, t.width, t.height, GL_RGBA, type, out);
  glReadBuffer(static_cast<GLenum>(buffer));
  glPixelStorei(GL_PACK_ALIGNMENT, alignment);
  glPixelStorei(GL_PACK_ROW_LENGTH, row_length);
  glPixelStorei(GL_PACK_SKIP_ROWS, skip_rows);
  glPixelStorei(GL_PACK_SKIP_PIXELS, skip_pixels);
  glBindBuffer(GL_PIXEL_PACK_BUFFER, static_cast<GLuint>(pack_buffer));
  glBindFramebuffer(GL_READ_FRAMEBUFFER, static_cast<GLuint>(fbo));
}
}  // namespace

Image Renderer::read_color() const {
  const ImportedTarget& t = impl_->last_target;
  Image img;
  if (t.width <= 0) return img;
  img.width = t.width;
  img.height = t.height;
  std::vector<std::uint8_t> rows(static_cast<std::size_t>(t.width) * t.height * 4);
  read_target(t, GL_UNSIGNED_BYTE, rows.data());
  img.rgba.resize(rows.size());
  const std::size_t stride = static_cast<std::size_t>(t.width) * 4;
  for (int y = 0; y < t.height; ++y)  // GL rows are bottom-up
    std::copy_n(&rows[static_cast<std::size_t>(t.height - 1 - y) * stride], stride, &img.rgba[static_cast<std::size_t>(y) * stride]);
  return img;
}

std::vector<float> Renderer::read_color_float() const {
  const ImportedTarget& t = impl_->last_target;
  std::vector<float> out;
  if (t.width <= 0) return out;
  out.resize(static_cast<std::size_t>(t.width) * t.height * 4);
  read_target(t, GL_FLOAT, out.data());
  return out;
}

}  // namespace dtlab::render

// The Renderer (see render.h): owns the scene's GPU data, the programs, the
// frame graph backend and the group order; builds one frame graph per frame
// from the method and what the frame calls for. Its public functions check
// their arguments into Errors and run the rest under detail::guarded, so no
// exception leaves them (detail/boundary.h).
#include <glad/gl.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <optional>
#include <sstream>

#include "study/render/detail/boundary.h"
#include "study/render/detail/gl_state.h"
#include "study/render/detail/method.h"
#include "study/render/detail/passes.h"
#include "study/render/detail/renderer_impl.h"
#include "study/render/render.h"

namespace dtlab::render {

Status validate(const DtSettings& s, int width, int height) {
  if (const auto p = check(s, width, height))
    return Error{"", 0, 0, "DtSettings." + std::string(to_string(p->field)), p->message, ErrorKind::invalid_input};
  return {};
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

Status detail::check_frame(const char* where, const FrameSettings& settings, int width, int height,
                          std::size_t objects) {
  auto bad = [where](const std::string& message) { return render_error(where, message, ErrorKind::invalid_input); };
  if (width <= 0 || height <= 0)
    return bad("target size must be positive, got " + std::to_string(width) + "x" + std::to_string(height));
  if (const auto p = check(settings.dt, width, height))
    return bad("DtSettings." + std::string(to_string(p->field)) + ": " + p->message);
  if (settings.method == Method::lens)
    if (const auto problem = check(settings.lens)) return bad("LensSettings." + *problem);
  if (settings.method == Method::screen_door)
    if (const auto problem = check(settings.screen_door)) return bad("ScreenDoorSettings." + *problem);
  if (settings.method == Method::vdt)
    if (const auto problem = check(settings.vdt)) return bad("VdtSettings." + *problem);
  if (settings.flat_colors.size() > objects) return bad("more flat colours than objects");
  return {};
}

Renderer::Renderer(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
Renderer::~Renderer() = default;

Result<std::unique_ptr<Renderer>> Renderer::create(const scene::Scene& scene) {
  return detail::guarded<Result<std::unique_ptr<Renderer>>>(
      "Renderer::create", [&]() -> Result<std::unique_ptr<Renderer>> {
        auto impl = std::make_unique<Impl>();
        impl->scene = scene;
        auto gpu = detail::SceneGpu::create(impl->scene);
        if (!gpu) return gpu.error();
        impl->gpu = std::move(gpu.value());
        auto programs = detail::compile_programs();
        if (!programs)  // the field and prefix every error of render.h carries (docs/render.md, "Errors")
          return detail::render_error("Renderer::create", programs.error().to_string(), ErrorKind::environment);
        impl->programs = std::move(programs.value());
        impl->sorter = std::make_unique<detail::GroupSorter>(impl->gpu->objects());
        return std::unique_ptr<Renderer>(new Renderer(std::move(impl)));
      });
}

const scene::Scene& Renderer::scene() const { return impl_->scene; }
const std::string& Renderer::last_graphviz() const { return impl_->graphviz; }

Result<double> Renderer::prepare(const FrameSettings& settings) {
  return detail::guarded<Result<double>>("Renderer::prepare", [&]() -> Result<double> {
    if (!technique::of(settings.method).cullable) return 0.0;  // culls nothing (OcclusionCuller::add_passes)
    detail::OcclusionCuller* culler = impl_->culler_for(settings);
    return culler != nullptr ? culler->prepare() : 0.0;
  });
}

Result<FrameReport> Renderer::render(const Camera& camera, const FrameSettings& settings, const ImportedTarget& target) {
  const std::size_t objects = impl_->gpu->objects().size();
  if (Status st = detail::check_frame("Renderer::render", settings, target.width, target.height, objects); !st)
    return st.error();
  return detail::guarded<Result<FrameReport>>("Renderer::render", [&]() -> Result<FrameReport> {
    FrameReport report = draw_frame(camera, settings, target);
    if (auto injected = detail::injected_gl_error()) report.gl_errors.push_back("pass 'present': " + *injected);
    if (auto fatal = detail::fatal_gl_error("Renderer::render", report.gl_errors)) return *fatal;
    return report;
  });
}

FrameReport Renderer::draw_frame(const Camera& camera, const FrameSettings& settings, const ImportedTarget& target) {
  using Clock = std::chrono::steady_clock;
  const auto t0 = Clock::now();
  detail::GlStateGuard guard;
  detail::FrameView view = detail::make_frame_view(impl_->gpu->objects(), impl_->scene, camera, target.width,
                                                   target.height, settings.dt, *impl_->sorter);
  const detail::MethodPasses& method = detail::passes_of(settings.method);
  detail::MethodSlot& slot = impl_->slots[static_cast<std::size_t>(settings.method)];
  std::optional<detail::PixelRect> footprint;
  if (method.footprint != nullptr) footprint = method.footprint(slot, settings, camera, target.width, target.height);
  const detail::FrameContext fc{*impl_->gpu, impl_->programs, view, settings, impl_->scene,
                                settings.float_color ? TextureFormat::rgba16f : TextureFormat::rgba8, {}};
  FrameGraph fg;
  const Handle output = fg.import_target("output", target);
  // Stage 1, occlusion culling (when on): its passes read the occluders' map back and drop the
  // hidden objects from the view's lists, which the method's passes are then declared over.
  CullingReport culling;
  if (detail::OcclusionCuller* culler = impl_->culler_for(settings);
      culler != nullptr && culler->add_passes(fg, view, fc, footprint, culling)) {
    detail::set_frame_baseline(impl_->gpu->vao());
    fg.flush(impl_->backend, settings.profile_passes, &impl_->gpu->counts());
  }
  // Stage 2: the method's passes, from the registry (detail/method.h), then present.
  const bool targets = !view.targets.empty();
  const detail::MethodFrame frame = method.add(fg, fc, slot);
  const Handle color = frame.color;
  const Handle occluded = frame.occluded;  // "some target is occluded": the effect was called for
  detail::add_present_pass(fg, fc, color, output);
  fg.compile();
  detail::set_frame_baseline(impl_->gpu->vao());
  fg.execute(impl_->backend, settings.profile_passes, &impl_->gpu->counts());
  if (settings.timed) glFinish();
  const auto t1 = Clock::now();
  // A frame-coherent method's next plan follows whether this frame needed the effect; an answer
  // not ready yet (untimed frame) leaves the guess as it was.
  if (method.frame_coherent) {
    if (!targets) slot.effect_hint = false;
    else if (!occluded.valid()) slot.effect_hint = true;
    else if (const auto a = fg.answer(occluded, impl_->backend, settings.timed)) slot.effect_hint = *a;
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

Result<FrameReport> Renderer::render_offscreen(const Camera& camera, const FrameSettings& settings, int width,
                                               int height) {
  if (width <= 0 || height <= 0 || width > 16384 || height > 16384)
    return detail::render_error("Renderer::render_offscreen",
                                "size must be 1..16384, got " + std::to_string(width) + "x" + std::to_string(height),
                                ErrorKind::invalid_input);
  if (Status st = detail::guarded<Status>("Renderer::render_offscreen", [&]() -> Status {
        impl_->ensure_offscreen(width, height, settings.float_color);
        return {};
      });
      !st)
    return st.error();
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

// The GL errors glReadPixels left, as an environment Error when one is fatal (boundary.h).
std::optional<Error> read_failure(const char* where) {
  std::vector<std::string> errors;
  for (GLenum e = glGetError(), n = 0; e != GL_NO_ERROR && n < 32; e = glGetError(), ++n)
    errors.emplace_back(detail::gl_error_name(e));
  return detail::fatal_gl_error(where, errors);
}
}  // namespace

Result<Image> Renderer::read_color() const {
  return detail::guarded<Result<Image>>("Renderer::read_color", [&]() -> Result<Image> {
    const ImportedTarget& t = impl_->last_target;
    Image img;
    if (t.width <= 0) return img;
    img.width = t.width;
    img.height = t.height;
    std::vector<std::uint8_t> rows(static_cast<std::size_t>(t.width) * t.height * 4);
    read_target(t, GL_UNSIGNED_BYTE, rows.data());
    if (auto failed = read_failure("Renderer::read_color")) return *failed;
    img.rgba.resize(rows.size());
    const std::size_t stride = static_cast<std::size_t>(t.width) * 4;
    for (int y = 0; y < t.height; ++y)  // GL rows are bottom-up
      std::copy_n(&rows[static_cast<std::size_t>(t.height - 1 - y) * stride], stride,
                  &img.rgba[static_cast<std::size_t>(y) * stride]);
    return img;
  });
}

Result<std::vector<float>> Renderer::read_color_float() const {
  return detail::guarded<Result<std::vector<float>>>("Renderer::read_color_float", [&]() -> Result<std::vector<float>> {
    const ImportedTarget& t = impl_->last_target;
    std::vector<float> out;
    if (t.width <= 0) return out;
    out.resize(static_cast<std::size_t>(t.width) * t.height * 4);
    read_target(t, GL_FLOAT, out.data());
    if (auto failed = read_failure("Renderer::read_color_float")) return *failed;
    return out;
  });
}

}  // namespace dtlab::render

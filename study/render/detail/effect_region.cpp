// Renderer::effect_region (see render.h): where the exact masks of the visual
// model lower alpha. The targets' silhouettes (or circles / ellipses) are
// rasterized at full resolution in one pass and read back; the chessboard
// distance to them (compositor.h) gives the gradient's reach, n + 1 pixels.
// Errors, never exceptions, leave it (detail/boundary.h).
#include <glad/gl.h>

#include <cmath>

#include "study/render/detail/boundary.h"
#include "study/render/detail/compositor.h"
#include "study/render/detail/gl_state.h"
#include "study/render/detail/passes.h"
#include "study/render/detail/renderer_impl.h"
#include "study/render/render.h"

namespace dtlab::render {

Result<std::vector<std::uint8_t>> Renderer::effect_region(const Camera& camera, const DtSettings& dt, int width,
                                                          int height) {
  constexpr const char* kWhere = "Renderer::effect_region";
  if (width <= 0 || height <= 0 || width > 16384 || height > 16384)
    return detail::render_error(kWhere, "size must be 1..16384, got " + std::to_string(width) + "x" + std::to_string(height),
                                ErrorKind::invalid_input);
  if (const auto p = check(dt, width, height))
    return detail::render_error(kWhere, "DtSettings." + std::string(to_string(p->field)) + ": " + p->message,
                                ErrorKind::invalid_input);
  return detail::guarded<Result<std::vector<std::uint8_t>>>(
      kWhere, [&]() -> Result<std::vector<std::uint8_t>> { return region_mask(camera, dt, width, height); });
}

std::vector<std::uint8_t> Renderer::region_mask(const Camera& camera, const DtSettings& dt, int width, int height) {
  const std::size_t n = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
  const detail::FrameView view =
      detail::make_frame_view(impl_->gpu->objects(), impl_->scene, camera, width, height, dt, *impl_->sorter);
  std::vector<std::uint8_t> out(n, 0);
  if (view.targets.empty()) return out;
  FrameSettings settings;
  settings.dt = dt;
  std::vector<std::uint8_t> covered_rows(n, 0);
  {
    detail::GlStateGuard guard;
    const detail::FrameContext fc{*impl_->gpu, impl_->programs, view, settings, impl_->scene, TextureFormat::r8, {}};
    FrameGraph fg;
    struct SilhouettesPassData {
      Handle coverage;
    };
    fg.add_pass<SilhouettesPassData>(
        "effect-region",
        [&](FrameGraph::Builder& b, SilhouettesPassData& d) {
          d.coverage = b.write(b.create("silhouettes", {width, height, TextureFormat::r8, false}));
          b.side_effect();  // read back on the CPU
        },
        [&](const SilhouettesPassData& d, PassResources& r) {
          glBindFramebuffer(GL_FRAMEBUFFER, r.framebuffer({d.coverage}));
          glViewport(0, 0, width, height);
          glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
          glClearColor(0.0f, 0.0f, 0.0f, 0.0f);
          glClear(GL_COLOR_BUFFER_BIT);
          for (std::size_t s = 0; s < view.targets.size(); ++s)
            detail::draw_target_seed(fc, static_cast<int>(s), 1.0f, view.view_proj, glm::vec4(1, 1, 0, 0), false);
          glReadPixels(0, 0, width, height, GL_RED, GL_UNSIGNED_BYTE, covered_rows.data());
        });
    fg.compile();
    detail::set_frame_baseline(impl_->gpu->vao());
    fg.execute(impl_->backend);
    const FrameReport report = fg.report(impl_->backend, true);
    if (auto fatal = detail::fatal_gl_error("Renderer::effect_region", report.gl_errors))
      throw detail::PassedError(*fatal);
    impl_->backend.end_frame();
  }
  std::vector<bool> covered(n);
  for (std::size_t i = 0; i < n; ++i) covered[i] = covered_rows[i] > 127;
  const int reach = static_cast<int>(std::ceil(dt.gradient_px)) + 2;
  const std::vector<int> dist = detail::chessboard_distance(covered, width, height, reach);
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      const std::size_t k = static_cast<std::size_t>(y) * static_cast<std::size_t>(width) + static_cast<std::size_t>(x);
      bool in = detail::gradient_alpha(static_cast<float>(dist[k]), dt.alpha_start, dt.gradient_px) < 1.0f || dist[k] == 0;
      if (in && view.searchlight.z >= 0.0f) {
        const float dx = static_cast<float>(x) + 0.5f - view.searchlight.x, dy = static_cast<float>(y) + 0.5f - view.searchlight.y;
        in = std::sqrt(dx * dx + dy * dy) <= view.searchlight.z;
      }
      out[static_cast<std::size_t>(height - 1 - y) * static_cast<std::size_t>(width) + static_cast<std::size_t>(x)] = in;
    }
  }
  return out;
}

}  // namespace dtlab::render

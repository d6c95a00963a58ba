// Renderer::visibility (see render.h and docs/render.md, "Visible pixels").
// Silhouettes: one GL_SAMPLES_PASSED query per target drawn alone, each
// pixel counted once (the stencil lets only a pixel's first fragment pass). Visible pixels: the method's own frame re-rendered in weight
// mode, where targets k, k+1, k+2 are flat red, green and blue and every
// other object and the background flat black: a channel's value at a pixel is
// then exactly the share of that target in the composited colour.
#include <glad/gl.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <string>

#include "study/render/detail/boundary.h"
#include "study/render/detail/gl_state.h"
#include "study/render/detail/passes.h"
#include "study/render/detail/renderer_impl.h"
#include "study/render/render.h"

namespace dtlab::render {

Result<std::vector<TargetVisibility>> Renderer::visibility(const Camera& camera, FrameSettings settings, int width,
                                                          int height) {
  settings.flat_colors.clear();  // the weight frames set their own
  const std::size_t objects = impl_->gpu->objects().size();
  if (Status st = detail::check_frame("Renderer::visibility", settings, width, height, objects); !st) return st.error();
  return detail::guarded<Result<std::vector<TargetVisibility>>>("Renderer::visibility",
                                                                [&]() -> Result<std::vector<TargetVisibility>> {
    return count_visibility(camera, std::move(settings), width, height);
  });
}

std::vector<TargetVisibility> Renderer::count_visibility(const Camera& camera, FrameSettings settings, int width,
                                                         int height) {
  const auto& objects = impl_->scene.objects;
  std::vector<TargetVisibility> out;
  std::vector<std::uint32_t> target_index;  // scene object index per entry of `out`
  for (std::uint32_t i = 0; i < objects.size(); ++i) {
    if (!objects[i].target) continue;
    out.push_back(TargetVisibility{objects[i].id, 0, 0});
    target_index.push_back(i);
  }
  if (out.empty()) return out;
  settings.timed = false;

  // The view: frustum test and screen rectangles.
  const detail::FrameView view = detail::make_frame_view(impl_->gpu->objects(), impl_->scene, camera, width, height,
                                                         settings.dt, *impl_->sorter);
  // Silhouette pixel counts.
  {
    FrameSettings plain = settings;
    plain.flat_colors.clear();
    detail::GlStateGuard guard;
    const detail::FrameContext fc{*impl_->gpu, impl_->programs, view, plain, impl_->scene, TextureFormat::r8, {}};
    std::vector<GLuint> queries(out.size(), 0);
    glGenQueries(static_cast<GLsizei>(queries.size()), queries.data());
    FrameGraph fg;
    struct SilhouettePassData {
      Handle scratch, stencil;
    };
    fg.add_pass<SilhouettePassData>(
        "silhouette-count",
        [&](FrameGraph::Builder& b, SilhouettePassData& d) {
          d.scratch = b.write(b.create("scratch", {width, height, TextureFormat::r8, false}));
          d.stencil = b.write(b.create("scratch-stencil", {width, height, TextureFormat::depth24_stencil8, false}));
          b.side_effect();  // its output is the query results, read on the CPU
        },
        [&](const SilhouettePassData& d, PassResources& r) {
          glBindFramebuffer(GL_FRAMEBUFFER, r.framebuffer({d.scratch}, d.stencil));
          glViewport(0, 0, width, height);
          glDisable(GL_SCISSOR_TEST);
          glDisable(GL_DEPTH_TEST);
          glDisable(GL_BLEND);
          glDisable(GL_CULL_FACE);
          glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
          glEnable(GL_STENCIL_TEST);
          glStencilFunc(GL_EQUAL, 0, 0xFF);  // a pixel's first fragment only
          glStencilOp(GL_KEEP, GL_KEEP, GL_INCR);
          glStencilMask(0xFF);
          glClearStencil(0);
          fc.use_alpha(view.view_proj, 1.0f, false);
          for (std::size_t k = 0; k < out.size(); ++k) {
            glClear(GL_STENCIL_BUFFER_BIT);
            glBeginQuery(GL_SAMPLES_PASSED, queries[k]);
            if (!view.rects[target_index[k]].empty()) fc.draw_alpha(target_index[k]);
            glEndQuery(GL_SAMPLES_PASSED);
          }
          glDisable(GL_STENCIL_TEST);
          glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
        });
    fg.compile();
    detail::set_frame_baseline(impl_->gpu->vao());
    fg.execute(impl_->backend);
    const FrameReport report = fg.report(impl_->backend, true);
    for (std::size_t k = 0; k < out.size(); ++k) {
      GLuint samples = 0;
      glGetQueryObjectuiv(queries[k], GL_QUERY_RESULT, &samples);
      out[k].silhouette_pixels = static_cast<long>(samples);
    }
    glDeleteQueries(static_cast<GLsizei>(queries.size()), queries.data());
    if (auto fatal = detail::fatal_gl_error("Renderer::visibility", report.gl_errors))
      throw detail::PassedError(*fatal);
  }

  // Visible pixels: weight frames; targets with disjoint rectangles share a channel.
  std::vector<std::vector<std::size_t>> slots;  // slot s: frame s / 3, channel s % 3
  for (std::size_t k = 0; k < out.size(); ++k) {
    const detail::PixelRect& rk = view.rects[target_index[k]];
    if (rk.empty() || out[k].silhouette_pixels == 0) continue;
    std::size_t s = 0;
    for (; s < slots.size(); ++s)
      if (std::none_of(slots[s].begin(), slots[s].end(),
                       [&](std::size_t j) { return view.rects[target_index[j]].overlaps(rk); }))
        break;
    if (s == slots.size()) slots.emplace_back();
    slots[s].push_back(k);
  }
  const int threshold = static_cast<int>(std::ceil(kVisibleShare * 255.0f - 1e-4f));  // 26 of 255
  for (std::size_t first = 0; first < slots.size(); first += 3) {
    settings.flat_colors.assign(objects.size(), glm::vec3(0.0f));
    for (std::size_t c = 0; c < 3 && first + c < slots.size(); ++c)
      for (std::size_t k : slots[first + c]) {
        glm::vec3 e(0.0f);
        e[static_cast<int>(c)] = 1.0f;
        settings.flat_colors[target_index[k]] = e;
      }
    detail::unwrap(render_offscreen(camera, settings, width, height));
    const Image img = detail::unwrap(read_color());
    if (const char* dir = std::getenv("DTLAB_VIS_DUMP"))
      (void)write_png(img, std::string(dir) + "/vis-" + std::string(to_string(settings.method)) + "-" +
                               std::to_string(first / 3) + ".png");
    for (std::size_t c = 0; c < 3 && first + c < slots.size(); ++c) {
      for (std::size_t k : slots[first + c]) {
        const detail::PixelRect& r = view.rects[target_index[k]];
        long n = 0;
        for (int y = r.y0; y < r.y1; ++y)
          for (int x = r.x0; x < r.x1; ++x)
            if (img.pixel(x, img.height - 1 - y)[c] >= threshold) ++n;
        out[k].visible_pixels = n;
      }
    }
  }
  return out;
}

}  // namespace dtlab::render

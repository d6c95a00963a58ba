// reference: exact per-pixel compositing. One pass renders each object in
// view alone (its own z-buffer: its frontmost surface, lit exactly as the
// other methods light it) into a float layer, reads the layer back, and the
// CPU compositor (compositor.h) folds all surfaces per pixel in exact depth
// order with full-resolution masks; the result is uploaded as the colour.
// Slow by design: it is the yardstick for the image error of the others.
#include <glad/gl.h>

#include "study/render/detail/compositor.h"
#include "study/render/detail/method.h"
#include "study/render/detail/passes.h"

namespace dtlab::render::detail {

Handle add_reference_pass(FrameGraph& fg, const FrameContext& fc) {
  struct ReferencePassData {
    Handle color, layer_color, layer_depth;
  };
  const auto& data = fg.add_pass<ReferencePassData>(
      "reference-composite",
      [&](FrameGraph::Builder& b, ReferencePassData& d) {
        d.color = b.write(b.create("color", {fc.width(), fc.height(), fc.color_format, false}));
        d.layer_color = b.write(b.create("layer-color", {fc.width(), fc.height(), TextureFormat::rgba32f, false}));
        d.layer_depth = b.write(b.create("layer-depth", {fc.width(), fc.height(), TextureFormat::depth32f, false}));
      },
      [&fc](const ReferencePassData& d, PassResources& r) {
        CompositeInput in;
        in.width = fc.width();
        in.height = fc.height();
        in.background = fc.background();
        in.dt = fc.settings.dt;
        in.transparency = uses_transparency(fc.settings.method) && !fc.view.targets.empty();
        in.searchlight = fc.view.searchlight;
        in.targets = fc.view.targets;
        in.impenetrable.resize(fc.gpu.objects().size());
        in.is_target.resize(fc.gpu.objects().size());
        for (std::size_t i = 0; i < fc.gpu.objects().size(); ++i) {
          in.impenetrable[i] = fc.gpu.objects()[i].impenetrable;
          in.is_target[i] = fc.gpu.objects()[i].target;
        }

        glBindFramebuffer(GL_FRAMEBUFFER, r.framebuffer({d.layer_color}, d.layer_depth));
        glViewport(0, 0, fc.width(), fc.height());
        glEnable(GL_SCISSOR_TEST);
        glDisable(GL_BLEND);
        glDisable(GL_STENCIL_TEST);
        glDisable(GL_CULL_FACE);
        glEnable(GL_DEPTH_TEST);
        glDepthFunc(GL_LESS);
        glDepthMask(GL_TRUE);
        glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
        glClearColor(0.0f, 0.0f, 0.0f, 0.0f);
        glClearDepth(1.0);
        fc.use_lit(fc.view.view_proj);
        for (std::uint32_t i = 0; i < fc.view.rects.size(); ++i) {
          const PixelRect& rect = fc.view.rects[i];
          if (rect.empty()) continue;
          const int w = rect.x1 - rect.x0, h = rect.y1 - rect.y0;
          glScissor(rect.x0, rect.y0, w, h);
          glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
          fc.draw_lit(i);
          ObjectLayer layer;
          layer.object = i;
          layer.rect = rect;
          layer.depth.resize(static_cast<std::size_t>(w) * h);
          layer.color.resize(layer.depth.size());
          glReadPixels(rect.x0, rect.y0, w, h, GL_RGBA, GL_FLOAT, layer.color.data());
          glReadPixels(rect.x0, rect.y0, w, h, GL_DEPTH_COMPONENT, GL_FLOAT, layer.depth.data());
          in.layers.push_back(std::move(layer));
        }
        glDisable(GL_SCISSOR_TEST);
        const CompositeOutput out = composite(in);
        glBindTexture(GL_TEXTURE_2D, r.texture(d.color));
        glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, fc.width(), fc.height(), GL_RGBA, GL_FLOAT, out.rgba.data());
        glBindTexture(GL_TEXTURE_2D, 0);
      });
  return data.color;
}

namespace {
MethodFrame add_reference(FrameGraph& fg, const FrameContext& fc, MethodSlot&) { return {add_reference_pass(fg, fc), {}}; }
}  // namespace

extern const MethodPasses k_passes_reference{nullptr, add_reference};

}  // namespace dtlab::render::detail

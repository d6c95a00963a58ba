// dt-seed: the article's image-space dynamic transparency, faithfully
// (Elmqvist, Assarsson & Tsigas 2008, section V; tech report 2006, 4.1-4.3).
// Passes, all conditional on the target-query (no target occluded: none run):
//   dt-clear      colour = background with alpha 1, depth 1, stencil 0;
//   impenetrable  impenetrable objects first, opaque (V.2);
//   objects a-b   each object in back-to-front order: depth pass, then colour
//                 pass with depth EQUAL blended with the destination alpha;
//   mask <id>     after each target (Algorithm 2): its silhouette (or circle /
//                 ellipse) at aT into an R x R buffer, n' ping-pong border
//                 passes (Algorithm 3), the upsampled mask multiplied into the
//                 framebuffer alpha, the silhouette re-rendered at full
//                 resolution with aT (line 11).
// Never: a per-target pass outside the target's own mask pass.
#include <glad/gl.h>

#include <cmath>
#include <string>
#include <vector>

#include <glm/gtc/type_ptr.hpp>

#include "study/render/detail/passes.h"

namespace dtlab::render::detail {

namespace {

void bind_main(const FrameContext& fc, PassResources& r, Handle color, Handle depth) {
  glBindFramebuffer(GL_FRAMEBUFFER, r.framebuffer({color}, depth));
  glViewport(0, 0, fc.width(), fc.height());
  glDisable(GL_SCISSOR_TEST);
}

}  // namespace

MainTargets add_seed_passes(FrameGraph& fg, const FrameContext& fc, MainTargets main, Handle query) {
  struct DtClearPassData {
    Handle color, depth;
  };
  const auto& cleared = fg.add_pass<DtClearPassData>(
      "dt-clear",
      [&](FrameGraph::Builder& b, DtClearPassData& d) {
        if (query.valid()) b.condition(query);
        d.color = b.write(main.color);
        d.depth = b.write(main.depth);
      },
      [&fc](const DtClearPassData& d, PassResources& r) {
        bind_main(fc, r, d.color, d.depth);
        clear_to_background(fc);
      });
  MainTargets cur{cleared.color, cleared.depth};

  struct DrawPassData {
    Handle color, depth;
  };
  if (!fc.view.impenetrable.empty()) {
    const auto& d = fg.add_pass<DrawPassData>(
        "impenetrable",
        [&](FrameGraph::Builder& b, DrawPassData& d) {
          if (query.valid()) b.condition(query);
          d.color = b.write(b.read(cur.color));
          d.depth = b.write(b.read(cur.depth));
        },
        [&fc](const DrawPassData& d, PassResources& r) {
          bind_main(fc, r, d.color, d.depth);
          for (auto i : fc.view.impenetrable) draw_opaque_object(fc, i, object_stencil(fc, i, false));
        });
    cur = {d.color, d.depth};
  }

  const MaskGrid& mask = fc.view.grid;
  const auto& order = fc.view.sorted;
  std::size_t start = 0;
  for (std::size_t k = 0; k <= order.size(); ++k) {
    const bool end = k == order.size();
    const bool target = !end && fc.view.target_slot[order[k]] >= 0;
    if (!end && !target) continue;
    // Objects [start, k] (the target included) in one pass.
    const std::size_t last = end ? k : k + 1;
    if (last > start) {
      std::vector<std::uint32_t> run(order.begin() + static_cast<long>(start), order.begin() + static_cast<long>(last));
      const std::string name = "objects " + std::to_string(start + 1) + "-" + std::to_string(last);
      const auto& d = fg.add_pass<DrawPassData>(
          name,
          [&](FrameGraph::Builder& b, DrawPassData& d) {
            if (query.valid()) b.condition(query);
            d.color = b.write(b.read(cur.color));
            d.depth = b.write(b.read(cur.depth));
          },
          [&fc, run = std::move(run)](const DrawPassData& d, PassResources& r) {
            bind_main(fc, r, d.color, d.depth);
            for (auto i : run) {
              draw_transparent_object(fc, i, false, object_stencil(fc, i, false));  // always two passes
              const int slot = fc.view.target_slot[i];
              if (slot >= 0 && fc.guard() && fc.view.targets[static_cast<std::size_t>(slot)].may_be_drawn_late)
                repair_target(fc, i);
            }
          });
      cur = {d.color, d.depth};
    }
    start = last;
    if (end) break;

    struct MaskPassData {
      Handle color, depth, ping, pong;
    };
    const int slot = fc.view.target_slot[order[k]];
    const TextureDesc mdesc{mask.width, mask.height, TextureFormat::r16f, true};
    const auto& m = fg.add_pass<MaskPassData>(
        "mask " + std::to_string(fc.gpu.objects()[order[k]].id),
        [&](FrameGraph::Builder& b, MaskPassData& d) {
          if (query.valid()) b.condition(query);
          d.ping = b.write(b.create("mask-ping", mdesc));
          d.pong = b.write(b.create("mask-pong", mdesc));
          d.color = b.write(b.read(cur.color));
          d.depth = b.write(b.read(cur.depth));
        },
        [&fc, slot, &mask](const MaskPassData& d, PassResources& r) {
          const DtSettings& dt = fc.settings.dt;
          const TargetView& t = fc.view.targets[static_cast<std::size_t>(slot)];
          // Every pass below changes only texels within n' + 1 of the texels the target covers, so
          // each runs over that tile of the buffer (the scissor); the rest of both buffers stays 1,
          // as the article's buffer-sized passes leave it.
          const PixelRect tile = t.cover.expand(mask.layers + 1).intersect({0, 0, mask.width, mask.height});
          glDisable(GL_SCISSOR_TEST);
          glDisable(GL_DEPTH_TEST);
          glDisable(GL_STENCIL_TEST);
          glDisable(GL_BLEND);
          glDisable(GL_CULL_FACE);
          glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
          glClearColor(1.0f, 1.0f, 1.0f, 1.0f);
          glViewport(0, 0, mask.width, mask.height);
          if (mask.layers > 1) {
            glBindFramebuffer(GL_FRAMEBUFFER, r.framebuffer({d.pong}));
            glClear(GL_COLOR_BUFFER_BIT);
          }
          // Algorithm 2, lines 1-2: the target at aT into B1 (everything else 1).
          glBindFramebuffer(GL_FRAMEBUFFER, r.framebuffer({d.ping}));
          glClear(GL_COLOR_BUFFER_BIT);
          draw_target_seed(fc, slot, dt.alpha_target, fc.view.view_proj,
                           glm::vec4(static_cast<float>(mask.width) / static_cast<float>(fc.width()),
                                     static_cast<float>(mask.height) / static_cast<float>(fc.height()), 0.0f, 0.0f),
                           false);
          // Lines 3-8: n ping-pong passes, each adding one layer of the gradient.
          Handle src = d.ping, dst = d.pong;
          const Program& border = fc.programs.border;
          fc.use_program(border);
          glUniform1i(border.loc("u_source"), 0);
          glActiveTexture(GL_TEXTURE0);
          glEnable(GL_SCISSOR_TEST);
          glScissor(tile.x0, tile.y0, tile.x1 - tile.x0, tile.y1 - tile.y0);
          for (int k = 1; k <= mask.layers; ++k) {
            glBindFramebuffer(GL_FRAMEBUFFER, r.framebuffer({dst}));
            glBindTexture(GL_TEXTURE_2D, r.texture(src));
            const float alpha_b = dt.alpha_start + (1.0f - dt.alpha_start) * static_cast<float>(k - 1) /
                                                       static_cast<float>(mask.layers);
            glUniform1f(border.loc("u_border_alpha"), alpha_b);
            fc.quad(border, 0.0f, 0.0f, static_cast<float>(mask.width), static_cast<float>(mask.height), mask.width,
                    mask.height);
            std::swap(src, dst);
          }
          glDisable(GL_SCISSOR_TEST);
          // Lines 9-11 on the framebuffer: mark the full-resolution silhouette, multiply the
          // upsampled mask elsewhere, then aT over the silhouette itself.
          bind_main(fc, r, d.color, d.depth);
          mark_target(fc, slot, false);
          begin_apply(fc, false);
          const Program& apply = fc.programs.mask_apply;
          fc.use_program(apply);
          glBindTexture(GL_TEXTURE_2D, r.texture(src));
          glUniform1i(apply.loc("u_mask"), 0);
          glUniform2f(apply.loc("u_screen"), static_cast<float>(fc.width()), static_cast<float>(fc.height()));
          glUniform3fv(apply.loc("u_searchlight"), 1, glm::value_ptr(fc.searchlight_uniform(true)));
          // Outside the target's support the upsampled mask is 1 (the shader would discard it).
          fc.quad(apply, static_cast<float>(t.support.x0), static_cast<float>(t.support.y0),
                  static_cast<float>(t.support.x1), static_cast<float>(t.support.y1), fc.width(), fc.height());
          finish_target(fc, slot);
          glBindTexture(GL_TEXTURE_2D, 0);
        });
    cur = {m.color, m.depth};
  }
  return cur;
}

}  // namespace dtlab::render::detail

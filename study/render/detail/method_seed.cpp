// dt-seed: the article's image-space dynamic transparency, faithfully
// (Elmqvist, Assarsson & Tsigas 2008, section V; tech report 2006, 4.1-4.3).
// Two frame plans, as dt-fast's (passes.h EffectFirst), chosen by whether the
// previous frame needed the effect; both give the same image:
//   standard-first  opaque, target-query, then the passes below, all
//                   conditional on the query (no target occluded: none run);
//   effect-first    the passes below unconditionally, every object writing its
//                   frontmost code (stencil bits 0-5) as it goes, then
//                   target-query, query-invert and (conditional on no target
//                   occluded) standard-fallback, the standard frame again.
// The passes of the effect:
//   seed-masks    Algorithm 2, lines 1-8, for every target: its silhouette (or
//                 circle / ellipse) at aT into a buffer of 1s, then n'
//                 ping-pong passes of Algorithm 3; each target in its own tile
//                 of the R x R grid (mask_atlas.h), all targets' tiles in one
//                 atlas, so the n' passes run once per frame, not per target
//                 (the same texels, fewer buffer switches);
//   dt-clear      colour = background with alpha 1, depth 1, stencil 0;
//   impenetrable  impenetrable objects first, opaque (V.2);
//   objects a-b   each object in back-to-front order: depth pass, then colour
//                 pass with depth EQUAL blended with the destination alpha;
//   mask <id>     after each target (Algorithm 2, lines 9-11): its upsampled
//                 mask multiplied into the framebuffer alpha, the silhouette
//                 re-rendered at full resolution with aT (line 11).
// Never: a per-target pass outside the target's own mask pass.
#include <glad/gl.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include <glm/gtc/type_ptr.hpp>

#include "study/render/detail/mask_atlas.h"
#include "study/render/detail/method.h"
#include "study/render/detail/passes.h"

namespace dtlab::render::detail {

namespace {

void bind_main(const FrameContext& fc, PassResources& r, Handle color, Handle depth) {
  glBindFramebuffer(GL_FRAMEBUFFER, r.framebuffer({color}, depth));
  glViewport(0, 0, fc.width(), fc.height());
  glDisable(GL_SCISSOR_TEST);
}

// Algorithm 2, lines 1-8, for every target at once; per atlas page, the buffer the last of the n'
// passes wrote.
std::vector<Handle> add_seed_masks_pass(FrameGraph& fg, const FrameContext& fc,
                                        const std::shared_ptr<const MaskAtlas>& atlas, Handle query) {
  struct SeedMasksPassData {
    std::vector<Handle> ping, pong;
  };
  const auto& masks = fg.add_pass<SeedMasksPassData>(
      "seed-masks",
      [&](FrameGraph::Builder& b, SeedMasksPassData& d) {
        if (query.valid()) b.condition(query);
        for (const MaskAtlas::Page& p : atlas->pages) {
          d.ping.push_back(b.write(b.create("mask-ping", {p.width, p.height, TextureFormat::r16f, true})));
          d.pong.push_back(b.write(b.create("mask-pong", {p.width, p.height, TextureFormat::r16f, true})));
        }
      },
      [&fc, atlas](const SeedMasksPassData& d, PassResources& r) {
        const DtSettings& dt = fc.settings.dt;
        const int layers = fc.view.grid.layers;
        glDisable(GL_SCISSOR_TEST);
        buffer_state();
        glClearColor(1.0f, 1.0f, 1.0f, 1.0f);
        for (std::size_t page = 0; page < atlas->pages.size(); ++page) {
          const MaskAtlas::Page& pg = atlas->pages[page];
          if (layers > 0) {
            glBindFramebuffer(GL_FRAMEBUFFER, r.framebuffer({d.pong[page]}));
            glClear(GL_COLOR_BUFFER_BIT);
          }
          // Lines 1-2: each target at aT into B1 (everything else 1).
          glBindFramebuffer(GL_FRAMEBUFFER, r.framebuffer({d.ping[page]}));
          glClear(GL_COLOR_BUFFER_BIT);
          draw_tile_coverage(fc, *atlas, static_cast<int>(page), dt.alpha_target);
          // Lines 3-8: n' ping-pong passes, each adding one layer of the gradient (Algorithm 3).
          // Pass k can change only texels within k of a target's cover (the rectangle its
          // silhouette can reach), so it runs over each tile's cover grown by k, every tile of the
          // page in one instanced draw. Every other texel holds 1 in both buffers (their clears;
          // no earlier pass wrote there, as the rectangles only grow), which is what a pass over
          // it would write: the buffers end as whole-page passes leave them.
          const std::vector<glm::vec4> covers = tile_covers(*atlas, static_cast<int>(page), layers);
          Handle src = d.ping[page], dst = d.pong[page];
          const Program& border = fc.programs.border;
          fc.use_program(border);
          glUniform1i(border.loc("u_source"), 0);
          glActiveTexture(GL_TEXTURE0);
          for (int k = 1; k <= layers; ++k) {
            glBindFramebuffer(GL_FRAMEBUFFER, r.framebuffer({dst}));
            glBindTexture(GL_TEXTURE_2D, r.texture(src));
            glUniform1f(border.loc("u_border_alpha"),
                        dt.alpha_start + (1.0f - dt.alpha_start) * static_cast<float>(k - 1) / static_cast<float>(layers));
            const float grow = static_cast<float>(k);
            draw_tile_rects(border, covers, glm::vec2(grow, grow), pg.width, pg.height);
            std::swap(src, dst);
          }
        }
        glBindTexture(GL_TEXTURE_2D, 0);
      });
  std::vector<Handle> out;
  for (std::size_t page = 0; page < atlas->pages.size(); ++page)
    out.push_back(fc.view.grid.layers % 2 == 1 ? masks.pong[page] : masks.ping[page]);
  return out;
}

// dt-clear onward into `main` (created here when not valid), each pass conditional on `query` when
// valid. With `codes`, every object writes its code into bits 0-5 where it is frontmost and the
// mask steps leave those bits alone (the effect-first plan's query reads them).
MainTargets add_seed_effect(FrameGraph& fg, const FrameContext& fc, const std::shared_ptr<const MaskAtlas>& atlas,
                            const std::vector<Handle>& mask_pages, MainTargets main, Handle query, bool codes) {
  struct DtClearPassData {
    Handle color, depth;
  };
  const auto& cleared = fg.add_pass<DtClearPassData>(
      "dt-clear",
      [&](FrameGraph::Builder& b, DtClearPassData& d) {
        if (query.valid()) b.condition(query);
        d.color = b.write(main.color.valid() ? main.color
                                             : b.create("color", {fc.width(), fc.height(), fc.color_format, false}));
        d.depth = b.write(main.depth.valid() ? main.depth
                                             : b.create("depth", {fc.width(), fc.height(), TextureFormat::depth24_stencil8, false}));
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
        [&fc, codes](const DrawPassData& d, PassResources& r) {
          bind_main(fc, r, d.color, d.depth);
          for (auto i : fc.view.impenetrable) draw_opaque_object(fc, i, object_stencil(fc, i, codes));
        });
    cur = {d.color, d.depth};
  }

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
          [&fc, codes, run = std::move(run)](const DrawPassData& d, PassResources& r) {
            bind_main(fc, r, d.color, d.depth);
            for (auto i : run) {
              draw_transparent_object(fc, i, false, object_stencil(fc, i, codes));  // always two passes
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
      Handle color, depth, mask;
    };
    const int slot = fc.view.target_slot[order[k]];
    const MaskTile& tile = atlas->tiles[static_cast<std::size_t>(slot)];
    const auto& m = fg.add_pass<MaskPassData>(
        "mask " + std::to_string(fc.gpu.objects()[order[k]].id),
        [&](FrameGraph::Builder& b, MaskPassData& d) {
          if (query.valid()) b.condition(query);
          if (tile.w > 0) d.mask = b.read(mask_pages[static_cast<std::size_t>(tile.page)]);
          d.color = b.write(b.read(cur.color));
          d.depth = b.write(b.read(cur.depth));
        },
        [&fc, slot, atlas, codes](const MaskPassData& d, PassResources& r) {
          // Lines 9-11 on the framebuffer: mark the full-resolution silhouette, multiply the
          // upsampled mask elsewhere, then aT over the silhouette itself.
          bind_main(fc, r, d.color, d.depth);
          mark_target(fc, slot, codes);
          if (d.mask.valid()) {
            begin_apply(fc, codes);
            const Program& apply = use_mask_apply(fc, *atlas, r.texture(d.mask), slot);
            // Outside the target's support the upsampled mask is 1.
            fc.quad(apply, fc.view.targets[static_cast<std::size_t>(slot)].support);
          }
          finish_target(fc, slot);
          glBindTexture(GL_TEXTURE_2D, 0);
        });
    cur = {m.color, m.depth};
  }
  return cur;
}

}  // namespace

MainTargets add_seed_passes(FrameGraph& fg, const FrameContext& fc, MainTargets main, Handle query) {
  auto atlas = std::make_shared<const MaskAtlas>(plan_mask_atlas(fc.view));
  const std::vector<Handle> mask_pages = add_seed_masks_pass(fg, fc, atlas, query);
  return add_seed_effect(fg, fc, atlas, mask_pages, main, query, false);
}

EffectFirst add_seed_direct_passes(FrameGraph& fg, const FrameContext& fc) {
  auto atlas = std::make_shared<const MaskAtlas>(plan_mask_atlas(fc.view));
  const std::vector<Handle> mask_pages = add_seed_masks_pass(fg, fc, atlas, Handle{});
  const MainTargets effect = add_seed_effect(fg, fc, atlas, mask_pages, MainTargets{}, Handle{}, true);
  // dt-seed's effect can change any pixel (its objects are drawn over the whole view).
  return add_effect_first_tail(fg, fc, effect, std::make_shared<const std::vector<PixelRect>>(1, fc.view.viewport()));
}

namespace {
MethodFrame add_seed(FrameGraph& fg, const FrameContext& fc, MethodSlot& slot) {
  return add_coherent(fg, fc, slot, add_seed_direct_passes, add_seed_passes);
}
}  // namespace

extern const MethodPasses k_passes_dt_seed{nullptr, add_seed, /*frame_coherent=*/true};

}  // namespace dtlab::render::detail

// dt-fast: the visual model of dt-seed at a cost close to standard's.
// Differences in method, not in model (docs/render.md, "dt-fast"):
//  * the standard frame (opaque pass) stays; only pixels a mask can change
//    (each target's support: silhouette or shape bounds + n + 1 pixels) are
//    re-rendered, in scissored regions of 32-pixel cells;
//  * every target's mask is computed at once, in one atlas of per-target
//    tiles at reduced resolution (texel = max(W, H) / R output pixels): the
//    silhouette is rasterized into its tile, then two separable passes give
//    the exact Chebyshev distance per tile (no ping-pong, no per-target
//    full-screen pass); the apply step reads the tile bilinearly;
//  * inside a region, objects that no earlier-drawn target's support touches
//    are drawn once with a plain z-buffer (alpha is 1 there, so blending is
//    a copy), the others with the depth + EQUAL colour passes.
// Passes: dt-masks, dt-composite, both conditional on the target-query.
#include <glad/gl.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <vector>

#include <glm/gtc/type_ptr.hpp>

#include "study/render/detail/passes.h"

namespace dtlab::render::detail {

namespace {

struct Tile {
  int slot = 0;
  int x = 0, y = 0, w = 0, h = 0;  // atlas texels
  PixelRect screen;                // the target's support (window pixels)
};

struct Atlas {
  float texel_px = 1.0f;  // output pixels per texel
  int reach = 1;          // distance (texels) past which alpha is 1 anyway
  int width = 1, height = 1;
  std::vector<Tile> tiles;  // by slot
};

int pow2_at_least(int v) {
  int p = 16;
  while (p < v) p *= 2;
  return p;
}

Atlas plan_atlas(const FrameContext& fc) {
  const DtSettings& dt = fc.settings.dt;
  Atlas a;
  a.texel_px = dt.mask_resolution > 0
                   ? std::max(1.0f, static_cast<float>(std::max(fc.width(), fc.height())) / dt.mask_resolution)
                   : 1.0f;
  for (int attempt = 0; attempt < 12; ++attempt) {
    a.reach = static_cast<int>(std::ceil((dt.gradient_px + 1.0f) / a.texel_px)) + 1;
    a.tiles.clear();
    long area = 0;
    int widest = 1;
    for (std::size_t s = 0; s < fc.view.targets.size(); ++s) {
      const PixelRect& sup = fc.view.targets[s].support;
      Tile t;
      t.slot = static_cast<int>(s);
      t.screen = sup;
      t.w = std::max(1, static_cast<int>(std::ceil(static_cast<float>(sup.x1 - sup.x0) / a.texel_px)));
      t.h = std::max(1, static_cast<int>(std::ceil(static_cast<float>(sup.y1 - sup.y0) / a.texel_px)));
      if (sup.empty()) t.w = t.h = 0;
      area += static_cast<long>(t.w) * t.h;
      widest = std::max(widest, t.w);
      a.tiles.push_back(t);
    }
    a.width = std::min(4096, pow2_at_least(std::max(widest, static_cast<int>(std::sqrt(static_cast<double>(area)) * 1.25))));
    // Shelf packing, tallest first.
    std::vector<Tile*> order;
    for (auto& t : a.tiles) order.push_back(&t);
    std::stable_sort(order.begin(), order.end(), [](const Tile* p, const Tile* q) { return p->h > q->h; });
    int x = 0, y = 0, shelf = 0;
    bool fits = widest <= a.width;
    for (Tile* t : order) {
      if (t->w == 0) continue;
      if (x + t->w > a.width) {
        y += shelf;
        x = 0;
        shelf = 0;
      }
      t->x = x;
      t->y = y;
      x += t->w;
      shelf = std::max(shelf, t->h);
    }
    a.height = pow2_at_least(y + shelf);
    if (fits && a.height <= 4096) return a;
    a.texel_px *= 1.5f;  // too many large targets for one atlas: coarser masks this frame
  }
  return a;
}

// Disjoint rectangles covering every 32-pixel cell that some target's support touches.
std::vector<PixelRect> plan_regions(const FrameContext& fc) {
  constexpr int kCell = 32;
  const int cw = (fc.width() + kCell - 1) / kCell, ch = (fc.height() + kCell - 1) / kCell;
  std::vector<char> marked(static_cast<std::size_t>(cw) * ch, 0);
  PixelRect limit = fc.view.viewport();
  const glm::vec3 sl = fc.view.searchlight;
  if (sl.z >= 0.0f)
    limit = limit.intersect({static_cast<int>(std::floor(sl.x - sl.z)) - 1, static_cast<int>(std::floor(sl.y - sl.z)) - 1,
                             static_cast<int>(std::ceil(sl.x + sl.z)) + 1, static_cast<int>(std::ceil(sl.y + sl.z)) + 1});
  for (const TargetView& t : fc.view.targets) {
    const PixelRect s = t.support.intersect(limit);
    if (s.empty()) continue;
    for (int cy = s.y0 / kCell; cy <= (s.y1 - 1) / kCell; ++cy)
      for (int cx = s.x0 / kCell; cx <= (s.x1 - 1) / kCell; ++cx) marked[static_cast<std::size_t>(cy) * cw + cx] = 1;
  }
  std::vector<PixelRect> runs;
  for (int cy = 0; cy < ch; ++cy) {
    for (int cx = 0; cx < cw;) {
      if (!marked[static_cast<std::size_t>(cy) * cw + cx]) {
        ++cx;
        continue;
      }
      int end = cx;
      while (end < cw && marked[static_cast<std::size_t>(cy) * cw + end]) ++end;
      PixelRect r{cx * kCell, cy * kCell, end * kCell, (cy + 1) * kCell};
      // Merge with a run of the row below that spans the same columns.
      bool merged = false;
      for (auto& prev : runs) {
        if (prev.x0 == r.x0 && prev.x1 == r.x1 && prev.y1 == r.y0) {
          prev.y1 = r.y1;
          merged = true;
          break;
        }
      }
      if (!merged) runs.push_back(r);
      cx = end;
    }
  }
  for (auto& r : runs) r = r.intersect(limit);
  runs.erase(std::remove_if(runs.begin(), runs.end(), [](const PixelRect& r) { return r.empty(); }), runs.end());
  return runs;
}

void scissor(const PixelRect& r) { glScissor(r.x0, r.y0, r.x1 - r.x0, r.y1 - r.y0); }

}  // namespace

MainTargets add_fast_passes(FrameGraph& fg, const FrameContext& fc, MainTargets main, Handle query) {
  auto atlas = std::make_shared<const Atlas>(plan_atlas(fc));
  auto regions = std::make_shared<const std::vector<PixelRect>>(plan_regions(fc));

  struct DtMasksPassData {
    Handle coverage, rows, distance;
  };
  const auto& masks = fg.add_pass<DtMasksPassData>(
      "dt-masks",
      [&](FrameGraph::Builder& b, DtMasksPassData& d) {
        b.condition(query);
        d.coverage = b.write(b.create("mask-coverage", {atlas->width, atlas->height, TextureFormat::r8, false}));
        d.rows = b.write(b.create("mask-rows", {atlas->width, atlas->height, TextureFormat::r16f, false}));
        d.distance = b.write(b.create("mask-distance", {atlas->width, atlas->height, TextureFormat::r16f, true}));
      },
      [&fc, atlas](const DtMasksPassData& d, PassResources& r) {
        const float W = static_cast<float>(fc.width()), H = static_cast<float>(fc.height());
        glDisable(GL_DEPTH_TEST);
        glDisable(GL_STENCIL_TEST);
        glDisable(GL_BLEND);
        glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
        glEnable(GL_SCISSOR_TEST);
        // Coverage: each target's silhouette (or shape) rasterized into its tile.
        glBindFramebuffer(GL_FRAMEBUFFER, r.framebuffer({d.coverage}));
        glClearColor(0.0f, 0.0f, 0.0f, 0.0f);
        for (const Tile& t : atlas->tiles) {
          if (t.w == 0) continue;
          glViewport(t.x, t.y, t.w, t.h);
          glScissor(t.x, t.y, t.w, t.h);
          glClear(GL_COLOR_BUFFER_BIT);
          const float span_x = static_cast<float>(t.w) * atlas->texel_px, span_y = static_cast<float>(t.h) * atlas->texel_px;
          glm::mat4 crop(1.0f);  // window pixels [screen.x0, screen.x0 + span) -> NDC [-1, 1]
          crop[0][0] = W / span_x;
          crop[3][0] = (W - 2.0f * static_cast<float>(t.screen.x0)) / span_x - 1.0f;
          crop[1][1] = H / span_y;
          crop[3][1] = (H - 2.0f * static_cast<float>(t.screen.y0)) / span_y - 1.0f;
          const glm::vec4 px_map(1.0f / atlas->texel_px, 1.0f / atlas->texel_px,
                                 static_cast<float>(t.x) - static_cast<float>(t.screen.x0) / atlas->texel_px,
                                 static_cast<float>(t.y) - static_cast<float>(t.screen.y0) / atlas->texel_px);
          draw_target_seed(fc, t.slot, 1.0f, crop * fc.view.view_proj, px_map, false);
        }
        glDisable(GL_SCISSOR_TEST);
        glViewport(0, 0, atlas->width, atlas->height);
        // Two separable passes: nearest covered texel per row, then Chebyshev per column.
        auto distance_pass = [&](const Program& p, Handle src, Handle dst, const char* sampler) {
          glBindFramebuffer(GL_FRAMEBUFFER, r.framebuffer({dst}));
          glUseProgram(p.id);
          glActiveTexture(GL_TEXTURE0);
          glBindTexture(GL_TEXTURE_2D, r.texture(src));
          glUniform1i(p.loc(sampler), 0);
          glUniform1i(p.loc("u_reach"), atlas->reach);
          for (const Tile& t : atlas->tiles) {
            if (t.w == 0) continue;
            glUniform4i(p.loc("u_tile"), t.x, t.y, t.x + t.w, t.y + t.h);
            fc.quad(p, static_cast<float>(t.x), static_cast<float>(t.y), static_cast<float>(t.x + t.w),
                    static_cast<float>(t.y + t.h), atlas->width, atlas->height);
          }
        };
        distance_pass(fc.programs.cheb_rows, d.coverage, d.rows, "u_coverage");
        distance_pass(fc.programs.cheb_cols, d.rows, d.distance, "u_rows");
        glBindTexture(GL_TEXTURE_2D, 0);
      });

  struct DtCompositePassData {
    Handle color, depth, distance;
  };
  const auto& comp = fg.add_pass<DtCompositePassData>(
      "dt-composite",
      [&](FrameGraph::Builder& b, DtCompositePassData& d) {
        b.condition(query);
        d.distance = b.read(masks.distance);
        d.color = b.write(b.read(main.color));
        d.depth = b.write(b.read(main.depth));
      },
      [&fc, atlas, regions](const DtCompositePassData& d, PassResources& r) {
        const DtSettings& dt = fc.settings.dt;
        glBindFramebuffer(GL_FRAMEBUFFER, r.framebuffer({d.color}, d.depth));
        glViewport(0, 0, fc.width(), fc.height());
        glEnable(GL_SCISSOR_TEST);
        const glm::vec3 bg = fc.background();
        std::vector<PixelRect> applied;  // supports of targets already drawn in this region
        for (const PixelRect& region : *regions) {
          scissor(region);
          glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
          glDepthMask(GL_TRUE);
          glStencilMask(0xFF);
          glClearColor(bg.r, bg.g, bg.b, 1.0f);
          glClearDepth(1.0);
          glClearStencil(0);
          glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT | GL_STENCIL_BUFFER_BIT);
          for (auto i : fc.view.impenetrable)
            if (fc.view.rects[i].overlaps(region)) draw_opaque_object(fc, i);
          applied.clear();
          for (auto i : fc.view.sorted) {
            const PixelRect part = fc.view.rects[i].intersect(region);
            if (!part.empty()) {
              const bool masked = std::any_of(applied.begin(), applied.end(), [&](const PixelRect& s) { return s.overlaps(part); });
              masked ? draw_transparent_object(fc, i) : draw_opaque_object(fc, i);
            }
            const int slot = fc.view.target_slot[i];
            if (slot < 0) continue;
            const TargetView& t = fc.view.targets[static_cast<std::size_t>(slot)];
            const PixelRect area = t.support.intersect(region);
            const Tile& tile = atlas->tiles[static_cast<std::size_t>(slot)];
            if (area.empty() || tile.w == 0) continue;
            applied.push_back(area);
            scissor(area);
            mark_target(fc, slot);
            begin_apply(fc);
            const Program& p = fc.programs.fast_apply;
            glUseProgram(p.id);
            glActiveTexture(GL_TEXTURE0);
            glBindTexture(GL_TEXTURE_2D, r.texture(d.distance));
            glUniform1i(p.loc("u_distance"), 0);
            glUniform2f(p.loc("u_atlas_size"), static_cast<float>(atlas->width), static_cast<float>(atlas->height));
            glUniform2f(p.loc("u_tile_origin"), static_cast<float>(tile.x), static_cast<float>(tile.y));
            glUniform2f(p.loc("u_tile_size"), static_cast<float>(tile.w), static_cast<float>(tile.h));
            glUniform2f(p.loc("u_screen_origin"), static_cast<float>(t.support.x0), static_cast<float>(t.support.y0));
            glUniform1f(p.loc("u_texel_px"), atlas->texel_px);
            glUniform1f(p.loc("u_alpha_start"), dt.alpha_start);
            glUniform1f(p.loc("u_gradient_px"), dt.gradient_px);
            glUniform3fv(p.loc("u_searchlight"), 1, glm::value_ptr(fc.searchlight_uniform(true)));
            fc.quad(p, static_cast<float>(area.x0), static_cast<float>(area.y0), static_cast<float>(area.x1),
                    static_cast<float>(area.y1), fc.width(), fc.height());
            finish_target(fc, slot);
            glBindTexture(GL_TEXTURE_2D, 0);
            scissor(region);
          }
        }
        glDisable(GL_SCISSOR_TEST);
      });
  return {comp.color, comp.depth};
}

}  // namespace dtlab::render::detail

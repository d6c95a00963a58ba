// dt-fast: the visual model of dt-seed at a cost close to standard's.
// Differences in method, not in model (docs/render.md, "dt-fast"):
//  * every target's mask is computed at once, in one atlas of per-target
//    tiles at reduced resolution (texel = max(W, H) / R output pixels): the
//    silhouette is rasterized into its tile, then two separable passes give
//    the exact Chebyshev distance per tile (no ping-pong, no per-target
//    full-screen pass); the apply step reads the tile bilinearly and is
//    scissored to the target's support (silhouette bounds + n + 1 pixels);
//  * objects that no earlier-drawn target's support touches are drawn once
//    with a plain z-buffer (alpha is 1 there, blending would be a copy);
//    convex objects seen from outside are drawn in one back-face-culled
//    pass instead of depth pass + depth-EQUAL colour pass (same surfaces);
//  * two frame plans, chosen by what the previous frame needed (frame
//    coherence, as the article's bubble sort):
//    standard-first  opaque, target-query, then (conditional) dt-masks and
//                    dt-composite re-render only the regions the masks touch;
//    effect-first    dt-masks, dt-direct draw the effect directly, then the
//                    target-query on its depth; if nothing is occluded,
//                    query-invert + standard-fallback restore the standard
//                    image in those regions (conditional on the inverted query).
//    Both give the same image; each is cheapest when its guess is right.
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

// Tiles are packed on shelves, tallest first; the distance passes run one quad per tile
// (cheaper on llvmpipe than one quad over the whole atlas with gutters between tiles).
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
    const bool fits = widest <= a.width;
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

// Disjoint rectangles covering every pixel some target's mask can change. Supports are merged
// when they overlap, or when their bounding box is not much larger than the two (one region
// re-draws each object once; many small regions would re-draw objects once per region).
std::vector<PixelRect> plan_regions(const FrameContext& fc) {
  PixelRect limit = fc.view.viewport();
  const glm::vec3 sl = fc.view.searchlight;
  if (sl.z >= 0.0f)
    limit = limit.intersect({static_cast<int>(std::floor(sl.x - sl.z)) - 1, static_cast<int>(std::floor(sl.y - sl.z)) - 1,
                             static_cast<int>(std::ceil(sl.x + sl.z)) + 1, static_cast<int>(std::ceil(sl.y + sl.z)) + 1});
  std::vector<PixelRect> rs;
  for (const TargetView& t : fc.view.targets) {
    const PixelRect s = t.support.intersect(limit);
    if (!s.empty()) rs.push_back(s);
  }
  auto bbox = [](const PixelRect& a, const PixelRect& b) {
    return PixelRect{std::min(a.x0, b.x0), std::min(a.y0, b.y0), std::max(a.x1, b.x1), std::max(a.y1, b.y1)};
  };
  for (bool merged = true; merged;) {
    merged = false;
    for (std::size_t i = 0; i < rs.size() && !merged; ++i) {
      for (std::size_t j = i + 1; j < rs.size() && !merged; ++j) {
        const PixelRect u = bbox(rs[i], rs[j]);
        if (rs[i].overlaps(rs[j]) || u.area() <= (rs[i].area() + rs[j].area()) * 3 / 2 + 4096) {
          rs[i] = u;
          rs.erase(rs.begin() + static_cast<long>(j));
          merged = true;
        }
      }
    }
  }
  return rs;
}

void scissor(const PixelRect& r) { glScissor(r.x0, r.y0, r.x1 - r.x0, r.y1 - r.y0); }

struct MaskHandles {
  Handle alpha;
};

MaskHandles add_masks_pass(FrameGraph& fg, const FrameContext& fc, const std::shared_ptr<const Atlas>& atlas,
                           Handle query) {
  struct DtMasksPassData {
    Handle coverage, rows, alpha;
  };
  const auto& masks = fg.add_pass<DtMasksPassData>(
      "dt-masks",
      [&](FrameGraph::Builder& b, DtMasksPassData& d) {
        if (query.valid()) b.condition(query);
        d.coverage = b.write(b.create("mask-coverage", {atlas->width, atlas->height, TextureFormat::r8, false}));
        d.rows = b.write(b.create("mask-rows", {atlas->width, atlas->height, TextureFormat::r16f, false}));
        d.alpha = b.write(b.create("mask-alpha", {atlas->width, atlas->height, TextureFormat::r8, true}));
      },
      [&fc, atlas](const DtMasksPassData& d, PassResources& r) {
        const float W = static_cast<float>(fc.width()), H = static_cast<float>(fc.height());
        glDisable(GL_DEPTH_TEST);
        glDisable(GL_STENCIL_TEST);
        glDisable(GL_BLEND);
        glDisable(GL_CULL_FACE);
        glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
        // Coverage: each target's silhouette (or shape) rasterized into its tile. One unscissored
        // clear (a scissored clear per tile is a draw in Mesa, and costs more).
        glBindFramebuffer(GL_FRAMEBUFFER, r.framebuffer({d.coverage}));
        glDisable(GL_SCISSOR_TEST);
        glClearColor(0.0f, 0.0f, 0.0f, 0.0f);
        glClear(GL_COLOR_BUFFER_BIT);
        glEnable(GL_SCISSOR_TEST);
        for (const Tile& t : atlas->tiles) {
          if (t.w == 0) continue;
          glViewport(t.x, t.y, t.w, t.h);
          glScissor(t.x, t.y, t.w, t.h);
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
        // Two separable passes: nearest covered texel per row, then Chebyshev per column (as alpha).
        auto distance_pass = [&](const Program& p, Handle src, Handle dst, const char* sampler) {
          glBindFramebuffer(GL_FRAMEBUFFER, r.framebuffer({dst}));
          fc.use_program(p);
          glActiveTexture(GL_TEXTURE0);
          glBindTexture(GL_TEXTURE_2D, r.texture(src));
          glUniform1i(p.loc(sampler), 0);
          glUniform1i(p.loc("u_reach"), atlas->reach);
          glUniform1f(p.loc("u_texel_px"), atlas->texel_px);
          glUniform1f(p.loc("u_alpha_start"), fc.settings.dt.alpha_start);
          glUniform1f(p.loc("u_gradient_px"), fc.settings.dt.gradient_px);
          for (const Tile& t : atlas->tiles) {
            if (t.w == 0) continue;
            glUniform4i(p.loc("u_tile"), t.x, t.y, t.x + t.w, t.y + t.h);
            fc.quad(p, static_cast<float>(t.x), static_cast<float>(t.y), static_cast<float>(t.x + t.w),
                    static_cast<float>(t.y + t.h), atlas->width, atlas->height);
          }
        };
        distance_pass(fc.programs.cheb_rows, d.coverage, d.rows, "u_coverage");
        distance_pass(fc.programs.cheb_cols, d.rows, d.alpha, "u_rows");
        glBindTexture(GL_TEXTURE_2D, 0);
      });
  return {masks.alpha};
}

// Target `slot`'s mask, restricted to `area`: mark, multiply the atlas tile's gradient, aT inside.
void apply_target_mask(const FrameContext& fc, const Atlas& atlas, unsigned alpha_texture, int slot,
                       const PixelRect& area, bool keep_codes, bool marked) {
  const TargetView& t = fc.view.targets[static_cast<std::size_t>(slot)];
  const Tile& tile = atlas.tiles[static_cast<std::size_t>(slot)];
  if (area.empty() || tile.w == 0) return;
  scissor(area);
  if (!marked) mark_target(fc, slot, keep_codes);
  begin_apply(fc, keep_codes);
  const Program& p = fc.programs.fast_apply;
  fc.use_program(p);
  glActiveTexture(GL_TEXTURE0);
  glBindTexture(GL_TEXTURE_2D, alpha_texture);
  glUniform1i(p.loc("u_mask"), 0);
  glUniform2f(p.loc("u_atlas_size"), static_cast<float>(atlas.width), static_cast<float>(atlas.height));
  glUniform2f(p.loc("u_tile_origin"), static_cast<float>(tile.x), static_cast<float>(tile.y));
  glUniform2f(p.loc("u_tile_size"), static_cast<float>(tile.w), static_cast<float>(tile.h));
  glUniform2f(p.loc("u_screen_origin"), static_cast<float>(t.support.x0), static_cast<float>(t.support.y0));
  glUniform1f(p.loc("u_texel_px"), atlas.texel_px);
  glUniform3fv(p.loc("u_searchlight"), 1, glm::value_ptr(fc.searchlight_uniform(true)));
  fc.quad(p, static_cast<float>(area.x0), static_cast<float>(area.y0), static_cast<float>(area.x1),
          static_cast<float>(area.y1), fc.width(), fc.height());
  finish_target(fc, slot);
  glBindTexture(GL_TEXTURE_2D, 0);
}

// The effect over `region` (already cleared): impenetrable objects, then back to front.
void draw_effect(const FrameContext& fc, const Atlas& atlas, unsigned alpha_texture, const PixelRect& region,
                 bool codes) {
  scissor(region);
  for (auto i : fc.view.impenetrable)
    if (fc.view.rects[i].overlaps(region)) draw_opaque_object(fc, i, object_stencil(fc, i, codes));
  std::vector<PixelRect> applied;  // supports of the targets already drawn
  for (auto i : fc.view.sorted) {
    const PixelRect part = fc.view.rects[i].intersect(region);
    const int slot = fc.view.target_slot[i];
    // Layer-limit counters and the shapes need the separate mark (mark_target resets the counter);
    // a target nothing sorted earlier can hide needs no repair (FrameView::may_be_drawn_late).
    const bool fused = slot >= 0 && fc.guard() && fc.view.single_pass[i] && fc.settings.dt.layer_limit == 0 &&
                       fc.settings.dt.shape == MaskShape::outline;
    bool marked = false;
    if (!part.empty()) {
      const bool masked =
          std::any_of(applied.begin(), applied.end(), [&](const PixelRect& s) { return s.overlaps(part); });
      const StencilWrite sw = object_stencil(fc, i, codes);
      masked ? draw_transparent_object(fc, i, true, sw) : draw_opaque_object(fc, i, sw);
      const bool late = slot >= 0 && fc.view.targets[static_cast<std::size_t>(slot)].may_be_drawn_late;
      if (fused && late) {
        scissor(fc.view.targets[static_cast<std::size_t>(slot)].support.intersect(region));
        repair_and_mark_target(fc, i);
        marked = true;
      } else if (slot >= 0 && fc.guard() && late) {
        repair_target(fc, i);
      }
    }
    if (slot < 0) continue;
    const PixelRect area = fc.view.targets[static_cast<std::size_t>(slot)].support.intersect(region);
    if (area.empty()) continue;
    applied.push_back(area);
    apply_target_mask(fc, atlas, alpha_texture, slot, area, codes, marked);
    scissor(region);
  }
}

void clear_region(const FrameContext& fc, const PixelRect& region) {
  scissor(region);
  clear_to_background(fc);
}

}  // namespace

bool fast_direct_possible(const FrameContext& fc) {
  return fc.settings.dt.layer_limit == 0 && fc.view.targets.size() <= 63;
}

MainTargets add_fast_passes(FrameGraph& fg, const FrameContext& fc, MainTargets main, Handle query) {
  auto atlas = std::make_shared<const Atlas>(plan_atlas(fc));
  auto regions = std::make_shared<const std::vector<PixelRect>>(plan_regions(fc));
  const MaskHandles masks = add_masks_pass(fg, fc, atlas, query);

  struct DtCompositePassData {
    Handle color, depth, alpha;
  };
  const auto& comp = fg.add_pass<DtCompositePassData>(
      "dt-composite",
      [&](FrameGraph::Builder& b, DtCompositePassData& d) {
        b.condition(query);
        d.alpha = b.read(masks.alpha);
        d.color = b.write(b.read(main.color));
        d.depth = b.write(b.read(main.depth));
      },
      [&fc, atlas, regions](const DtCompositePassData& d, PassResources& r) {
        glBindFramebuffer(GL_FRAMEBUFFER, r.framebuffer({d.color}, d.depth));
        glViewport(0, 0, fc.width(), fc.height());
        glEnable(GL_SCISSOR_TEST);
        for (const PixelRect& region : *regions) {
          clear_region(fc, region);
          draw_effect(fc, *atlas, r.texture(d.alpha), region, false);
        }
        glDisable(GL_SCISSOR_TEST);
      });
  return {comp.color, comp.depth};
}

FastDirect add_fast_direct_passes(FrameGraph& fg, const FrameContext& fc) {
  auto atlas = std::make_shared<const Atlas>(plan_atlas(fc));
  auto regions = std::make_shared<const std::vector<PixelRect>>(plan_regions(fc));
  const MaskHandles masks = add_masks_pass(fg, fc, atlas, Handle{});

  struct DtDirectPassData {
    Handle color, depth, alpha;
  };
  const auto& direct = fg.add_pass<DtDirectPassData>(
      "dt-direct",
      [&](FrameGraph::Builder& b, DtDirectPassData& d) {
        d.alpha = b.read(masks.alpha);
        d.color = b.write(b.create("color", {fc.width(), fc.height(), fc.color_format, false}));
        d.depth = b.write(b.create("depth", {fc.width(), fc.height(), TextureFormat::depth24_stencil8, false}));
      },
      [&fc, atlas](const DtDirectPassData& d, PassResources& r) {
        glBindFramebuffer(GL_FRAMEBUFFER, r.framebuffer({d.color}, d.depth));
        glViewport(0, 0, fc.width(), fc.height());
        glEnable(GL_SCISSOR_TEST);
        clear_region(fc, fc.view.viewport());
        draw_effect(fc, *atlas, r.texture(d.alpha), fc.view.viewport(), true);
        glDisable(GL_SCISSOR_TEST);
      });
  const Handle query = add_target_query_pass(fg, fc, direct.depth);

  // Q_not = "no target occluded", computed on the GPU: a conditional write to a 1x1 depth
  // buffer, then a query that passes only where that write did not happen.
  struct QueryInvertPassData {
    Handle query, scratch, inverted;
  };
  const auto& inv = fg.add_pass<QueryInvertPassData>(
      "query-invert",
      [&](FrameGraph::Builder& b, QueryInvertPassData& d) {
        d.query = b.read(query);
        d.scratch = b.write(b.create("invert-scratch", {1, 1, TextureFormat::depth32f, false}));
        d.inverted = b.write(b.create_query("no-target-occluded"));
      },
      [&fc](const QueryInvertPassData& d, PassResources& r) {
        glBindFramebuffer(GL_FRAMEBUFFER, r.framebuffer({}, d.scratch));
        glViewport(0, 0, 1, 1);
        glDisable(GL_SCISSOR_TEST);
        glDisable(GL_STENCIL_TEST);
        glDisable(GL_BLEND);
        glDisable(GL_CULL_FACE);
        glEnable(GL_DEPTH_TEST);
        glDepthMask(GL_TRUE);
        glClearDepth(1.0);
        glClear(GL_DEPTH_BUFFER_BIT);
        const Program& p = fc.programs.quad_alpha;
        fc.use_program(p);
        glUniform3f(p.loc("u_searchlight"), 0.0f, 0.0f, -1.0f);
        glBeginConditionalRender(r.query(d.query), GL_QUERY_WAIT);
        glDepthFunc(GL_ALWAYS);
        glUniform1f(p.loc("u_z"), -1.0f);  // depth 0 where some target is occluded
        fc.quad(p, 0.0f, 0.0f, 1.0f, 1.0f, 1, 1);
        glEndConditionalRender();
        glDepthFunc(GL_LESS);
        glDepthMask(GL_FALSE);
        glUniform1f(p.loc("u_z"), 0.0f);  // depth 0.5: passes only if the write above did not happen
        glBeginQuery(GL_ANY_SAMPLES_PASSED, r.query(d.inverted));
        fc.quad(p, 0.0f, 0.0f, 1.0f, 1.0f, 1, 1);
        glEndQuery(GL_ANY_SAMPLES_PASSED);
        glDepthMask(GL_TRUE);
        glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
      });

  struct FallbackPassData {
    Handle color, depth;
  };
  const auto& fb = fg.add_pass<FallbackPassData>(
      "standard-fallback",
      [&](FrameGraph::Builder& b, FallbackPassData& d) {
        b.condition(inv.inverted);
        d.color = b.write(b.read(direct.color));
        d.depth = b.write(b.read(direct.depth));
      },
      [&fc, regions](const FallbackPassData& d, PassResources& r) {
        glBindFramebuffer(GL_FRAMEBUFFER, r.framebuffer({d.color}, d.depth));
        glViewport(0, 0, fc.width(), fc.height());
        glEnable(GL_SCISSOR_TEST);
        for (const PixelRect& region : *regions) {
          clear_region(fc, region);
          for (std::uint32_t i = 0; i < fc.view.rects.size(); ++i)
            if (fc.view.rects[i].overlaps(region)) draw_opaque_object(fc, i);
        }
        glDisable(GL_SCISSOR_TEST);
      });
  return {fb.color, query};
}

}  // namespace dtlab::render::detail

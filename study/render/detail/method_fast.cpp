// dt-fast: dt-seed's picture at a cost close to standard's. The same masks
// (dt-seed's R x R texel grid, its rings of a0 + (1 - a0)(d - 1)/n', aT
// where covered, bilinear upsampling, the full-resolution silhouette at aT),
// the same order and alpha rule; different algorithms (docs/render.md,
// "dt-fast"):
//  * every target's mask at once, in atlas pages of per-target tiles of that
//    grid: the silhouette rasterized into its tile at the grid's own texel
//    positions, then two separable passes give the exact Chebyshev distance
//    (the rings Algorithm 3's ping-pong passes grow) and write the texel's
//    value; no ping-pong, no per-target full-screen pass;
//  * objects that no earlier-drawn target's support touches are drawn once
//    with a plain z-buffer (alpha is 1 there, blending would be a copy);
//    convex objects seen from outside in one back-face-culled pass;
//  * a target's silhouette is marked in the stencil by its own depth pass,
//    and its mask multiplied into alpha only over the parts of its support
//    that a later-drawn object covers (nothing else ever reads that alpha);
//  * two frame plans, chosen by what the previous frame needed (frame
//    coherence, as the article's bubble sort):
//    standard-first  opaque, target-query, then (conditional) dt-masks and
//                    dt-composite re-render only the regions the masks touch;
//    effect-first    dt-masks, dt-direct draw the effect directly, then the
//                    target-query on its depth; if nothing is occluded,
//                    query-invert + standard-fallback restore the standard
//                    image in those regions (conditional on the inverted query).
//    Both give the same image; each is cheapest when its guess is right.
// Never: writes alpha where no later object can read it (the final alpha is
// the cumulative alpha only under later objects).
#include <glad/gl.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <vector>

#include <glm/gtc/type_ptr.hpp>

#include "study/render/detail/mask_atlas.h"
#include "study/render/detail/method.h"
#include "study/render/detail/passes.h"

namespace dtlab::render::detail {

namespace {

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

// The parts of `area` that an object drawn after position k of the sorted order covers (its
// screen rectangle), as disjoint rectangles on a 32-pixel cell grid: the only pixels where the
// alpha that target k's mask leaves is ever read (by a later object's blend or mask).
std::vector<PixelRect> later_cover(const FrameContext& fc, std::size_t k, const PixelRect& area) {
  constexpr int kCell = 16;
  const int cw = (area.x1 - area.x0 + kCell - 1) / kCell, ch = (area.y1 - area.y0 + kCell - 1) / kCell;
  std::vector<char> cell(static_cast<std::size_t>(cw) * static_cast<std::size_t>(ch), 0);
  bool any = false;
  const auto& order = fc.view.sorted;
  for (std::size_t j = k + 1; j < order.size(); ++j) {
    const PixelRect r = fc.view.rects[order[j]].intersect(area);
    if (r.empty()) continue;
    if (r == area) return {area};
    any = true;
    for (int cy = (r.y0 - area.y0) / kCell; cy <= (r.y1 - 1 - area.y0) / kCell; ++cy)
      for (int cx = (r.x0 - area.x0) / kCell; cx <= (r.x1 - 1 - area.x0) / kCell; ++cx)
        cell[static_cast<std::size_t>(cy) * static_cast<std::size_t>(cw) + static_cast<std::size_t>(cx)] = 1;
  }
  if (!any) return {};
  // Runs of covered cells per row; a run equal to one of the row below extends that rectangle.
  std::vector<PixelRect> out;
  std::vector<std::size_t> open, next;  // indices into `out` ending at the current row
  for (int cy = 0; cy < ch; ++cy) {
    next.clear();
    const int y0 = area.y0 + cy * kCell, y1 = std::min(area.y1, y0 + kCell);
    for (int cx = 0; cx < cw;) {
      if (!cell[static_cast<std::size_t>(cy) * static_cast<std::size_t>(cw) + static_cast<std::size_t>(cx)]) {
        ++cx;
        continue;
      }
      int end = cx;
      while (end < cw && cell[static_cast<std::size_t>(cy) * static_cast<std::size_t>(cw) + static_cast<std::size_t>(end)]) ++end;
      const int x0 = area.x0 + cx * kCell, x1 = std::min(area.x1, area.x0 + end * kCell);
      auto it = std::find_if(open.begin(), open.end(), [&](std::size_t o) { return out[o].x0 == x0 && out[o].x1 == x1; });
      if (it != open.end()) {
        out[*it].y1 = y1;
        next.push_back(*it);
      } else {
        out.push_back({x0, y0, x1, y1});
        next.push_back(out.size() - 1);
      }
      cx = end;
    }
    open.swap(next);
  }
  return out;
}

// One alpha texture per atlas page.
struct MaskHandles {
  std::vector<Handle> alpha;
};

MaskHandles add_masks_pass(FrameGraph& fg, const FrameContext& fc, const std::shared_ptr<const MaskAtlas>& atlas,
                           Handle query) {
  struct DtMasksPassData {
    std::vector<Handle> coverage, rows, alpha;
  };
  const auto& masks = fg.add_pass<DtMasksPassData>(
      "dt-masks",
      [&](FrameGraph::Builder& b, DtMasksPassData& d) {
        if (query.valid()) b.condition(query);
        for (const MaskAtlas::Page& p : atlas->pages) {
          d.coverage.push_back(b.write(b.create("mask-coverage", {p.width, p.height, TextureFormat::r8, false})));
          d.rows.push_back(b.write(b.create("mask-rows", {p.width, p.height, TextureFormat::r16f, false})));
          d.alpha.push_back(b.write(b.create("mask-alpha", {p.width, p.height, TextureFormat::r16f, true})));
        }
      },
      [&fc, atlas](const DtMasksPassData& d, PassResources& r) {
        const MaskGrid& g = fc.view.grid;
        const DtSettings& dt = fc.settings.dt;
        buffer_state();
        for (std::size_t page = 0; page < atlas->pages.size(); ++page) {
          const MaskAtlas::Page& pg = atlas->pages[page];
          // Coverage (one unscissored clear: a scissored clear per tile is a draw in Mesa).
          glBindFramebuffer(GL_FRAMEBUFFER, r.framebuffer({d.coverage[page]}));
          glDisable(GL_SCISSOR_TEST);
          glClearColor(0.0f, 0.0f, 0.0f, 0.0f);
          glClear(GL_COLOR_BUFFER_BIT);
          draw_tile_coverage(fc, *atlas, static_cast<int>(page), 1.0f);
          // Two separable passes: nearest covered texel per row, then Chebyshev per column (as the
          // texel's mask value), each over only the texels of each tile it can change (every tile
          // of the page in one instanced draw): rows over the cover's rows, n' texels to each side;
          // columns over the cover grown by n'. Everywhere else the clears leave what a pass would
          // write: n' + 1 ("no covered texel in reach") in the rows page, 1 in the mask page. A
          // tile's padding of n' + 1 texels keeps every other tile's coverage more than n' texels
          // from its texels, so the passes need no tile bounds.
          const std::vector<glm::vec4> covers = tile_covers(*atlas, static_cast<int>(page), g.layers);
          const float reach = static_cast<float>(g.layers);
          auto distance_pass = [&](const Program& p, Handle src, Handle dst, const char* sampler, float clear,
                                   glm::vec2 grow) {
            glBindFramebuffer(GL_FRAMEBUFFER, r.framebuffer({dst}));
            glClearColor(clear, clear, clear, clear);
            glClear(GL_COLOR_BUFFER_BIT);
            fc.use_program(p);
            glActiveTexture(GL_TEXTURE0);
            glBindTexture(GL_TEXTURE_2D, r.texture(src));
            glUniform1i(p.loc(sampler), 0);
            glUniform1i(p.loc("u_reach"), g.layers);
            glUniform1i(p.loc("u_layers"), g.layers);
            glUniform1f(p.loc("u_alpha_target"), dt.alpha_target);
            glUniform1f(p.loc("u_alpha_start"), dt.alpha_start);
            draw_tile_rects(p, covers, grow, pg.width, pg.height);
          };
          distance_pass(fc.programs.cheb_rows, d.coverage[page], d.rows[page], "u_coverage", reach + 1.0f,
                        glm::vec2(reach, 0.0f));
          distance_pass(fc.programs.cheb_cols, d.rows[page], d.alpha[page], "u_rows", 1.0f, glm::vec2(reach, reach));
        }
        glBindTexture(GL_TEXTURE_2D, 0);
      });
  return {masks.alpha};
}

void quads(const FrameContext& fc, const Program& p, const std::vector<PixelRect>& rects, const PixelRect& within) {
  for (const PixelRect& r : rects) {
    const PixelRect q = r.intersect(within);
    if (!q.empty()) fc.quad(p, q);
  }
}

// Target `slot`'s mask over `rects`, its silhouette already marked (bit 7) by its own depth pass:
// the gradient multiplied into alpha outside the mark, then aT inside it (inside the searchlight),
// clearing the mark. Quads only: the target's mesh is not drawn again.
void apply_marked(const FrameContext& fc, const MaskAtlas& atlas, unsigned alpha_texture, int slot,
                  const std::vector<PixelRect>& rects) {
  alpha_multiply_state();
  glStencilFunc(GL_EQUAL, 0x00, 0x80);  // outside the silhouette
  glStencilOp(GL_KEEP, GL_KEEP, GL_KEEP);
  glStencilMask(0x00);
  quads(fc, use_mask_apply(fc, atlas, alpha_texture, slot), rects, fc.view.viewport());
  const Program& p = use_target_alpha_quad(fc);
  glStencilFunc(GL_EQUAL, 0x80, 0x80);  // the silhouette
  glStencilOp(GL_KEEP, GL_KEEP, GL_ZERO);
  glStencilMask(0x80);                  // clears the mark
  quads(fc, p, rects, fc.view.targets[static_cast<std::size_t>(slot)].rect);
  glBindTexture(GL_TEXTURE_2D, 0);
}

// Target `slot`'s mask over `rects` the general way (layer limit, circle / ellipse, or a target
// a sort error may hide): mark its whole silhouette or shape, multiply the gradient outside, aT
// inside (the target drawn again for both).
void apply_unmarked(const FrameContext& fc, const MaskAtlas& atlas, unsigned alpha_texture, int slot,
                    const std::vector<PixelRect>& rects, bool keep_codes) {
  PixelRect box = rects.front();
  for (const PixelRect& r : rects)
    box = {std::min(box.x0, r.x0), std::min(box.y0, r.y0), std::max(box.x1, r.x1), std::max(box.y1, r.y1)};
  scissor(box);
  mark_target(fc, slot, keep_codes);
  begin_apply(fc, keep_codes);
  quads(fc, use_mask_apply(fc, atlas, alpha_texture, slot), rects, box);
  finish_target(fc, slot);
  glBindTexture(GL_TEXTURE_2D, 0);
}

// Whether target `slot`'s own draw marks its silhouette (the pixels where it is frontmost when
// drawn; where an object drawn before it hides it, the mask's bilinear sample applies instead of
// exactly aT, which inside the silhouette is aT too): outline masks without a layer counter, and
// not when the R1 guard repairs the target (the repair needs the mark bit first).
bool marks_in_own_pass(const FrameContext& fc, int slot) {
  const TargetView& t = fc.view.targets[static_cast<std::size_t>(slot)];
  return fc.settings.dt.shape == MaskShape::outline && fc.settings.dt.layer_limit == 0 &&
         !(fc.guard() && t.may_be_drawn_late);
}

// The effect over `region` (already cleared): impenetrable objects, then back to front. Whether
// an object is drawn as the article draws it (depth pass, then a blended depth-EQUAL colour pass)
// or once with a z-buffer depends only on the whole frame's supports, never on the region, so
// both frame plans draw every region the same way; the z-buffer draws give depth ties to the
// later object, as a depth-EQUAL pass does.
void draw_effect(const FrameContext& fc, const MaskAtlas& atlas, const std::vector<unsigned>& alpha_textures,
                 const PixelRect& region, bool codes) {
  scissor(region);
  for (auto i : fc.view.impenetrable)
    if (fc.view.rects[i].overlaps(region)) draw_opaque_object(fc, i, object_stencil(fc, i, codes));
  std::vector<PixelRect> supports;  // of the targets already drawn
  const auto& order = fc.view.sorted;
  for (std::size_t k = 0; k < order.size(); ++k) {
    const std::uint32_t i = order[k];
    const int slot = fc.view.target_slot[i];
    const bool marked = slot >= 0 && marks_in_own_pass(fc, slot);
    if (fc.view.rects[i].overlaps(region)) {
      const bool masked = std::any_of(supports.begin(), supports.end(),
                                      [&](const PixelRect& s) { return s.overlaps(fc.view.rects[i]); });
      StencilWrite sw = object_stencil(fc, i, codes);
      sw.mark = marked;
      masked ? draw_transparent_object(fc, i, true, sw) : draw_opaque_object(fc, i, sw, GL_LEQUAL);
      if (slot >= 0 && fc.guard() && fc.view.targets[static_cast<std::size_t>(slot)].may_be_drawn_late)
        repair_target(fc, i);
    }
    if (slot < 0) continue;
    const TargetView& t = fc.view.targets[static_cast<std::size_t>(slot)];
    supports.push_back(t.support);
    const PixelRect area = t.support.intersect(region);
    const MaskTile& tile = atlas.tiles[static_cast<std::size_t>(slot)];
    if (area.empty() || tile.w == 0) continue;
    const std::vector<PixelRect> rects = later_cover(fc, k, area);
    if (!rects.empty()) {
      const unsigned texture = alpha_textures[static_cast<std::size_t>(tile.page)];
      marked ? apply_marked(fc, atlas, texture, slot, rects) : apply_unmarked(fc, atlas, texture, slot, rects, codes);
    }
    scissor(region);
  }
}

std::vector<unsigned> textures(PassResources& r, const std::vector<Handle>& hs) {
  std::vector<unsigned> out;
  for (Handle h : hs) out.push_back(r.texture(h));
  return out;
}

}  // namespace

MainTargets add_fast_passes(FrameGraph& fg, const FrameContext& fc, MainTargets main, Handle query) {
  auto atlas = std::make_shared<const MaskAtlas>(plan_mask_atlas(fc.view));
  auto regions = std::make_shared<const std::vector<PixelRect>>(plan_regions(fc));
  const MaskHandles masks = add_masks_pass(fg, fc, atlas, query);

  struct DtCompositePassData {
    Handle color, depth;
    std::vector<Handle> alpha;
  };
  const auto& comp = fg.add_pass<DtCompositePassData>(
      "dt-composite",
      [&](FrameGraph::Builder& b, DtCompositePassData& d) {
        if (query.valid()) b.condition(query);
        for (Handle h : masks.alpha) d.alpha.push_back(b.read(h));
        d.color = b.write(b.read(main.color));
        d.depth = b.write(b.read(main.depth));
      },
      [&fc, atlas, regions](const DtCompositePassData& d, PassResources& r) {
        glBindFramebuffer(GL_FRAMEBUFFER, r.framebuffer({d.color}, d.depth));
        glViewport(0, 0, fc.width(), fc.height());
        glEnable(GL_SCISSOR_TEST);
        const std::vector<unsigned> alpha = textures(r, d.alpha);
        for (const PixelRect& region : *regions) {
          clear_region(fc, region);
          draw_effect(fc, *atlas, alpha, region, false);
        }
        glDisable(GL_SCISSOR_TEST);
      });
  return {comp.color, comp.depth};
}

EffectFirst add_fast_direct_passes(FrameGraph& fg, const FrameContext& fc) {
  auto atlas = std::make_shared<const MaskAtlas>(plan_mask_atlas(fc.view));
  auto regions = std::make_shared<const std::vector<PixelRect>>(plan_regions(fc));
  const MaskHandles masks = add_masks_pass(fg, fc, atlas, Handle{});

  struct DtDirectPassData {
    Handle color, depth;
    std::vector<Handle> alpha;
  };
  const auto& direct = fg.add_pass<DtDirectPassData>(
      "dt-direct",
      [&](FrameGraph::Builder& b, DtDirectPassData& d) {
        for (Handle h : masks.alpha) d.alpha.push_back(b.read(h));
        d.color = b.write(b.create("color", {fc.width(), fc.height(), fc.color_format, false}));
        d.depth = b.write(b.create("depth", {fc.width(), fc.height(), TextureFormat::depth24_stencil8, false}));
      },
      [&fc, atlas, regions](const DtDirectPassData& d, PassResources& r) {
        glBindFramebuffer(GL_FRAMEBUFFER, r.framebuffer({d.color}, d.depth));
        glViewport(0, 0, fc.width(), fc.height());
        glEnable(GL_SCISSOR_TEST);
        // The standard frame outside the regions: the regions' depth at 0 first, so no fragment
        // lands in them, then every object (but those wholly inside a region) in scene order,
        // exactly as the `opaque` pass draws them; then the effect in each region, exactly as
        // `dt-composite` draws it. So both plans give the same image, tie for tie.
        clear_region(fc, fc.view.viewport());
        glDepthMask(GL_TRUE);
        glClearDepth(0.0);
        for (const PixelRect& region : *regions) {
          scissor(region);
          glClear(GL_DEPTH_BUFFER_BIT);
        }
        glDisable(GL_SCISSOR_TEST);
        for (std::uint32_t i = 0; i < fc.view.rects.size(); ++i) {
          const PixelRect& rect = fc.view.rects[i];
          if (rect.empty() || std::any_of(regions->begin(), regions->end(), [&](const PixelRect& g) {
                return g.intersect(rect) == rect;
              }))
            continue;
          draw_opaque_object(fc, i, object_stencil(fc, i, true));
        }
        glEnable(GL_SCISSOR_TEST);
        const std::vector<unsigned> alpha = textures(r, d.alpha);
        for (const PixelRect& region : *regions) {
          clear_region(fc, region);
          draw_effect(fc, *atlas, alpha, region, true);
        }
        glDisable(GL_SCISSOR_TEST);
      });
  return add_effect_first_tail(fg, fc, {direct.color, direct.depth}, regions);
}

namespace {
MethodFrame add_fast(FrameGraph& fg, const FrameContext& fc, MethodSlot& slot) {
  return add_coherent(fg, fc, slot, add_fast_direct_passes, add_fast_passes);
}
}  // namespace

extern const MethodPasses k_passes_dt_fast{nullptr, add_fast, /*frame_coherent=*/true};

}  // namespace dtlab::render::detail

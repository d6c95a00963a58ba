// Internal: the masks of all targets of a frame in atlas pages, one tile per
// target holding the texels of the frame's mask grid (frame_view.h MaskGrid)
// around it, so that dt-seed's Algorithm 2 and dt-fast's distance passes can
// run once per page instead of once per target. Guarantees: a tile holds its
// target's covered texels padded by n' + 1 texels on every side (beyond the
// grid too), so nothing one tile's coverage does reaches another tile's texels
// in n' passes; the coverage is rasterized at the grid's own texel positions
// (the viewport is the grid moved by whole texels), as an R x R buffer sees it.
// Never: samples outside a tile's texels inside the grid.
#pragma once
#include <vector>

#include "study/render/detail/passes.h"

namespace dtlab::render::detail {

struct MaskTile {
  int page = 0;
  int x = 0, y = 0, w = 0, h = 0;  // atlas texels; w = 0: the target covers no texel
  PixelRect texels;  // the grid texels it holds: cover + n' + 1 each side (beyond the grid: never covered)
  PixelRect inside;  // those inside the grid (samples are clamped to them, as an R x R buffer clamps)
};

struct MaskAtlas {
  struct Page {
    int width = 1, height = 1;  // powers of two around the page's tiles
  };
  std::vector<Page> pages;     // at most 4096 x 4096 texels each (or the largest tile)
  std::vector<MaskTile> tiles;  // by target slot
};

// Shelf-packs the tiles of every target in view, tallest first.
MaskAtlas plan_mask_atlas(const FrameView& view);

// Draws every target of `page` into its tile with `value` (the bound framebuffer is the page's,
// already cleared); leaves the scissor test off and the viewport on the whole page.
void draw_tile_coverage(const FrameContext& fc, const MaskAtlas& atlas, int page, float value);

// The rectangles (atlas texels x0, y0, x1, y1) of page `page`'s tiles' covers: the texels their
// targets' silhouettes can cover, inside the n' + 1 padding.
std::vector<glm::vec4> tile_covers(const MaskAtlas& atlas, int page, int layers);
// Draws `covers`, each grown by `grow` texels (x, y) on each side, with `p` (a TILES program, bound,
// its other uniforms set) into the bound framebuffer of a `width` x `height` page: instanced draws.
void draw_tile_rects(const Program& p, const std::vector<glm::vec4>& covers, glm::vec2 grow, int width, int height);

// Binds the program that multiplies target `slot`'s mask (its tile of `texture`) into alpha over
// window pixels (fast_apply.frag; with a layer limit its variant that discards where the mask is
// 1, so the layer counter restarts only where alpha drops). Returns it for FrameContext::quad.
const Program& use_mask_apply(const FrameContext& fc, const MaskAtlas& atlas, unsigned texture, int slot);

}  // namespace dtlab::render::detail

// Mask atlas pages (see mask_atlas.h).
#include <glad/gl.h>

#include <algorithm>
#include <cmath>

#include <glm/gtc/type_ptr.hpp>

#include "study/render/detail/mask_atlas.h"

namespace dtlab::render::detail {

namespace {
int pow2_at_least(int v) {
  int p = 16;
  while (p < v) p *= 2;
  return p;
}
}  // namespace

MaskAtlas plan_mask_atlas(const FrameView& view) {
  const MaskGrid& g = view.grid;
  MaskAtlas a;
  long area = 0;
  int widest = 1, tallest = 1;
  for (const TargetView& t : view.targets) {
    MaskTile tile;
    if (!t.cover.empty()) {
      tile.texels = t.cover.expand(g.layers + 1);
      tile.inside = tile.texels.intersect({0, 0, g.width, g.height});
      tile.w = tile.texels.x1 - tile.texels.x0;
      tile.h = tile.texels.y1 - tile.texels.y0;
    }
    area += static_cast<long>(tile.w) * tile.h;
    widest = std::max(widest, tile.w);
    tallest = std::max(tallest, tile.h);
    a.tiles.push_back(tile);
  }
  const int side = std::max({4096, widest, tallest});
  const int width = std::min(side, pow2_at_least(std::max(widest, static_cast<int>(std::sqrt(static_cast<double>(area)) * 1.25))));
  std::vector<MaskTile*> order;
  for (auto& t : a.tiles)
    if (t.w > 0) order.push_back(&t);
  std::stable_sort(order.begin(), order.end(), [](const MaskTile* p, const MaskTile* q) { return p->h > q->h; });
  int x = 0, y = 0, shelf = 0, page = 0;
  auto close_page = [&] { a.pages.push_back({width, pow2_at_least(y + shelf)}); };
  for (MaskTile* t : order) {
    if (x + t->w > width) {  // next shelf
      y += shelf;
      x = 0;
      shelf = 0;
    }
    if (y + t->h > side) {  // next page
      close_page();
      ++page;
      x = y = shelf = 0;
    }
    t->page = page;
    t->x = x;
    t->y = y;
    x += t->w;
    shelf = std::max(shelf, t->h);
  }
  close_page();
  return a;
}

void draw_tile_coverage(const FrameContext& fc, const MaskAtlas& atlas, int page, float value) {
  const MaskGrid& g = fc.view.grid;
  glEnable(GL_SCISSOR_TEST);
  for (std::size_t slot = 0; slot < atlas.tiles.size(); ++slot) {
    const MaskTile& t = atlas.tiles[slot];
    if (t.w == 0 || t.page != page) continue;
    const int ox = t.x - t.texels.x0, oy = t.y - t.texels.y0;
    glViewport(ox, oy, g.width, g.height);
    glScissor(t.x, t.y, t.w, t.h);
    draw_target_seed(fc, static_cast<int>(slot), value, fc.view.view_proj,
                     glm::vec4(1.0f / g.texel_x, 1.0f / g.texel_y, static_cast<float>(ox), static_cast<float>(oy)),
                     false);
  }
  glDisable(GL_SCISSOR_TEST);
  const MaskAtlas::Page& pg = atlas.pages[static_cast<std::size_t>(page)];
  glViewport(0, 0, pg.width, pg.height);
}

std::vector<glm::vec4> tile_covers(const MaskAtlas& atlas, int page, int layers) {
  std::vector<glm::vec4> covers;
  const float pad = static_cast<float>(layers + 1);
  for (const MaskTile& t : atlas.tiles)
    if (t.w > 0 && t.page == page)
      covers.emplace_back(static_cast<float>(t.x) + pad, static_cast<float>(t.y) + pad,
                          static_cast<float>(t.x + t.w) - pad, static_cast<float>(t.y + t.h) - pad);
  return covers;
}

void draw_tile_rects(const Program& p, const std::vector<glm::vec4>& covers, glm::vec2 grow, int width, int height) {
  constexpr std::size_t kTilesPerDraw = 64;  // fullscreen.vert's kMaxTiles
  glUniform2f(p.loc("u_size"), static_cast<float>(width), static_cast<float>(height));
  glUniform2f(p.loc("u_grow"), grow.x, grow.y);
  glUniform1f(p.loc("u_z"), 0.0f);
  for (std::size_t i = 0; i < covers.size(); i += kTilesPerDraw) {
    const auto n = static_cast<GLsizei>(std::min(kTilesPerDraw, covers.size() - i));
    glUniform4fv(p.loc("u_tiles"), n, glm::value_ptr(covers[i]));
    glDrawArraysInstanced(GL_TRIANGLE_STRIP, 0, 4, n);
  }
}

const Program& use_mask_apply(const FrameContext& fc, const MaskAtlas& atlas, unsigned texture, int slot) {
  const MaskTile& tile = atlas.tiles[static_cast<std::size_t>(slot)];
  const MaskAtlas::Page& pg = atlas.pages[static_cast<std::size_t>(tile.page)];
  const MaskGrid& g = fc.view.grid;
  const Program& p = fc.settings.dt.layer_limit > 0 ? fc.programs.fast_apply_counter : fc.programs.fast_apply;
  fc.use_program(p);
  glActiveTexture(GL_TEXTURE0);
  glBindTexture(GL_TEXTURE_2D, texture);
  glUniform1i(p.loc("u_mask"), 0);
  glUniform2f(p.loc("u_atlas_size"), static_cast<float>(pg.width), static_cast<float>(pg.height));
  glUniform2f(p.loc("u_tile_origin"), static_cast<float>(tile.x), static_cast<float>(tile.y));
  glUniform4f(p.loc("u_clamp"), static_cast<float>(tile.x + tile.inside.x0 - tile.texels.x0) + 0.5f,
              static_cast<float>(tile.y + tile.inside.y0 - tile.texels.y0) + 0.5f,
              static_cast<float>(tile.x + tile.inside.x1 - tile.texels.x0) - 0.5f,
              static_cast<float>(tile.y + tile.inside.y1 - tile.texels.y0) - 0.5f);
  glUniform2f(p.loc("u_tile_texel0"), static_cast<float>(tile.texels.x0), static_cast<float>(tile.texels.y0));
  glUniform2f(p.loc("u_texel_px"), g.texel_x, g.texel_y);
  glUniform3fv(p.loc("u_searchlight"), 1, glm::value_ptr(fc.searchlight_uniform(true)));
  return p;
}

}  // namespace dtlab::render::detail

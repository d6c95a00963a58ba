// screen-door: dt-seed's picture by sub-pixel screen-door transparency (Poon
// 2000, chapter 4, Figure 7): an enlarged frame buffer whose magnification is
// the mask side s, opaque and transparent surfaces z-buffered in any order,
// each transparent one rasterized through its mask, then the buffer box-
// filtered back to the output. Alpha of a surface at a pixel: dt-seed's rule
// (docs/render.md, "The visual model"), the product of the masks M_T(p) of the
// targets sorted before its object; M_T is the exact full-resolution mask that
// `reference` uses. Masks come from pixel_masks.h, per pixel, in rendering
// order (the back-to-front sort; priority = nearest, i.e. latest). Passes, all
// conditional on the target query (no target occluded: none run):
//   sd-silhouettes  each target alone, read back: the exact masks M_T;
//   sd-region k     one per chunk of (2048 / s)^2 output pixels that meets a
//                   target's support (the thesis renders a 96 x 96 region; the
//                   chunks cover the supports, where some alpha can be below 1;
//                   elsewhere every alpha is 1 and the frame is the opaque one):
//                   masks generated and uploaded, every object in the chunk drawn
//                   on the s-times enlarged buffer, resolved into the colour.
// The masked draw and the resolve are the method's own programs
// (shaders/screen_door.frag, shaders/sd_resolve.frag), linked in its
// MethodState on its first frame.
// Never: blends (order independence is the z-buffer's); a layer limit or the R1
// guard (not part of the thesis's model; docs/render.md says so).
#include <glad/gl.h>

#include <algorithm>
#include <memory>
#include <string>
#include <vector>

#include <glm/gtc/type_ptr.hpp>

#include "study/render/detail/compositor.h"
#include "study/render/detail/method.h"
#include "study/render/detail/passes.h"
#include "study/render/detail/pixel_masks.h"

namespace dtlab::render::detail {

namespace {

constexpr int kEnlargedSide = 2048;  // enlarged chunk side in sub-pixels (chunk: 2048 / s output pixels)
constexpr int kMaskTextureWidth = 8192;

// The method's own programs, linked on its first frame, deleted with the renderer.
class ScreenDoorPrograms final : public MethodState {
 public:
  ~ScreenDoorPrograms() override {
    delete_program(masked);
    delete_program(resolve);
  }
  Program masked;   // object.vert + screen_door.frag: keeps the sub-pixels of its mask (discards)
  Program resolve;  // fullscreen.vert + sd_resolve.frag: the enlarged buffer box-filtered to output pixels
};

// CPU results of sd-silhouettes, read by the sd-region passes (their declared read of the
// silhouette texture orders them after it), and the programs they draw with.
struct ScreenDoorState {
  const ScreenDoorPrograms* programs = nullptr;
  bool active = false;          // the target query saw an occluded target
  std::vector<MaskField> fields;  // per target slot
  std::unique_ptr<MaskCache> cache;
};

struct Entry {
  std::uint32_t object = 0;
  int slot = -1;   // target slot, or -1
  bool drawn = false;  // its rectangle meets the chunk
  int layer = -1;  // its block in the chunk's mask texture (-1: alpha 1 over the whole chunk)
  PixelRect block;     // the pixels its block holds: its rectangle within the chunk
  glm::ivec2 origin{0};  // the block's first texel
};

struct Chunk {
  PixelRect rect;
  std::vector<Entry> sequence;  // sorted order: objects drawn in the chunk, and targets whose mask reaches it
  int layers = 0;
  int tex_width = 1, tex_height = 1;  // the mask texture: blocks packed in shelves
};

MaskGeneration generation(ScreenDoorMasks m) {
  switch (m) {
    case ScreenDoorMasks::tabular: return MaskGeneration::tabular;
    case ScreenDoorMasks::pixel_tree: return MaskGeneration::pixel_tree;
    case ScreenDoorMasks::white_noise: return MaskGeneration::white_noise;
  }
  return MaskGeneration::tabular;
}

std::vector<Chunk> plan_chunks(const FrameContext& fc, int side) {
  const FrameView& v = fc.view;
  const int c = kEnlargedSide / side, words = side * side / 32;
  std::vector<Chunk> out;
  for (int y0 = 0; y0 < v.height; y0 += c) {
    for (int x0 = 0; x0 < v.width; x0 += c) {
      Chunk ch;
      ch.rect = PixelRect{x0, y0, x0 + c, y0 + c}.intersect(v.viewport());
      bool reached = false;  // some target's support meets the chunk
      for (std::uint32_t i : v.sorted) {
        const int slot = v.target_slot[i];
        const bool drawn = v.rects[i].overlaps(ch.rect);
        const bool mask = slot >= 0 && v.targets[static_cast<std::size_t>(slot)].support.overlaps(ch.rect);
        if (!drawn && !mask) continue;
        Entry e{i, slot, drawn, -1, {}, {}};
        if (drawn && reached) {  // sorted after a target that reaches here
          e.layer = ch.layers++;
          e.block = v.rects[i].intersect(ch.rect);
        }
        reached = reached || mask;
        ch.sequence.push_back(e);
      }
      if (ch.layers == 0) continue;  // every alpha is 1 here: the opaque frame stands
      for (std::uint32_t i : v.impenetrable)
        if (v.rects[i].overlaps(ch.rect)) ch.sequence.insert(ch.sequence.begin(), Entry{i, -1, true, -1, {}, {}});
      int x = 0, y = 0, shelf = 0;  // shelf packing, blocks of (width x words) x height texels
      for (Entry& e : ch.sequence) {
        if (e.layer < 0) continue;
        const int bw = (e.block.x1 - e.block.x0) * words, bh = e.block.y1 - e.block.y0;
        if (x + bw > kMaskTextureWidth) {
          x = 0;
          y += shelf;
          shelf = 0;
        }
        e.origin = {x, y};
        x += bw;
        shelf = std::max(shelf, bh);
        ch.tex_width = std::max(ch.tex_width, x);
      }
      ch.tex_height = y + shelf;
      out.push_back(std::move(ch));
    }
  }
  return out;
}

void sd_silhouettes(const FrameContext& fc, ScreenDoorState& st, unsigned query, unsigned fbo) {
  GLuint any = 1;
  if (query != 0) glGetQueryObjectuiv(query, GL_QUERY_RESULT, &any);
  st.active = any != 0;
  if (!st.active) return;
  const FrameView& v = fc.view;
  glBindFramebuffer(GL_FRAMEBUFFER, fbo);
  glViewport(0, 0, fc.width(), fc.height());
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_STENCIL_TEST);
  glDisable(GL_BLEND);
  glDisable(GL_CULL_FACE);
  glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
  glEnable(GL_SCISSOR_TEST);
  glBindBuffer(GL_PIXEL_PACK_BUFFER, 0);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  fc.use_alpha(v.view_proj, 1.0f, false);
  for (const TargetView& t : v.targets) {
    if (t.rect.empty()) {
      st.fields.push_back(exact_mask(fc.settings.dt, v.searchlight, t, nullptr));
      continue;
    }
    const int w = t.rect.x1 - t.rect.x0, h = t.rect.y1 - t.rect.y0;
    glScissor(t.rect.x0, t.rect.y0, w, h);
    glClearColor(0.0f, 0.0f, 0.0f, 0.0f);
    glClear(GL_COLOR_BUFFER_BIT);
    fc.draw_alpha(t.object);
    std::vector<std::uint8_t> covered(static_cast<std::size_t>(w) * h);
    glReadPixels(t.rect.x0, t.rect.y0, w, h, GL_RED, GL_UNSIGNED_BYTE, covered.data());
    ObjectLayer layer;  // exact_mask reads coverage from depth < 1
    layer.object = t.object;
    layer.rect = t.rect;
    layer.depth.resize(covered.size());
    for (std::size_t k = 0; k < covered.size(); ++k) layer.depth[k] = covered[k] > 127 ? 0.5f : 1.0f;
    st.fields.push_back(exact_mask(fc.settings.dt, v.searchlight, t, &layer));
  }
  glDisable(GL_SCISSOR_TEST);
}

// The chunk's masks: per masked object a block over its rectangle within the chunk (words per
// pixel side by side); a pixel where the object keeps alpha 1 has its full mask.
std::vector<std::uint32_t> chunk_masks(const FrameContext& fc, ScreenDoorState& st, const Chunk& ch, int side,
                                       const TextureDesc& desc) {
  const int words = side * side / 32;
  std::vector<std::uint32_t> tex(static_cast<std::size_t>(desc.width) * desc.height, 0xffffffffu);
  std::vector<std::pair<float, int>> seq;
  std::vector<const Entry*> who;
  for (int y = ch.rect.y0; y < ch.rect.y1; ++y) {
    for (int x = ch.rect.x0; x < ch.rect.x1; ++x) {
      float a = 1.0f;
      seq.clear();
      who.clear();
      for (const Entry& e : ch.sequence) {
        const PixelRect& r = fc.view.rects[e.object];
        if (e.layer >= 0 && a < 1.0f && x >= r.x0 && x < r.x1 && y >= r.y0 && y < r.y1) {
          seq.emplace_back(a, 0);
          who.push_back(&e);
        }
        if (e.slot >= 0) a *= st.fields[static_cast<std::size_t>(e.slot)].at(x, y);
      }
      if (seq.empty()) continue;
      for (std::size_t k = 0; k < seq.size(); ++k) seq[k].second = static_cast<int>(seq.size() - 1 - k);  // 0: nearest
      const std::vector<PixelMask>& masks = st.cache->get(seq);
      for (std::size_t k = 0; k < seq.size(); ++k) {
        const Entry& e = *who[k];
        const std::size_t tx = static_cast<std::size_t>(e.origin.x + (x - e.block.x0) * words);
        const std::size_t ty = static_cast<std::size_t>(e.origin.y + (y - e.block.y0));
        std::copy(masks[k].words.begin(), masks[k].words.end(), tex.begin() + static_cast<long>(ty * desc.width + tx));
      }
    }
  }
  return tex;
}

// The chunk's objects on the enlarged buffer (bound), through a projection cropped to the chunk.
void draw_enlarged(const FrameContext& fc, const ScreenDoorPrograms& programs, const Chunk& ch, int side,
                   unsigned mask_texture) {
  const int words = side * side / 32;
  const float W = static_cast<float>(fc.width()), H = static_cast<float>(fc.height());
  const PixelRect& r = ch.rect;
  const float sx = W / static_cast<float>(r.x1 - r.x0), sy = H / static_cast<float>(r.y1 - r.y0);
  const float cx = static_cast<float>(r.x0 + r.x1) / W - 1.0f, cy = static_cast<float>(r.y0 + r.y1) / H - 1.0f;
  glm::mat4 crop(1.0f);  // NDC of the chunk -> [-1, 1]
  crop[0][0] = sx;
  crop[1][1] = sy;
  crop[3][0] = -sx * cx;
  crop[3][1] = -sy * cy;
  const glm::mat4 vp = crop * fc.view.view_proj;
  fc.use_lit(vp);
  for (const Entry& e : ch.sequence)
    if (e.drawn && e.layer < 0) fc.draw_lit(e.object);
  const Program& p = programs.masked;
  fc.use_program(p);
  glUniformMatrix4fv(p.loc("u_view_proj"), 1, GL_FALSE, glm::value_ptr(vp));
  glUniform3fv(p.loc("u_eye"), 1, glm::value_ptr(fc.view.camera.eye));
  glUniform1i(p.loc("u_sd_masks"), 0);
  glUniform1i(p.loc("u_sd_side"), side);
  glUniform1i(p.loc("u_sd_words"), words);
  glActiveTexture(GL_TEXTURE0);
  glBindTexture(GL_TEXTURE_2D, mask_texture);
  for (const Entry& e : ch.sequence) {
    if (e.layer < 0) continue;
    const ObjectRecord& o = fc.gpu.objects()[e.object];
    glUniform2i(p.loc("u_sd_origin"), e.origin.x, e.origin.y);
    glUniform4i(p.loc("u_sd_block"), e.block.x0 - ch.rect.x0, e.block.y0 - ch.rect.y0, e.block.x1 - ch.rect.x0,
                e.block.y1 - ch.rect.y0);
    glUniformMatrix4fv(p.loc("u_model"), 1, GL_FALSE, glm::value_ptr(o.model));
    glUniformMatrix3fv(p.loc("u_normal_matrix"), 1, GL_FALSE, glm::value_ptr(o.normal_matrix));
    glUniform3fv(p.loc("u_tint"), 1, glm::value_ptr(o.tint));
    glUniform4fv(p.loc("u_flat"), 1, glm::value_ptr(fc.flat_color(e.object)));
    fc.gpu.draw(o);
  }
  glBindTexture(GL_TEXTURE_2D, 0);
}

struct RegionPassData {
  Handle silhouette, color, enlarged, enlarged_depth, masks;
};

// One sd-region pass: the chunk's masks uploaded, its objects drawn on the enlarged buffer, the
// box filter into the colour.
void sd_region(const FrameContext& fc, ScreenDoorState& st, const Chunk& ch, int side, const RegionPassData& d,
               PassResources& r) {
  const TextureDesc& md = r.desc(d.masks);
  const std::vector<std::uint32_t> tex = chunk_masks(fc, st, ch, side, md);
  glBindBuffer(GL_PIXEL_UNPACK_BUFFER, 0);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
  glBindTexture(GL_TEXTURE_2D, r.texture(d.masks));
  glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, md.width, md.height, GL_RED_INTEGER, GL_UNSIGNED_INT, tex.data());
  // The enlarged buffer: background, then every object of the chunk z-buffered.
  const int ew = (ch.rect.x1 - ch.rect.x0) * side, eh = (ch.rect.y1 - ch.rect.y0) * side;
  glBindFramebuffer(GL_FRAMEBUFFER, r.framebuffer({d.enlarged}, d.enlarged_depth));
  glViewport(0, 0, ew, eh);
  glEnable(GL_SCISSOR_TEST);
  glScissor(0, 0, ew, eh);
  glDisable(GL_BLEND);
  glDisable(GL_STENCIL_TEST);
  glDisable(GL_CULL_FACE);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  clear_to_background(fc);
  draw_enlarged(fc, *st.programs, ch, side, r.texture(d.masks));
  // Resolve: the box filter into the chunk's output pixels.
  glBindFramebuffer(GL_FRAMEBUFFER, r.framebuffer({d.color}));
  glViewport(0, 0, fc.width(), fc.height());
  scissor(ch.rect);
  glDisable(GL_DEPTH_TEST);
  glDepthMask(GL_FALSE);
  const Program& p = st.programs->resolve;
  fc.use_program(p);
  glUniform1i(p.loc("u_enlarged"), 0);
  glUniform1i(p.loc("u_side"), side);
  glUniform2i(p.loc("u_origin"), ch.rect.x0, ch.rect.y0);
  glBindTexture(GL_TEXTURE_2D, r.texture(d.enlarged));
  fc.quad(p, ch.rect);
  glBindTexture(GL_TEXTURE_2D, 0);
  glDisable(GL_SCISSOR_TEST);
  glDepthMask(GL_TRUE);
}

// The effect's passes, conditional on `query` like dt-seed's: `sd-silhouettes` reads the targets'
// silhouettes back for their exact masks; then one `sd-region` pass per chunk of the targets'
// supports renders every object in the chunk on an enlarged buffer (s x s sub-pixels per pixel),
// each keeping the sub-pixels of its mask, and box-filters the chunk back into the colour.
// Returns the final colour and depth.
MainTargets add_screen_door_passes(FrameGraph& fg, const FrameContext& fc, const ScreenDoorPrograms& programs,
                                   MainTargets main, Handle query) {
  const int side = fc.settings.screen_door.mask_side;
  auto state = std::make_shared<ScreenDoorState>();
  state->programs = &programs;
  MaskTable::Options options;
  options.generation = generation(fc.settings.screen_door.masks);
  state->cache = std::make_unique<MaskCache>(side * side, options);
  auto chunks = std::make_shared<const std::vector<Chunk>>(plan_chunks(fc, side));
  if (chunks->empty()) return main;

  struct SilhouettePassData {
    Handle query, silhouette;
  };
  const auto& sil = fg.add_pass<SilhouettePassData>(
      "sd-silhouettes",
      [&](FrameGraph::Builder& b, SilhouettePassData& d) {
        if (query.valid()) {
          b.condition(query);
          d.query = b.read(query);
        }
        d.silhouette = b.write(b.create("sd-silhouette", {fc.width(), fc.height(), TextureFormat::r8, false}));
      },
      [&fc, state](const SilhouettePassData& d, PassResources& r) {
        sd_silhouettes(fc, *state, d.query.valid() ? r.query(d.query) : 0u, r.framebuffer({d.silhouette}));
      });

  Handle color = main.color;
  for (std::size_t k = 0; k < chunks->size(); ++k) {
    const Chunk& ch = (*chunks)[k];
    const auto& reg = fg.add_pass<RegionPassData>(
        "sd-region " + std::to_string(k + 1),
        [&](FrameGraph::Builder& b, RegionPassData& d) {
          if (query.valid()) b.condition(query);
          d.silhouette = b.read(sil.silhouette);
          d.color = b.write(b.read(color));
          d.enlarged = b.write(b.create("sd-enlarged", {kEnlargedSide, kEnlargedSide, fc.color_format, false}));
          d.enlarged_depth = b.write(
              b.create("sd-enlarged-depth", {kEnlargedSide, kEnlargedSide, TextureFormat::depth24_stencil8, false}));
          d.masks = b.write(b.create("sd-masks", {ch.tex_width, ch.tex_height, TextureFormat::r32ui, false}));
        },
        [&fc, state, chunks, k, side](const RegionPassData& d, PassResources& r) {
          if (state->active) sd_region(fc, *state, (*chunks)[k], side, d, r);
        });
    color = reg.color;
  }
  return {color, main.depth};
}

MethodFrame add_screen_door(FrameGraph& fg, const FrameContext& fc, MethodSlot& slot) {
  if (!slot.state) {
    auto programs = std::make_unique<ScreenDoorPrograms>();
    programs->masked = link_method_program("screen-door", "object.vert", "screen_door.frag", "", "lighting.glsl");
    programs->resolve = link_method_program("screen-door", "fullscreen.vert", "sd_resolve.frag");
    slot.state = std::move(programs);
  }
  const auto& programs = static_cast<const ScreenDoorPrograms&>(*slot.state);
  return add_standard_first(fg, fc, [&programs](FrameGraph& g, const FrameContext& c, MainTargets main, Handle query) {
    return add_screen_door_passes(g, c, programs, main, query);
  });
}

}  // namespace

extern const MethodPasses k_passes_screen_door{nullptr, add_screen_door};

}  // namespace dtlab::render::detail

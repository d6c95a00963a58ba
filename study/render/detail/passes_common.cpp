// Passes every method shares: opaque (the standard frame), target-query, present;
// and the GL sequences of dynamic transparency both GPU methods use (see passes.h).
#include <glad/gl.h>

#include <stdexcept>

#include <glm/gtc/type_ptr.hpp>

#include "study/render/detail/passes.h"

namespace dtlab::render::detail {

// --- FrameContext --------------------------------------------------------------------------

glm::vec4 FrameContext::flat_color(std::uint32_t object) const {
  if (settings.flat_colors.empty()) return glm::vec4(0.0f);
  const glm::vec3 c = object < settings.flat_colors.size() ? settings.flat_colors[object] : glm::vec3(0.0f);
  return glm::vec4(c, 1.0f);
}

glm::vec3 FrameContext::background() const {
  return settings.flat_colors.empty() ? settings.background : glm::vec3(0.0f);
}

glm::vec3 FrameContext::searchlight_uniform(bool on) const {
  return on ? view.searchlight : glm::vec3(0.0f, 0.0f, -1.0f);
}

void FrameContext::use_program(const Program& p) const {
  if (bound.program == p.id) return;
  glUseProgram(p.id);
  bound.program = p.id;
}

FrameContext::Uniforms& FrameContext::uniforms_of(const Program& p) const {
  for (Uniforms& u : bound.uniforms) {
    if (u.program == &p) return u;
    if (u.program == nullptr) {
      u.program = &p;
      return u;
    }
  }
  throw std::logic_error("FrameContext: more scene programs than uniform caches");
}

void FrameContext::use_lit(const glm::mat4& view_proj, bool searchlight) const {
  const bool cut = searchlight && active();
  // Weight frames (every object a flat colour) take the FLAT variant: the same output for less
  // work per triangle.
  const bool flat = !settings.flat_colors.empty();
  const Program& p =
      flat ? (cut ? programs.object_flat_sl : programs.object_flat) : (cut ? programs.object_sl : programs.object);
  use_program(p);
  bound.lit = &p;
  Uniforms& u = uniforms_of(p);
  if (!u.valid || u.vp != view_proj) {
    glUniformMatrix4fv(p.loc("u_view_proj"), 1, GL_FALSE, glm::value_ptr(view_proj));
    glUniform3fv(p.loc("u_eye"), 1, glm::value_ptr(view.camera.eye));
    u.vp = view_proj;
  }
  if (cut && (!u.valid || u.searchlight != view.searchlight)) {
    glUniform3fv(p.loc("u_searchlight"), 1, glm::value_ptr(view.searchlight));
    u.searchlight = view.searchlight;
  }
  u.valid = true;
}

void FrameContext::draw_lit(std::uint32_t object) const {
  const Program& p = *bound.lit;
  const ObjectRecord& o = gpu.objects()[object];
  glUniformMatrix4fv(p.loc("u_model"), 1, GL_FALSE, glm::value_ptr(o.model));
  glUniformMatrix3fv(p.loc("u_normal_matrix"), 1, GL_FALSE, glm::value_ptr(o.normal_matrix));
  glUniform3fv(p.loc("u_tint"), 1, glm::value_ptr(o.tint));
  glUniform4fv(p.loc("u_flat"), 1, glm::value_ptr(flat_color(object)));
  gpu.draw(o);
}

void FrameContext::use_alpha(const glm::mat4& view_proj, float alpha, bool searchlight, bool outside_one) const {
  const bool cut = searchlight && active();
  const Program& p = cut ? programs.object_alpha_sl : programs.object_alpha;
  use_program(p);
  bound.alpha = &p;
  Uniforms& u = uniforms_of(p);
  if (!u.valid || u.vp != view_proj) {
    glUniformMatrix4fv(p.loc("u_view_proj"), 1, GL_FALSE, glm::value_ptr(view_proj));
    u.vp = view_proj;
  }
  if (!u.valid || u.alpha != alpha) {
    glUniform1f(p.loc("u_alpha"), alpha);
    u.alpha = alpha;
  }
  if (cut && (!u.valid || u.searchlight != view.searchlight)) {
    glUniform3fv(p.loc("u_searchlight"), 1, glm::value_ptr(view.searchlight));
    u.searchlight = view.searchlight;
  }
  if (cut && (!u.valid || u.outside_one != static_cast<int>(outside_one))) {
    glUniform1i(p.loc("u_outside_one"), outside_one ? 1 : 0);
    u.outside_one = outside_one ? 1 : 0;
  }
  u.valid = true;
}

void FrameContext::draw_alpha(std::uint32_t object) const {
  const ObjectRecord& o = gpu.objects()[object];
  glUniformMatrix4fv(bound.alpha->loc("u_model"), 1, GL_FALSE, glm::value_ptr(o.model));
  gpu.draw(o);
}

void FrameContext::quad(const Program& p, float x0, float y0, float x1, float y1, int w, int h) const {
  const float fw = static_cast<float>(w), fh = static_cast<float>(h);
  glUniform4f(p.loc("u_rect"), x0 / fw * 2.0f - 1.0f, y0 / fh * 2.0f - 1.0f, x1 / fw * 2.0f - 1.0f,
              y1 / fh * 2.0f - 1.0f);
  glDrawArrays(GL_TRIANGLE_STRIP, 0, 4);
}

void FrameContext::quad(const Program& p, const PixelRect& r) const {
  quad(p, static_cast<float>(r.x0), static_cast<float>(r.y0), static_cast<float>(r.x1), static_cast<float>(r.y1), width(),
       height());
}

// --- shared GL sequences -------------------------------------------------------------------

void clear_to_background(const FrameContext& fc) {
  glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
  glDepthMask(GL_TRUE);
  glStencilMask(0xFF);
  const glm::vec3 bg = fc.background();
  glClearColor(bg.r, bg.g, bg.b, 1.0f);
  glClearDepth(1.0);
  glClearStencil(0);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT | GL_STENCIL_BUFFER_BIT);
}

void scissor(const PixelRect& r) { glScissor(r.x0, r.y0, r.x1 - r.x0, r.y1 - r.y0); }

void clear_region(const FrameContext& fc, const PixelRect& region) {
  scissor(region);
  clear_to_background(fc);
}

StencilWrite object_stencil(const FrameContext& fc, std::uint32_t i, bool codes) {
  const ObjectRecord& o = fc.gpu.objects()[i];
  StencilWrite w;
  if (codes) {
    const int slot = fc.view.target_slot[i];
    w.ref = slot < 0 ? 0 : fc.view.targets[static_cast<std::size_t>(slot)].code;
    w.mask = 0x3F;
  }
  if (fc.track_impenetrable() || (codes && o.impenetrable)) {
    w.ref |= o.impenetrable ? 0x40 : 0x00;
    w.mask |= 0x40;
  }
  if (o.target && fc.guard()) {
    w.ref |= 0x80;
    w.mask |= 0x80;
  }
  return w;
}

namespace {
void stencil_writes(const StencilWrite& w) {
  if (w.mask == 0 && !w.mark) {
    glDisable(GL_STENCIL_TEST);
    return;
  }
  glEnable(GL_STENCIL_TEST);
  glStencilFunc(GL_ALWAYS, w.mark ? w.ref | 0x80 : w.ref, 0xFF);
  glStencilOp(GL_KEEP, GL_KEEP, GL_REPLACE);
  glStencilMask(static_cast<GLuint>(w.mark ? w.mask | 0x80 : w.mask));
}
}  // namespace

void draw_opaque_object(const FrameContext& fc, std::uint32_t i, StencilWrite sw, unsigned depth_func) {
  static_assert(GL_LESS == 0x0201, "passes.h spells GL_LESS as its value");
  fc.use_lit(fc.view.view_proj);
  glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(static_cast<GLenum>(depth_func));
  glDepthMask(GL_TRUE);
  glDisable(GL_BLEND);
  glDisable(GL_CULL_FACE);
  stencil_writes(sw);
  fc.draw_lit(i);
}

void draw_transparent_object(const FrameContext& fc, std::uint32_t i, bool single_pass, StencilWrite sw) {
  const ObjectRecord& o = fc.gpu.objects()[i];
  const int limit = fc.settings.dt.layer_limit;
  // The layer limit needs the depth pass (its colour draws count in the stencil).
  const bool one = single_pass && fc.view.single_pass[i] && limit <= 0;
  const bool floor = o.target && fc.guard();
  fc.use_lit(fc.view.view_proj);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glDepthMask(GL_TRUE);
  if (one) {
    // Convex and seen from outside: the front faces are exactly the frontmost surface.
    glEnable(GL_CULL_FACE);
    glCullFace(GL_BACK);
    glFrontFace(o.mirrored ? GL_CW : GL_CCW);
  } else {
    // Step 1 (article V.3): the object's own z-buffer pass selects its frontmost surfaces.
    glDisable(GL_CULL_FACE);
    glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
    glDisable(GL_BLEND);
    stencil_writes(sw);
    fc.draw_lit(i);
    glDepthFunc(GL_EQUAL);
    glDepthMask(GL_FALSE);
    sw = StencilWrite{};
  }
  if (floor) {
    // R1 guard, step 1: alpha = max(alpha, aT) on the surfaces about to be blended (no depth
    // writes, so the colour draw below passes on exactly the same fragments).
    fc.use_alpha(fc.view.view_proj, fc.settings.dt.alpha_target, false);
    glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_TRUE);
    glDepthMask(GL_FALSE);
    glEnable(GL_BLEND);
    glBlendEquationSeparate(GL_FUNC_ADD, GL_MAX);
    glDisable(GL_STENCIL_TEST);
    fc.draw_alpha(i);
    glBlendEquationSeparate(GL_FUNC_ADD, GL_FUNC_ADD);
    glDepthMask(one ? GL_TRUE : GL_FALSE);
    fc.use_lit(fc.view.view_proj);
  }
  // Step 2: blend exactly those surfaces with the destination alpha; alpha itself stays.
  glBlendFuncSeparate(GL_DST_ALPHA, GL_ONE_MINUS_DST_ALPHA, GL_ZERO, GL_ONE);
  glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
  const bool uniforms_set = !one && !floor;  // the depth pass set this object's uniforms
  if (limit <= 0) {
    glEnable(GL_BLEND);
    stencil_writes(sw);
    uniforms_set ? fc.gpu.draw(o) : fc.draw_lit(i);
  } else {
    // Layer limit: bits 0-5 count surfaces drawn since the last mask made the pixel
    // transparent. Past the limit a surface is drawn opaque and resets alpha to 1.
    glEnable(GL_STENCIL_TEST);
    glStencilFunc(GL_LEQUAL, limit + 1, 0x3F);  // (limit + 1) <= count
    glStencilOp(GL_KEEP, GL_KEEP, GL_KEEP);
    glStencilMask(0x00);
    glDisable(GL_BLEND);
    uniforms_set ? fc.gpu.draw(o) : fc.draw_lit(i);
    glStencilFunc(GL_GEQUAL, limit, 0x3F);  // limit >= count
    glStencilOp(GL_KEEP, GL_KEEP, GL_INCR);
    glStencilMask(0x3F);
    glEnable(GL_BLEND);
    fc.gpu.draw(o);
  }
}

void repair_target(const FrameContext& fc, std::uint32_t i) {
  const ObjectRecord& o = fc.gpu.objects()[i];
  fc.use_lit(fc.view.view_proj, true);
  glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_FALSE);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_GREATER);  // hidden by something already drawn
  glDepthMask(GL_FALSE);
  glEnable(GL_BLEND);
  glBlendColor(0.0f, 0.0f, 0.0f, fc.settings.dt.alpha_target);
  glBlendFuncSeparate(GL_ONE_MINUS_CONSTANT_ALPHA, GL_CONSTANT_ALPHA, GL_ZERO, GL_ONE);
  glEnable(GL_STENCIL_TEST);
  glStencilFunc(GL_EQUAL, 0x00, 0xC0);  // not frontmost already, not behind an impenetrable surface
  glStencilOp(GL_KEEP, GL_KEEP, GL_INVERT);
  glStencilMask(0x80);                  // once per pixel
  if (fc.view.single_pass[i]) {
    glEnable(GL_CULL_FACE);
    glCullFace(GL_BACK);
    glFrontFace(o.mirrored ? GL_CW : GL_CCW);
  } else {
    glDisable(GL_CULL_FACE);
  }
  fc.draw_lit(i);
}

void repair_and_mark_target(const FrameContext& fc, std::uint32_t i) {
  const ObjectRecord& o = fc.gpu.objects()[i];
  fc.use_lit(fc.view.view_proj, true);
  glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_FALSE);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_GREATER);
  glDepthMask(GL_FALSE);
  glEnable(GL_BLEND);
  glBlendColor(0.0f, 0.0f, 0.0f, fc.settings.dt.alpha_target);
  glBlendFuncSeparate(GL_ONE_MINUS_CONSTANT_ALPHA, GL_CONSTANT_ALPHA, GL_ZERO, GL_ONE);
  glEnable(GL_STENCIL_TEST);
  glStencilFunc(GL_EQUAL, 0x80, 0x40);  // passes where bit 6 is clear; REPLACE writes bit 7
  glStencilOp(GL_REPLACE, GL_REPLACE, GL_REPLACE);
  glStencilMask(0x80);
  glEnable(GL_CULL_FACE);
  glCullFace(GL_BACK);
  glFrontFace(o.mirrored ? GL_CW : GL_CCW);
  fc.draw_lit(i);
}

void draw_target_seed(const FrameContext& fc, int slot, float alpha, const glm::mat4& view_proj, glm::vec4 px_map,
                      bool searchlight, bool outside_one) {
  const TargetView& t = fc.view.targets[static_cast<std::size_t>(slot)];
  if (fc.settings.dt.shape == MaskShape::outline) {
    fc.use_alpha(view_proj, alpha, searchlight, outside_one);
    fc.draw_alpha(t.object);
    return;
  }
  // Shapes are analytic, drawn over the whole viewport and cut by the shader.
  const Program& p = fc.programs.shape;
  fc.use_program(p);
  glUniform2f(p.loc("u_center"), t.shape_center.x * px_map.x + px_map.z, t.shape_center.y * px_map.y + px_map.w);
  glUniform2f(p.loc("u_radii"), t.shape_radii.x * px_map.x, t.shape_radii.y * px_map.y);
  glUniform1f(p.loc("u_alpha"), alpha);
  glUniform3fv(p.loc("u_searchlight"), 1, glm::value_ptr(fc.searchlight_uniform(searchlight)));
  glUniform1i(p.loc("u_outside_one"), outside_one ? 1 : 0);
  glUniform4f(p.loc("u_rect"), -1.0f, -1.0f, 1.0f, 1.0f);
  glDrawArrays(GL_TRIANGLE_STRIP, 0, 4);
}

void buffer_state() {
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_STENCIL_TEST);
  glDisable(GL_BLEND);
  glDisable(GL_CULL_FACE);
  glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
}

void alpha_multiply_state() {
  glDisable(GL_CULL_FACE);
  glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_TRUE);
  glDisable(GL_DEPTH_TEST);
  glDepthMask(GL_FALSE);
  glEnable(GL_BLEND);
  glBlendFuncSeparate(GL_ZERO, GL_ONE, GL_ZERO, GL_SRC_ALPHA);  // dst.a *= src.a
  glEnable(GL_STENCIL_TEST);
}

void mark_target(const FrameContext& fc, int slot, bool keep_codes) {
  glDisable(GL_CULL_FACE);
  glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
  glDisable(GL_DEPTH_TEST);
  glDepthMask(GL_FALSE);
  glDisable(GL_BLEND);
  glEnable(GL_STENCIL_TEST);
  glStencilFunc(GL_ALWAYS, 0x81, 0xFF);  // bit 7: silhouette; bits 0-5: layer counter = 1
  glStencilOp(GL_KEEP, GL_KEEP, GL_REPLACE);
  glStencilMask(keep_codes ? 0x80 : 0xBF);  // never bit 6
  // The whole silhouette, also outside the searchlight, so finish_target clears every mark.
  draw_target_seed(fc, slot, 1.0f, fc.view.view_proj, glm::vec4(1, 1, 0, 0), false);
}

void begin_apply(const FrameContext&, bool keep_codes) {
  alpha_multiply_state();
  glStencilFunc(GL_EQUAL, 0x01, 0x80);  // outside the marked silhouette
  glStencilOp(GL_KEEP, GL_KEEP, GL_REPLACE);
  glStencilMask(keep_codes ? 0x00 : 0x3F);  // the counter restarts at 1 where the mask is below 1
}

const Program& use_target_alpha_quad(const FrameContext& fc) {
  const Program& p = fc.programs.quad_alpha;
  fc.use_program(p);
  glUniform1f(p.loc("u_alpha"), fc.settings.dt.alpha_target);
  glUniform3fv(p.loc("u_searchlight"), 1, glm::value_ptr(fc.searchlight_uniform(true)));
  glUniform1i(p.loc("u_outside_one"), 1);
  glUniform1f(p.loc("u_z"), 0.0f);
  return p;
}

void finish_target(const FrameContext& fc, int slot) {
  alpha_multiply_state();
  glStencilFunc(GL_EQUAL, 0x80, 0x80);  // the marked silhouette
  glStencilOp(GL_KEEP, GL_KEEP, GL_ZERO);
  glStencilMask(0x80);                  // clears the mark, keeps the rest
  // aT inside the searchlight, 1 (no change) outside it: every marked pixel is visited once (the
  // first fragment clears its mark). An outline's marks lie inside the target's silhouette
  // bounds, so one quad over them visits the same pixels as the mesh would, for four vertices
  // instead of the mesh's triangles; a shape is a quad already.
  if (fc.settings.dt.shape != MaskShape::outline) {
    draw_target_seed(fc, slot, fc.settings.dt.alpha_target, fc.view.view_proj, glm::vec4(1, 1, 0, 0), true, true);
    return;
  }
  const Program& p = use_target_alpha_quad(fc);
  fc.quad(p, fc.view.targets[static_cast<std::size_t>(slot)].rect);
}

// --- opaque, target-query, present -----------------------------------------------------------

MainTargets add_opaque_pass(FrameGraph& fg, const FrameContext& fc, bool stencil_codes) {
  struct OpaquePassData {
    Handle color, depth;
  };
  const auto& data = fg.add_pass<OpaquePassData>(
      "opaque",
      [&](FrameGraph::Builder& b, OpaquePassData& d) {
        d.color = b.write(b.create("color", {fc.width(), fc.height(), fc.color_format, false}));
        d.depth = b.write(b.create("depth", {fc.width(), fc.height(), TextureFormat::depth24_stencil8, false}));
      },
      [&fc, stencil_codes](const OpaquePassData& d, PassResources& r) {
        glBindFramebuffer(GL_FRAMEBUFFER, r.framebuffer({d.color}, d.depth));
        glViewport(0, 0, fc.width(), fc.height());
        glDisable(GL_SCISSOR_TEST);
        glDisable(GL_BLEND);
        glDisable(GL_CULL_FACE);
        glEnable(GL_DEPTH_TEST);
        glDepthFunc(GL_LESS);
        glDepthMask(GL_TRUE);
        clear_to_background(fc);
        if (stencil_codes) {
          glEnable(GL_STENCIL_TEST);
          glStencilOp(GL_KEEP, GL_KEEP, GL_REPLACE);
        } else {
          glDisable(GL_STENCIL_TEST);
        }
        fc.use_lit(fc.view.view_proj);
        const auto& rects = fc.view.rects;
        for (std::uint32_t i = 0; i < rects.size(); ++i) {
          if (rects[i].empty()) continue;
          if (stencil_codes) {  // the frontmost object's code, for the target query
            const int slot = fc.view.target_slot[i];
            glStencilFunc(GL_ALWAYS, slot < 0 ? 0 : fc.view.targets[static_cast<std::size_t>(slot)].code, 0xFF);
          }
          fc.draw_lit(i);
        }
        glDisable(GL_STENCIL_TEST);
      });
  return {data.color, data.depth};
}

Handle add_target_query_pass(FrameGraph& fg, const FrameContext& fc, Handle depth, int code_bits) {
  struct TargetQueryPassData {
    Handle depth, query;
  };
  const auto& data = fg.add_pass<TargetQueryPassData>(
      "target-query",
      [&](FrameGraph::Builder& b, TargetQueryPassData& d) {
        d.depth = b.read(depth);
        d.query = b.write(b.create_query("any-target-occluded"));
      },
      [&fc, code_bits](const TargetQueryPassData& d, PassResources& r) {
        glBindFramebuffer(GL_FRAMEBUFFER, r.framebuffer({}, d.depth));
        glViewport(0, 0, fc.width(), fc.height());
        glDisable(GL_SCISSOR_TEST);
        glDisable(GL_BLEND);
        glDisable(GL_CULL_FACE);
        glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
        glEnable(GL_DEPTH_TEST);
        glDepthFunc(GL_GREATER);  // behind the frontmost surface ...
        glDepthMask(GL_FALSE);
        glEnable(GL_STENCIL_TEST);  // ... and that surface is not the target itself
        glStencilOp(GL_KEEP, GL_KEEP, GL_KEEP);
        glStencilMask(0x00);
        glBeginQuery(GL_ANY_SAMPLES_PASSED, r.query(d.query));
        fc.use_alpha(fc.view.view_proj, 0.0f, true);
        for (const TargetView& t : fc.view.targets) {
          glStencilFunc(GL_NOTEQUAL, t.code, static_cast<GLuint>(code_bits));
          // A convex target seen from outside: where its back face is behind another object's
          // surface, so is its front face (anything between the two would be inside it and hide
          // the back face only, with the front face frontmost: code equal). Front faces suffice.
          if (fc.view.single_pass[t.object]) {
            glEnable(GL_CULL_FACE);
            glCullFace(GL_BACK);
            glFrontFace(fc.gpu.objects()[t.object].mirrored ? GL_CW : GL_CCW);
          } else {
            glDisable(GL_CULL_FACE);
          }
          fc.draw_alpha(t.object);
        }
        glEndQuery(GL_ANY_SAMPLES_PASSED);
        glDisable(GL_CULL_FACE);
        glFrontFace(GL_CCW);
        glDisable(GL_STENCIL_TEST);
        glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
      });
  return data.query;
}

void add_present_pass(FrameGraph& fg, const FrameContext& fc, Handle color, Handle output) {
  struct PresentPassData {
    Handle color, output;
  };
  fg.add_pass<PresentPassData>(
      "present",
      [&](FrameGraph::Builder& b, PresentPassData& d) {
        d.color = b.read(color);
        d.output = b.write(output);  // imported: this pass is a root
      },
      [&fc](const PresentPassData& d, PassResources& r) {
        glBindFramebuffer(GL_READ_FRAMEBUFFER, r.framebuffer({d.color}));
        glBindFramebuffer(GL_DRAW_FRAMEBUFFER, r.framebuffer({d.output}));
        glDisable(GL_SCISSOR_TEST);
        glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
        glBlitFramebuffer(0, 0, fc.width(), fc.height(), 0, 0, fc.width(), fc.height(), GL_COLOR_BUFFER_BIT,
                          GL_NEAREST);
      });
}

// --- the effect-first plan's tail (dt-seed, dt-fast) ---------------------------------------

bool effect_first_possible(const FrameContext& fc) {
  return fc.settings.dt.layer_limit == 0 && !fc.view.codes_exhausted && fc.view.max_code <= 0x3F;
}

EffectFirst add_effect_first_tail(FrameGraph& fg, const FrameContext& fc, MainTargets effect,
                                  std::shared_ptr<const std::vector<PixelRect>> regions) {
  const Handle query = add_target_query_pass(fg, fc, effect.depth, 0x3F);

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
        d.color = b.write(b.read(effect.color));
        d.depth = b.write(b.read(effect.depth));
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

// The vdt method (docs/render.md, "vdt"; detail/vdt.h): view-dependent
// transparency after Diepstraten, Weiskopf & Ertl (2002). Section 6.2's five
// steps as frame-graph passes: the nearest and second-nearest transparent
// front faces into two depth textures (the second by peeling: a fragment at or
// in front of the first map is discarded, where the paper shifted depths by a
// texture shader after reading the depth buffer back), the opaque objects
// against the second map, the nearest transparent faces blended at exactly the
// first map's depth with GL_SRC_ALPHA, GL_DST_ALPHA (the paper's blend), and
// the opaque foreground drawn again. Guarantees: every pass sets the GL state
// it relies on, and attribute 3 of the scene's VAO is disabled again when the
// blend pass ends. The peeling and blend programs are the method's own
// (shaders/vdt_peel.frag, shaders/vdt.frag), linked on its first frame with
// a transparent object in view. Never: reads anything back to the CPU.
#include <glad/gl.h>

#include <algorithm>
#include <cmath>
#include <sstream>

#include <glm/gtc/type_ptr.hpp>

#include "study/render/detail/method.h"
#include "study/render/detail/passes.h"
#include "study/render/detail/vdt.h"
#include "study/render/render.h"

namespace dtlab::render::detail {

namespace {

constexpr GLuint kAlphaAttribute = 3;  // object.vert's a_alpha (VERTEX_ALPHA)

bool transparent(const ObjectRecord& o) { return !o.target && !o.impenetrable; }

void begin_pass(const FrameContext& fc, unsigned framebuffer) {
  glBindFramebuffer(GL_FRAMEBUFFER, framebuffer);
  glViewport(0, 0, fc.width(), fc.height());
  glDisable(GL_SCISSOR_TEST);
  glDisable(GL_STENCIL_TEST);
}

// Back faces culled, the winding of each object's front faces set before its draw ("only
// front-facing polygons are drawn", section 6.2).
void front_faces_only(const FrameContext& fc, std::uint32_t i) {
  glEnable(GL_CULL_FACE);
  glCullFace(GL_BACK);
  glFrontFace(fc.gpu.objects()[i].mirrored ? GL_CW : GL_CCW);
}

// Depth only, depth test LESS, every transparent object's front faces; with `peel`, the
// fragments at or in front of `peel` are discarded first.
void draw_transparent_depth(const FrameContext& fc, const VdtFrame& frame, unsigned peel) {
  glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
  glDisable(GL_BLEND);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glDepthMask(GL_TRUE);
  glClearDepth(1.0);
  glClear(GL_DEPTH_BUFFER_BIT);
  if (peel != 0) {
    const Program& p = frame.programs->peel;
    fc.use_program(p);
    fc.bound.alpha = &p;
    glUniformMatrix4fv(p.loc("u_view_proj"), 1, GL_FALSE, glm::value_ptr(fc.view.view_proj));
    glUniform1f(p.loc("u_alpha"), 1.0f);
    glUniform1i(p.loc("u_peel"), 0);
    glActiveTexture(GL_TEXTURE0);
    glBindTexture(GL_TEXTURE_2D, peel);
  } else {
    fc.use_alpha(fc.view.view_proj, 1.0f, false);
  }
  for (std::uint32_t i : frame.transparent) {
    front_faces_only(fc, i);
    fc.draw_alpha(i);
  }
  if (peel != 0) glBindTexture(GL_TEXTURE_2D, 0);
  glDisable(GL_CULL_FACE);
  glFrontFace(GL_CCW);
}

// Every colour channel written, blending on (the caller sets its functions), the depth test on.
void blended_colour_state(GLenum depth_func, GLboolean depth_write) {
  glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(depth_func);
  glDepthMask(depth_write);
  glEnable(GL_BLEND);
}

// Opaque objects, lit, z-buffered (LESS) over what the depth buffer holds, writing their fixed
// alpha (the destination weight of the later blend) through the constant blend colour.
void draw_opaque(const FrameContext& fc, const VdtFrame& frame) {
  blended_colour_state(GL_LESS, GL_TRUE);
  glDisable(GL_CULL_FACE);
  glBlendColor(0.0f, 0.0f, 0.0f, fc.settings.vdt.opaque_alpha);
  glBlendFuncSeparate(GL_ONE, GL_ZERO, GL_CONSTANT_ALPHA, GL_ZERO);
  fc.use_lit(fc.view.view_proj);
  for (std::uint32_t i : frame.opaque) fc.draw_lit(i);
  glDisable(GL_BLEND);
}

// The nearest transparent front faces (depth EQUAL against their own map), C = a C_t + a_dst C_dst.
void draw_blend(const FrameContext& fc, const VdtFrame& frame) {
  blended_colour_state(GL_EQUAL, GL_FALSE);
  glBlendFuncSeparate(GL_SRC_ALPHA, GL_DST_ALPHA, GL_ZERO, GL_ONE);  // the destination alpha stays
  const Program& p = frame.programs->blend;
  fc.use_program(p);
  fc.bound.lit = &p;
  glUniformMatrix4fv(p.loc("u_view_proj"), 1, GL_FALSE, glm::value_ptr(fc.view.view_proj));
  glUniform3fv(p.loc("u_eye"), 1, glm::value_ptr(fc.view.camera.eye));
  glBindBuffer(GL_ARRAY_BUFFER, frame.alpha_buffer);
  glEnableVertexAttribArray(kAlphaAttribute);
  for (std::size_t k = 0; k < frame.transparent.size(); ++k) {
    const std::uint32_t i = frame.transparent[k];
    glVertexAttribPointer(kAlphaAttribute, 1, GL_FLOAT, GL_FALSE, sizeof(float),
                          reinterpret_cast<const void*>(frame.alpha_offset[k]));
    front_faces_only(fc, i);
    fc.draw_lit(i);
  }
  glDisableVertexAttribArray(kAlphaAttribute);
  glDisable(GL_CULL_FACE);
  glFrontFace(GL_CCW);
  glDisable(GL_BLEND);
  glDepthFunc(GL_LESS);
}

}  // namespace

bool VdtState::prepare(const FrameContext& fc, VdtFrame& frame) {
  const auto& objects = fc.gpu.objects();
  for (std::uint32_t i = 0; i < objects.size(); ++i) {
    if (fc.view.rects[i].empty() || !objects[i].drawable()) continue;
    (transparent(objects[i]) ? frame.transparent : frame.opaque).push_back(i);
  }
  if (frame.transparent.empty()) return false;
  if (programs_.peel.id == 0) programs_.peel = link_method_program("vdt", "object.vert", "vdt_peel.frag");
  if (programs_.blend.id == 0)
    programs_.blend = link_method_program("vdt", "object.vert", "vdt.frag", "VERTEX_ALPHA", "lighting.glsl");
  frame.programs = &programs_;
  // Attribute 3 is read at (index + base vertex), like the mesh's own attributes, so an object's
  // block of alphas starts at least at its base vertex: the pointer offset (start - base vertex)
  // is then never negative. Objects are laid out in base-vertex order; the gaps stay unused.
  std::vector<std::uint32_t> order = frame.transparent;
  std::stable_sort(order.begin(), order.end(),
                   [&](std::uint32_t a, std::uint32_t b) { return objects[a].base_vertex < objects[b].base_vertex; });
  if (topology_.size() != fc.scene.meshes.size()) topology_.assign(fc.scene.meshes.size(), std::nullopt);
  alphas_.clear();
  std::vector<std::ptrdiff_t> offset_of(objects.size(), 0);
  for (std::uint32_t i : order) {
    const ObjectRecord& o = objects[i];
    std::optional<VdtTopology>& topo = topology_[o.mesh];
    if (!topo) topo = vdt_topology(fc.scene.meshes[o.mesh]);
    const std::size_t start = std::max(alphas_.size(), static_cast<std::size_t>(o.base_vertex));
    alphas_.resize(start, 0.0f);
    const std::vector<float> a = vdt_vertex_alpha(*topo, o.model, fc.view.camera.eye, fc.settings.vdt.falloff);
    alphas_.insert(alphas_.end(), a.begin(), a.end());
    offset_of[i] = static_cast<std::ptrdiff_t>((start - static_cast<std::size_t>(o.base_vertex)) * sizeof(float));
  }
  for (std::uint32_t i : frame.transparent) frame.alpha_offset.push_back(offset_of[i]);
  if (buffer_ == 0) glGenBuffers(1, &buffer_);
  glBindBuffer(GL_ARRAY_BUFFER, buffer_);
  glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(alphas_.size() * sizeof(float)), alphas_.data(),
               GL_STREAM_DRAW);
  frame.alpha_buffer = buffer_;
  return true;
}

void VdtState::destroy() {
  delete_program(programs_.peel);
  delete_program(programs_.blend);
  if (buffer_ != 0) glDeleteBuffers(1, &buffer_);
  buffer_ = 0;
}

Handle add_vdt_passes(FrameGraph& fg, const FrameContext& fc, const VdtFrame& frame) {
  const TextureDesc map{fc.width(), fc.height(), TextureFormat::depth32f, false};
  struct VdtDepthPassData {
    Handle peel, depth;
  };
  // Steps 1 and 3 of section 6.2: the nearest transparent front faces, then the second nearest.
  const Handle nearest = fg.add_pass<VdtDepthPassData>(
                              "vdt-nearest",
                              [&](FrameGraph::Builder& b, VdtDepthPassData& d) {
                                d.depth = b.write(b.create("vdt-nearest-depth", map));
                              },
                              [&fc, &frame](const VdtDepthPassData& d, PassResources& r) {
                                begin_pass(fc, r.framebuffer({}, d.depth));
                                draw_transparent_depth(fc, frame, 0);
                              })
                             .depth;
  const Handle second = fg.add_pass<VdtDepthPassData>(
                              "vdt-second",
                              [&](FrameGraph::Builder& b, VdtDepthPassData& d) {
                                d.peel = b.read(nearest);
                                d.depth = b.write(b.create("vdt-second-depth", map));
                              },
                              [&fc, &frame](const VdtDepthPassData& d, PassResources& r) {
                                begin_pass(fc, r.framebuffer({}, d.depth));
                                draw_transparent_depth(fc, frame, r.texture(d.peel));
                              })
                            .depth;

  struct VdtColorPassData {
    Handle color, depth;
  };
  // Step 4: the opaque objects against D2, over the background with its weight as alpha.
  const auto& opaque = fg.add_pass<VdtColorPassData>(
      "vdt-opaque",
      [&](FrameGraph::Builder& b, VdtColorPassData& d) {
        d.color = b.write(b.create("color", {fc.width(), fc.height(), fc.color_format, false}));
        d.depth = b.write(b.read(second));
      },
      [&fc, &frame](const VdtColorPassData& d, PassResources& r) {
        begin_pass(fc, r.framebuffer({d.color}, d.depth));
        const glm::vec3 bg = fc.background();
        glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
        glClearColor(bg.r, bg.g, bg.b, fc.settings.vdt.background_alpha);
        glClear(GL_COLOR_BUFFER_BIT);
        draw_opaque(fc, frame);
      });
  // Step 5: D1 again as the depth buffer; the nearest transparent faces blended at exactly their
  // depth, then the opaque objects in front of them ("the missing opaque foreground objects").
  const auto& blend = fg.add_pass<VdtColorPassData>(
      "vdt-blend",
      [&](FrameGraph::Builder& b, VdtColorPassData& d) {
        d.color = b.write(b.read(opaque.color));
        d.depth = b.write(b.read(nearest));
      },
      [&fc, &frame](const VdtColorPassData& d, PassResources& r) {
        begin_pass(fc, r.framebuffer({d.color}, d.depth));
        draw_blend(fc, frame);
      });
  const auto& foreground = fg.add_pass<VdtColorPassData>(
      "vdt-foreground",
      [&](FrameGraph::Builder& b, VdtColorPassData& d) {
        d.color = b.write(b.read(blend.color));
        d.depth = b.write(b.read(blend.depth));
      },
      [&fc, &frame](const VdtColorPassData& d, PassResources& r) {
        begin_pass(fc, r.framebuffer({d.color}, d.depth));
        draw_opaque(fc, frame);
      });
  return foreground.color;
}

namespace {

// The vdt state (alpha buffer, edge lists) and this frame's object classes (the passes read them
// when they run).
class VdtMethodState final : public MethodState {
 public:
  ~VdtMethodState() override { state.destroy(); }
  VdtState state;
  VdtFrame frame;
};

// No transparent object in view: standard's frame.
MethodFrame add_vdt(FrameGraph& fg, const FrameContext& fc, MethodSlot& slot) {
  if (!slot.state) slot.state = std::make_unique<VdtMethodState>();
  auto& v = static_cast<VdtMethodState&>(*slot.state);
  v.frame = VdtFrame{};
  if (v.state.prepare(fc, v.frame)) return {add_vdt_passes(fg, fc, v.frame), {}};
  return add_standard_first(fg, fc, nullptr);
}

}  // namespace

extern const MethodPasses k_passes_vdt{nullptr, add_vdt};

}  // namespace dtlab::render::detail

// The lens method (docs/render.md, "lens"): Ropinski & Hinrichs (2004),
// "Real-Time Rendering of 3D Magic Lenses having arbitrary convex Shapes".
// The lens geometry is rendered twice into depth maps (farthest surface:
// cleared to 0, depth test GREATER; nearest: cleared to 1, LESS, as the
// paper's DepthBuffer1), then the scene three times, behind / inside / in
// front of the lens, each pass keeping its class of fragments by a second
// depth test against those maps (the paper's shadow-map comparison, here a
// texelFetch at the fragment's window pixel and a discard). Two scene passes
// more than `standard` whatever the lens's shape.
// Guarantees: outside the lens footprint and wherever the lens holds no
// geometry the frame equals `standard`'s (same shader maths, same depths);
// targets and impenetrable surfaces are never erased. The second depth test
// is the method's own program (shaders/lens.frag), linked in its LensState
// on the first lens frame. Never: draws the lens itself into the colour.
#include <glad/gl.h>

#include <glm/gtc/type_ptr.hpp>

#include "study/render/detail/lens_volume.h"
#include "study/render/detail/method.h"
#include "study/render/detail/passes.h"

namespace dtlab::render::detail {

namespace {

enum class Class { behind = 0, inside = 1, in_front = 2 };

// The lens volume uploaded for this frame (world-space triangles, attribute 0 of `vao`) and the
// program of the three scene passes.
struct LensGpu {
  unsigned vao = 0;
  int vertices = 0;
  bool eye_inside = false;  // no entry surface: the front map is 0 over the whole view
  PixelRect footprint;      // pixels the lens can cover (conservative); passes 2 and 3 change nothing outside
  const Program* program = nullptr;  // object.vert + lens.frag: the second depth test (discards)
};

// One of the two lens depth maps: the farthest (`back`) or nearest surface of the volume per pixel.
// Depth clamping keeps a lens crossing the near (far) plane closed: its surfaces nearer than the
// near plane land at depth 0, those beyond the far plane at 1, instead of being clipped away.
void draw_lens_depth(const FrameContext& fc, const LensGpu& lens, bool back) {
  glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
  glDisable(GL_BLEND);
  glDisable(GL_STENCIL_TEST);
  glDisable(GL_CULL_FACE);
  glEnable(GL_DEPTH_TEST);
  glDepthMask(GL_TRUE);
  glClearDepth(back ? 0.0 : 1.0);
  if (!back && lens.eye_inside) glClearDepth(0.0);  // every ray starts inside: nothing is in front
  glClear(GL_DEPTH_BUFFER_BIT);
  glClearDepth(1.0);
  if (!back && lens.eye_inside) return;
  glDepthFunc(back ? GL_GREATER : GL_LESS);
  glEnable(GL_DEPTH_CLAMP);
  fc.use_alpha(fc.view.view_proj, 1.0f, false);
  const glm::mat4 identity(1.0f);
  glUniformMatrix4fv(fc.bound.alpha->loc("u_model"), 1, GL_FALSE, glm::value_ptr(identity));
  glBindVertexArray(lens.vao);
  glDrawArrays(GL_TRIANGLES, 0, lens.vertices);
  glBindVertexArray(fc.gpu.vao());
  glDisable(GL_DEPTH_CLAMP);
}

// renderScene(NORMAL or LENS_STYLE) restricted to one class by the second depth test. Passes 2
// and 3 change nothing outside the lens's footprint, so there they are scissored to it and skip the
// objects whose screen rectangles miss it (the paper's section 5: bounding volumes spare the
// second pass most of the scene).
void draw_scene_class(const FrameContext& fc, const LensGpu& gpu_lens, Class c, unsigned back, unsigned front) {
  const Program& p = *gpu_lens.program;
  fc.use_program(p);
  fc.bound.lit = &p;
  glUniformMatrix4fv(p.loc("u_view_proj"), 1, GL_FALSE, glm::value_ptr(fc.view.view_proj));
  glUniform3fv(p.loc("u_eye"), 1, glm::value_ptr(fc.view.camera.eye));
  glUniform1i(p.loc("u_lens_back"), 0);
  glUniform1i(p.loc("u_lens_front"), 1);
  glUniform1i(p.loc("u_lens_class"), static_cast<int>(c));
  const LensSettings& lens = fc.settings.lens;
  const bool styled = c == Class::inside;
  // In weight mode (flat colours) the tint counts as "not a target": black.
  const glm::vec3 tint = fc.settings.flat_colors.empty() ? lens.tint : glm::vec3(0.0f);
  const float weight = styled && lens.style == LensStyle::tint ? lens.tint_strength : 0.0f;
  glUniform4f(p.loc("u_lens_tint"), tint.r, tint.g, tint.b, weight);
  glActiveTexture(GL_TEXTURE0);
  glBindTexture(GL_TEXTURE_2D, back);
  glActiveTexture(GL_TEXTURE1);
  glBindTexture(GL_TEXTURE_2D, front);
  glActiveTexture(GL_TEXTURE0);
  glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glDepthMask(GL_TRUE);
  glDisable(GL_BLEND);
  glDisable(GL_CULL_FACE);
  glDisable(GL_STENCIL_TEST);
  const bool wire = styled && lens.style == LensStyle::wireframe;
  if (wire) glPolygonMode(GL_FRONT_AND_BACK, GL_LINE);
  const PixelRect area = c == Class::behind ? fc.view.viewport() : gpu_lens.footprint;
  if (c != Class::behind) {
    glEnable(GL_SCISSOR_TEST);
    scissor(area);
  }
  const auto& rects = fc.view.rects;
  for (std::uint32_t i = 0; i < rects.size(); ++i) {
    if (rects[i].empty() || !rects[i].overlaps(area)) continue;
    // The eraser: no fragment of a distractor survives inside the lens. Targets stay, and so do
    // impenetrable surfaces (rule R3 of the reference study: a WALKTHROUGH's floor, ceiling and
    // outer walls, which no condition makes see-through).
    const ObjectRecord& o = fc.gpu.objects()[i];
    if (styled && lens.style == LensStyle::eraser && !o.target && !o.impenetrable) continue;
    fc.draw_lit(i);
  }
  if (wire) glPolygonMode(GL_FRONT_AND_BACK, GL_FILL);
  glDisable(GL_SCISSOR_TEST);
  glBindTexture(GL_TEXTURE_2D, 0);
  glActiveTexture(GL_TEXTURE1);
  glBindTexture(GL_TEXTURE_2D, 0);
  glActiveTexture(GL_TEXTURE0);
}

void begin_pass(const FrameContext& fc, unsigned framebuffer) {
  glBindFramebuffer(GL_FRAMEBUFFER, framebuffer);
  glViewport(0, 0, fc.width(), fc.height());
  glDisable(GL_SCISSOR_TEST);
}

// Two lens-only depth passes (`lens-back`, `lens-front`: the volume's farthest and nearest
// surface per pixel) and the paper's three scene passes in its order, each keeping one class of
// fragments by the second depth test: `lens-behind` (normal), `lens-inside` (the lens style),
// `lens-in-front` (normal). Returns the final colour.
Handle add_lens_passes(FrameGraph& fg, const FrameContext& fc, const LensGpu& lens) {
  struct LensDepthPassData {
    Handle depth;
  };
  const TextureDesc map{fc.width(), fc.height(), TextureFormat::depth32f, false};
  auto lens_map = [&](const char* pass, const char* name, bool back) {
    return fg
        .add_pass<LensDepthPassData>(
            pass, [&](FrameGraph::Builder& b, LensDepthPassData& d) { d.depth = b.write(b.create(name, map)); },
            [&fc, &lens, back](const LensDepthPassData& d, PassResources& r) {
              begin_pass(fc, r.framebuffer({}, d.depth));
              draw_lens_depth(fc, lens, back);
            })
        .depth;
  };
  // The paper's DepthBuffer1 of pass 1 (back faces) and of passes 2 and 3 (front faces).
  const Handle back = lens_map("lens-back", "lens-back-depth", true);
  const Handle front = lens_map("lens-front", "lens-front-depth", false);

  struct LensScenePassData {
    Handle back, front, color, depth;
  };
  // Pass 1: the geometry behind the lens (and, where there is no lens, everything).
  const auto& behind = fg.add_pass<LensScenePassData>(
      "lens-behind",
      [&](FrameGraph::Builder& b, LensScenePassData& d) {
        d.back = b.read(back);
        d.color = b.write(b.create("color", {fc.width(), fc.height(), fc.color_format, false}));
        d.depth = b.write(b.create("depth", {fc.width(), fc.height(), TextureFormat::depth24_stencil8, false}));
      },
      [&fc, &lens](const LensScenePassData& d, PassResources& r) {
        begin_pass(fc, r.framebuffer({d.color}, d.depth));
        clear_to_background(fc);
        draw_scene_class(fc, lens, Class::behind, r.texture(d.back), r.texture(d.back));
      });
  // Passes 2 and 3: inside (lens style), then in front (normal), over what the previous pass left.
  auto scene_pass = [&](const char* name, Class c, Handle color, Handle depth) {
    const auto& data = fg.add_pass<LensScenePassData>(
        name,
        [&](FrameGraph::Builder& b, LensScenePassData& d) {
          d.back = b.read(back);
          d.front = b.read(front);
          d.color = b.write(b.read(color));  // drawn over what the previous pass left
          d.depth = b.write(b.read(depth));
        },
        [&fc, &lens, c](const LensScenePassData& d, PassResources& r) {
          begin_pass(fc, r.framebuffer({d.color}, d.depth));
          if (lens.footprint.empty()) return;  // the lens is out of view: passes 2 and 3 draw nothing
          draw_scene_class(fc, lens, c, r.texture(d.back), r.texture(d.front));
        });
    return std::pair{data.color, data.depth};
  };
  const auto [inside_color, inside_depth] = scene_pass("lens-inside", Class::inside, behind.color, behind.depth);
  return scene_pass("lens-in-front", Class::in_front, inside_color, inside_depth).first;
}

// The lens's program and GL buffer, re-filled every lens frame (a few hundred triangles), and this
// frame's volume on the GPU (the passes read it when they run).
class LensState final : public MethodState {
 public:
  ~LensState() override {
    delete_program(program);
    if (vao_ != 0) glDeleteVertexArrays(1, &vao_);
    if (vbo_ != 0) glDeleteBuffers(1, &vbo_);
  }
  // Uploads `v` into the lens buffer (inside the frame's GlStateGuard: binds VAO and array buffer).
  void upload(const LensVolume& v) {
    if (vao_ == 0) {
      glGenVertexArrays(1, &vao_);
      glGenBuffers(1, &vbo_);
      glBindVertexArray(vao_);
      glBindBuffer(GL_ARRAY_BUFFER, vbo_);
      glEnableVertexAttribArray(0);
      glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, sizeof(glm::vec3), nullptr);
    }
    glBindBuffer(GL_ARRAY_BUFFER, vbo_);
    glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(v.triangles.size() * sizeof(glm::vec3)), v.triangles.data(),
                 GL_STREAM_DRAW);
    gpu = LensGpu{vao_, static_cast<int>(v.triangles.size()), v.eye_inside, footprint, &program};
  }
  Program program;     // object.vert + lens.frag, linked on the first lens frame
  LensVolume volume;   // this frame's, from footprint()
  PixelRect footprint;
  LensGpu gpu;

 private:
  unsigned vao_ = 0, vbo_ = 0;
};

LensState& lens_state(MethodSlot& slot) {
  if (!slot.state) slot.state = std::make_unique<LensState>();
  return static_cast<LensState&>(*slot.state);
}

std::optional<PixelRect> lens_footprint_of(MethodSlot& slot, const FrameSettings& s, const Camera& camera, int width,
                                           int height) {
  LensState& l = lens_state(slot);
  l.volume = make_lens_volume(s.lens, camera, width, height);
  l.footprint = lens_footprint(l.volume, camera, width, height);
  return l.footprint;
}

MethodFrame add_lens(FrameGraph& fg, const FrameContext& fc, MethodSlot& slot) {
  LensState& l = lens_state(slot);
  if (l.program.id == 0) l.program = link_method_program("lens", "object.vert", "lens.frag", "", "lighting.glsl");
  l.upload(l.volume);
  return {add_lens_passes(fg, fc, l.gpu), {}};
}

}  // namespace

extern const MethodPasses k_passes_lens{lens_footprint_of, add_lens};

}  // namespace dtlab::render::detail

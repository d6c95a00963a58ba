// Internal: the state a Renderer owns (see render.h): the scene, its GPU
// buffers, the programs, the frame graph backend (texture pool), the group
// order kept between frames, the offscreen output of render_offscreen().
// Needs the renderer's GL context current when destroyed.
#pragma once
#include <glad/gl.h>

#include <array>
#include <memory>
#include <string>

#include "study/render/detail/boundary.h"
#include "study/render/detail/gl_backend.h"
#include "study/render/detail/method.h"
#include "study/render/detail/occlusion_culling.h"
#include "study/render/detail/passes.h"
#include "study/render/detail/programs.h"
#include "study/render/detail/scene_gpu.h"
#include "study/render/detail/sort.h"
#include "study/render/render.h"

namespace dtlab::render {

namespace detail {
// Every range a frame of `settings` at width x height over `objects` objects needs (render.h,
// check()), as an invalid_input Error from the public function `where`.
Status check_frame(const char* where, const FrameSettings& settings, int width, int height, std::size_t objects);
}  // namespace detail

struct Renderer::Impl {
  scene::Scene scene;
  std::unique_ptr<detail::SceneGpu> gpu;
  detail::Programs programs;
  detail::GlBackend backend;
  std::unique_ptr<detail::GroupSorter> sorter;
  std::string graphviz;
  // Offscreen output for render_offscreen(): colour texture + framebuffer.
  unsigned out_fbo = 0, out_tex = 0;
  int out_w = 0, out_h = 0;
  bool out_float = false;
  // Each method's state between frames (detail/method.h), by technique::Method.
  std::array<detail::MethodSlot, technique::kMethodCount> slots;
  // Where the last frame was presented (for read_color).
  ImportedTarget last_target;
  bool last_float = false;

  std::unique_ptr<detail::OcclusionCuller> culler;  // made on the first frame with occlusion culling on

  ~Impl() {
    for (detail::MethodSlot& s : slots) s.state.reset();
    culler.reset();
    if (out_fbo != 0) glDeleteFramebuffers(1, &out_fbo);
    if (out_tex != 0) glDeleteTextures(1, &out_tex);
    programs.destroy();
  }

  // The occlusion culler when `settings` ask for culling and the scene has a floor plan to cull
  // with (made on first use), else nullptr.
  detail::OcclusionCuller* culler_for(const FrameSettings& settings) {
    if (!settings.occlusion_culling || !scene.plan) return nullptr;
    if (!culler) culler = std::make_unique<detail::OcclusionCuller>(scene, gpu->objects());
    return culler.get();
  }

  // The offscreen output of render_offscreen() at w x h; GlFailure if the driver cannot make it.
  void ensure_offscreen(int w, int h, bool fp) {
    if (out_fbo != 0 && out_w == w && out_h == h && out_float == fp) return;
    if (out_fbo != 0) glDeleteFramebuffers(1, &out_fbo);
    if (out_tex != 0) glDeleteTextures(1, &out_tex);
    GLint prev_tex = 0, prev_fbo = 0, prev_unpack = 0;
    glGetIntegerv(GL_TEXTURE_BINDING_2D, &prev_tex);
    glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &prev_fbo);
    glGetIntegerv(GL_PIXEL_UNPACK_BUFFER_BINDING, &prev_unpack);
    glBindBuffer(GL_PIXEL_UNPACK_BUFFER, 0);  // else the null data pointer is an offset into it
    glGenTextures(1, &out_tex);
    glBindTexture(GL_TEXTURE_2D, out_tex);
    glTexImage2D(GL_TEXTURE_2D, 0, fp ? GL_RGBA16F : GL_RGBA8, w, h, 0, GL_RGBA, fp ? GL_FLOAT : GL_UNSIGNED_BYTE,
                 nullptr);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glGenFramebuffers(1, &out_fbo);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, out_fbo);
    glFramebufferTexture2D(GL_DRAW_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, out_tex, 0);
    const GLenum status = glCheckFramebufferStatus(GL_DRAW_FRAMEBUFFER);
    glBindTexture(GL_TEXTURE_2D, static_cast<GLuint>(prev_tex));
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, static_cast<GLuint>(prev_fbo));
    glBindBuffer(GL_PIXEL_UNPACK_BUFFER, static_cast<GLuint>(prev_unpack));
    if (status != GL_FRAMEBUFFER_COMPLETE) {  // the driver could not allocate the colour texture
      if (last_target.framebuffer == out_fbo) last_target = {};  // read_color: nothing to read
      glDeleteFramebuffers(1, &out_fbo);
      glDeleteTextures(1, &out_tex);
      out_fbo = out_tex = 0;
      out_w = out_h = 0;
      throw detail::GlFailure("the offscreen target of " + std::to_string(w) + "x" + std::to_string(h) +
                              " is incomplete (status " + std::to_string(status) + ")");
    }
    out_w = w;
    out_h = h;
    out_float = fp;
  }
};

}  // namespace dtlab::render

// Internal: the state a Renderer owns (see render.h): the scene, its GPU
// buffers, the programs, the frame graph backend (texture pool), the group
// order kept between frames, the offscreen output of render_offscreen().
// Needs the renderer's GL context current when destroyed.
#pragma once
#include <glad/gl.h>

#include <memory>
#include <stdexcept>
#include <string>

#include "study/render/detail/gl_backend.h"
#include "study/render/detail/lens_volume.h"
#include "study/render/detail/occlusion_culling.h"
#include "study/render/detail/passes.h"
#include "study/render/detail/programs.h"
#include "study/render/detail/scene_gpu.h"
#include "study/render/detail/sort.h"
#include "study/render/detail/vdt.h"
#include "study/render/render.h"

namespace dtlab::render {

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
  // dt-fast, dt-seed: did the last frame of the method need the effect (some target occluded)?
  // Picks the frame plan (passes.h EffectFirst): effect-first when it did, standard-first otherwise.
  bool fast_effect_hint = false;
  bool seed_effect_hint = false;
  // Where the last frame was presented (for read_color).
  ImportedTarget last_target;
  bool last_float = false;

  // The lens method's volume, re-uploaded every lens frame (a few hundred triangles).
  unsigned lens_vao = 0, lens_vbo = 0;
  // The vdt method's per-vertex alpha buffer and the meshes' edge lists (built on first use).
  detail::VdtState vdt;
  std::unique_ptr<detail::OcclusionCuller> culler;  // made on the first frame with occlusion culling on

  ~Impl() {
    vdt.destroy();
    culler.reset();
    if (lens_vao != 0) glDeleteVertexArrays(1, &lens_vao);
    if (lens_vbo != 0) glDeleteBuffers(1, &lens_vbo);
    if (out_fbo != 0) glDeleteFramebuffers(1, &out_fbo);
    if (out_tex != 0) glDeleteTextures(1, &out_tex);
    programs.destroy();
  }

  // Uploads `v` into the lens buffer (inside the frame's GlStateGuard: binds VAO and array buffer).
  detail::LensGpu upload_lens(const detail::LensVolume& v) {
    if (lens_vao == 0) {
      glGenVertexArrays(1, &lens_vao);
      glGenBuffers(1, &lens_vbo);
      glBindVertexArray(lens_vao);
      glBindBuffer(GL_ARRAY_BUFFER, lens_vbo);
      glEnableVertexAttribArray(0);
      glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, sizeof(glm::vec3), nullptr);
    }
    glBindBuffer(GL_ARRAY_BUFFER, lens_vbo);
    glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(v.triangles.size() * sizeof(glm::vec3)), v.triangles.data(),
                 GL_STREAM_DRAW);
    return detail::LensGpu{lens_vao, static_cast<int>(v.triangles.size()), v.eye_inside, {}};
  }

  // The occlusion culler when `settings` ask for culling and the scene has a floor plan to cull
  // with (made on first use), else nullptr.
  detail::OcclusionCuller* culler_for(const FrameSettings& settings) {
    if (!settings.occlusion_culling || !scene.plan) return nullptr;
    if (!culler) culler = std::make_unique<detail::OcclusionCuller>(scene, gpu->objects());
    return culler.get();
  }

  // Occlusion culling of `view` (in place) when `settings` ask for it; throws on a shader error.
  CullingReport cull(detail::FrameView& view, const FrameSettings& settings, const detail::PixelRect& lens_footprint) {
    detail::OcclusionCuller* c = culler_for(settings);
    if (c == nullptr) return {};
    const detail::FrameContext fc{*gpu, programs, view, settings, scene, TextureFormat::rgba8, {}};
    auto r = c->run(view, fc, lens_footprint);
    if (!r) throw std::runtime_error("occlusion culling: " + r.error().to_string());
    return r.value();
  }

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
    glBindTexture(GL_TEXTURE_2D, static_cast<GLuint>(prev_tex));
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, static_cast<GLuint>(prev_fbo));
    glBindBuffer(GL_PIXEL_UNPACK_BUFFER, static_cast<GLuint>(prev_unpack));
    out_w = w;
    out_h = h;
    out_float = fp;
  }
};

}  // namespace dtlab::render

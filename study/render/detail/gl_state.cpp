// Snapshot and restore of the GL state the renderer touches (see gl_state.h).
#include <glad/gl.h>

#include "study/render/detail/gl_state.h"

namespace dtlab::render::detail {

namespace {
int get_int(GLenum e) {
  GLint v = 0;
  glGetIntegerv(e, &v);
  return v;
}
void set(GLenum cap, bool on) { on ? glEnable(cap) : glDisable(cap); }
}  // namespace

GlStateGuard::GlStateGuard() {
  program_ = get_int(GL_CURRENT_PROGRAM);
  vao_ = get_int(GL_VERTEX_ARRAY_BINDING);
  array_buffer_ = get_int(GL_ARRAY_BUFFER_BINDING);
  draw_fbo_ = get_int(GL_DRAW_FRAMEBUFFER_BINDING);
  read_fbo_ = get_int(GL_READ_FRAMEBUFFER_BINDING);
  active_texture_ = get_int(GL_ACTIVE_TEXTURE);
  for (int i = 0; i < kTextureUnits; ++i) {
    glActiveTexture(static_cast<GLenum>(GL_TEXTURE0 + i));
    textures_[i] = get_int(GL_TEXTURE_BINDING_2D);
  }
  glActiveTexture(static_cast<GLenum>(active_texture_));
  glGetIntegerv(GL_VIEWPORT, viewport_);
  glGetIntegerv(GL_SCISSOR_BOX, scissor_box_);
  scissor_ = glIsEnabled(GL_SCISSOR_TEST);
  blend_ = glIsEnabled(GL_BLEND);
  depth_test_ = glIsEnabled(GL_DEPTH_TEST);
  stencil_test_ = glIsEnabled(GL_STENCIL_TEST);
  cull_face_ = glIsEnabled(GL_CULL_FACE);
  polygon_offset_fill_ = glIsEnabled(GL_POLYGON_OFFSET_FILL);
  multisample_ = glIsEnabled(GL_MULTISAMPLE);
  front_face_ = get_int(GL_FRONT_FACE);
  cull_face_mode_ = get_int(GL_CULL_FACE_MODE);
  GLboolean b = GL_TRUE;
  glGetBooleanv(GL_DEPTH_WRITEMASK, &b);
  depth_mask_ = b;
  GLboolean cm[4];
  glGetBooleanv(GL_COLOR_WRITEMASK, cm);
  for (int i = 0; i < 4; ++i) color_mask_[i] = cm[i];
  blend_src_rgb_ = get_int(GL_BLEND_SRC_RGB);
  blend_dst_rgb_ = get_int(GL_BLEND_DST_RGB);
  blend_src_a_ = get_int(GL_BLEND_SRC_ALPHA);
  blend_dst_a_ = get_int(GL_BLEND_DST_ALPHA);
  blend_eq_rgb_ = get_int(GL_BLEND_EQUATION_RGB);
  blend_eq_a_ = get_int(GL_BLEND_EQUATION_ALPHA);
  depth_func_ = get_int(GL_DEPTH_FUNC);
  const GLenum f[2][7] = {
      {GL_STENCIL_FUNC, GL_STENCIL_REF, GL_STENCIL_VALUE_MASK, GL_STENCIL_WRITEMASK, GL_STENCIL_FAIL,
       GL_STENCIL_PASS_DEPTH_FAIL, GL_STENCIL_PASS_DEPTH_PASS},
      {GL_STENCIL_BACK_FUNC, GL_STENCIL_BACK_REF, GL_STENCIL_BACK_VALUE_MASK, GL_STENCIL_BACK_WRITEMASK,
       GL_STENCIL_BACK_FAIL, GL_STENCIL_BACK_PASS_DEPTH_FAIL, GL_STENCIL_BACK_PASS_DEPTH_PASS}};
  for (int s = 0; s < 2; ++s) {
    stencil_func_[s] = get_int(f[s][0]);
    stencil_ref_[s] = get_int(f[s][1]);
    stencil_value_mask_[s] = get_int(f[s][2]);
    stencil_writemask_[s] = get_int(f[s][3]);
    stencil_fail_[s] = get_int(f[s][4]);
    stencil_zfail_[s] = get_int(f[s][5]);
    stencil_zpass_[s] = get_int(f[s][6]);
  }
  glGetFloatv(GL_COLOR_CLEAR_VALUE, clear_color_);
  glGetDoublev(GL_DEPTH_CLEAR_VALUE, &clear_depth_);
  clear_stencil_ = get_int(GL_STENCIL_CLEAR_VALUE);
}

GlStateGuard::~GlStateGuard() {
  glUseProgram(static_cast<GLuint>(program_));
  glBindVertexArray(static_cast<GLuint>(vao_));
  glBindBuffer(GL_ARRAY_BUFFER, static_cast<GLuint>(array_buffer_));
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, static_cast<GLuint>(draw_fbo_));
  glBindFramebuffer(GL_READ_FRAMEBUFFER, static_cast<GLuint>(read_fbo_));
  for (int i = 0; i < kTextureUnits; ++i) {
    glActiveTexture(static_cast<GLenum>(GL_TEXTURE0 + i));
    glBindTexture(GL_TEXTURE_2D, static_cast<GLuint>(textures_[i]));
  }
  glActiveTexture(static_cast<GLenum>(active_texture_));
  glViewport(viewport_[0], viewport_[1], viewport_[2], viewport_[3]);
  glScissor(scissor_box_[0], scissor_box_[1], scissor_box_[2], scissor_box_[3]);
  set(GL_SCISSOR_TEST, scissor_);
  set(GL_BLEND, blend_);
  set(GL_DEPTH_TEST, depth_test_);
  set(GL_STENCIL_TEST, stencil_test_);
  set(GL_CULL_FACE, cull_face_);
  set(GL_POLYGON_OFFSET_FILL, polygon_offset_fill_);
  set(GL_MULTISAMPLE, multisample_);
  glFrontFace(static_cast<GLenum>(front_face_));
  glCullFace(static_cast<GLenum>(cull_face_mode_));
  glDepthMask(depth_mask_ ? GL_TRUE : GL_FALSE);
  glColorMask(color_mask_[0], color_mask_[1], color_mask_[2], color_mask_[3]);
  glBlendFuncSeparate(static_cast<GLenum>(blend_src_rgb_), static_cast<GLenum>(blend_dst_rgb_),
                      static_cast<GLenum>(blend_src_a_), static_cast<GLenum>(blend_dst_a_));
  glBlendEquationSeparate(static_cast<GLenum>(blend_eq_rgb_), static_cast<GLenum>(blend_eq_a_));
  glDepthFunc(static_cast<GLenum>(depth_func_));
  const GLenum face[2] = {GL_FRONT, GL_BACK};
  for (int s = 0; s < 2; ++s) {
    glStencilFuncSeparate(face[s], static_cast<GLenum>(stencil_func_[s]), stencil_ref_[s],
                          static_cast<GLuint>(stencil_value_mask_[s]));
    glStencilMaskSeparate(face[s], static_cast<GLuint>(stencil_writemask_[s]));
    glStencilOpSeparate(face[s], static_cast<GLenum>(stencil_fail_[s]), static_cast<GLenum>(stencil_zfail_[s]),
                        static_cast<GLenum>(stencil_zpass_[s]));
  }
  glClearColor(clear_color_[0], clear_color_[1], clear_color_[2], clear_color_[3]);
  glClearDepth(clear_depth_);
  glClearStencil(clear_stencil_);
}

}  // namespace dtlab::render::detail

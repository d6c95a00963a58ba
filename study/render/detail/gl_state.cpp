// Snapshot and restore of the GL state the renderer touches, and the frame
// baseline (see gl_state.h).
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

// Saved, restored, and off in the baseline.
const GLenum kCapList[GlStateGuard::kCaps] = {
    GL_SCISSOR_TEST,        GL_BLEND,           GL_DEPTH_TEST,          GL_STENCIL_TEST,
    GL_CULL_FACE,           GL_POLYGON_OFFSET_FILL, GL_POLYGON_OFFSET_LINE, GL_POLYGON_OFFSET_POINT,
    GL_MULTISAMPLE,         GL_SAMPLE_ALPHA_TO_COVERAGE, GL_SAMPLE_ALPHA_TO_ONE, GL_SAMPLE_COVERAGE,
    GL_SAMPLE_MASK,         GL_COLOR_LOGIC_OP,  GL_RASTERIZER_DISCARD,  GL_DEPTH_CLAMP,
    GL_FRAMEBUFFER_SRGB,    GL_DITHER,          GL_PRIMITIVE_RESTART,   GL_POLYGON_SMOOTH,
    GL_LINE_SMOOTH,         GL_PROGRAM_POINT_SIZE, GL_CLIP_DISTANCE0,   GL_CLIP_DISTANCE1,
    GL_CLIP_DISTANCE2,      GL_CLIP_DISTANCE3,  GL_CLIP_DISTANCE4,      GL_CLIP_DISTANCE5,
    GL_CLIP_DISTANCE6,      GL_CLIP_DISTANCE7};

struct PixelStore {
  GLenum alignment, row_length, skip_rows, skip_pixels;
};
constexpr PixelStore kPack{GL_PACK_ALIGNMENT, GL_PACK_ROW_LENGTH, GL_PACK_SKIP_ROWS, GL_PACK_SKIP_PIXELS};
constexpr PixelStore kUnpack{GL_UNPACK_ALIGNMENT, GL_UNPACK_ROW_LENGTH, GL_UNPACK_SKIP_ROWS, GL_UNPACK_SKIP_PIXELS};
void pixel_store(const PixelStore& p, int alignment, int row_length, int skip_rows, int skip_pixels) {
  glPixelStorei(p.alignment, alignment);
  glPixelStorei(p.row_length, row_length);
  glPixelStorei(p.skip_rows, skip_rows);
  glPixelStorei(p.skip_pixels, skip_pixels);
}
}  // namespace

GlStateGuard::GlStateGuard() {
  program_ = get_int(GL_CURRENT_PROGRAM);
  vao_ = get_int(GL_VERTEX_ARRAY_BINDING);
  array_buffer_ = get_int(GL_ARRAY_BUFFER_BINDING);
  pack_buffer_ = get_int(GL_PIXEL_PACK_BUFFER_BINDING);
  unpack_buffer_ = get_int(GL_PIXEL_UNPACK_BUFFER_BINDING);
  draw_fbo_ = get_int(GL_DRAW_FRAMEBUFFER_BINDING);
  read_fbo_ = get_int(GL_READ_FRAMEBUFFER_BINDING);
  read_buffer_ = get_int(GL_READ_BUFFER);  // of the bound read framebuffer
  active_texture_ = get_int(GL_ACTIVE_TEXTURE);
  for (int i = 0; i < kTextureUnits; ++i) {
    glActiveTexture(static_cast<GLenum>(GL_TEXTURE0 + i));
    textures_[i] = get_int(GL_TEXTURE_BINDING_2D);
    samplers_[i] = get_int(GL_SAMPLER_BINDING);
  }
  glActiveTexture(static_cast<GLenum>(active_texture_));
  glGetIntegerv(GL_VIEWPORT, viewport_);
  glGetIntegerv(GL_SCISSOR_BOX, scissor_box_);
  glGetDoublev(GL_DEPTH_RANGE, depth_range_);
  for (int i = 0; i < kCaps; ++i) caps_[i] = glIsEnabled(kCapList[i]);
  front_face_ = get_int(GL_FRONT_FACE);
  cull_face_mode_ = get_int(GL_CULL_FACE_MODE);
  GLint modes[2] = {GL_FILL, GL_FILL};  // core profile: front and back are always equal
  glGetIntegerv(GL_POLYGON_MODE, modes);
  polygon_mode_ = modes[0];
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
  glGetFloatv(GL_BLEND_COLOR, blend_color_);
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
  pack_alignment_ = get_int(kPack.alignment);
  pack_row_length_ = get_int(kPack.row_length);
  pack_skip_rows_ = get_int(kPack.skip_rows);
  pack_skip_pixels_ = get_int(kPack.skip_pixels);
  unpack_alignment_ = get_int(kUnpack.alignment);
  unpack_row_length_ = get_int(kUnpack.row_length);
  unpack_skip_rows_ = get_int(kUnpack.skip_rows);
  unpack_skip_pixels_ = get_int(kUnpack.skip_pixels);
  glGetFloatv(GL_COLOR_CLEAR_VALUE, clear_color_);
  glGetDoublev(GL_DEPTH_CLEAR_VALUE, &clear_depth_);
  clear_stencil_ = get_int(GL_STENCIL_CLEAR_VALUE);
}

GlStateGuard::~GlStateGuard() {
  glUseProgram(static_cast<GLuint>(program_));
  glBindVertexArray(static_cast<GLuint>(vao_));
  glBindBuffer(GL_ARRAY_BUFFER, static_cast<GLuint>(array_buffer_));
  glBindBuffer(GL_PIXEL_PACK_BUFFER, static_cast<GLuint>(pack_buffer_));
  glBindBuffer(GL_PIXEL_UNPACK_BUFFER, static_cast<GLuint>(unpack_buffer_));
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, static_cast<GLuint>(draw_fbo_));
  glBindFramebuffer(GL_READ_FRAMEBUFFER, static_cast<GLuint>(read_fbo_));
  glReadBuffer(static_cast<GLenum>(read_buffer_));
  for (int i = 0; i < kTextureUnits; ++i) {
    glActiveTexture(static_cast<GLenum>(GL_TEXTURE0 + i));
    glBindTexture(GL_TEXTURE_2D, static_cast<GLuint>(textures_[i]));
    glBindSampler(static_cast<GLuint>(i), static_cast<GLuint>(samplers_[i]));
  }
  glActiveTexture(static_cast<GLenum>(active_texture_));
  glViewport(viewport_[0], viewport_[1], viewport_[2], viewport_[3]);
  glScissor(scissor_box_[0], scissor_box_[1], scissor_box_[2], scissor_box_[3]);
  glDepthRange(depth_range_[0], depth_range_[1]);
  for (int i = 0; i < kCaps; ++i) set(kCapList[i], caps_[i]);
  glFrontFace(static_cast<GLenum>(front_face_));
  glCullFace(static_cast<GLenum>(cull_face_mode_));
  glPolygonMode(GL_FRONT_AND_BACK, static_cast<GLenum>(polygon_mode_));
  glDepthMask(depth_mask_ ? GL_TRUE : GL_FALSE);
  glColorMask(color_mask_[0], color_mask_[1], color_mask_[2], color_mask_[3]);
  glBlendFuncSeparate(static_cast<GLenum>(blend_src_rgb_), static_cast<GLenum>(blend_dst_rgb_),
                      static_cast<GLenum>(blend_src_a_), static_cast<GLenum>(blend_dst_a_));
  glBlendEquationSeparate(static_cast<GLenum>(blend_eq_rgb_), static_cast<GLenum>(blend_eq_a_));
  glBlendColor(blend_color_[0], blend_color_[1], blend_color_[2], blend_color_[3]);
  glDepthFunc(static_cast<GLenum>(depth_func_));
  const GLenum face[2] = {GL_FRONT, GL_BACK};
  for (int s = 0; s < 2; ++s) {
    glStencilFuncSeparate(face[s], static_cast<GLenum>(stencil_func_[s]), stencil_ref_[s],
                          static_cast<GLuint>(stencil_value_mask_[s]));
    glStencilMaskSeparate(face[s], static_cast<GLuint>(stencil_writemask_[s]));
    glStencilOpSeparate(face[s], static_cast<GLenum>(stencil_fail_[s]), static_cast<GLenum>(stencil_zfail_[s]),
                        static_cast<GLenum>(stencil_zpass_[s]));
  }
  pixel_store(kPack, pack_alignment_, pack_row_length_, pack_skip_rows_, pack_skip_pixels_);
  pixel_store(kUnpack, unpack_alignment_, unpack_row_length_, unpack_skip_rows_, unpack_skip_pixels_);
  glClearColor(clear_color_[0], clear_color_[1], clear_color_[2], clear_color_[3]);
  glClearDepth(clear_depth_);
  glClearStencil(clear_stencil_);
}

void set_frame_baseline(unsigned vao) {
  glBindVertexArray(vao);
  for (GLenum cap : kCapList) glDisable(cap);
  glPolygonMode(GL_FRONT_AND_BACK, GL_FILL);
  glFrontFace(GL_CCW);
  glBlendEquation(GL_FUNC_ADD);
  glDepthRange(0.0, 1.0);
  glBindBuffer(GL_PIXEL_PACK_BUFFER, 0);
  glBindBuffer(GL_PIXEL_UNPACK_BUFFER, 0);
  pixel_store(kPack, 1, 0, 0, 0);
  pixel_store(kUnpack, 1, 0, 0, 0);
  for (GLuint unit = 0; unit < GlStateGuard::kTextureUnits; ++unit) glBindSampler(unit, 0);
}

}  // namespace dtlab::render::detail

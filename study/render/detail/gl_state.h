// Saves the OpenGL state the renderer changes and restores it on destruction,
// so drawing a frame into a target the caller owns (a window that a Dear
// ImGui UI draws into afterwards) leaves that caller's state as it was.
// Covers: program, VAO, array/element buffers, framebuffer bindings, viewport,
// scissor, blend, depth, stencil, colour mask, cull face and mode, front
// face, polygon offset and multisample enables, textures on the units the
// renderer uses. Never: saves state it does not restore.
#pragma once

namespace dtlab::render::detail {

class GlStateGuard {
 public:
  GlStateGuard();   // snapshots the state; needs a current context
  ~GlStateGuard();  // restores it
  GlStateGuard(const GlStateGuard&) = delete;
  GlStateGuard& operator=(const GlStateGuard&) = delete;

  static constexpr int kTextureUnits = 4;  // units 0..3 are the only ones the renderer binds

 private:
  int program_, vao_, array_buffer_, draw_fbo_, read_fbo_, active_texture_;
  int textures_[kTextureUnits];
  int viewport_[4], scissor_box_[4];
  bool scissor_, blend_, depth_test_, stencil_test_, cull_face_, depth_mask_, polygon_offset_fill_, multisample_;
  int front_face_, cull_face_mode_;
  bool color_mask_[4];
  int blend_src_rgb_, blend_dst_rgb_, blend_src_a_, blend_dst_a_, blend_eq_rgb_, blend_eq_a_;
  int depth_func_;
  int stencil_func_[2], stencil_ref_[2], stencil_value_mask_[2], stencil_writemask_[2];
  int stencil_fail_[2], stencil_zfail_[2], stencil_zpass_[2];
  float clear_color_[4];
  double clear_depth_;
  int clear_stencil_;
};

}  // namespace dtlab::render::detail

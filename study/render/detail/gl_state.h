// Saves the OpenGL state the renderer changes and restores it on destruction,
// so drawing a frame into a target the caller owns (a window that a Dear
// ImGui UI draws into afterwards) leaves that caller's state as it was; and
// sets the renderer's own baseline for state no pass sets itself, so a
// caller's unusual state (logic op, rasterizer discard, a bound pixel unpack
// buffer, ...) cannot change a frame.
// Covers: program, VAO, array buffer, pixel pack/unpack buffers, framebuffer
// bindings and the read buffer, viewport, scissor, depth range, the enables
// of kCaps, cull face and mode, front face, polygon mode, blend functions,
// equations and colour, depth, stencil, colour mask, pixel pack/unpack
// alignment and row length, textures and samplers on units 0-3, clear values.
// Never: saves state it does not restore, or sets a baseline it did not save.
#pragma once

namespace dtlab::render::detail {

class GlStateGuard {
 public:
  GlStateGuard();   // snapshots the state; needs a current context
  ~GlStateGuard();  // restores it
  GlStateGuard(const GlStateGuard&) = delete;
  GlStateGuard& operator=(const GlStateGuard&) = delete;

  static constexpr int kTextureUnits = 4;  // units 0..3 are the only ones the renderer binds
  static constexpr int kCaps = 30;         // capabilities saved, restored and given a baseline

 private:
  int program_, vao_, array_buffer_, pack_buffer_, unpack_buffer_, draw_fbo_, read_fbo_, read_buffer_, active_texture_;
  int textures_[kTextureUnits], samplers_[kTextureUnits];
  int viewport_[4], scissor_box_[4];
  double depth_range_[2];
  bool caps_[kCaps];
  bool depth_mask_;
  int front_face_, cull_face_mode_, polygon_mode_;
  bool color_mask_[4];
  int blend_src_rgb_, blend_dst_rgb_, blend_src_a_, blend_dst_a_, blend_eq_rgb_, blend_eq_a_;
  float blend_color_[4];
  int depth_func_;
  int stencil_func_[2], stencil_ref_[2], stencil_value_mask_[2], stencil_writemask_[2];
  int stencil_fail_[2], stencil_zfail_[2], stencil_zpass_[2];
  int pack_alignment_, pack_row_length_, pack_skip_rows_, pack_skip_pixels_;
  int unpack_alignment_, unpack_row_length_, unpack_skip_rows_, unpack_skip_pixels_;
  float clear_color_[4];
  double clear_depth_;
  int clear_stencil_;
};

// The renderer's baseline, set once per frame inside a GlStateGuard: `vao` bound, every cap of
// the guard's list off (multisample, dithering, logic op, rasterizer discard, depth clamp, sRGB
// writes, clip distances, ...), filled polygons, counter-clockwise front faces, blend equation
// ADD, depth range [0, 1], no pixel pack/unpack buffer, tight pixel packing, samplers 0-3 unbound.
void set_frame_baseline(unsigned vao);

}  // namespace dtlab::render::detail

// Poon's run-time occlusion culling (see occlusion_culling.h).
#include <glad/gl.h>

#include <algorithm>
#include <chrono>
#include <cmath>

#include "study/render/detail/occlusion_culling.h"

namespace dtlab::render::detail {

namespace {
constexpr int kMapSide = 128;  // the thesis's opacity map: 128 x 128 (its longer side here)
using Clock = std::chrono::steady_clock;
double ms_since(Clock::time_point t) { return std::chrono::duration<double, std::milli>(Clock::now() - t).count(); }
}  // namespace

OcclusionCuller::OcclusionCuller(const scene::Scene& scene, const std::vector<ObjectRecord>& objects)
    : scene_(scene), objects_(objects), hierarchy_(build_hierarchy(objects)) {}

OcclusionCuller::~OcclusionCuller() {
  for (unsigned* f : {&depth_fbo_, &map_fbo_})
    if (*f != 0) glDeleteFramebuffers(1, f);
  for (unsigned* t : {&depth_tex_, &map_tex_})
    if (*t != 0) glDeleteTextures(1, t);
  if (reduce_.id != 0) glDeleteProgram(reduce_.id);
}

void OcclusionCuller::ensure_targets(int width, int height) {
  if (depth_fbo_ != 0 && width_ == width && height_ == height) return;
  for (unsigned* f : {&depth_fbo_, &map_fbo_})
    if (*f != 0) glDeleteFramebuffers(1, f);
  for (unsigned* t : {&depth_tex_, &map_tex_})
    if (*t != 0) glDeleteTextures(1, t);
  width_ = width;
  height_ = height;
  block_ = std::max(1, (std::max(width, height) + kMapSide - 1) / kMapSide);
  map_w_ = (width + block_ - 1) / block_;
  map_h_ = (height + block_ - 1) / block_;
  glBindBuffer(GL_PIXEL_UNPACK_BUFFER, 0);
  auto texture = [](unsigned& tex, GLint internal, int w, int h, GLenum format, GLenum type) {
    glGenTextures(1, &tex);
    glBindTexture(GL_TEXTURE_2D, tex);
    glTexImage2D(GL_TEXTURE_2D, 0, internal, w, h, 0, format, type, nullptr);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_COMPARE_MODE, GL_NONE);
  };
  texture(depth_tex_, GL_DEPTH_COMPONENT24, width, height, GL_DEPTH_COMPONENT, GL_UNSIGNED_INT);
  texture(map_tex_, GL_R32F, map_w_, map_h_, GL_RED, GL_FLOAT);
  glGenFramebuffers(1, &depth_fbo_);
  glBindFramebuffer(GL_FRAMEBUFFER, depth_fbo_);
  glFramebufferTexture2D(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_TEXTURE_2D, depth_tex_, 0);
  glDrawBuffer(GL_NONE);
  glReadBuffer(GL_NONE);
  glGenFramebuffers(1, &map_fbo_);
  glBindFramebuffer(GL_FRAMEBUFFER, map_fbo_);
  glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, map_tex_, 0);
}

std::vector<float> OcclusionCuller::occluder_map(const FrameView& view, const FrameContext& fc, CullingReport& report) {
  const int W = view.width, H = view.height;
  ensure_targets(W, H);
  // Step 2: the grid point's occluders in view, depth only, no lighting.
  glBindFramebuffer(GL_FRAMEBUFFER, depth_fbo_);
  glViewport(0, 0, W, H);
  glDisable(GL_SCISSOR_TEST);
  glDisable(GL_BLEND);
  glDisable(GL_STENCIL_TEST);
  glDisable(GL_CULL_FACE);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glDepthMask(GL_TRUE);
  glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
  glClearDepth(1.0);
  glClear(GL_DEPTH_BUFFER_BIT);
  glBindVertexArray(fc.gpu.vao());
  fc.use_alpha(view.view_proj, 1.0f, false);
  for (auto i : database_->nearest(view.camera.eye))
    if (!view.rects[i].empty()) {
      fc.draw_alpha(i);
      ++report.occluders;
    }
  // The small map: farthest depth per block (one pixel of border), then read back.
  glBindFramebuffer(GL_FRAMEBUFFER, map_fbo_);
  glViewport(0, 0, map_w_, map_h_);
  glDisable(GL_DEPTH_TEST);
  glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
  fc.use_program(reduce_);
  glActiveTexture(GL_TEXTURE0);
  glBindTexture(GL_TEXTURE_2D, depth_tex_);
  glUniform1i(reduce_.loc("u_depth"), 0);
  glUniform1i(reduce_.loc("u_block"), block_);
  glUniform2i(reduce_.loc("u_size"), W, H);
  glUniform4f(reduce_.loc("u_rect"), -1.0f, -1.0f, 1.0f, 1.0f);
  glUniform1f(reduce_.loc("u_z"), 0.0f);
  glDrawArrays(GL_TRIANGLE_STRIP, 0, 4);
  std::vector<float> depth(static_cast<std::size_t>(map_w_) * map_h_);
  const auto t = Clock::now();
  glBindBuffer(GL_PIXEL_PACK_BUFFER, 0);
  glPixelStorei(GL_PACK_ALIGNMENT, 4);
  glPixelStorei(GL_PACK_ROW_LENGTH, 0);
  glPixelStorei(GL_PACK_SKIP_ROWS, 0);
  glPixelStorei(GL_PACK_SKIP_PIXELS, 0);
  glBindFramebuffer(GL_READ_FRAMEBUFFER, map_fbo_);
  glReadBuffer(GL_COLOR_ATTACHMENT0);
  glReadPixels(0, 0, map_w_, map_h_, GL_RED, GL_FLOAT, depth.data());
  report.readback_ms = ms_since(t);
  return depth;
}

namespace {

// Pixels a transparency method or a method with a footprint may change: each target's mask support
// (in active mode cut to the searchlight circle's box, where masks act), the footprint (a lens's).
std::vector<PixelRect> holes(const FrameView& view, Method method, const PixelRect* footprint) {
  std::vector<PixelRect> out;
  if (uses_transparency(method)) {
    const glm::vec3 sl = view.searchlight;
    const PixelRect circle = sl.z >= 0.0f ? PixelRect{static_cast<int>(std::floor(sl.x - sl.z)) - 1,
                                                      static_cast<int>(std::floor(sl.y - sl.z)) - 1,
                                                      static_cast<int>(std::ceil(sl.x + sl.z)) + 2,
                                                      static_cast<int>(std::ceil(sl.y + sl.z)) + 2}
                                          : view.viewport();
    for (const TargetView& t : view.targets) out.push_back(t.support.intersect(circle));
  }
  if (footprint != nullptr) out.push_back(*footprint);
  return out;
}

}  // namespace

double OcclusionCuller::prepare() {
  if (database_) return 0.0;
  const auto t = Clock::now();
  database_ = std::make_unique<OccluderDatabase>(build_occluder_database(scene_, objects_));
  return ms_since(t);
}

Result<CullingReport> OcclusionCuller::run(FrameView& view, const FrameContext& fc, const PixelRect* footprint) {
  CullingReport report;
  if (!scene_.plan) return report;
  report.ran = true;
  for (std::uint32_t i = 0; i < objects_.size(); ++i)
    if (!view.rects[i].empty()) {
      ++report.objects_in_view;
      report.triangles_in_view += objects_[i].index_count / 3;
    }
  // A method under which no wall hides anything by itself (vdt: every inner wall is see-through)
  // culls nothing: no occluder database, no GPU work.
  if (!technique::of(fc.settings.method).cullable) return report;
  report.preprocess_ms = prepare();
  if (reduce_.id == 0) {
    auto p = link_program("fullscreen.vert", "depth_reduce.frag");
    if (!p) return p.error();
    reduce_ = std::move(p.value());
  }
  const auto t0 = Clock::now();
  const auto& occluders = database_->nearest(view.camera.eye);
  if (std::none_of(occluders.begin(), occluders.end(), [&](std::uint32_t i) { return !view.rects[i].empty(); })) {
    report.ms = ms_since(t0);  // no occluder in view: nothing can be hidden, no GPU work
    return report;
  }
  // Steps 2-3: the occluders' map, the opacity and sparse depth maps.
  // (occluder_map sizes the map: call it before reading map_w_, map_h_, block_.)
  std::vector<float> depth = occluder_map(view, fc, report);
  const OcclusionMap map =
      make_occlusion_map(std::move(depth), map_w_, map_h_, block_, holes(view, fc.settings.method, footprint));
  // Step 4: the hierarchy; targets stay under a transparency method (a mask may reveal them).
  const bool transparency = uses_transparency(fc.settings.method);
  std::vector<bool> keep(objects_.size(), false);
  for (std::uint32_t i = 0; i < objects_.size(); ++i) keep[i] = view.rects[i].empty() || (transparency && objects_[i].target);
  std::vector<bool> culled;
  const CullCounts counts = cull_hierarchy(hierarchy_, objects_, map, view.view_proj, view.width, view.height, keep, culled);
  report.nodes_tested = counts.nodes_tested;
  report.nodes_culled = counts.nodes_culled;
  // Step 5: culled objects leave the frame's lists.
  for (std::uint32_t i = 0; i < objects_.size(); ++i) {
    if (view.rects[i].empty() || !culled[i]) continue;
    ++report.objects_culled;
    report.triangles_culled += objects_[i].index_count / 3;
    view.rects[i] = {};
  }
  auto drop = [&](std::vector<std::uint32_t>& list) {
    list.erase(std::remove_if(list.begin(), list.end(), [&](std::uint32_t i) { return culled[i]; }), list.end());
  };
  drop(view.impenetrable);
  drop(view.sorted);
  report.ms = ms_since(t0);
  return report;
}

}  // namespace dtlab::render::detail

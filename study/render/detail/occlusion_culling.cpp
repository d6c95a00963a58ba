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
  delete_program(reduce_);
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

namespace {
struct OccluderDepthData {
  Handle depth;
};
struct OccluderMapData {
  Handle depth, map;
};
struct CullTestData {
  Handle map;
};
}  // namespace

bool OcclusionCuller::add_passes(FrameGraph& fg, FrameView& view, const FrameContext& fc,
                                 std::optional<PixelRect> footprint, CullingReport& report) {
  report = {};
  if (!scene_.plan) return false;
  report.ran = true;
  for (std::uint32_t i = 0; i < objects_.size(); ++i)
    if (!view.rects[i].empty()) {
      ++report.objects_in_view;
      report.triangles_in_view += objects_[i].index_count / 3;
    }
  // A method under which no wall hides anything by itself (vdt: every inner wall is see-through)
  // culls nothing: no occluder database, no GPU work.
  if (!technique::of(fc.settings.method).cullable) return false;
  report.preprocess_ms = prepare();
  if (reduce_.id == 0) reduce_ = link_method_program("occlusion culling", "fullscreen.vert", "depth_reduce.frag");
  const std::vector<std::uint32_t>& occluders = database_->nearest(view.camera.eye);
  if (std::none_of(occluders.begin(), occluders.end(), [&](std::uint32_t i) { return !view.rects[i].empty(); }))
    return false;  // no occluder in view: nothing can be hidden, no GPU work
  const int W = view.width, H = view.height;
  const int block = std::max(1, (std::max(W, H) + kMapSide - 1) / kMapSide);
  const int map_w = (W + block - 1) / block, map_h = (H + block - 1) / block;

  // Step 2: the grid point's occluders in view, depth only, no lighting.
  const auto& depth = fg.add_pass<OccluderDepthData>(
      "cull-occluders",
      [&](FrameGraph::Builder& b, OccluderDepthData& d) {
        d.depth = b.write(b.create("occluder depth", {W, H, TextureFormat::depth24_stencil8, false}));
      },
      [this, &view, &fc, &occluders, &report, W, H](const OccluderDepthData& d, PassResources& r) {
        started_ = Clock::now();
        glBindFramebuffer(GL_FRAMEBUFFER, r.framebuffer({}, d.depth));
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
        for (auto i : occluders)
          if (!view.rects[i].empty()) {
            fc.draw_alpha(i);
            ++report.occluders;
          }
      });
  // Step 3 on the GPU: the farthest depth per block of the map (one pixel of border).
  const auto& map = fg.add_pass<OccluderMapData>(
      "cull-map",
      [&](FrameGraph::Builder& b, OccluderMapData& d) {
        d.depth = b.read(depth.depth);
        d.map = b.write(b.create("occluder map", {map_w, map_h, TextureFormat::r32f, false}));
      },
      [this, &fc, W, H, block, map_w, map_h](const OccluderMapData& d, PassResources& r) {
        glBindFramebuffer(GL_FRAMEBUFFER, r.framebuffer({d.map}));
        glViewport(0, 0, map_w, map_h);
        glDisable(GL_DEPTH_TEST);
        glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
        fc.use_program(reduce_);
        glActiveTexture(GL_TEXTURE0);
        glBindTexture(GL_TEXTURE_2D, r.texture(d.depth));
        glUniform1i(reduce_.loc("u_depth"), 0);
        glUniform1i(reduce_.loc("u_block"), block);
        glUniform2i(reduce_.loc("u_size"), W, H);
        glUniform4f(reduce_.loc("u_rect"), -1.0f, -1.0f, 1.0f, 1.0f);
        glUniform1f(reduce_.loc("u_z"), 0.0f);
        glDrawArrays(GL_TRIANGLE_STRIP, 0, 4);
      });
  // Steps 3-5 on the CPU: the map read back, the opacity and sparse depth maps, the hierarchy,
  // and the hidden objects out of the frame's lists.
  fg.add_pass<CullTestData>(
      "cull-test",
      [&](FrameGraph::Builder& b, CullTestData& d) {
        d.map = b.read(map.map);
        b.side_effect();  // its output is the view's lists, read on the CPU
      },
      [this, &view, &fc, footprint, &report, map_w, map_h, block](const CullTestData& d, PassResources& r) {
        std::vector<float> depths(static_cast<std::size_t>(map_w) * map_h);
        const auto t = Clock::now();
        glBindBuffer(GL_PIXEL_PACK_BUFFER, 0);
        glPixelStorei(GL_PACK_ALIGNMENT, 4);
        glPixelStorei(GL_PACK_ROW_LENGTH, 0);
        glPixelStorei(GL_PACK_SKIP_ROWS, 0);
        glPixelStorei(GL_PACK_SKIP_PIXELS, 0);
        glBindFramebuffer(GL_READ_FRAMEBUFFER, r.framebuffer({d.map}));
        glReadBuffer(GL_COLOR_ATTACHMENT0);
        glReadPixels(0, 0, map_w, map_h, GL_RED, GL_FLOAT, depths.data());
        report.readback_ms = ms_since(t);
        const OcclusionMap occlusion = make_occlusion_map(std::move(depths), map_w, map_h, block,
                                                          holes(view, fc.settings.method, footprint ? &*footprint : nullptr));
        cull(view, occlusion, uses_transparency(fc.settings.method), report);
        report.ms = ms_since(started_);
      });
  return true;
}

void OcclusionCuller::cull(FrameView& view, const OcclusionMap& map, bool transparency, CullingReport& report) const {
  // Step 4: the hierarchy; targets stay under a transparency method (a mask may reveal them).
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
}

}  // namespace dtlab::render::detail

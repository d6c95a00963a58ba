// The opacity map, the sparse depth map and the hierarchy test (see occlusion_map.h).
#include <algorithm>
#include <array>
#include <numeric>

#include "study/render/detail/occlusion_map.h"

namespace dtlab::render::detail {

bool OcclusionMap::behind(int x0, int y0, int x1, int y1, float near) const {
  for (int y = y0; y < y1; ++y) {
    const std::size_t row = static_cast<std::size_t>(y * width);
    for (int x = x0; x < x1;) {
      // Depth rises (or stays) from x to its peak: the peak, or the rectangle's last texel, is the
      // farthest of the run, so one comparison stands for the whole run.
      const int k = std::min(x + static_cast<int>(steps[row + static_cast<std::size_t>(x)]) - 1, x1 - 1);
      if (!(depth[row + static_cast<std::size_t>(k)] < near)) return false;
      x = k + 1;
    }
  }
  return true;
}

OcclusionMap make_occlusion_map(std::vector<float> depth, int width, int height, int block,
                                const std::vector<PixelRect>& holes) {
  OcclusionMap m;
  m.width = width;
  m.height = height;
  m.block = block;
  m.depth = std::move(depth);
  for (const PixelRect& r : holes) {  // every texel that shares a pixel with a hole
    if (r.empty()) continue;
    const int x0 = std::max(0, r.x0 / block), y0 = std::max(0, r.y0 / block);
    const int x1 = std::min(width, (r.x1 + block - 1) / block), y1 = std::min(height, (r.y1 + block - 1) / block);
    for (int y = y0; y < y1; ++y)
      for (int x = x0; x < x1; ++x) m.depth[static_cast<std::size_t>(y * width + x)] = 1.0f;
  }
  // Opacity values: covered texels in the rectangle from the lower left corner up to (s, t).
  m.opacity.assign(static_cast<std::size_t>((width + 1) * (height + 1)), 0);
  m.steps.assign(m.depth.size(), 1);
  for (int y = 0; y < height; ++y) {
    int row_sum = 0;
    for (int x = 0; x < width; ++x) {
      row_sum += m.depth[static_cast<std::size_t>(y * width + x)] < 1.0f ? 1 : 0;
      const std::size_t at = static_cast<std::size_t>((y + 1) * (width + 1) + x + 1);
      m.opacity[at] = m.opacity[at - static_cast<std::size_t>(width + 1)] + row_sum;
    }
    if (row_sum == 0) continue;  // a row no occluder covers is never walked
    // Right to left: while depth rises (or stays) towards the right, one more texel to the peak.
    std::uint16_t* s = &m.steps[static_cast<std::size_t>(y * width)];
    const float* d = &m.depth[static_cast<std::size_t>(y * width)];
    for (int x = width - 2; x >= 0; --x)
      s[x] = d[x] <= d[x + 1] ? static_cast<std::uint16_t>(s[x + 1] + 1) : std::uint16_t{1};
  }
  return m;
}

namespace {

int build(Hierarchy& h, const std::vector<ObjectRecord>& objects, std::vector<std::uint32_t> ids, long leaf_triangles) {
  const int at = static_cast<int>(h.nodes.size());
  h.nodes.emplace_back();
  glm::vec3 lo(1e30f), hi(-1e30f), clo(1e30f), chi(-1e30f);
  long triangles = 0;
  for (auto i : ids) {
    const ObjectRecord& o = objects[i];
    lo = glm::min(lo, o.world_min);
    hi = glm::max(hi, o.world_max);
    const glm::vec3 c = 0.5f * (o.world_min + o.world_max);
    clo = glm::min(clo, c);
    chi = glm::max(chi, c);
    triangles += o.index_count / 3;
  }
  h.nodes[static_cast<std::size_t>(at)].lo = lo;
  h.nodes[static_cast<std::size_t>(at)].hi = hi;
  if (ids.size() == 1 || triangles <= leaf_triangles) {
    h.nodes[static_cast<std::size_t>(at)].objects = std::move(ids);
    return at;
  }
  const glm::vec3 ext = chi - clo;
  const int axis = ext.x >= ext.y && ext.x >= ext.z ? 0 : (ext.y >= ext.z ? 1 : 2);
  std::stable_sort(ids.begin(), ids.end(), [&](std::uint32_t a, std::uint32_t b) {
    return objects[a].world_min[axis] + objects[a].world_max[axis] < objects[b].world_min[axis] + objects[b].world_max[axis];
  });
  const auto mid = ids.begin() + static_cast<long>(ids.size() / 2);
  std::vector<std::uint32_t> left(ids.begin(), mid), right(mid, ids.end());
  const int l = build(h, objects, std::move(left), leaf_triangles);
  const int r = build(h, objects, std::move(right), leaf_triangles);
  h.nodes[static_cast<std::size_t>(at)].left = l;
  h.nodes[static_cast<std::size_t>(at)].right = r;
  return at;
}

enum class Verdict { outside, hidden, stop, open };

// The thesis's two conditions for a box (8 world points): its image covered (OPF = area) and its
// nearest depth farther than the occluders'; below the coverage ratio, stop descending.
Verdict test(const std::array<glm::vec3, 8>& corners, const OcclusionMap& map, const glm::mat4& vp, int w, int h,
             float min_coverage) {
  const PixelRect r = screen_rect(std::vector<glm::vec3>(corners.begin(), corners.end()), vp, w, h);
  if (r.empty()) return Verdict::outside;
  float near = 1.0f;
  for (const auto& p : corners) {
    const glm::vec4 c = vp * glm::vec4(p, 1.0f);
    near = c.w <= 1e-6f || c.z < -c.w ? 0.0f : std::min(near, 0.5f * c.z / c.w + 0.5f);
    if (near <= 0.0f) break;
  }
  const int b = map.block;
  const int x0 = std::max(0, r.x0 / b), y0 = std::max(0, r.y0 / b);
  const int x1 = std::min(map.width, (r.x1 + b - 1) / b), y1 = std::min(map.height, (r.y1 + b - 1) / b);
  const int area = (x1 - x0) * (y1 - y0);
  const int covered = map.opf(x0, x1, y0, y1);
  // A margin of a few depth-buffer steps: the occluders' depth is rasterized, the node's exact.
  if (covered == area && near > 0.0f && map.behind(x0, y0, x1, y1, near - 4e-6f)) return Verdict::hidden;
  return static_cast<float>(covered) < min_coverage * static_cast<float>(area) ? Verdict::stop : Verdict::open;
}

std::array<glm::vec3, 8> corners_of(glm::vec3 lo, glm::vec3 hi, const glm::mat4& m = glm::mat4(1.0f)) {
  std::array<glm::vec3, 8> c;
  for (int k = 0; k < 8; ++k)
    c[static_cast<std::size_t>(k)] =
        glm::vec3(m * glm::vec4((k & 1) ? hi.x : lo.x, (k & 2) ? hi.y : lo.y, (k & 4) ? hi.z : lo.z, 1.0f));
  return c;
}

struct Walk {
  const Hierarchy& h;
  const std::vector<ObjectRecord>& objects;
  const OcclusionMap& map;
  const glm::mat4& vp;
  int w, hgt;
  const std::vector<bool>& keep;
  std::vector<bool>& culled;
  float min_coverage;
  CullCounts counts;

  void hide(int n) {
    const auto& node = h.nodes[static_cast<std::size_t>(n)];
    if (node.left >= 0) {
      hide(node.left);
      hide(node.right);
    }
    for (auto i : node.objects)
      if (!keep[i]) culled[i] = true;
  }
  void visit(int n) {
    const auto& node = h.nodes[static_cast<std::size_t>(n)];
    ++counts.nodes_tested;
    const Verdict v = test(corners_of(node.lo, node.hi), map, vp, w, hgt, min_coverage);
    if (v == Verdict::hidden) {
      ++counts.nodes_culled;
      hide(n);
      return;
    }
    if (v != Verdict::open) return;
    if (node.left >= 0) {
      visit(node.left);
      visit(node.right);
      return;
    }
    for (auto i : node.objects) {  // the leaf's objects by their own (tighter) boxes
      const ObjectRecord& o = objects[i];
      if (!keep[i] && test(corners_of(o.mesh_min, o.mesh_max, o.model), map, vp, w, hgt, 0.0f) == Verdict::hidden)
        culled[i] = true;
    }
  }
};

}  // namespace

Hierarchy build_hierarchy(const std::vector<ObjectRecord>& objects, long leaf_triangles) {
  Hierarchy h;
  std::vector<std::uint32_t> ids;
  for (std::uint32_t i = 0; i < objects.size(); ++i)
    if (objects[i].drawable()) ids.push_back(i);
  if (!ids.empty()) build(h, objects, std::move(ids), leaf_triangles);
  return h;
}

CullCounts cull_hierarchy(const Hierarchy& h, const std::vector<ObjectRecord>& objects, const OcclusionMap& map,
                          const glm::mat4& view_proj, int width, int height, const std::vector<bool>& keep,
                          std::vector<bool>& culled, float min_coverage) {
  culled.assign(objects.size(), false);
  if (h.nodes.empty() || map.width <= 0) return {};
  Walk walk{h, objects, map, view_proj, width, height, keep, culled, min_coverage, {}};
  walk.visit(0);
  return walk.counts;
}

}  // namespace dtlab::render::detail

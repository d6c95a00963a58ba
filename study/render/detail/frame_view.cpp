// Per-frame CPU geometry (see frame_view.h).
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "study/render/detail/frame_view.h"
#include "study/render/render.h"
#include "study/scene/transform.h"

namespace dtlab::render::detail {

namespace {

struct Projected {
  bool outside = false;     // every point outside one frustum plane
  bool unbounded = false;   // some point at or behind the eye plane: bounds unknown, use the viewport
  glm::vec4 bounds{0.0f};   // window pixels, when neither
};

// Projects points to window pixels; classifies against the frustum.
template <class PointFn>
Projected project(std::size_t n, PointFn point, const glm::mat4& vp, int w, int h) {
  Projected out;
  int outside_mask = 0x3f;
  float x0 = std::numeric_limits<float>::max(), y0 = x0, x1 = -x0, y1 = -x0;
  for (std::size_t i = 0; i < n; ++i) {
    const glm::vec4 c = scene::transform_point(vp, point(i));
    int m = 0;
    if (c.x < -c.w) m |= 1;
    if (c.x > c.w) m |= 2;
    if (c.y < -c.w) m |= 4;
    if (c.y > c.w) m |= 8;
    if (c.z < -c.w) m |= 16;
    if (c.z > c.w) m |= 32;
    outside_mask &= m;
    if (c.w <= 1e-6f || c.z < -c.w) {
      out.unbounded = true;
      continue;
    }
    const float sx = (c.x / c.w * 0.5f + 0.5f) * static_cast<float>(w);
    const float sy = (c.y / c.w * 0.5f + 0.5f) * static_cast<float>(h);
    x0 = std::min(x0, sx);
    y0 = std::min(y0, sy);
    x1 = std::max(x1, sx);
    y1 = std::max(y1, sy);
  }
  out.outside = n == 0 || outside_mask != 0;
  out.bounds = glm::vec4(x0, y0, x1, y1);
  return out;
}

PixelRect to_pixels(const glm::vec4& b, int w, int h) {
  // One extra pixel on each side: rasterization samples pixel centres, bounds are exact floats.
  PixelRect r{static_cast<int>(std::floor(std::max(b.x, -1e6f))) - 1, static_cast<int>(std::floor(std::max(b.y, -1e6f))) - 1,
              static_cast<int>(std::ceil(std::min(b.z, 1e6f))) + 1, static_cast<int>(std::ceil(std::min(b.w, 1e6f))) + 1};
  return r.intersect({0, 0, w, h});
}

}  // namespace

PixelRect screen_rect(const std::vector<glm::vec3>& points, const glm::mat4& view_proj, int width, int height) {
  const Projected p = project(points.size(), [&](std::size_t i) { return points[i]; }, view_proj, width, height);
  return p.unbounded ? PixelRect{0, 0, width, height} : to_pixels(p.bounds, width, height);
}

namespace {

// Greedy colouring: each target the smallest code no earlier target with an overlapping
// rectangle has. A target fragment can only be hidden, at a pixel, by an object whose rectangle
// holds that pixel; so equal codes never meet. 0 when all 255 codes are taken around it.
void assign_codes(FrameView& v) {
  for (std::size_t k = 0; k < v.targets.size(); ++k) {
    std::vector<bool> taken(256, false);
    for (std::size_t j = 0; j < k; ++j)
      if (v.targets[j].rect.overlaps(v.targets[k].rect)) taken[static_cast<std::size_t>(v.targets[j].code)] = true;
    int code = 1;
    while (code < 256 && taken[static_cast<std::size_t>(code)]) ++code;
    if (code == 256) {
      v.targets[k].code = 0;
      v.codes_exhausted = true;
    } else {
      v.targets[k].code = code;
      v.max_code = std::max(v.max_code, code);
    }
  }
}

// The 8 corners of an object's own box, transformed to the world (a parallelepiped around it).
std::array<glm::vec3, 8> box_corners(const ObjectRecord& o) {
  std::array<glm::vec3, 8> c;
  for (int k = 0; k < 8; ++k)
    c[static_cast<std::size_t>(k)] = glm::vec3(o.model * glm::vec4((k & 1) ? o.mesh_max.x : o.mesh_min.x,
                                                                   (k & 2) ? o.mesh_max.y : o.mesh_min.y,
                                                                   (k & 4) ? o.mesh_max.z : o.mesh_min.z, 1.0f));
  return c;
}

// True if one face plane of the box `o` has the eye and every point of `t` strictly on its
// outer side: `o` (inside its box) then lies wholly beyond that plane and cannot come between
// the eye and any point of `t`.
bool separated(const std::array<glm::vec3, 8>& o, glm::vec3 eye, const std::array<glm::vec3, 8>& t) {
  // Faces by corner index bits: for axis a, the corners with bit a clear (side 0) or set (side 1).
  glm::vec3 centre(0.0f);
  for (const auto& c : o) centre += c * 0.125f;
  for (int axis = 0; axis < 3; ++axis) {
    const int u = 1 << ((axis + 1) % 3), w = 1 << ((axis + 2) % 3);
    for (int side = 0; side < 2; ++side) {
      const int base = side ? (1 << axis) : 0;
      const glm::vec3 p0 = o[static_cast<std::size_t>(base)];
      glm::vec3 n = glm::cross(o[static_cast<std::size_t>(base | u)] - p0, o[static_cast<std::size_t>(base | w)] - p0);
      if (glm::dot(n, n) < 1e-20f) continue;  // a flat box: this face says nothing
      if (glm::dot(n, centre - p0) > 0.0f) n = -n;  // outward
      const float d = glm::dot(n, p0);
      const float margin = 1e-4f * std::sqrt(glm::dot(n, n));
      if (glm::dot(n, eye) - d <= margin) continue;
      bool all = true;
      for (const auto& c : t)
        if (glm::dot(n, c) - d <= margin) {
          all = false;
          break;
        }
      if (all) return true;
    }
  }
  return false;
}

}  // namespace

MaskGrid mask_grid(const DtSettings& dt, int width, int height) {
  MaskGrid g;
  g.width = dt.mask_resolution > 0 ? dt.mask_resolution : width;
  g.height = dt.mask_resolution > 0 ? dt.mask_resolution : height;
  g.texel_x = static_cast<float>(width) / static_cast<float>(g.width);
  g.texel_y = static_cast<float>(height) / static_cast<float>(g.height);
  // One border pass adds one texel; a texel spans sqrt(tx ty) output pixels.
  const double texel = std::sqrt(static_cast<double>(g.texel_x) * g.texel_y);
  if (dt.gradient_px > 0.0f) g.layers = std::max(1, static_cast<int>(std::lround(dt.gradient_px / texel)));
  return g;
}

FrameView make_frame_view(const std::vector<ObjectRecord>& objects, const scene::Scene& scene,
                          const Camera& camera, int width, int height, const DtSettings& dt, GroupSorter& sorter) {
  FrameView v;
  v.width = width;
  v.height = height;
  v.camera = camera;
  v.view_proj = camera.view_proj();
  v.grid = mask_grid(dt, width, height);
  const MaskGrid& g = v.grid;
  const PixelRect viewport{0, 0, width, height};
  v.rects.resize(objects.size());
  v.target_slot.assign(objects.size(), -1);
  v.single_pass.assign(objects.size(), false);
  const int margin = static_cast<int>(std::ceil(dt.gradient_px)) + 1;
  for (std::uint32_t i = 0; i < objects.size(); ++i) {
    const ObjectRecord& o = objects[i];
    if (!o.drawable()) continue;
    // The corners of the object's own box, transformed: tighter on screen than its world AABB.
    const glm::mat4 box_mvp = v.view_proj * o.model;
    const Projected box = project(
        8,
        [&](std::size_t c) {
          return glm::vec3((c & 1) ? o.mesh_max.x : o.mesh_min.x, (c & 2) ? o.mesh_max.y : o.mesh_min.y,
                           (c & 4) ? o.mesh_max.z : o.mesh_min.z);
        },
        box_mvp, width, height);
    if (box.outside) continue;
    v.rects[i] = box.unbounded ? viewport : to_pixels(box.bounds, width, height);
    // One culled pass is exact only for a convex object seen from outside, not cut by the near plane.
    const glm::vec3 pad(2.0f * camera.near_plane);
    const bool outside = glm::any(glm::lessThan(camera.eye, o.world_min - pad)) ||
                         glm::any(glm::greaterThan(camera.eye, o.world_max + pad));
    v.single_pass[i] = o.convex && !box.unbounded && outside;
    if (v.rects[i].empty()) continue;
    if (o.impenetrable) v.impenetrable.push_back(i);
    if (!o.target) continue;
    // Targets: tight bounds from the transformed vertices.
    const auto& verts = scene.meshes[o.mesh].vertices;
    const glm::mat4 mvp = v.view_proj * o.model;
    const Projected tight = project(verts.size(), [&](std::size_t k) { return verts[k].position; }, mvp, width, height);
    if (tight.outside) continue;
    TargetView t;
    t.object = i;
    t.bounds = tight.unbounded ? glm::vec4(0.0f, 0.0f, static_cast<float>(width), static_cast<float>(height))
                               : tight.bounds;
    t.rect = tight.unbounded ? viewport : to_pixels(t.bounds, width, height);
    if (t.rect.empty()) continue;
    v.rects[i] = v.rects[i].intersect(t.rect.expand(1));
    const glm::vec2 half(0.5f * (t.bounds.z - t.bounds.x), 0.5f * (t.bounds.w - t.bounds.y));
    t.shape_center = glm::vec2(0.5f * (t.bounds.x + t.bounds.z), 0.5f * (t.bounds.y + t.bounds.w));
    if (dt.shape == MaskShape::circle) {
      t.shape_radii = glm::vec2(glm::length(half));
    } else {
      t.shape_radii = half * std::sqrt(2.0f);
    }
    PixelRect extent = t.rect;
    if (dt.shape != MaskShape::outline)
      extent = to_pixels(glm::vec4(t.shape_center - t.shape_radii, t.shape_center + t.shape_radii), width, height);
    // Texels whose centres can lie in the extent, and the pixels whose bilinear sample can read a
    // texel up to n' texels from those (a sample reads the texels around it: one more each side).
    t.cover = {static_cast<int>(std::floor(static_cast<float>(extent.x0) / g.texel_x)),
               static_cast<int>(std::floor(static_cast<float>(extent.y0) / g.texel_y)),
               static_cast<int>(std::floor(static_cast<float>(extent.x1) / g.texel_x)) + 1,
               static_cast<int>(std::floor(static_cast<float>(extent.y1) / g.texel_y)) + 1};
    t.cover = t.cover.intersect({0, 0, g.width, g.height});
    const PixelRect grid_support{
        static_cast<int>(std::floor(static_cast<float>(t.cover.x0 - g.layers - 1) * g.texel_x)),
        static_cast<int>(std::floor(static_cast<float>(t.cover.y0 - g.layers - 1) * g.texel_y)),
        static_cast<int>(std::ceil(static_cast<float>(t.cover.x1 + g.layers + 1) * g.texel_x)),
        static_cast<int>(std::ceil(static_cast<float>(t.cover.y1 + g.layers + 1) * g.texel_y))};
    const PixelRect exact_support = extent.expand(margin);  // the reference's exact mask
    t.support = PixelRect{std::min(grid_support.x0, exact_support.x0), std::min(grid_support.y0, exact_support.y0),
                          std::max(grid_support.x1, exact_support.x1), std::max(grid_support.y1, exact_support.y1)}
                    .intersect(viewport);
    v.target_slot[i] = static_cast<int>(v.targets.size());
    v.targets.push_back(t);
  }
  assign_codes(v);
  for (auto i : sorter.sort(camera.eye, camera.forward))
    if (!v.rects[i].empty()) v.sorted.push_back(i);
  // Depth ranges along the view direction (from the world boxes) for the sort-error test.
  std::vector<glm::vec2> range(objects.size());
  for (auto i : v.sorted) {
    const ObjectRecord& o = objects[i];
    float lo = std::numeric_limits<float>::max(), hi = -lo;
    for (int c = 0; c < 8; ++c) {
      const glm::vec3 p((c & 1) ? o.world_max.x : o.world_min.x, (c & 2) ? o.world_max.y : o.world_min.y,
                        (c & 4) ? o.world_max.z : o.world_min.z);
      const float d = glm::dot(p - camera.eye, camera.forward);
      lo = std::min(lo, d);
      hi = std::max(hi, d);
    }
    range[i] = {lo, hi};
  }
  for (std::size_t k = 0; k < v.sorted.size(); ++k) {
    const int slot = v.target_slot[v.sorted[k]];
    if (slot < 0) continue;
    TargetView& t = v.targets[static_cast<std::size_t>(slot)];
    const auto target_box = box_corners(objects[t.object]);
    for (std::size_t j = 0; j < k && !t.may_be_drawn_late; ++j) {
      const auto o = v.sorted[j];
      t.may_be_drawn_late = v.rects[o].overlaps(t.rect) && range[o].x < range[t.object].y &&
                            !separated(box_corners(objects[o]), camera.eye, target_box);
    }
  }
  if (dt.mode == DtMode::active)
    v.searchlight = glm::vec3(dt.searchlight_center.x, static_cast<float>(height) - dt.searchlight_center.y,
                              dt.searchlight_radius);
  return v;
}

}  // namespace dtlab::render::detail

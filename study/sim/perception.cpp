// look() (perception.h): packed weight frames. In weight mode every object is
// drawn flat black except the coloured ones, and a channel's 8-bit value at a
// pixel is that channel's objects' share of the composited colour. An object's
// share is zero outside its silhouette, which lies inside the screen rectangle
// of its projected vertices; objects with disjoint rectangles therefore
// never share a pixel, and a channel may hold several of them. Greedy packing
// in request order into (frame, channel) slots.
#include "study/sim/perception.h"

#include <algorithm>
#include <cmath>

#include "study/scene/transform.h"

namespace dtlab::sim {

namespace {

struct Rect {
  int x0 = 0, y0 = 0, x1 = 0, y1 = 0;  // pixels [x0, x1) x [y0, y1), row 0 at the top
  bool empty() const { return x1 <= x0 || y1 <= y0; }
  bool overlaps(const Rect& o) const { return x0 < o.x1 && o.x0 < x1 && y0 < o.y1 && o.y0 < y1; }
  long area() const { return empty() ? 0 : static_cast<long>(x1 - x0) * (y1 - y0); }
};

// Screen rectangle of an object: the bounds of its projected vertices, grown by one pixel for
// rasterisation (a pixel is covered when its centre is inside a triangle, so every covered pixel
// lies within the vertices' bounds); the whole screen if a vertex lies behind the eye (its
// triangles are clipped against the near plane), empty if every vertex does.
Rect screen_rect(const glm::mat4& view_proj, const ObjectBounds& b, int width, int height) {
  float nx0 = 1e30f, ny0 = 1e30f, nx1 = -1e30f, ny1 = -1e30f;
  std::size_t behind = 0;
  for (const glm::vec3& q : b.points) {
    const glm::vec4 p = scene::transform_point(view_proj, q);
    if (p.w <= 1e-4f) {
      ++behind;
      continue;
    }
    nx0 = std::min(nx0, p.x / p.w);
    nx1 = std::max(nx1, p.x / p.w);
    ny0 = std::min(ny0, p.y / p.w);
    ny1 = std::max(ny1, p.y / p.w);
  }
  if (b.points.empty() || behind == b.points.size()) return {};
  if (behind > 0) return {0, 0, width, height};
  if (nx1 < -1.0f || nx0 > 1.0f || ny1 < -1.0f || ny0 > 1.0f) return {};  // outside the view
  Rect r;
  r.x0 = static_cast<int>(std::floor((nx0 + 1.0f) * 0.5f * static_cast<float>(width))) - 1;
  r.x1 = static_cast<int>(std::ceil((nx1 + 1.0f) * 0.5f * static_cast<float>(width))) + 1;
  r.y0 = static_cast<int>(std::floor((1.0f - ny1) * 0.5f * static_cast<float>(height))) - 1;
  r.y1 = static_cast<int>(std::ceil((1.0f - ny0) * 0.5f * static_cast<float>(height))) + 1;
  r.x0 = std::clamp(r.x0, 0, width);
  r.x1 = std::clamp(r.x1, 0, width);
  r.y0 = std::clamp(r.y0, 0, height);
  r.y1 = std::clamp(r.y1, 0, height);
  return r;
}

// Pixels whose centre lies inside one of the object's triangles (each pixel once), within `r`.
// Triangles reaching behind the eye are skipped: the silhouette is then a lower bound (only
// objects touching the eye have such triangles).
long silhouette(const glm::mat4& view_proj, const ObjectBounds& b, const Rect& r, int width, int height) {
  if (r.empty() || !b.mesh) return 0;
  const int w = r.x1 - r.x0, h = r.y1 - r.y0;
  std::vector<std::uint8_t> covered(static_cast<std::size_t>(w) * static_cast<std::size_t>(h), 0);
  const glm::mat4 m = view_proj * b.transform;
  std::vector<glm::vec3> screen(b.mesh->vertices.size());  // x, y in pixels (row 0 at the top), w
  for (std::size_t i = 0; i < screen.size(); ++i) {
    const glm::vec4 p = scene::transform_point(m, b.mesh->vertices[i].position);
    screen[i] = p.w > 1e-4f ? glm::vec3((p.x / p.w + 1.0f) * 0.5f * static_cast<float>(width),
                                        (1.0f - p.y / p.w) * 0.5f * static_cast<float>(height), p.w)
                            : glm::vec3(0.0f, 0.0f, -1.0f);
  }
  const auto& idx = b.mesh->indices;
  for (std::size_t t = 0; t + 2 < idx.size(); t += 3) {
    const glm::vec3 a = screen[idx[t]], c1 = screen[idx[t + 1]], c2 = screen[idx[t + 2]];
    if (a.z < 0 || c1.z < 0 || c2.z < 0) continue;
    const float area = (c1.x - a.x) * (c2.y - a.y) - (c1.y - a.y) * (c2.x - a.x);
    if (std::abs(area) < 1e-12f) continue;
    const int x0 = std::max(r.x0, static_cast<int>(std::floor(std::min({a.x, c1.x, c2.x}))));
    const int x1 = std::min(r.x1 - 1, static_cast<int>(std::ceil(std::max({a.x, c1.x, c2.x}))));
    const int y0 = std::max(r.y0, static_cast<int>(std::floor(std::min({a.y, c1.y, c2.y}))));
    const int y1 = std::min(r.y1 - 1, static_cast<int>(std::ceil(std::max({a.y, c1.y, c2.y}))));
    const float s = area > 0 ? 1.0f : -1.0f;  // either winding: the silhouette ignores culling
    for (int y = y0; y <= y1; ++y)
      for (int x = x0; x <= x1; ++x) {
        const float px = static_cast<float>(x) + 0.5f, py = static_cast<float>(y) + 0.5f;
        const float e0 = s * ((c1.x - a.x) * (py - a.y) - (c1.y - a.y) * (px - a.x));
        const float e1 = s * ((c2.x - c1.x) * (py - c1.y) - (c2.y - c1.y) * (px - c1.x));
        const float e2 = s * ((a.x - c2.x) * (py - c2.y) - (a.y - c2.y) * (px - c2.x));
        if (e0 >= 0 && e1 >= 0 && e2 >= 0)
          covered[static_cast<std::size_t>(y - r.y0) * static_cast<std::size_t>(w) + static_cast<std::size_t>(x - r.x0)] = 1;
      }
  }
  long n = 0;
  for (std::uint8_t c : covered) n += c;
  return n;
}

}  // namespace

std::vector<ObjectBounds> object_bounds(const scene::Scene& scene) {
  // Distinct mesh positions once per mesh (meshes repeat vertices per face for flat normals).
  std::vector<std::vector<glm::vec3>> positions(scene.meshes.size());
  for (std::size_t m = 0; m < scene.meshes.size(); ++m) {
    auto& ps = positions[m];
    for (const scene::Vertex& v : scene.meshes[m].vertices) ps.push_back(v.position);
    std::sort(ps.begin(), ps.end(), [](const glm::vec3& a, const glm::vec3& b) {
      return a.x != b.x ? a.x < b.x : a.y != b.y ? a.y < b.y : a.z < b.z;
    });
    ps.erase(std::unique(ps.begin(), ps.end()), ps.end());
  }
  std::vector<ObjectBounds> out;
  out.reserve(scene.objects.size());
  for (const scene::Object& o : scene.objects) {
    ObjectBounds b{&scene.meshes[o.mesh], o.transform, {}, glm::vec3(1e30f), glm::vec3(-1e30f)};
    for (const glm::vec3& p : positions[o.mesh]) {
      const glm::vec3 w(scene::transform_point(o.transform, p));
      b.points.push_back(w);
      b.min = glm::min(b.min, w);
      b.max = glm::max(b.max, w);
    }
    if (b.points.empty()) b.min = b.max = glm::vec3(o.transform[3]);
    out.push_back(std::move(b));
  }
  return out;
}

Result<View> look(render::Renderer& renderer, const render::Camera& camera, const render::FrameSettings& settings, int width,
          int height, std::span<const std::uint32_t> objects, const std::vector<ObjectBounds>& bounds) {
  const scene::Scene& sc = renderer.scene();
  View view;
  view.seen.resize(objects.size());
  const glm::mat4 vp = camera.view_proj();

  // Pack into slots (frame * 3 + channel).
  std::vector<Rect> rects(objects.size());
  std::vector<int> slot(objects.size(), -1);
  std::vector<std::vector<Rect>> slots;
  for (std::size_t i = 0; i < objects.size(); ++i) {
    view.seen[i].index = objects[i];
    rects[i] = screen_rect(vp, bounds[objects[i]], width, height);
    view.seen[i].rect_px = rects[i].area();
    if (rects[i].empty()) continue;
    view.seen[i].silhouette_px = silhouette(vp, bounds[objects[i]], rects[i], width, height);
    std::size_t s = 0;
    for (; s < slots.size(); ++s)
      if (std::none_of(slots[s].begin(), slots[s].end(), [&](const Rect& r) { return r.overlaps(rects[i]); })) break;
    if (s == slots.size()) slots.emplace_back();
    slots[s].push_back(rects[i]);
    slot[i] = static_cast<int>(s);
  }

  // Same threshold as Renderer::visibility: a share >= kVisibleShare is >= 26 of 255.
  const int visible = static_cast<int>(std::ceil(render::kVisibleShare * 255.0f - 1e-4f));
  const int clear = static_cast<int>(std::ceil(0.9f * 255.0f - 1e-4f));
  render::FrameSettings weight = settings;
  weight.timed = true;
  // At least one frame: the participant looks at the view even when nothing of interest is in it.
  const std::size_t frames = std::max<std::size_t>(1, (slots.size() + 2) / 3);
  for (std::size_t f = 0; f < frames; ++f) {
    weight.flat_colors.assign(sc.objects.size(), glm::vec3(0.0f));
    for (std::size_t i = 0; i < objects.size(); ++i) {
      if (slot[i] < 0 || static_cast<std::size_t>(slot[i]) / 3 != f) continue;
      glm::vec3 e(0.0f);
      e[slot[i] % 3] = 1.0f;
      weight.flat_colors[objects[i]] = e;
    }
    const auto report = renderer.render_offscreen(camera, weight, width, height);
    if (!report) return report.error();
    view.frame_ms.push_back(report->frame_ms);
    const auto read = renderer.read_color();
    if (!read) return read.error();
    const render::Image& img = read.value();
    for (std::size_t i = 0; i < objects.size(); ++i) {
      if (slot[i] < 0 || static_cast<std::size_t>(slot[i]) / 3 != f) continue;
      const int c = slot[i] % 3;
      const Rect& r = rects[i];
      long n = 0, m = 0;
      for (int y = r.y0; y < r.y1; ++y)
        for (int x = r.x0; x < r.x1; ++x) {
          const int v = img.pixel(x, y)[c];
          n += v >= visible;
          m += v >= clear;
        }
      view.seen[i].visible_px = n;
      view.seen[i].clear_px = m;
    }
  }
  return view;
}

float aid_radius_px(const render::FrameSettings& settings, const render::Camera& camera, int height) {
  if (technique::of(settings.method).reads(technique::Group::lens)) {
    const render::LensSettings& l = settings.lens;
    if (!l.follows_cursor) return 0.0f;
    // The lens's radius at its distance, projected: tan(half angle) = radius / distance, and
    // proj[1][1] = 1 / tan(fov_y / 2) maps it to normalised device units (half the height).
    if (l.radius >= l.distance) return 1e9f;  // the eye inside the lens: it covers the view
    return l.radius / l.distance * camera.proj[1][1] * 0.5f * static_cast<float>(height);
  }
  if (render::uses_transparency(settings.method) && settings.dt.mode == render::DtMode::active)
    return settings.dt.searchlight_radius;
  return 0.0f;
}

std::vector<glm::vec2> aid_spots(const render::FrameSettings& settings, const render::Camera& camera,
                                 bool mouse_turns_view, int width, int height) {
  const float r = aid_radius_px(settings, camera, height);
  if (mouse_turns_view || r <= 0.0f) return {};
  const float w = static_cast<float>(width), h = static_cast<float>(height);
  // Cells of one diameter, at least one per axis (a huge aid: one spot at the centre), and no more
  // than kMaxAidSpots: a smaller aid is swept over as many spots, leaving gaps between them.
  const float cell = std::max(2.0f * r, std::sqrt(w * h / static_cast<float>(kMaxAidSpots)));
  const int nx = std::max(1, static_cast<int>(std::ceil(w / cell - 1e-4f)));
  const int ny = std::max(1, static_cast<int>(std::ceil(h / cell - 1e-4f)));
  std::vector<glm::vec2> spots;
  spots.reserve(static_cast<std::size_t>(nx) * static_cast<std::size_t>(ny));
  for (int j = 0; j < ny; ++j)
    for (int k = 0; k < nx; ++k) {
      const int i = j % 2 == 0 ? k : nx - 1 - k;
      spots.emplace_back((static_cast<float>(i) + 0.5f) * w / static_cast<float>(nx),
                         (static_cast<float>(j) + 0.5f) * h / static_cast<float>(ny));
    }
  return spots;
}

}  // namespace dtlab::sim

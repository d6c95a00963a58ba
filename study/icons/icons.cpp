// Icon rendering: the one-object scene, the fitted 3/4 view camera and the
// keyed, supersampled frame (see icons.h). Uses study/render's public API only.
#include "study/icons/icons.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include <glm/gtc/matrix_transform.hpp>

#include "study/icons/detail/keying.h"
#include "study/render/render.h"

namespace dtlab::icons {

namespace {
constexpr float kDegree = 3.14159265358979f / 180.0f;
}

void validate(const IconOptions& o) {
  auto bad = [](const std::string& field, const std::string& range) {
    throw std::invalid_argument("icon options: " + field + " must be " + range);
  };
  if (o.size < kMinSize || o.size > kMaxSize)
    bad("size", "in " + std::to_string(kMinSize) + ".." + std::to_string(kMaxSize) + ", got " + std::to_string(o.size));
  if (o.supersample < 1 || o.supersample > 8) bad("supersample", "in 1..8, got " + std::to_string(o.supersample));
  if (!(o.azimuth_deg >= -360.0f && o.azimuth_deg <= 360.0f)) bad("azimuth_deg", "in -360..360");
  if (!(o.elevation_deg >= 0.0f && o.elevation_deg <= 80.0f)) bad("elevation_deg", "in 0..80");
  if (!(o.fov_deg >= 5.0f && o.fov_deg <= 90.0f)) bad("fov_deg", "in 5..90");
  if (!(o.margin >= 0.0f && o.margin <= 0.3f)) bad("margin", "in 0..0.3");
}

scene::Scene icon_scene(const scene::ModelInfo& model) {
  scene::Scene s;
  s.kind = scene::Kind::walkthrough;
  s.task = scene::Task::T3;
  s.meshes.push_back(model.build());
  scene::Object o;
  o.id = 1;
  o.kind = std::string(model.kind);
  o.color = glm::vec3(1.0f);  // as the WALKTHROUGH generator places models: vertex colours carry the colour
  o.group = 1;
  s.objects.push_back(o);
  s.answer.task = scene::Task::T3;
  s.answer.target_kind = o.kind;
  glm::vec3 lo(std::numeric_limits<float>::max()), hi(std::numeric_limits<float>::lowest());
  for (const scene::Vertex& v : s.meshes[0].vertices) {
    lo = glm::min(lo, v.position);
    hi = glm::max(hi, v.position);
  }
  s.bounds_min = lo;
  s.bounds_max = hi;
  s.camera.mode = scene::CameraStart::Mode::orbit;
  s.camera.target = 0.5f * (lo + hi);
  return s;
}

render::Camera icon_camera(const scene::Mesh& mesh, const IconOptions& options) {
  validate(options);
  if (mesh.vertices.empty()) throw std::invalid_argument("icon_camera: mesh '" + mesh.name + "' has no vertices");
  glm::vec3 lo(std::numeric_limits<float>::max()), hi(std::numeric_limits<float>::lowest());
  for (const scene::Vertex& v : mesh.vertices) {
    lo = glm::min(lo, v.position);
    hi = glm::max(hi, v.position);
  }
  const glm::vec3 center = 0.5f * (lo + hi);
  float radius = 0.0f;
  for (const scene::Vertex& v : mesh.vertices) radius = std::max(radius, glm::length(v.position - center));
  radius = std::max(radius, 1e-4f);
  const float az = options.azimuth_deg * kDegree, el = options.elevation_deg * kDegree;
  const glm::vec3 to_eye(std::sin(az) * std::cos(el), std::sin(el), std::cos(az) * std::cos(el));
  // Far enough that the bounding sphere fills the field of view: every vertex is in front.
  const float distance = radius / std::sin(0.5f * options.fov_deg * kDegree);
  const glm::vec3 eye = center + distance * to_eye;
  const glm::mat4 view = glm::lookAt(eye, center, glm::vec3(0.0f, 1.0f, 0.0f));

  // Projected extent of the mesh on the plane at distance 1 in front of the eye.
  float u0 = std::numeric_limits<float>::max(), u1 = -u0, v0 = u0, v1 = -u0;
  for (const scene::Vertex& vtx : mesh.vertices) {
    const glm::vec4 p = view * glm::vec4(vtx.position, 1.0f);
    const float depth = -p.z;  // > 0: distance > radius
    u0 = std::min(u0, p.x / depth);
    u1 = std::max(u1, p.x / depth);
    v0 = std::min(v0, p.y / depth);
    v1 = std::max(v1, p.y / depth);
  }
  const float half = 0.5f * std::max(u1 - u0, v1 - v0) / (1.0f - 2.0f * options.margin);
  const float uc = 0.5f * (u0 + u1), vc = 0.5f * (v0 + v1);
  const float near_plane = 0.5f * (distance - radius), far_plane = 2.0f * (distance + radius);

  render::Camera c;
  c.view = view;
  c.proj = glm::frustum((uc - half) * near_plane, (uc + half) * near_plane, (vc - half) * near_plane,
                        (vc + half) * near_plane, near_plane, far_plane);
  c.eye = eye;
  c.forward = -to_eye;
  c.near_plane = near_plane;
  c.far_plane = far_plane;
  return c;
}

Result<render::Image> render_icon(const scene::ModelInfo& model, const IconOptions& options) {
  validate(options);
  const scene::Scene s = icon_scene(model);
  const render::Camera camera = icon_camera(s.meshes[0], options);
  auto renderer = render::Renderer::create(s);
  if (!renderer) return renderer.error();
  render::Renderer& r = *renderer.value();
  const int side = options.size * options.supersample;
  render::FrameSettings settings;
  settings.method = render::Method::standard;
  // The icon over black, then over white (the keying needs both).
  auto over = [&](glm::vec3 background) -> Result<render::Image> {
    settings.background = background;
    if (auto drawn = r.render_offscreen(camera, settings, side, side); !drawn) return drawn.error();
    return r.read_color();
  };
  auto over_black = over(glm::vec3(0.0f));
  if (!over_black) return over_black.error();
  auto over_white = over(glm::vec3(1.0f));
  if (!over_white) return over_white.error();
  return detail::key_and_downsample(over_black.value(), over_white.value(), options.supersample);
}

double coverage(const render::Image& icon) {
  if (icon.width <= 0 || icon.height <= 0) return 0.0;
  long long sum = 0;
  for (std::size_t i = 3; i < icon.rgba.size(); i += 4) sum += icon.rgba[i];
  return static_cast<double>(sum) / (255.0 * icon.width * icon.height);
}

Result<std::vector<Icon>> render_all(const IconOptions& options) {
  std::vector<Icon> icons;
  for (const scene::ModelInfo& m : scene::model_catalogue()) {
    auto img = render_icon(m, options);
    if (!img) return img.error();
    icons.push_back({&m, std::move(img.value())});
  }
  return icons;
}

Status save_png(const render::Image& image, const std::string& path) { return render::write_png(image, path, true); }

}  // namespace dtlab::icons

// Builders for the hand-made render test scenes (see scenes.h).
#include "tests/render/scenes.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>

namespace dtlab::render::testing {

platform::GlContext& headless_context() {
  static std::unique_ptr<platform::GlContext> ctx = [] {
    auto c = platform::create_headless(64, 64);
    if (!c) {
      std::fprintf(stderr, "cannot create the headless GL context: %s\n", c.error().to_string().c_str());
      std::abort();
    }
    return std::move(c.value());
  }();
  ctx->make_current();
  return *ctx;
}

scene::Mesh quad_mesh(float x0, float y0, float x1, float y1, float z) {
  scene::Mesh m;
  m.name = "quad";
  const glm::vec3 n(0.0f, 0.0f, 1.0f);
  m.vertices = {{{x0, y0, z}, n, glm::vec3(1.0f)},
                {{x1, y0, z}, n, glm::vec3(1.0f)},
                {{x1, y1, z}, n, glm::vec3(1.0f)},
                {{x0, y1, z}, n, glm::vec3(1.0f)}};
  m.indices = {0, 1, 2, 0, 2, 3};
  return m;
}

scene::Mesh box_mesh(glm::vec3 lo, glm::vec3 hi) {
  scene::Mesh m;
  m.name = "box";
  auto face = [&](glm::vec3 n, glm::vec3 a, glm::vec3 b, glm::vec3 c, glm::vec3 d) {
    const auto base = static_cast<std::uint32_t>(m.vertices.size());
    for (const glm::vec3& p : {a, b, c, d}) m.vertices.push_back({p, n, glm::vec3(1.0f)});
    m.indices.insert(m.indices.end(), {base, base + 1, base + 2, base, base + 2, base + 3});
  };
  face({0, 0, 1}, {lo.x, lo.y, hi.z}, {hi.x, lo.y, hi.z}, {hi.x, hi.y, hi.z}, {lo.x, hi.y, hi.z});
  face({0, 0, -1}, {hi.x, lo.y, lo.z}, {lo.x, lo.y, lo.z}, {lo.x, hi.y, lo.z}, {hi.x, hi.y, lo.z});
  face({1, 0, 0}, {hi.x, lo.y, hi.z}, {hi.x, lo.y, lo.z}, {hi.x, hi.y, lo.z}, {hi.x, hi.y, hi.z});
  face({-1, 0, 0}, {lo.x, lo.y, lo.z}, {lo.x, lo.y, hi.z}, {lo.x, hi.y, hi.z}, {lo.x, hi.y, lo.z});
  face({0, 1, 0}, {lo.x, hi.y, hi.z}, {hi.x, hi.y, hi.z}, {hi.x, hi.y, lo.z}, {lo.x, hi.y, lo.z});
  face({0, -1, 0}, {lo.x, lo.y, lo.z}, {hi.x, lo.y, lo.z}, {hi.x, lo.y, hi.z}, {lo.x, lo.y, hi.z});
  return m;
}

scene::Mesh sphere_mesh(glm::vec3 center, float radius, int stacks, int slices) {
  scene::Mesh m;
  m.name = "sphere";
  for (int i = 0; i <= stacks; ++i) {
    const float th = static_cast<float>(M_PI) * static_cast<float>(i) / static_cast<float>(stacks);
    for (int j = 0; j <= slices; ++j) {
      const float ph = 2.0f * static_cast<float>(M_PI) * static_cast<float>(j) / static_cast<float>(slices);
      const glm::vec3 n(std::sin(th) * std::cos(ph), std::cos(th), std::sin(th) * std::sin(ph));
      m.vertices.push_back({center + radius * n, n, glm::vec3(1.0f)});
    }
  }
  for (int i = 0; i < stacks; ++i) {
    for (int j = 0; j < slices; ++j) {
      const auto a = static_cast<std::uint32_t>(i * (slices + 1) + j), b = a + static_cast<std::uint32_t>(slices + 1);
      m.indices.insert(m.indices.end(), {a, b, a + 1, a + 1, b, b + 1});
    }
  }
  return m;
}

std::uint32_t add_object(scene::Scene& s, scene::Mesh mesh, glm::vec3 color, bool target, bool impenetrable) {
  s.meshes.push_back(std::move(mesh));
  scene::Object o;
  o.id = static_cast<std::uint32_t>(s.objects.size() + 1);
  o.kind = s.meshes.back().name;
  o.color = color;
  o.mesh = static_cast<std::uint32_t>(s.meshes.size() - 1);
  o.target = target;
  o.impenetrable = impenetrable;
  s.objects.push_back(o);
  return static_cast<std::uint32_t>(s.objects.size() - 1);
}

Camera front_camera(int width, int height) {
  return walk_camera(glm::vec3(0.0f), 0.0f, 0.0f, glm::radians(60.0f),
                     static_cast<float>(width) / static_cast<float>(height), 0.1f, 100.0f);
}

glm::vec2 project(const Camera& camera, glm::vec3 p, int width, int height) {
  const glm::vec4 c = camera.view_proj() * glm::vec4(p, 1.0f);
  return {(c.x / c.w * 0.5f + 0.5f) * static_cast<float>(width), (c.y / c.w * 0.5f + 0.5f) * static_cast<float>(height)};
}

glm::ivec3 rgb_at(const Image& img, int x, int y_from_bottom) {
  const std::uint8_t* p = img.pixel(x, img.height - 1 - y_from_bottom);
  return {p[0], p[1], p[2]};
}

int alpha_at(const Image& img, int x, int y_from_bottom) { return img.pixel(x, img.height - 1 - y_from_bottom)[3]; }

void maybe_dump(const Image& img, const std::string& suffix) {
  const char* dir = std::getenv("DTLAB_TEST_PNG_DIR");
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  if (dir == nullptr || info == nullptr) return;
  std::string name = std::string(info->test_suite_name()) + "." + info->name() + suffix;
  for (auto& c : name)
    if (c == '/') c = '_';
  (void)write_png(img, std::string(dir) + "/" + name + ".png");
}

}  // namespace dtlab::render::testing

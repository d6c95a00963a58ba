// SceneView, Texture, icons and the floor plan (view.h).
#include <glad/gl.h>
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include <algorithm>
#include <cmath>

#include "app/run/view.h"
#include "study/icons/icons.h"
#include "study/render/camera.h"
#include "study/scene/models.h"

namespace dtlab::run {

Result<std::unique_ptr<SceneView>> SceneView::create(const scene::Scene& scene, const render::FrameSettings& frame) {
  return create(scene, frame, scene.camera);
}

Result<std::unique_ptr<SceneView>> SceneView::create(const scene::Scene& scene, const render::FrameSettings& frame,
                                                     const scene::CameraStart& start) {
  std::unique_ptr<SceneView> v(new SceneView(scene, frame, start));
  auto r = render::Renderer::create(scene);
  if (!r) return r.error();
  v->renderer_ = std::move(r.value());
  // Occlusion culling's occluder database now, not in the first frame.
  if (auto prepared = v->renderer_->prepare(frame); !prepared) return prepared.error();
  v->yaw_ = start.yaw;
  v->pitch_ = start.pitch;
  v->position_ = start.position;
  return v;
}

void SceneView::steer(const Input& input, double dt, bool mouse_free) {
  if (walking()) {
    // Yaw only: the mouse (captured) and the Left/Right arrows turn; Up/Down walk; no strafing.
    yaw_ -= static_cast<float>(input.cursor_delta().x * kTurnRadPerPixel);
    if (input.key_down(GLFW_KEY_LEFT)) yaw_ += static_cast<float>(kTurnRadPerSecond * dt);
    if (input.key_down(GLFW_KEY_RIGHT)) yaw_ -= static_cast<float>(kTurnRadPerSecond * dt);
    const glm::vec3 forward = render::forward_from_angles(yaw_, 0.0f);
    const float step = static_cast<float>(kWalkUnitsPerSecond * dt);
    if (input.key_down(GLFW_KEY_UP)) position_ += forward * step;
    if (input.key_down(GLFW_KEY_DOWN)) position_ -= forward * step;
    yaw_ = std::remainder(yaw_, 2.0f * static_cast<float>(M_PI));
    return;
  }
  // Orbit the centre at the fixed distance by left-drag.
  if (mouse_free && input.button_down(GLFW_MOUSE_BUTTON_LEFT) && !input.button_pressed(GLFW_MOUSE_BUTTON_LEFT)) {
    yaw_ -= static_cast<float>(input.cursor_delta().x * kOrbitRadPerPixel);
    pitch_ += static_cast<float>(input.cursor_delta().y * kOrbitRadPerPixel);
    pitch_ = std::clamp(pitch_, -1.48f, 1.48f);
    yaw_ = std::remainder(yaw_, 2.0f * static_cast<float>(M_PI));
  }
}

render::Camera SceneView::camera(int width, int height) const {
  const scene::CameraStart& c = start_;
  const float aspect = static_cast<float>(width) / static_cast<float>(std::max(1, height));
  if (walking()) return render::walk_camera(position_, yaw_, 0.0f, c.fov_y, aspect, c.near_plane, c.far_plane);
  return render::orbit_camera(c.target, c.distance, yaw_, pitch_, c.fov_y, aspect, c.near_plane, c.far_plane);
}

Status SceneView::draw(int width, int height, glm::vec2 cursor) {
  render::FrameSettings s = frame_;
  const glm::vec2 pointer = walking() ? glm::vec2(width / 2.0f, height / 2.0f) : cursor;
  technique::aim(s, pointer);
  auto drawn = renderer_->render(camera(width, height), s, render::ImportedTarget{0, width, height});
  if (!drawn) return drawn.error();
  return {};
}

store::CameraPose SceneView::pose(double t_s) const {
  const render::Camera cam = camera(4, 3);  // the eye does not depend on the aspect
  return store::CameraPose{t_s, cam.eye.x, cam.eye.y, cam.eye.z, yaw_, walking() ? 0.0 : pitch_};
}

Texture::Texture(const render::Image& image) : w_(image.width), h_(image.height) {
  GLint previous = 0;
  glGetIntegerv(GL_TEXTURE_BINDING_2D, &previous);
  glGenTextures(1, &name_);
  glBindTexture(GL_TEXTURE_2D, name_);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, w_, h_, 0, GL_RGBA, GL_UNSIGNED_BYTE, image.rgba.data());
  glBindTexture(GL_TEXTURE_2D, static_cast<GLuint>(previous));
}

Texture::~Texture() { glDeleteTextures(1, &name_); }

ImTextureID Texture::id() const { return reinterpret_cast<ImTextureID>(static_cast<std::uintptr_t>(name_)); }

Result<std::unique_ptr<Texture>> icon_texture(const std::string& kind, int size) {
  const scene::ModelInfo* model = scene::find_model(kind);
  if (!model) return Error{"", 0, 0, "kind", "no model of kind \"" + kind + "\"", ErrorKind::internal};
  icons::IconOptions o;
  o.size = std::clamp(size, icons::kMinSize, icons::kMaxSize);
  o.supersample = 2;
  auto img = icons::render_icon(*model, o);
  if (!img) return img.error();
  return std::make_unique<Texture>(img.value());
}

std::optional<glm::vec2> floor_plan(const scene::FloorPlan& plan, glm::vec3 start, float side,
                                    std::optional<glm::vec2> mark, const std::string& start_label) {
  const ImVec2 origin = ImGui::GetCursorScreenPos();
  const float cells = static_cast<float>(std::max(plan.width, plan.height));
  const float cell_px = side / cells;
  const float world = cells * plan.cell_size;  // world units across the box
  ImGui::InvisibleButton("floor plan", ImVec2(side, side));
  const bool clicked = ImGui::IsItemClicked(ImGuiMouseButton_Left);
  ImDrawList* dl = ImGui::GetWindowDrawList();
  auto at = [&](float cx, float cy) { return ImVec2(origin.x + cx * cell_px, origin.y + cy * cell_px); };
  const ImU32 floor = IM_COL32(250, 248, 240, 255), wall = IM_COL32(60, 60, 70, 255);
  dl->AddRectFilled(at(0, 0), at(static_cast<float>(plan.width), static_cast<float>(plan.height)), floor);
  auto room = [&](int x, int y) { return plan.room[static_cast<std::size_t>(y * plan.width + x)]; };
  auto door = [&](int x0, int y0, int x1, int y1) {
    return std::any_of(plan.doors.begin(), plan.doors.end(), [&](const scene::FloorPlan::Door& d) {
      return (d.x0 == x0 && d.y0 == y0 && d.x1 == x1 && d.y1 == y1) || (d.x0 == x1 && d.y0 == y1 && d.x1 == x0 && d.y1 == y0);
    });
  };
  const float thick = std::max(2.0f, cell_px * 0.12f);
  for (int y = 0; y < plan.height; ++y)
    for (int x = 0; x < plan.width; ++x) {
      const float fx = static_cast<float>(x), fy = static_cast<float>(y);
      if (x + 1 < plan.width && room(x, y) != room(x + 1, y)) {
        // A wall between the two cells, with a gap where a doorway joins them.
        if (door(x, y, x + 1, y)) {
          dl->AddLine(at(fx + 1, fy), at(fx + 1, fy + 0.3f), wall, thick);
          dl->AddLine(at(fx + 1, fy + 0.7f), at(fx + 1, fy + 1), wall, thick);
        } else {
          dl->AddLine(at(fx + 1, fy), at(fx + 1, fy + 1), wall, thick);
        }
      }
      if (y + 1 < plan.height && room(x, y) != room(x, y + 1)) {
        if (door(x, y, x, y + 1)) {
          dl->AddLine(at(fx, fy + 1), at(fx + 0.3f, fy + 1), wall, thick);
          dl->AddLine(at(fx + 0.7f, fy + 1), at(fx + 1, fy + 1), wall, thick);
        } else {
          dl->AddLine(at(fx, fy + 1), at(fx + 1, fy + 1), wall, thick);
        }
      }
    }
  dl->AddRect(at(0, 0), at(static_cast<float>(plan.width), static_cast<float>(plan.height)), wall, 0, 0, thick * 1.5f);
  // The start: a blue disc where the walk began.
  const ImVec2 s = at(start.x / plan.cell_size, start.z / plan.cell_size);
  dl->AddCircleFilled(s, cell_px * 0.35f, IM_COL32(40, 90, 220, 255));
  dl->AddText(ImVec2(s.x + cell_px * 0.45f, s.y - cell_px * 0.5f), IM_COL32(40, 90, 220, 255), start_label.c_str());
  if (mark) {
    const ImVec2 m = at(mark->x / plan.cell_size, mark->y / plan.cell_size);
    const float r = cell_px * 0.4f;
    dl->AddLine(ImVec2(m.x - r, m.y - r), ImVec2(m.x + r, m.y + r), IM_COL32(220, 30, 30, 255), thick);
    dl->AddLine(ImVec2(m.x - r, m.y + r), ImVec2(m.x + r, m.y - r), IM_COL32(220, 30, 30, 255), thick);
  }
  if (!clicked) return std::nullopt;
  const ImVec2 p = ImGui::GetIO().MousePos;
  const float u = std::clamp((p.x - origin.x) / side, 0.0f, 1.0f), v = std::clamp((p.y - origin.y) / side, 0.0f, 1.0f);
  return glm::vec2(u * world, v * world);
}

}  // namespace dtlab::run

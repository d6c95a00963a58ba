// What a trial screen shows and lets a person steer: the scene drawn by the
// real renderer with the trial's method and settings into the window, the
// camera as the reference study moved it (ABSTRACT: orbit the cube centre at
// a fixed distance by left-drag; WALKTHROUGH: turn with the mouse, cursor
// captured, yaw only, move with the arrow keys at eye height, no strafing,
// no collision), the "find this" icon, and the floor plan a T3 answer is
// marked on. Guarantees: nothing here re-implements rendering; every frame
// goes through render::Renderer. Never: writes to the study database.
#pragma once
#include <memory>
#include <optional>
#include <string>

#include <glm/glm.hpp>
#include <imgui.h>

#include "app/run/input.h"
#include "study/render/render.h"
#include "study/scene/scene.h"
#include "study/store/store.h"

namespace dtlab::run {

// Steering constants (docs/run.md, "Moving"): the sim uses the same walk speed.
inline constexpr double kOrbitRadPerPixel = 0.006;
inline constexpr double kTurnRadPerPixel = 0.003;
inline constexpr double kTurnRadPerSecond = 1.6;  // Left/Right arrows
inline constexpr double kWalkUnitsPerSecond = 4.5;

class SceneView {
 public:
  // Uploads the scene; needs the window's GL context current. The view starts at the scene's own
  // camera, or at `start` (the depth test's fixed view); `scene` must outlive the view. Errors:
  // the renderer's (a shader, the occluder database's allocation).
  static Result<std::unique_ptr<SceneView>> create(const scene::Scene& scene, const render::FrameSettings& frame);
  static Result<std::unique_ptr<SceneView>> create(const scene::Scene& scene, const render::FrameSettings& frame,
                                                   const scene::CameraStart& start);

  // One frame of steering from the input (`dt` seconds since the last frame). `mouse_free`:
  // the UI does not want the mouse (no widget under it).
  void steer(const Input& input, double dt, bool mouse_free);
  // Draws into the default framebuffer; the active mode's searchlight follows `cursor` (pixels,
  // origin top-left) in ABSTRACT and stays at the view's centre in WALKTHROUGH. Errors: the
  // renderer's (render.h: environment when the GL fails; the caller ends the screen with it).
  Status draw(int width, int height, glm::vec2 cursor);
  store::CameraPose pose(double t_s) const;
  render::Camera camera(int width, int height) const;
  bool walking() const { return start_.mode == scene::CameraStart::Mode::walk; }
  const scene::Scene& scene() const { return scene_; }

 private:
  SceneView(const scene::Scene& scene, const render::FrameSettings& frame, const scene::CameraStart& start)
      : scene_(scene), frame_(frame), start_(start) {}
  const scene::Scene& scene_;
  render::FrameSettings frame_;
  scene::CameraStart start_;  // where the view began: projection, mode, orbit centre and distance
  std::unique_ptr<render::Renderer> renderer_;
  float yaw_ = 0, pitch_ = 0;
  glm::vec3 position_{0.0f};
};

// An RGBA image in a GL texture, for ImGui::Image. Needs the window's context current.
class Texture {
 public:
  explicit Texture(const render::Image& image);
  ~Texture();
  Texture(const Texture&) = delete;
  Texture& operator=(const Texture&) = delete;
  ImTextureID id() const;
  int width() const { return w_; }
  int height() const { return h_; }

 private:
  unsigned name_ = 0;
  int w_ = 0, h_ = 0;
};

// The "find this" icon of a WALKTHROUGH object kind (study/icons), side `size` pixels.
Result<std::unique_ptr<Texture>> icon_texture(const std::string& kind, int size);

// Draws the floor plan (rooms, walls, doorways, the start cell labelled `start_label`) into the
// current ImGui window in a box of side `side` pixels at the cursor, registered as an item; returns
// the world (x, z) of a left click inside it this frame, if any. `mark`: a position to draw a cross at.
std::optional<glm::vec2> floor_plan(const scene::FloorPlan& plan, glm::vec3 start, float side,
                                    std::optional<glm::vec2> mark, const std::string& start_label);

}  // namespace dtlab::run

// Camera maths (see camera.h).
#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

#include "study/render/camera.h"

namespace dtlab::render {

glm::vec3 forward_from_angles(float yaw, float pitch) {
  return glm::vec3(-std::sin(yaw) * std::cos(pitch), std::sin(pitch), -std::cos(yaw) * std::cos(pitch));
}

namespace {
Camera make(glm::vec3 eye, glm::vec3 forward, float fov_y, float aspect, float n, float f) {
  Camera c;
  c.eye = eye;
  c.forward = glm::normalize(forward);
  // Up is +y unless we look straight up or down; then use the yaw direction's -z.
  glm::vec3 up(0.0f, 1.0f, 0.0f);
  if (std::abs(glm::dot(up, c.forward)) > 0.999f) up = glm::vec3(0.0f, 0.0f, -1.0f);
  c.view = glm::lookAt(eye, eye + c.forward, up);
  c.proj = glm::perspective(fov_y, aspect, n, f);
  c.near_plane = n;
  c.far_plane = f;
  return c;
}
}  // namespace

Camera orbit_camera(glm::vec3 center, float distance, float yaw, float pitch, float fov_y, float aspect,
                    float near_plane, float far_plane) {
  const glm::vec3 fwd = forward_from_angles(yaw, pitch);
  return make(center - distance * fwd, fwd, fov_y, aspect, near_plane, far_plane);
}

Camera walk_camera(glm::vec3 position, float yaw, float pitch, float fov_y, float aspect, float near_plane,
                   float far_plane) {
  return make(position, forward_from_angles(yaw, pitch), fov_y, aspect, near_plane, far_plane);
}

Camera camera_from_start(const scene::CameraStart& s, float aspect) {
  if (s.mode == scene::CameraStart::Mode::orbit)
    return orbit_camera(s.target, s.distance, s.yaw, s.pitch, s.fov_y, aspect, s.near_plane, s.far_plane);
  return walk_camera(s.position, s.yaw, s.pitch, s.fov_y, aspect, s.near_plane, s.far_plane);
}

}  // namespace dtlab::render

// Cameras for the renderer: view and projection matrices from a scene's
// CameraStart (orbit around a centre, or walk at eye height), with optional
// overrides of yaw, pitch, distance and position. Pure maths (glm), no GL.
// Guarantees: yaw 0 looks along -z, positive pitch looks up, matrices are
// finite for any finite input (a zero-length view never occurs: the forward
// vector is built from angles). Never: reads global state.
#pragma once
#include <glm/glm.hpp>

#include "study/scene/scene.h"

namespace dtlab::render {

struct Camera {
  glm::mat4 view{1.0f};
  glm::mat4 proj{1.0f};
  glm::vec3 eye{0.0f};
  glm::vec3 forward{0.0f, 0.0f, -1.0f};  // unit view direction
  float near_plane = 0.1f;
  float far_plane = 1000.0f;
  glm::mat4 view_proj() const { return proj * view; }
};

// The unit view direction for yaw/pitch in radians (yaw 0 = -z, yaw pi/2 = -x).
glm::vec3 forward_from_angles(float yaw, float pitch);

// The camera a trial starts with, for a viewport of aspect width/height.
Camera camera_from_start(const scene::CameraStart& start, float aspect);

// Orbit camera: eye at `center - distance * forward(yaw, pitch)`, looking at center.
Camera orbit_camera(glm::vec3 center, float distance, float yaw, float pitch, float fov_y, float aspect,
                    float near_plane, float far_plane);

// Walk camera: eye at `position`, looking along forward(yaw, pitch).
Camera walk_camera(glm::vec3 position, float yaw, float pitch, float fov_y, float aspect, float near_plane,
                   float far_plane);

}  // namespace dtlab::render

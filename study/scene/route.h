// Walks through a WALKTHROUGH floor plan for benchmarks and tests: a route
// of eye poses from the start cell, cell by cell through doorways, to the
// cell farthest from it, and the pose with the longest straight line of cells
// ahead (a corridor view). Pure and deterministic (breadth-first search in
// cell order); no GL, no randomness. Never: modifies the scene.
#pragma once
#include <vector>

#include <glm/glm.hpp>

#include "study/scene/scene.h"

namespace dtlab::scene {

struct Pose {
  glm::vec3 position{0.0f};  // eye, at the scene's start eye height
  float yaw = 0.0f;          // radians, CameraStart's convention (0 looks along -z)
  bool doorway = false;      // standing in a doorway (on the wall line, in the opening)
};

// The cells of a shortest walk from the start cell to the farthest reachable cell (ties: the
// lowest cell index), as poses: each cell's centre looking towards the next cell, and the
// doorway between two cells of different rooms. Empty without a floor plan.
std::vector<Pose> walkthrough_route(const Scene& scene);

// The cell centre and axis direction with the most cells ahead in a straight line that one can
// walk (same room or through a doorway); the first in cell and direction order on ties.
Pose longest_sightline(const Scene& scene);

}  // namespace dtlab::scene

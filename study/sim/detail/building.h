// The WALKTHROUGH building as the simulated participant knows it from
// walking it: rooms (from Scene::plan), their centres, the doorways between
// them, shortest routes through doorways, and how many walls lie between two
// points. Pure geometry on the floor plan; no GL, no randomness.
// Guarantees: routes pass only through doorways; the same plan gives the same
// rooms, routes and counts. Never: looks at objects.
#pragma once
#include <vector>

#include <glm/glm.hpp>

#include "study/scene/scene.h"

namespace dtlab::sim::detail {

struct Building {
  struct Link {
    int to = 0;
    glm::vec2 door{0.0f};  // world (x, z) of the doorway's middle
  };
  const scene::FloorPlan* plan = nullptr;
  std::vector<glm::vec2> centre;          // per room id: mean of its cells' centres, world (x, z)
  std::vector<std::vector<Link>> links;   // per room id, in door order

  int rooms() const { return static_cast<int>(centre.size()); }
  int room_at(glm::vec2 p) const;          // room id of the cell holding p; -1 outside the plan
  int walls_between(glm::vec2 a, glm::vec2 b) const;  // room boundaries crossed not through a doorway
  // The nearest room (route length) not yet visited, or -1; and the route to its centre.
  int nearest_unvisited(glm::vec2 from, int from_room, const std::vector<char>& visited,
                        std::vector<glm::vec2>& route) const;
};

Building make_building(const scene::FloorPlan& plan);

}  // namespace dtlab::sim::detail

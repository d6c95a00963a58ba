// Building (building.h): rooms and doorways of a floor plan, Dijkstra routes
// from room centre to doorway to room centre, wall counts by sampling.
#include "study/sim/detail/building.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>
#include <tuple>

namespace dtlab::sim::detail {

Building make_building(const scene::FloorPlan& plan) {
  Building b;
  b.plan = &plan;
  int rooms = 0;
  for (int r : plan.room) rooms = std::max(rooms, r + 1);
  b.centre.assign(static_cast<std::size_t>(rooms), glm::vec2(0.0f));
  std::vector<int> cells(static_cast<std::size_t>(rooms), 0);
  for (int z = 0; z < plan.height; ++z)
    for (int x = 0; x < plan.width; ++x) {
      const int r = plan.room[static_cast<std::size_t>(z * plan.width + x)];
      if (r < 0) continue;
      b.centre[static_cast<std::size_t>(r)] += glm::vec2((x + 0.5f) * plan.cell_size, (z + 0.5f) * plan.cell_size);
      ++cells[static_cast<std::size_t>(r)];
    }
  for (int r = 0; r < rooms; ++r)
    if (cells[static_cast<std::size_t>(r)] > 0) b.centre[static_cast<std::size_t>(r)] /= static_cast<float>(cells[static_cast<std::size_t>(r)]);
  b.links.assign(static_cast<std::size_t>(rooms), {});
  for (const scene::FloorPlan::Door& d : plan.doors) {
    const int a = plan.room[static_cast<std::size_t>(d.y0 * plan.width + d.x0)];
    const int c = plan.room[static_cast<std::size_t>(d.y1 * plan.width + d.x1)];
    if (a < 0 || c < 0 || a == c) continue;
    const glm::vec2 mid((0.5f * static_cast<float>(d.x0 + d.x1) + 0.5f) * plan.cell_size,
                        (0.5f * static_cast<float>(d.y0 + d.y1) + 0.5f) * plan.cell_size);
    b.links[static_cast<std::size_t>(a)].push_back({c, mid});
    b.links[static_cast<std::size_t>(c)].push_back({a, mid});
  }
  return b;
}

int Building::room_at(glm::vec2 p) const {
  const int x = static_cast<int>(std::floor(p.x / plan->cell_size));
  const int z = static_cast<int>(std::floor(p.y / plan->cell_size));
  if (x < 0 || z < 0 || x >= plan->width || z >= plan->height) return -1;
  return plan->room[static_cast<std::size_t>(z * plan->width + x)];
}

int Building::walls_between(glm::vec2 a, glm::vec2 b) const {
  // Sample every tenth of a cell; a change of room counts as a wall unless the two cells
  // are the two sides of a doorway.
  std::set<std::tuple<int, int, int, int>> doors;
  for (const auto& d : plan->doors) {
    doors.insert({d.x0, d.y0, d.x1, d.y1});
    doors.insert({d.x1, d.y1, d.x0, d.y0});
  }
  const float len = glm::length(b - a);
  const int steps = std::max(1, static_cast<int>(std::ceil(len / (0.1f * plan->cell_size))));
  int walls = 0;
  int px = static_cast<int>(std::floor(a.x / plan->cell_size)), pz = static_cast<int>(std::floor(a.y / plan->cell_size));
  for (int i = 1; i <= steps; ++i) {
    const glm::vec2 p = a + (b - a) * (static_cast<float>(i) / static_cast<float>(steps));
    const int x = static_cast<int>(std::floor(p.x / plan->cell_size)), z = static_cast<int>(std::floor(p.y / plan->cell_size));
    if (x == px && z == pz) continue;
    const int r0 = room_at({(px + 0.5f) * plan->cell_size, (pz + 0.5f) * plan->cell_size});
    const int r1 = room_at({(x + 0.5f) * plan->cell_size, (z + 0.5f) * plan->cell_size});
    if (r0 != r1 && !doors.count({px, pz, x, z})) ++walls;
    px = x;
    pz = z;
  }
  return walls;
}

int Building::nearest_unvisited(glm::vec2 from, int from_room, const std::vector<char>& visited,
                                std::vector<glm::vec2>& route) const {
  // Dijkstra over rooms; a room's node is its entry point: `from` for the start room, else the
  // doorway it was entered by. Cost = walking distance; the goal is the target room's centre.
  const int n = rooms();
  constexpr float kInf = std::numeric_limits<float>::infinity();
  std::vector<float> dist(static_cast<std::size_t>(n), kInf);
  std::vector<glm::vec2> entry(static_cast<std::size_t>(n));
  std::vector<int> prev(static_cast<std::size_t>(n), -1);
  std::vector<char> done(static_cast<std::size_t>(n), 0);
  dist[static_cast<std::size_t>(from_room)] = 0;
  entry[static_cast<std::size_t>(from_room)] = from;
  int best = -1;
  float best_cost = kInf;
  for (;;) {
    int u = -1;
    for (int r = 0; r < n; ++r)
      if (!done[static_cast<std::size_t>(r)] && dist[static_cast<std::size_t>(r)] < kInf &&
          (u < 0 || dist[static_cast<std::size_t>(r)] < dist[static_cast<std::size_t>(u)]))
        u = r;
    if (u < 0) break;
    done[static_cast<std::size_t>(u)] = 1;
    const auto uu = static_cast<std::size_t>(u);
    if (!visited[uu]) {
      const float cost = dist[uu] + glm::length(centre[uu] - entry[uu]);
      if (cost < best_cost) {
        best_cost = cost;
        best = u;
      }
    }
    for (const Link& l : links[uu]) {
      const auto v = static_cast<std::size_t>(l.to);
      const float d = dist[uu] + glm::length(l.door - entry[uu]);
      if (d < dist[v]) {
        dist[v] = d;
        entry[v] = l.door;
        prev[v] = u;
      }
    }
  }
  route.clear();
  if (best < 0) return -1;
  route.push_back(centre[static_cast<std::size_t>(best)]);
  for (int r = best; r != from_room; r = prev[static_cast<std::size_t>(r)]) route.push_back(entry[static_cast<std::size_t>(r)]);
  std::reverse(route.begin(), route.end());
  return best;
}

}  // namespace dtlab::sim::detail

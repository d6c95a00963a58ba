// Routes through a WALKTHROUGH floor plan (see route.h).
#include <algorithm>
#include <cmath>
#include <deque>
#include <set>
#include <tuple>

#include "study/scene/route.h"

namespace dtlab::scene {

namespace {

// The four axis steps and their yaw (0 = -z, pi/2 = -x).
constexpr int kDx[4] = {0, -1, 0, 1}, kDz[4] = {-1, 0, 1, 0};
constexpr float kHalfPi = 1.57079632679f;

struct Grid {
  const FloorPlan& plan;
  std::set<std::tuple<int, int, int, int>> doors;
  explicit Grid(const FloorPlan& p) : plan(p) {
    for (const auto& d : p.doors) doors.insert({d.x0, d.y0, d.x1, d.y1});
  }
  bool inside(int x, int z) const { return x >= 0 && z >= 0 && x < plan.width && z < plan.height; }
  int room(int x, int z) const { return plan.room[static_cast<std::size_t>(z * plan.width + x)]; }
  bool door(int x0, int z0, int x1, int z1) const {
    return doors.count({std::min(x0, x1), std::min(z0, z1), std::max(x0, x1), std::max(z0, z1)}) > 0;
  }
  // One step from (x, z) in direction k: inside, and the same room or a doorway between them.
  bool can_step(int x, int z, int k) const {
    const int nx = x + kDx[k], nz = z + kDz[k];
    return inside(nx, nz) && (room(x, z) == room(nx, nz) || door(x, z, nx, nz));
  }
};

glm::vec3 centre(const Scene& s, float x, float z) {
  return {(x + 0.5f) * s.plan->cell_size, s.camera.position.y, (z + 0.5f) * s.plan->cell_size};
}

}  // namespace

std::vector<Pose> walkthrough_route(const Scene& scene) {
  if (!scene.plan) return {};
  const FloorPlan& plan = *scene.plan;
  const Grid g(plan);
  const int n = plan.width * plan.height;
  const int start_x = std::clamp(static_cast<int>(std::floor(scene.camera.position.x / plan.cell_size)), 0, plan.width - 1);
  const int start_z = std::clamp(static_cast<int>(std::floor(scene.camera.position.z / plan.cell_size)), 0, plan.height - 1);
  const int start = start_z * plan.width + start_x;
  std::vector<int> dist(static_cast<std::size_t>(n), -1), from(static_cast<std::size_t>(n), -1);
  std::deque<int> queue{start};
  dist[static_cast<std::size_t>(start)] = 0;
  int far = start;
  while (!queue.empty()) {
    const int c = queue.front();
    queue.pop_front();
    const int x = c % plan.width, z = c / plan.width;
    if (dist[static_cast<std::size_t>(c)] > dist[static_cast<std::size_t>(far)] ||
        (dist[static_cast<std::size_t>(c)] == dist[static_cast<std::size_t>(far)] && c < far))
      far = c;
    for (int k = 0; k < 4; ++k) {
      if (!g.can_step(x, z, k)) continue;
      const int nc = (z + kDz[k]) * plan.width + x + kDx[k];
      if (dist[static_cast<std::size_t>(nc)] >= 0) continue;
      dist[static_cast<std::size_t>(nc)] = dist[static_cast<std::size_t>(c)] + 1;
      from[static_cast<std::size_t>(nc)] = c;
      queue.push_back(nc);
    }
  }
  std::vector<int> cells;
  for (int c = far; c >= 0; c = from[static_cast<std::size_t>(c)]) cells.push_back(c);
  std::reverse(cells.begin(), cells.end());
  std::vector<Pose> route;
  for (std::size_t i = 0; i < cells.size(); ++i) {
    const int x = cells[i] % plan.width, z = cells[i] / plan.width;
    const int next = i + 1 < cells.size() ? cells[i + 1] : cells[i];
    const int dx = next % plan.width - x, dz = next / plan.width - z;
    Pose p;
    p.position = centre(scene, static_cast<float>(x), static_cast<float>(z));
    p.yaw = i + 1 < cells.size() ? std::atan2(-static_cast<float>(dx), -static_cast<float>(dz))
                                 : (route.empty() ? 0.0f : route.back().yaw);
    route.push_back(p);
    if (i + 1 < cells.size() && g.room(x, z) != g.room(x + dx, z + dz)) {
      Pose d = p;
      d.position = centre(scene, static_cast<float>(x) + 0.5f * static_cast<float>(dx),
                          static_cast<float>(z) + 0.5f * static_cast<float>(dz));
      d.doorway = true;
      route.push_back(d);
    }
  }
  return route;
}

Pose longest_sightline(const Scene& scene) {
  Pose best;
  if (!scene.plan) return best;
  const FloorPlan& plan = *scene.plan;
  const Grid g(plan);
  int best_run = -1;
  for (int z = 0; z < plan.height; ++z)
    for (int x = 0; x < plan.width; ++x)
      for (int k = 0; k < 4; ++k) {
        int run = 0, cx = x, cz = z;
        while (g.can_step(cx, cz, k)) {
          cx += kDx[k];
          cz += kDz[k];
          ++run;
        }
        if (run <= best_run) continue;
        best_run = run;
        best.position = centre(scene, static_cast<float>(x), static_cast<float>(z));
        best.yaw = static_cast<float>(k) * kHalfPi;
      }
  return best;
}

}  // namespace dtlab::scene

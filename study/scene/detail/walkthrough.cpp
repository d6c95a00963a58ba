// WALKTHROUGH scenes (STUDY.md, VI.4-VI.5): a floor plan of rectangular rooms
// on a grid (recursive splits), one doorway between every pair of adjacent
// rooms, walls with thickness split around the doorways (lintel above), a
// floor and a ceiling, and n models standing in distinct grid cells.
// Placement cannot fail: each model fits inside its cell's interior by
// construction (validate() checks footprints against the cell), and cells
// are drawn without replacement, so models never meet walls or each other.
#include <algorithm>
#include <cmath>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "study/scene/detail/generators.h"
#include "study/common/random.h"
#include "study/scene/detail/sampling.h"
#include "study/scene/detail/walkthrough_layout.h"
#include "study/scene/models.h"
#include "study/scene/primitives.h"

namespace dtlab::scene::detail {
namespace {

constexpr std::uint64_t kStreamWalkthrough = 0x3a1c'7485ULL;
const glm::vec3 kInnerWall{0.80f, 0.80f, 0.84f};
const glm::vec3 kOuterWall{0.66f, 0.68f, 0.74f};
const glm::vec3 kFloor{0.46f, 0.42f, 0.38f};
const glm::vec3 kCeiling{0.92f, 0.92f, 0.90f};

struct Rect {
  int x, z, w, d;
};

// Recursive splits: a side longer than room_max must be split; a room that
// could be split is split with probability 1/2, so sizes vary.
void split(const WalkthroughParams& p, SceneRandom& rng, Rect r, std::vector<Rect>& rooms) {
  const bool must_w = r.w > p.room_max, must_d = r.d > p.room_max;
  const bool can_w = r.w >= 2 * p.room_min, can_d = r.d >= 2 * p.room_min;
  if (!must_w && !must_d && (!(can_w || can_d) || rng.below(2) == 0)) {
    rooms.push_back(r);
    return;
  }
  bool along_x;  // cut perpendicular to x (splits the width)
  if (must_w != must_d) along_x = must_w;
  else if (must_w) along_x = r.w != r.d ? r.w > r.d : rng.below(2) == 0;
  else if (can_w != can_d) along_x = can_w;
  else along_x = rng.below(2) == 0;
  if (along_x) {
    const int cut = rng.between(p.room_min, r.w - p.room_min);
    split(p, rng, {r.x, r.z, cut, r.d}, rooms);
    split(p, rng, {r.x + cut, r.z, r.w - cut, r.d}, rooms);
  } else {
    const int cut = rng.between(p.room_min, r.d - p.room_min);
    split(p, rng, {r.x, r.z, r.w, cut}, rooms);
    split(p, rng, {r.x, r.z + cut, r.w, r.d - cut}, rooms);
  }
}

}  // namespace

FloorPlan generate_floor_plan(const WalkthroughParams& p, SceneRandom& rng) {
  FloorPlan plan;
  plan.width = p.grid_width;
  plan.height = p.grid_depth;
  plan.cell_size = p.cell_size;
  std::vector<Rect> rooms;
  split(p, rng, {0, 0, p.grid_width, p.grid_depth}, rooms);
  plan.room.assign(static_cast<std::size_t>(p.grid_width * p.grid_depth), -1);
  for (std::size_t id = 0; id < rooms.size(); ++id)
    for (int z = rooms[id].z; z < rooms[id].z + rooms[id].d; ++z)
      for (int x = rooms[id].x; x < rooms[id].x + rooms[id].w; ++x)
        plan.room[static_cast<std::size_t>(z * p.grid_width + x)] = static_cast<int>(id);

  // Every edge between cells of two different rooms, grouped by room pair
  // (ordered map: deterministic), then one doorway per pair, drawn uniformly.
  std::map<std::pair<int, int>, std::vector<FloorPlan::Door>> shared;
  auto room_at = [&](int x, int z) { return plan.room[static_cast<std::size_t>(z * p.grid_width + x)]; };
  for (int z = 0; z < p.grid_depth; ++z) {
    for (int x = 0; x < p.grid_width; ++x) {
      const int a = room_at(x, z);
      if (x + 1 < p.grid_width && room_at(x + 1, z) != a)
        shared[std::minmax(a, room_at(x + 1, z))].push_back({x, z, x + 1, z});
      if (z + 1 < p.grid_depth && room_at(x, z + 1) != a)
        shared[std::minmax(a, room_at(x, z + 1))].push_back({x, z, x, z + 1});
    }
  }
  for (const auto& [pair, edges] : shared) plan.doors.push_back(edges[rng.below(edges.size())]);
  return plan;
}

Result<Scene> generate_walkthrough(Task task, std::uint64_t seed, const WalkthroughParams& p) {
  SceneRandom rng(seed, kStreamWalkthrough + static_cast<std::uint64_t>(task));
  Scene scene;
  scene.kind = Kind::walkthrough;
  scene.task = task;
  scene.seed = seed;
  scene.plan = generate_floor_plan(p, rng);
  const FloorPlan& plan = *scene.plan;

  // Structure: floor, ceiling, walls (all on the shared unit box, mesh 0).
  scene.meshes.push_back(box_mesh(glm::vec3(0.5f)));
  scene.meshes.back().name = "unit_box";
  auto add_box = [&](std::string kind, glm::vec3 lo, glm::vec3 hi, glm::vec3 color, bool impenetrable) {
    Object o;
    o.id = static_cast<std::uint32_t>(scene.objects.size() + 1);
    o.kind = std::move(kind);
    o.color = color;
    o.transform = glm::mat4(1.0f);
    o.transform[0][0] = hi.x - lo.x;
    o.transform[1][1] = hi.y - lo.y;
    o.transform[2][2] = hi.z - lo.z;
    o.transform[3] = glm::vec4(0.5f * (lo + hi), 1.0f);
    o.mesh = 0;
    o.impenetrable = impenetrable;
    o.group = o.id;  // every wall its own group (tech report section 4: a building's walls sort separately)
    scene.objects.push_back(std::move(o));
  };
  const float W = static_cast<float>(p.grid_width) * p.cell_size, D = static_cast<float>(p.grid_depth) * p.cell_size;
  const float t = p.wall_thickness, H = p.wall_height, slab = 0.1f;
  add_box("floor", {-0.5f * t, -slab, -0.5f * t}, {W + 0.5f * t, 0.0f, D + 0.5f * t}, kFloor, true);
  add_box("ceiling", {-0.5f * t, H, -0.5f * t}, {W + 0.5f * t, H + slab, D + 0.5f * t}, kCeiling, true);
  for (const WallBox& w : wall_boxes(plan, p))
    add_box("wall", w.lo, w.hi, w.outer ? kOuterWall : kInnerWall, w.outer);

  // Kinds: T3 one object of the target kind, T4 count_min..count_max of it;
  // the rest drawn uniformly from the other allowed kinds, then shuffled.
  const std::vector<std::string> allowed = allowed_kinds(p);
  const std::string target_kind = allowed[rng.below(allowed.size())];
  const int same = task == Task::T3 ? 1 : rng.between(p.count_min, p.count_max);
  std::vector<std::string> kinds(static_cast<std::size_t>(same), target_kind);
  std::vector<std::string> others;
  for (const auto& k : allowed)
    if (k != target_kind) others.push_back(k);
  for (int i = same; i < p.objects; ++i) kinds.push_back(others[rng.below(others.size())]);
  for (std::size_t i = kinds.size(); i > 1; --i) std::swap(kinds[i - 1], kinds[rng.below(i)]);

  // Cells: n distinct cells, never the start cell (partial Fisher-Yates).
  const int start_x = p.grid_width / 2, start_z = p.grid_depth / 2;
  std::vector<int> cells;
  for (int c = 0; c < p.grid_width * p.grid_depth; ++c)
    if (c != start_z * p.grid_width + start_x) cells.push_back(c);
  for (std::size_t i = 0; i < kinds.size(); ++i) std::swap(cells[i], cells[i + rng.below(cells.size() - i)]);

  std::map<std::string, std::uint32_t> mesh_of;  // kind -> mesh index, meshes in catalogue order
  for (const ModelInfo& m : model_catalogue()) {
    if (std::find(kinds.begin(), kinds.end(), m.kind) == kinds.end()) continue;
    mesh_of[std::string(m.kind)] = static_cast<std::uint32_t>(scene.meshes.size());
    scene.meshes.push_back(m.build());
  }

  for (std::size_t i = 0; i < kinds.size(); ++i) {
    const ModelInfo& info = *find_model(kinds[i]);
    const int cx = cells[i] % p.grid_width, cz = cells[i] / p.grid_width;
    const double half_free = cell_half_interior(p) - info.footprint_radius;
    const double x = (cx + 0.5) * p.cell_size + rng.uniform(-half_free, half_free);
    const double z = (cz + 0.5) * p.cell_size + rng.uniform(-half_free, half_free);
    const glm::dmat3 yaw = yaw_matrix(sample_direction(rng));
    Object o;
    o.id = static_cast<std::uint32_t>(scene.objects.size() + 1);
    o.kind = kinds[i];
    o.color = glm::vec3(1.0f);  // the model's vertex colours carry its colours
    o.transform = glm::mat4(glm::dmat4(yaw));
    o.transform[3] = glm::vec4(static_cast<float>(x), 0.0f, static_cast<float>(z), 1.0f);
    o.mesh = mesh_of.at(kinds[i]);
    o.target = true;  // "all objects are made visible through the walls" (VI.4)
    o.group = o.id;
    scene.objects.push_back(std::move(o));
    if (kinds[i] == target_kind && task == Task::T3) scene.answer.position = {static_cast<float>(x), static_cast<float>(z)};
  }

  scene.answer.task = task;
  scene.answer.target_kind = target_kind;
  if (task == Task::T4) scene.answer.count = same;

  scene.bounds_min = {-0.5f * t, -slab, -0.5f * t};
  scene.bounds_max = {W + 0.5f * t, H + slab, D + 0.5f * t};
  CameraStart& cam = scene.camera;
  cam.mode = CameraStart::Mode::walk;
  cam.position = {(static_cast<float>(start_x) + 0.5f) * p.cell_size, p.eye_height,
                  (static_cast<float>(start_z) + 0.5f) * p.cell_size};
  cam.yaw = 0.0f;
  cam.pitch = 0.0f;
  cam.fov_y = p.fov_y;
  cam.near_plane = 0.05f;
  cam.far_plane = 2.0f * (W + D);
  return scene;
}

}  // namespace dtlab::scene::detail

// WALKTHROUGH invariants over 1000 seeds per task (STUDY.md VI.4-VI.5),
// checked against the geometry itself: rooms are rectangles of allowed size,
// every pair of adjacent rooms has exactly one doorway and every cell is
// reachable, walls block every other room boundary and leave every doorway
// open, the outline/floor/ceiling are impenetrable, models stand in rooms
// touching neither walls nor each other, and the answer key matches the scene.
#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <queue>
#include <set>
#include <tuple>

#include "study/scene/generate.h"
#include "study/scene/models.h"
#include "tests/scene/mesh_checks.h"

namespace dtlab::scene {
namespace {

using testing::Aabb;
using testing::world_aabb;

constexpr int kSeeds = 1000;

bool inside(const Aabb& b, glm::vec3 p) {
  return p.x > b.lo.x && p.x < b.hi.x && p.y > b.lo.y && p.y < b.hi.y && p.z > b.lo.z && p.z < b.hi.z;
}

struct Walls {
  std::vector<Aabb> boxes;
  std::vector<bool> impenetrable;
  const Aabb* hit(glm::vec3 p, bool* impen = nullptr) const {
    for (std::size_t i = 0; i < boxes.size(); ++i)
      if (inside(boxes[i], p)) {
        if (impen) *impen = impenetrable[i];
        return &boxes[i];
      }
    return nullptr;
  }
};

void check_plan(const FloorPlan& plan, const WalkthroughParams& p) {
  ASSERT_EQ(plan.width, p.grid_width);
  ASSERT_EQ(plan.height, p.grid_depth);
  ASSERT_EQ(plan.room.size(), static_cast<std::size_t>(plan.width * plan.height));
  auto room = [&](int x, int z) { return plan.room[static_cast<std::size_t>(z * plan.width + x)]; };
  // Rooms are filled rectangles with sides in [room_min, room_max].
  std::map<int, std::tuple<int, int, int, int, int>> extent;  // id -> x0, z0, x1, z1, cells
  for (int z = 0; z < plan.height; ++z)
    for (int x = 0; x < plan.width; ++x) {
      ASSERT_GE(room(x, z), 0);
      auto [it, fresh] = extent.try_emplace(room(x, z), x, z, x, z, 0);
      auto& [x0, z0, x1, z1, n] = it->second;
      x0 = std::min(x0, x), z0 = std::min(z0, z), x1 = std::max(x1, x), z1 = std::max(z1, z), ++n;
    }
  for (const auto& [id, e] : extent) {
    const auto [x0, z0, x1, z1, n] = e;
    const int w = x1 - x0 + 1, d = z1 - z0 + 1;
    EXPECT_EQ(n, w * d) << "room " << id << " is not a rectangle";
    EXPECT_GE(std::min(w, d), p.room_min);
    EXPECT_LE(std::max(w, d), p.room_max);
  }
  // Every adjacent pair of rooms: exactly one doorway, on an edge they share.
  std::map<std::pair<int, int>, int> doors_of_pair;
  std::set<std::pair<int, int>> adjacent;
  for (int z = 0; z < plan.height; ++z)
    for (int x = 0; x < plan.width; ++x) {
      if (x + 1 < plan.width && room(x, z) != room(x + 1, z)) adjacent.insert(std::minmax(room(x, z), room(x + 1, z)));
      if (z + 1 < plan.height && room(x, z) != room(x, z + 1)) adjacent.insert(std::minmax(room(x, z), room(x, z + 1)));
    }
  for (const auto& d : plan.doors) {
    ASSERT_EQ(std::abs(d.x1 - d.x0) + std::abs(d.y1 - d.y0), 1) << "a doorway joins edge-adjacent cells";
    ASSERT_NE(room(d.x0, d.y0), room(d.x1, d.y1)) << "a doorway joins two rooms";
    ++doors_of_pair[std::minmax(room(d.x0, d.y0), room(d.x1, d.y1))];
  }
  EXPECT_EQ(doors_of_pair.size(), adjacent.size()) << "every adjacency has a door";
  for (const auto& pair : adjacent) EXPECT_EQ(doors_of_pair[pair], 1) << pair.first << "-" << pair.second;
  // Every cell is reachable from the start cell, moving inside rooms and through doorways.
  std::set<std::tuple<int, int, int, int>> open;
  for (const auto& d : plan.doors) {
    open.insert({d.x0, d.y0, d.x1, d.y1});
    open.insert({d.x1, d.y1, d.x0, d.y0});
  }
  std::vector<char> seen(plan.room.size(), 0);
  std::queue<std::pair<int, int>> todo;
  todo.push({plan.width / 2, plan.height / 2});
  seen[static_cast<std::size_t>(plan.height / 2 * plan.width + plan.width / 2)] = 1;
  while (!todo.empty()) {
    const auto [x, z] = todo.front();
    todo.pop();
    for (auto [dx, dz] : {std::pair{1, 0}, {-1, 0}, {0, 1}, {0, -1}}) {
      const int nx = x + dx, nz = z + dz;
      if (nx < 0 || nz < 0 || nx >= plan.width || nz >= plan.height) continue;
      auto& s = seen[static_cast<std::size_t>(nz * plan.width + nx)];
      if (s || (room(x, z) != room(nx, nz) && !open.count({x, z, nx, nz}))) continue;
      s = 1;
      todo.push({nx, nz});
    }
  }
  EXPECT_EQ(std::count(seen.begin(), seen.end(), 1), static_cast<long>(seen.size())) << "unreachable cells";
}

// The walls as built: blocking where they must, open at the doorways.
void check_walls(const Scene& s, const Walls& walls, const WalkthroughParams& p) {
  const FloorPlan& plan = *s.plan;
  auto room = [&](int x, int z) { return plan.room[static_cast<std::size_t>(z * plan.width + x)]; };
  std::set<std::tuple<int, int, int, int>> doors;
  for (const auto& d : plan.doors) doors.insert({d.x0, d.y0, d.x1, d.y1});
  const float cs = plan.cell_size, y_low = 0.5f * p.door_height, y_lintel = 0.5f * (p.door_height + p.wall_height);
  // Edge (x0,z0)-(x1,z1) between two cells: midpoint, and a point a little off centre.
  auto edge_point = [&](int x0, int z0, int x1, int z1, float y, float along) {
    const float mx = 0.5f * (x0 + x1 + 1) * cs, mz = 0.5f * (z0 + z1 + 1) * cs;
    return x0 != x1 ? glm::vec3(mx, y, mz + along) : glm::vec3(mx + along, y, mz);
  };
  for (int z = 0; z < plan.height; ++z)
    for (int x = 0; x < plan.width; ++x)
      for (auto [dx, dz] : {std::pair{1, 0}, {0, 1}}) {
        const int nx = x + dx, nz = z + dz;
        if (nx >= plan.width || nz >= plan.height || room(x, z) == room(nx, nz)) continue;
        if (doors.count({x, z, nx, nz})) {
          for (float along : {0.0f, 0.45f * p.door_width, -0.45f * p.door_width})
            EXPECT_EQ(walls.hit(edge_point(x, z, nx, nz, y_low, along)), nullptr) << "doorway blocked at " << x << "," << z;
          EXPECT_NE(walls.hit(edge_point(x, z, nx, nz, y_lintel, 0.0f)), nullptr) << "no lintel at " << x << "," << z;
        } else {
          bool impen = true;
          EXPECT_NE(walls.hit(edge_point(x, z, nx, nz, y_low, 0.0f), &impen), nullptr) << "missing wall at " << x << "," << z;
          EXPECT_FALSE(impen) << "inner walls are penetrable";
        }
      }
  // The outline: walls everywhere, impenetrable.
  for (int i = 0; i < plan.width; ++i)
    for (glm::vec3 q : {glm::vec3((i + 0.5f) * cs, y_low, 0.0f), glm::vec3((i + 0.5f) * cs, y_low, plan.height * cs)}) {
      bool impen = false;
      EXPECT_NE(walls.hit(q, &impen), nullptr);
      EXPECT_TRUE(impen) << "outer walls are impenetrable";
    }
  for (int i = 0; i < plan.height; ++i)
    for (glm::vec3 q : {glm::vec3(0.0f, y_low, (i + 0.5f) * cs), glm::vec3(plan.width * cs, y_low, (i + 0.5f) * cs)}) {
      bool impen = false;
      EXPECT_NE(walls.hit(q, &impen), nullptr);
      EXPECT_TRUE(impen) << "outer walls are impenetrable";
    }
}

void check_scene(const Scene& s, const WalkthroughParams& p, std::uint64_t seed) {
  SCOPED_TRACE("seed " + std::to_string(seed));
  ASSERT_EQ(s.kind, Kind::walkthrough);
  ASSERT_TRUE(s.plan.has_value());
  check_plan(*s.plan, p);
  const float cs = p.cell_size, W = p.grid_width * cs, D = p.grid_depth * cs;

  Walls walls;
  int floors = 0, ceilings = 0;
  std::vector<const Object*> models;
  std::set<std::uint32_t> groups;
  for (const Object& o : s.objects) {
    EXPECT_TRUE(groups.insert(o.group).second) << "one object per group";
    EXPECT_EQ(o.order_in_group, 0u);
    const Aabb box = world_aabb(s, o);
    if (o.kind == "wall") {
      walls.boxes.push_back(box);
      walls.impenetrable.push_back(o.impenetrable);
      EXPECT_FALSE(o.target);
      EXPECT_GE(box.lo.y, -1e-4f);
      EXPECT_LE(box.hi.y, p.wall_height + 1e-4f);
      EXPECT_NEAR(std::min(box.hi.x - box.lo.x, box.hi.z - box.lo.z), p.wall_thickness, 1e-4f) << "walls have thickness";
    } else if (o.kind == "floor" || o.kind == "ceiling") {
      (o.kind == "floor" ? floors : ceilings)++;
      EXPECT_TRUE(o.impenetrable);
      EXPECT_FALSE(o.target);
      EXPECT_LE(box.lo.x, 0.0f);
      EXPECT_LE(box.lo.z, 0.0f);
      EXPECT_GE(box.hi.x, W);
      EXPECT_GE(box.hi.z, D);
      EXPECT_NEAR(o.kind == "floor" ? box.hi.y : box.lo.y, o.kind == "floor" ? 0.0f : p.wall_height, 1e-4f);
    } else {
      ASSERT_NE(find_model(o.kind), nullptr) << o.kind;
      EXPECT_EQ(s.meshes[o.mesh].name, o.kind);
      EXPECT_TRUE(o.target) << "all walkthrough objects are shown through walls";
      EXPECT_FALSE(o.impenetrable);
      models.push_back(&o);
    }
  }
  EXPECT_EQ(floors, 1);
  EXPECT_EQ(ceilings, 1);
  check_walls(s, walls, p);
  ASSERT_EQ(models.size(), static_cast<std::size_t>(p.objects));

  // Models: inside one cell's interior, on the floor, clear of every wall and of each other.
  std::vector<Aabb> boxes;
  const int start = p.grid_depth / 2 * p.grid_width + p.grid_width / 2;
  for (const Object* o : models) {
    const Aabb b = world_aabb(s, *o);
    const int cx = static_cast<int>((b.lo.x + b.hi.x) * 0.5f / cs), cz = static_cast<int>((b.lo.z + b.hi.z) * 0.5f / cs);
    EXPECT_GT(b.lo.x, cx * cs + 0.5f * p.wall_thickness);
    EXPECT_LT(b.hi.x, (cx + 1) * cs - 0.5f * p.wall_thickness);
    EXPECT_GT(b.lo.z, cz * cs + 0.5f * p.wall_thickness);
    EXPECT_LT(b.hi.z, (cz + 1) * cs - 0.5f * p.wall_thickness);
    EXPECT_NE(cz * p.grid_width + cx, start) << "a model stands where the participant starts";
    EXPECT_NEAR(b.lo.y, 0.0f, 0.02f);
    EXPECT_LT(b.hi.y, p.wall_height);
    for (const Aabb& w : walls.boxes) EXPECT_FALSE(b.overlaps(w)) << o->kind << " " << o->id << " intersects a wall";
    for (const Aabb& other : boxes) EXPECT_FALSE(b.overlaps(other)) << o->kind << " " << o->id << " intersects a model";
    boxes.push_back(b);
  }

  // Answer key.
  std::map<std::string, int> count;
  for (const Object* o : models) ++count[o->kind];
  EXPECT_EQ(s.answer.task, s.task);
  if (s.task == Task::T3) {
    ASSERT_EQ(count[s.answer.target_kind], 1) << "T3: the target kind appears exactly once";
    for (const Object* o : models)
      if (o->kind == s.answer.target_kind) {
        EXPECT_EQ(s.answer.position, glm::vec2(o->transform[3].x, o->transform[3].z));
      }
  } else {
    EXPECT_EQ(count[s.answer.target_kind], s.answer.count);
    EXPECT_GE(s.answer.count, p.count_min);
    EXPECT_LE(s.answer.count, p.count_max);
  }

  // Start: centre cell, eye height, walking, not inside a wall.
  EXPECT_EQ(s.camera.mode, CameraStart::Mode::walk);
  EXPECT_EQ(s.camera.position, glm::vec3((p.grid_width / 2 + 0.5f) * cs, p.eye_height, (p.grid_depth / 2 + 0.5f) * cs));
  EXPECT_LE(glm::length(glm::vec2(s.camera.position.x - 0.5f * W, s.camera.position.z - 0.5f * D)), cs) << "near the plan's centre";
  EXPECT_EQ(walls.hit(s.camera.position), nullptr);
  EXPECT_EQ(s.camera.pitch, 0.0f);
}

TEST(Walkthrough, InvariantsHoldForEverySeed) {
  const Params params;
  const WalkthroughParams& p = params.walkthrough;
  std::map<std::string, int> t3_targets;
  std::set<int> t4_counts;
  std::size_t min_tris = ~std::size_t{0}, max_tris = 0;
  for (Task task : {Task::T3, Task::T4}) {
    for (std::uint64_t i = 0; i < kSeeds; ++i) {
      const std::uint64_t seed = i * 1000003 + (task == Task::T3 ? 11 : 13);
      const auto r = generate(Kind::walkthrough, task, seed, params);
      ASSERT_TRUE(r.ok()) << "seed " << seed << ": " << r.error().to_string();
      check_scene(*r, p, seed);
      if (::testing::Test::HasFatalFailure()) return;
      if (task == Task::T3) ++t3_targets[r->answer.target_kind];
      else t4_counts.insert(r->answer.count);
      const std::size_t tris = testing::scene_triangles(*r);
      min_tris = std::min(min_tris, tris);
      max_tris = std::max(max_tris, tris);
    }
  }
  EXPECT_EQ(t3_targets.size(), model_catalogue().size()) << "every kind is sometimes the T3 target";
  EXPECT_EQ(t4_counts, (std::set<int>{3, 4, 5, 6, 7, 8}));
  EXPECT_GE(min_tris, 50000u) << "models detailed enough to look like what they are";
  RecordProperty("min_triangles", static_cast<int>(min_tris));
  RecordProperty("max_triangles", static_cast<int>(max_tris));
  std::printf("walkthrough triangles over %d scenes: %zu .. %zu\n", 2 * kSeeds, min_tris, max_tris);
}

TEST(Walkthrough, OtherGridsAndKindListsHoldTheInvariants) {
  Params params;
  WalkthroughParams& p = params.walkthrough;
  p.grid_width = 9;
  p.grid_depth = 5;
  p.room_min = 1;
  p.room_max = 3;
  p.objects = 30;
  p.kinds = {"chair", "cat", "lamp"};
  p.count_min = 10;
  p.count_max = 20;
  for (Task task : {Task::T3, Task::T4})
    for (std::uint64_t seed = 0; seed < 100; ++seed) {
      const auto r = generate(Kind::walkthrough, task, seed, params);
      ASSERT_TRUE(r.ok()) << r.error().to_string();
      check_scene(*r, p, seed);
      for (const Object& o : r->objects)
        if (find_model(o.kind)) {
          EXPECT_TRUE(o.kind == "chair" || o.kind == "cat" || o.kind == "lamp") << o.kind;
        }
    }
}

struct BadParam {
  const char* name;
  void (*edit)(WalkthroughParams&);
  Task task;
  const char* field;
};

void PrintTo(const BadParam& b, std::ostream* os) { *os << b.name; }  // readable ctest names

class WalkthroughBadParams : public ::testing::TestWithParam<BadParam> {};

TEST_P(WalkthroughBadParams, AreReportedWithTheirField) {
  Params params;
  GetParam().edit(params.walkthrough);
  const auto r = generate(Kind::walkthrough, GetParam().task, 1, params);
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.error().field, GetParam().field) << r.error().to_string();
}

INSTANTIATE_TEST_SUITE_P(
    Cases, WalkthroughBadParams,
    ::testing::Values(
        BadParam{"ZeroGrid", [](WalkthroughParams& p) { p.grid_width = 0; }, Task::T3, "walkthrough.grid_width"},
        BadParam{"RoomMaxTooSmall", [](WalkthroughParams& p) { p.room_min = 4; p.room_max = 5; }, Task::T3, "walkthrough.room_max"},
        BadParam{"RoomMinTooBig", [](WalkthroughParams& p) { p.room_min = 17; p.room_max = 40; }, Task::T3, "walkthrough.room_min"},
        BadParam{"TooManyObjects", [](WalkthroughParams& p) { p.objects = 256; }, Task::T3, "walkthrough.objects"},
        BadParam{"UnknownKind", [](WalkthroughParams& p) { p.kinds = {"dog", "unicorn"}; }, Task::T3, "walkthrough.kinds"},
        BadParam{"OneKind", [](WalkthroughParams& p) { p.kinds = {"dog"}; }, Task::T4, "walkthrough.kinds"},
        BadParam{"DuplicateKind", [](WalkthroughParams& p) { p.kinds = {"dog", "dog"}; }, Task::T4, "walkthrough.kinds"},
        BadParam{"CellTooSmall", [](WalkthroughParams& p) { p.cell_size = 2.0f; p.door_width = 1.0f; }, Task::T3, "walkthrough.cell_size"},
        BadParam{"CountRange", [](WalkthroughParams& p) { p.count_min = 9; p.count_max = 3; }, Task::T4, "walkthrough.count_min"},
        BadParam{"DoorTooTall", [](WalkthroughParams& p) { p.door_height = 3.5f; }, Task::T3, "walkthrough.door_height"},
        BadParam{"DoorTooWide", [](WalkthroughParams& p) { p.door_width = 4.0f; }, Task::T3, "walkthrough.door_width"},
        BadParam{"ThickWalls", [](WalkthroughParams& p) { p.wall_thickness = 1.5f; }, Task::T3, "walkthrough.wall_thickness"},
        BadParam{"EyeAboveCeiling", [](WalkthroughParams& p) { p.eye_height = 3.0f; }, Task::T3, "walkthrough.eye_height"}),
    [](const auto& info) { return std::string(info.param.name); });

TEST(Walkthrough, WrongTaskIsAnError) {
  for (Task t : {Task::T1, Task::T2}) {
    const auto r = generate(Kind::walkthrough, t, 1);
    ASSERT_FALSE(r.ok());
    EXPECT_EQ(r.error().field, "task");
    EXPECT_NE(r.error().message.find("walkthrough"), std::string::npos);
  }
}

}  // namespace
}  // namespace dtlab::scene

// Wall boxes and allowed kinds of the WALKTHROUGH building; see walkthrough_layout.h.
#include "study/scene/detail/walkthrough_layout.h"

#include <set>
#include <tuple>

#include "study/scene/models.h"

namespace dtlab::scene::detail {

std::vector<std::string> allowed_kinds(const WalkthroughParams& p) {
  if (!p.kinds.empty()) return p.kinds;
  std::vector<std::string> all;
  for (const ModelInfo& m : model_catalogue()) all.emplace_back(m.kind);
  return all;
}

std::vector<WallBox> wall_boxes(const FloorPlan& plan, const WalkthroughParams& p) {
  std::set<std::tuple<int, int, int, int>> doors;
  for (const auto& d : plan.doors) doors.insert({d.x0, d.y0, d.x1, d.y1});
  auto room_at = [&](int x, int z) { return plan.room[static_cast<std::size_t>(z * plan.width + x)]; };
  const float cs = plan.cell_size, t = p.wall_thickness, H = p.wall_height;
  std::vector<WallBox> out;

  // One grid line: `cells` edges, edge i a wall if wall(i), a doorway if door(i).
  // `horizontal`: the line is z = line * cs and runs along x; else x = line * cs along z.
  auto line_walls = [&](bool horizontal, int line, int cells, auto wall, auto door, bool outer) {
    const float at = static_cast<float>(line) * cs;
    auto emit = [&](float from, float to, float y0, float y1, bool lintel) {
      if (horizontal) out.push_back({{from, y0, at - 0.5f * t}, {to, y1, at + 0.5f * t}, outer, lintel});
      else out.push_back({{at - 0.5f * t, y0, from}, {at + 0.5f * t, y1, to}, outer, lintel});
    };
    for (int i = 0; i < cells;) {
      if (!wall(i)) {
        ++i;
        continue;
      }
      const int a = i;
      while (i < cells && wall(i)) ++i;
      float from = static_cast<float>(a) * cs - 0.5f * t;
      for (int e = a; e < i; ++e) {
        if (!door(e)) continue;
        const float g0 = (static_cast<float>(e) + 0.5f) * cs - 0.5f * p.door_width, g1 = g0 + p.door_width;
        emit(from, g0, 0.0f, H, false);
        emit(g0, g1, p.door_height, H, true);
        from = g1;
      }
      emit(from, static_cast<float>(i) * cs + 0.5f * t, 0.0f, H, false);
    }
  };

  for (int k = 0; k <= plan.height; ++k) {  // lines z = k * cs, edges between (x, k-1) and (x, k)
    const bool outer = k == 0 || k == plan.height;
    line_walls(
        true, k, plan.width, [&](int x) { return outer || room_at(x, k - 1) != room_at(x, k); },
        [&](int x) { return !outer && doors.count({x, k - 1, x, k}) > 0; }, outer);
  }
  for (int k = 0; k <= plan.width; ++k) {  // lines x = k * cs, edges between (k-1, z) and (k, z)
    const bool outer = k == 0 || k == plan.width;
    line_walls(
        false, k, plan.height, [&](int z) { return outer || room_at(k - 1, z) != room_at(k, z); },
        [&](int z) { return !outer && doors.count({k - 1, z, k, z}) > 0; }, outer);
  }
  return out;
}

}  // namespace dtlab::scene::detail

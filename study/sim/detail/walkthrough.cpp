// WALKTHROUGH tasks of the simulated participant (docs/sim.md, "T3" and
// "T4"). Both walk the same tour: look around at the start, then go to the
// nearest room it has neither visited nor seen into, through doorways,
// turning in place at each stop and looking at each view through look(). A
// room counts as seen into when the agent noticed its landmark (the first
// placed object in it) from outside -- through a doorway, or through a wall
// when the rendering shows objects through walls. What ends the search
// differs by task, never by condition. Objects of interest are those of the
// kind shown in the "find this" panel (Answer::target_kind, which the
// participant is shown); the answer key's position and count are never read.
#include <algorithm>
#include <cmath>
#include <map>
#include <sstream>

#include "study/sim/detail/agent.h"
#include "study/sim/detail/building.h"

namespace dtlab::sim::detail {

namespace {

constexpr double kPi = 3.14159265358979;

glm::vec2 floor_position(const scene::Object& o) { return {o.transform[3].x, o.transform[3].z}; }

}  // namespace

// Views per full turn at a stop: at least 2 pi / turn_step, and enough that views of the camera's
// horizontal field of view leave no gap (at 60 degrees vertical and 4:3 it is 75 degrees, so
// 90-degree turns would leave four blind sectors of 15 degrees: 5 views of 72 degrees instead).
int views_per_stop(const TrialRun& run) {
  const double aspect = static_cast<double>(run.width) / static_cast<double>(run.height);
  const double fov_x = 2 * std::atan(std::tan(0.5 * static_cast<double>(run.spec.scene->camera.fov_y)) * aspect);
  const double need = std::max(2 * kPi / run.model.turn_step, 2 * kPi / fov_x);
  return std::max(1, static_cast<int>(std::ceil(need - 1e-9)));
}

namespace {

struct Walker {
  TrialRun& run;
  Building building;
  glm::vec2 pos;       // world (x, z)
  int room = 0;
  float yaw = 0;
  double walked = 0;   // world units walked so far
  std::vector<char> visited, seen_into;
  std::vector<std::uint32_t> wanted;               // objects of the shown kind
  std::vector<std::uint32_t> interest;             // wanted, then the landmarks that are not wanted
  std::map<std::uint32_t, int> landmark_room;      // landmark object -> its room

  Walker(TrialRun& r, const std::string& kind) : run(r), building(make_building(*r.spec.scene->plan)) {
    const scene::Scene& sc = *r.spec.scene;
    const scene::CameraStart& c = sc.camera;
    pos = {c.position.x, c.position.z};
    yaw = c.yaw;
    room = std::max(0, building.room_at(pos));
    visited.assign(static_cast<std::size_t>(building.rooms()), 0);
    seen_into = visited;
    visited[static_cast<std::size_t>(room)] = 1;
    for (std::uint32_t i = 0; i < sc.objects.size(); ++i) {
      if (!sc.objects[i].target) continue;  // the placed models (walls, floor and ceiling are not)
      if (sc.objects[i].kind == kind) wanted.push_back(i);
      const int rm = building.room_at(floor_position(sc.objects[i]));
      bool first = rm >= 0;
      for (const auto& [obj, other] : landmark_room) first = first && other != rm;
      if (first) landmark_room[i] = rm;
    }
    interest = wanted;
    for (const auto& [obj, rm] : landmark_room)
      if (std::find(wanted.begin(), wanted.end(), obj) == wanted.end()) interest.push_back(obj);
  }

  render::Camera camera() const {
    const scene::CameraStart& c = run.spec.scene->camera;
    return render::walk_camera({pos.x, c.position.y, pos.y}, yaw, 0.0f, c.fov_y,
                               static_cast<float>(run.width) / static_cast<float>(run.height), c.near_plane,
                               c.far_plane);
  }
  glm::vec2 eye() const { return pos; }

  // Renders the view; rooms whose landmark it notices count as seen into. The returned
  // entries are those of `wanted` (the first wanted.size() of `interest`).
  View look() {
    View v = run.look(camera(), yaw, 0.0f, interest);
    for (std::size_t i = 0; i < v.seen.size(); ++i) {
      const auto it = landmark_room.find(v.seen[i].index);
      if (it == landmark_room.end()) continue;
      if (run.notice(v.seen[i].visible_px)) seen_into[static_cast<std::size_t>(it->second)] = 1;
    }
    v.seen.resize(wanted.size());
    return v;
  }

  // Turns around in place: views_per_stop() views, 2 pi / views apart (so they cover the full
  // circle), calling `at_view` after each until it returns false.
  template <class F>
  void look_around(F&& at_view) {
    const int views = views_per_stop(run);
    const double step = 2 * kPi / views;
    for (int k = 0; k < views && !run.out_of_time(); ++k) {
      if (k > 0) {
        run.turn(step);
        yaw += static_cast<float>(step);
      }
      if (!at_view(look())) return;
    }
  }

  // Walks to the nearest room neither visited nor seen into (with `thorough`, the nearest
  // not visited); false if none is left.
  bool go_on(bool thorough) {
    std::vector<char> done = visited;
    if (!thorough)
      for (std::size_t r = 0; r < done.size(); ++r) done[r] = done[r] || seen_into[r];
    std::vector<glm::vec2> route;
    const int next = building.nearest_unvisited(pos, room, done, route);
    if (next < 0) return false;
    for (const glm::vec2& p : route) {
      const glm::vec2 d = p - pos;
      const float len = glm::length(d);
      if (len < 1e-4f) continue;
      const float heading = std::atan2(-d.x, -d.y);  // yaw 0 looks along -z, yaw pi/2 along -x
      const float turn = std::remainder(heading - yaw, static_cast<float>(2 * kPi));
      run.turn(turn);
      yaw += turn;
      run.walk(len);
      walked += len;
      pos = p;
    }
    room = next;
    visited[static_cast<std::size_t>(room)] = 1;
    return true;
  }
};

}  // namespace

// T3: walk until the object of the shown kind is noticed; mark where it was seen, with an
// error growing with the distance it was seen from, the walls in between and the way walked.
// When every room is visited or seen into without a find, it visits the rooms only seen into;
// when every room is visited, it guesses.
void run_find_unique(TrialRun& run) {
  const scene::Scene& sc = *run.spec.scene;
  Walker w(run, sc.answer.target_kind);
  std::optional<glm::vec2> mark;
  bool thorough = false;
  for (;;) {
    w.look_around([&](const View& v) {
      int noticed = 0;
      for (const Seen& s : v.seen) {
        if (!run.notice(s.visible_px)) continue;
        ++noticed;
        const glm::vec2 at = floor_position(sc.objects[s.index]);
        const double dist = glm::length(at - w.eye());
        const int walls = w.building.walls_between(w.eye(), at);
        const double sd = (run.model.map_base + run.model.map_per_unit * dist + run.model.map_per_wall * walls) * run.traits.map_error +
                          run.model.map_per_walked * std::sqrt(w.walked);
        const float side = static_cast<float>(sc.plan->width) * sc.plan->cell_size;
        const float depth = static_cast<float>(sc.plan->height) * sc.plan->cell_size;
        mark = glm::vec2(std::clamp(static_cast<float>(at.x + run.rng.normal(0.0, sd)), 0.0f, side),
                         std::clamp(static_cast<float>(at.y + run.rng.normal(0.0, sd)), 0.0f, depth));
        run.spend(run.scaled(run.model.notice_find_s));
        break;
      }
      run.trace.noticed.push_back(noticed);
      run.spend(run.scaled(run.model.walk_scan_s));
      return !mark;
    });
    if (mark || run.out_of_time()) break;
    if (!w.go_on(thorough)) {
      if (thorough) break;
      thorough = true;
      if (!w.go_on(true)) break;
    }
  }
  if (!mark) {
    // Never seen: a guess at the centre of a room drawn at random.
    mark = w.building.centre[static_cast<std::size_t>(run.rng.below(static_cast<std::uint64_t>(w.building.rooms())))];
  }
  std::ostringstream text;
  text << mark->x << "," << mark->y;
  run.finish(store::Position{mark->x, mark->y}, text.str(), run.model.mark_map_s);
}

// T4: walk and count the objects of the shown kind; a noticed object seen before is recognised
// unless identity memory fails (only when seen again from another room); the agent answers
// when every room is visited or seen into, or after patience_rooms stops in a row without a
// new find (counted from its first find on).
void run_count_kind(TrialRun& run) {
  const scene::Scene& sc = *run.spec.scene;
  Walker w(run, sc.answer.target_kind);
  std::map<std::uint32_t, int> counted;  // object index -> room it was last seen from
  long count = 0;
  int idle_rooms = 0;  // stops in a row without a new find
  for (;;) {
    bool found = false;
    w.look_around([&](const View& v) {
      int fresh = 0, noticed = 0;
      double effort = 0;
      for (const Seen& s : v.seen) {
        if (!run.notice(s.visible_px)) continue;
        ++noticed;
        const double fragment = 1.0 - completeness(s);
        auto it = counted.find(s.index);
        if (it != counted.end()) {
          const bool moved = it->second != w.room;
          it->second = w.room;
          effort += run.model.check_known_s * (1.0 + run.model.fragment_effort * fragment);
          const double p_fail = (1.0 - run.traits.memory) * (1.0 + run.model.fragment_memory * fragment);
          if (!moved || !run.rng.chance(p_fail)) continue;
        } else {
          counted.emplace(s.index, w.room);
        }
        ++count;
        ++fresh;
        effort += run.model.count_kind_s * (1.0 + run.model.fragment_effort * fragment);
        if (s.clear_px * 2 < s.visible_px) effort += run.model.see_through_s;  // counted while mostly seen through walls
      }
      run.trace.noticed.push_back(noticed);
      run.spend(run.scaled(run.model.walk_scan_s + effort));
      found = found || fresh > 0;
      return true;
    });
    // Patience runs from the first find on: nobody answers "none" after a few empty rooms.
    idle_rooms = found ? 0 : count > 0 ? idle_rooms + 1 : 0;
    if (run.out_of_time() || idle_rooms >= run.traits.patience_rooms) break;
    if (!w.go_on(false)) break;
  }
  run.finish(store::Count{count}, std::to_string(count), run.model.answer_count_s);
}

}  // namespace dtlab::sim::detail

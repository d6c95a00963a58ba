// ABSTRACT tasks of the simulated participant (docs/sim.md, "T1" and "T2").
// Both orbit the cube in mouse drags and look at each view through look();
// the strategy (view schedule, stopping rule) is the same in every condition.
// Never reads the answer key: targets are found by colour (pure red) and
// shape (cone), as a participant finds them.
#include <algorithm>
#include <cmath>
#include <map>

#include "study/scene/letters.h"
#include "study/sim/detail/agent.h"

namespace dtlab::sim::detail {

namespace {

bool is_red(const scene::Object& o) { return o.color == glm::vec3(1.0f, 0.0f, 0.0f); }

struct Orbit {
  float yaw = 0, pitch = 0;
  render::Camera camera(const TrialRun& run) const {
    const scene::CameraStart& c = run.spec.scene->camera;
    return render::orbit_camera(c.target, c.distance, yaw, pitch, c.fov_y,
                                static_cast<float>(run.width) / static_cast<float>(run.height), c.near_plane,
                                c.far_plane);
  }
};

}  // namespace

// T1: count the red objects. Each view, a red object is noticed with P(notice); a noticed one
// already counted is recognised unless identity memory fails (then it is counted again); the
// agent answers after `patience` views in a row that added nothing.
void run_count_targets(TrialRun& run) {
  const scene::Scene& sc = *run.spec.scene;
  std::vector<std::uint32_t> red;
  for (std::uint32_t i = 0; i < sc.objects.size(); ++i)
    if (is_red(sc.objects[i])) red.push_back(i);

  Orbit o{sc.camera.yaw, sc.camera.pitch};
  std::map<std::uint32_t, float> counted;  // object index -> yaw at which it was last seen
  long count = 0;
  int idle = 0;
  for (int k = 0; k < run.model.max_views && !run.out_of_time(); ++k) {
    if (k > 0) {
      const float pitch = (k % 2) ? static_cast<float>(run.model.orbit_pitch_high) : static_cast<float>(run.model.orbit_pitch_low);
      run.drag(run.model.orbit_yaw_step, pitch - o.pitch);
      o.yaw += static_cast<float>(run.model.orbit_yaw_step);
      o.pitch = pitch;
    }
    const View v = run.look(o.camera(run), o.yaw, o.pitch, red);
    int fresh = 0, noticed = 0;
    double effort = 0;  // seconds of counting and checking in this view
    for (const Seen& s : v.seen) {
      if (!run.notice(s.visible_px)) continue;
      ++noticed;
      // A fragment (part of the object hidden) is harder to count and to recognise again.
      const double fragment = 1.0 - completeness(s);
      auto it = counted.find(s.index);
      if (it != counted.end()) {
        const double turned = std::abs(o.yaw - it->second);
        const double p_fail =
            (1.0 - run.traits.memory) * std::min(1.0, turned / 3.14159265358979) * (1.0 + run.model.fragment_memory * fragment);
        it->second = o.yaw;
        effort += run.model.check_known_s * (1.0 + run.model.fragment_effort * fragment);
        if (!run.rng.chance(p_fail)) continue;
      } else {
        counted.emplace(s.index, o.yaw);
      }
      ++count;
      ++fresh;
      effort += run.model.count_new_s * (1.0 + run.model.fragment_effort * fragment);
      if (s.clear_px * 2 < s.visible_px) effort += run.model.see_through_s;  // counted while mostly seen through something
    }
    run.trace.noticed.push_back(noticed);
    run.spend(run.scaled(run.model.scan_base_s + effort));
    idle = fresh == 0 ? idle + 1 : 0;
    if (idle >= run.traits.patience) break;
  }
  run.finish(store::Count{count}, std::to_string(count), run.model.answer_count_s);
}

// T2: name the letter of the red cones. A view is legible to the share of the letter's cones
// noticed in it times the foreshortening of the horizontal grid (|sin pitch| / sin 45 degrees,
// at most 1); at legibility >= the participant's threshold it reads the letter, right with
// probability 0.5 + 0.5 * legibility^2, else it names another letter. Out of time: a guess.
void run_identify_letter(TrialRun& run) {
  const scene::Scene& sc = *run.spec.scene;
  std::vector<std::uint32_t> cones;
  for (std::uint32_t i = 0; i < sc.objects.size(); ++i)
    if (is_red(sc.objects[i]) && sc.objects[i].kind == "cone") cones.push_back(i);
  std::string letters = run.spec.setup ? run.spec.setup->params.abstract.letters : std::string("CKRXY");
  if (letters.empty()) letters = "CKRXY";

  Orbit o{sc.camera.yaw, sc.camera.pitch};
  std::optional<char> read;
  double legibility = 0;
  for (int k = 0; k < run.model.max_views && !run.out_of_time(); ++k) {
    if (k > 0) {
      // Steep views from alternating sides, turning 60 degrees about the vertical each time.
      const float pitch = static_cast<float>(k % 2 ? run.model.letter_pitch : -run.model.letter_pitch);
      run.drag(1.047198, pitch - o.pitch);
      o.yaw += 1.047198f;
      o.pitch = pitch;
    }
    const View v = run.look(o.camera(run), o.yaw, o.pitch, cones);
    int noticed = 0;
    double effort = 0;
    for (const Seen& s : v.seen) {
      if (!run.notice(s.visible_px)) continue;
      ++noticed;
      effort += run.model.letter_cone_s * (1.0 + run.model.fragment_effort * (1.0 - completeness(s)));
      if (s.clear_px * 2 < s.visible_px) effort += run.model.see_through_s;
    }
    run.trace.noticed.push_back(noticed);
    run.spend(run.scaled(run.model.scan_base_s + effort));
    const double share = cones.empty() ? 0.0 : static_cast<double>(noticed) / static_cast<double>(cones.size());
    legibility = share * std::min(1.0, std::abs(std::sin(static_cast<double>(o.pitch))) / std::sin(0.785398));
    if (legibility >= run.traits.legibility) {
      // What the cones spell is what the scene shows; reading it right is the model's chance.
      const char shown = sc.answer.letter;
      if (run.rng.chance(0.5 + 0.5 * legibility * legibility) || letters.size() < 2) {
        read = shown;
      } else {
        std::string others;
        for (char c : letters)
          if (c != shown) others += c;
        read = others[run.rng.below(others.size())];
      }
      break;
    }
  }
  if (!read) read = letters[run.rng.below(letters.size())];  // out of views or time: a guess
  run.finish(store::Letter{std::string(1, *read)}, std::string(1, *read), run.model.answer_letter_s);
}

}  // namespace dtlab::sim::detail

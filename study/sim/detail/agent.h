// Internals of the simulated participant: the state of one trial (simulated
// clock, what was rendered, the input events that would have produced the
// moves) and the perception primitives every task uses. Guarantees: every
// rendered frame adds exactly one camera pose and one measured frame time;
// the simulated clock only moves forward. Never: decides what was noticed
// from anything but what look() returns (objects of interest are chosen by
// what a participant is told to look for: red, red cones, the kind shown).
#pragma once
#include <algorithm>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "study/render/camera.h"
#include "study/common/random.h"
#include "study/sim/perception.h"
#include "study/sim/sim.h"

namespace dtlab::sim::detail {

using dtlab::Stream;

class TrialRun {
 public:
  TrialRun(const session::TrialSpec& spec, const ModelParams& params, const Traits& traits, std::uint64_t seed,
           render::Renderer& renderer, int width, int height);

  const session::TrialSpec& spec;
  const ModelParams& model;  // the agent model's constants (docs/sim.md, "Parameters")
  const Traits& traits;
  Stream rng;
  render::Renderer& renderer;
  const int width, height;
  const std::vector<ObjectBounds> bounds;
  TrialTrace trace;
  session::TrialOutcome out;
  std::optional<Error> failure;  // the renderer's first Error in this trial

  double now() const { return t_; }
  double limit() const { return spec.time_limit_s; }
  bool out_of_time() const { return t_ >= spec.time_limit_s; }
  // Spends `seconds` (already scaled by the participant's speed) of simulated time.
  void spend(double seconds) { t_ += std::max(0.0, seconds); }
  double scaled(double seconds) const { return seconds * traits.speed; }

  // Renders the view and returns what it shows of `objects`; records frames and poses. When the
  // renderer fails, keeps its first Error in `failure`, sees nothing and ends the trial's time
  // (the agent winds down; the participant returns the Error, not an outcome).
  View look(const render::Camera& camera, float yaw, float pitch, std::span<const std::uint32_t> objects);
  // P(notice) of an object with `visible_px` pixels in this viewport (model "Perception").
  double notice_probability(long visible_px) const;
  // One uniform draw per call whatever the pixels, so two conditions of one trial use the same
  // random numbers object by object (common random numbers): more visible pixels never notice less.
  bool notice(long visible_px) {
    const double u = rng.uniform();
    return visible_px > 0 && u < notice_probability(visible_px);
  }

  // Input events and simulated time of moving the camera.
  void drag(double dyaw, double dpitch);  // orbit: left-drag of the mouse
  void turn(double dyaw);                 // walkthrough: mouse motion turns about the vertical axis
  void walk(double distance);             // walkthrough: arrow key Up held
  // Finishes: the answer event (text), the time it took to enter, completion time and stamps.
  void finish(std::optional<store::Answer> answer, const std::string& text, double entry_s);

 private:
  double t_ = 0;
};

// How much of an object a view shows: visible pixels over its unoccluded silhouette, at most 1.
inline double completeness(const Seen& s) {
  return s.silhouette_px > 0 ? std::min(1.0, static_cast<double>(s.visible_px) / static_cast<double>(s.silhouette_px))
                             : 0.0;
}

// WALKTHROUGH: views in one full turn at a stop (walkthrough.cpp): 2 pi / turn_step, more if
// the viewport's horizontal field of view is narrower than turn_step, so the views cover the circle.
int views_per_stop(const TrialRun& run);

// The tasks (abstract.cpp, walkthrough.cpp).
void run_count_targets(TrialRun& run);   // T1
void run_identify_letter(TrialRun& run); // T2
void run_find_unique(TrialRun& run);     // T3
void run_count_kind(TrialRun& run);      // T4

}  // namespace dtlab::sim::detail

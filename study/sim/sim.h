// Simulated participants: a session::Responder that does the reference
// study's tasks by LOOKING at the scene through the real renderer (headless,
// weight-mode frames of the trial's own method, perception.h), so that
// condition effects emerge from what the rendering shows. The agent follows
// the same strategy under every condition; only what it sees differs.
// docs/sim.md documents every parameter below and why it has its value.
// Guarantees: the same (protocol, participant index, sim seed) gives the same
// answers and simulated completion times on every run of one build (measured
// frame times and wall-clock stamps differ); a trial's outcome depends only on
// the trial and the participant's traits, never on earlier trials, so a
// resumed session answers exactly as an uninterrupted one. Completion times
// are SIMULATED seconds from the model, not wall-clock time.
// Never: creates a GL context (calls need the caller's context current), reads
// the answer key to decide what it saw, or changes the scene or the settings.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "study/session/session.h"

namespace dtlab::sim {

// The model's constants (docs/sim.md, "Parameters", justifies each).
struct ModelParams {
  // Perception: P(notice) = attention * (1 - exp(-A / notice_px)), A = visible pixels scaled to an
  // 800 x 600 screen (the article's resolution), so the model does not depend on --width/--height.
  double notice_px = 150.0;
  // Identity memory: an object seen again is taken for a new one with probability
  // (1 - memory) * (rotation since it was last seen / pi) in ABSTRACT; (1 - memory) when seen
  // again from another room in WALKTHROUGH.
  // ABSTRACT orbit.
  double orbit_yaw_step = 0.785398;        // radians between views (45 degrees)
  double orbit_pitch_low = 0.3, orbit_pitch_high = 0.75;  // T1 alternates these pitches
  double letter_pitch = 1.0;               // T2: pitch of the views after the first (from below, steep)
  int max_views = 16;                      // ABSTRACT: views before the agent answers anyway
  // Durations in seconds (multiplied by the participant's speed).
  double drag_base_s = 0.4, drag_s_per_rad = 1.2;  // one mouse drag of the orbit
  double scan_base_s = 1.0;                 // looking over a view
  double aid_spot_s = 0.25;                 // an aid that follows the cursor: moving it to the next spot of the
                                            // sweep and looking there (docs/sim.md, "Active aids")
  double count_new_s = 0.7;                 // counting one more target
  double check_known_s = 0.12;              // recognising one counted before
  double fragment_effort = 1.5;             // counting/checking time x (1 + this * hidden share) for a fragment
  double fragment_memory = 2.0;             // identity-memory failures x (1 + this * hidden share)
  double see_through_s = 0.25;              // extra for counting a target seen mostly through surfaces (share < 0.9)
  double letter_cone_s = 0.15;              // T2: per letter cone read
  double answer_count_s = 2.0, answer_letter_s = 1.0, mark_map_s = 5.0;  // entering the answer
  // WALKTHROUGH.
  double walk_speed = 4.5;                  // world units per second (arrow keys)
  double turn_step = 1.570796;              // largest turn between views at a stop (90 degrees); smaller
                                            // when the view is narrower, so the views cover the circle
  double turn_base_s = 0.15, turn_s_per_rad = 0.3;  // one turn of the camera (mouse)
  double walk_scan_s = 0.45;                // looking over a view in a building
  double count_kind_s = 0.7;                // T4: counting one more object of the kind
  double notice_find_s = 1.0;               // T3: confirming the target once noticed
  // T3 map error (world units): sd = map_base + map_per_unit * distance seen + map_per_wall * walls
  // between, times the participant's map_error trait; plus map_per_walked * sqrt(distance walked).
  double map_base = 10.0, map_per_unit = 0.15, map_per_wall = 0.5, map_per_walked = 0.4;
  // Questionnaire: rating = 2 + rating_gain * log2(reference time / cell time) + noise.
  double rating_gain = 1.5, rating_noise = 0.5;
  double depth_noise = 0.25;                // sd of log apparent-size estimates in the depth test
};

// One participant's random effects (drawn once from the agent seed).
struct Traits {
  double speed = 1.0;        // duration multiplier, lognormal(0, 0.30)
  double attention = 0.95;   // ceiling of P(notice), N(0.95, 0.03) clamped to [0.8, 1]
  double memory = 0.985;     // identity memory, N(0.985, 0.008) clamped to [0.9, 0.999]
  int patience = 2;          // ABSTRACT: views without news before answering, 2 or 3
  int patience_rooms = 4;    // WALKTHROUGH T4: rooms in a row without a new find before answering, 3..5
  double legibility = 0.6;   // T2: share of the letter that must be legible to read it, N(0.6, 0.08) in [0.4, 0.95]
  double map_error = 1.0;    // T3: multiplier of the map error, lognormal(0, 0.25)
  double rating_bias = 0.0;  // questionnaire: added to every rating, N(0, 0.3)
};

// The agent's seed: mix64(participant_seed(master, index), mix64(sim_seed)).
std::uint64_t agent_seed(std::uint64_t master_seed, int enrollment_index, std::uint64_t sim_seed);
Traits draw_traits(std::uint64_t agent_seed);

struct SimOptions {
  int width = 160, height = 120;  // the viewport the agent looks at (every view is rendered at this size)
  std::uint64_t seed = 0;         // sim seed: varies the agents without changing the plans
  ModelParams model;
};

// What one trial looked like from inside (for tests and `--json` diagnostics).
struct TrialTrace {
  int views = 0;                 // views looked at (camera poses recorded = frames rendered >= views)
  int aid_spots = 0;             // cursor positions an active aid was swept over, all views together
  std::vector<int> noticed;      // per view: objects of interest noticed in it
  std::vector<int> visible;      // per view: objects of interest with any visible pixel
  double simulated_s = 0;        // the completion time reported
  bool timed_out = false;
};

class SimulatedParticipant final : public session::Responder {
 public:
  explicit SimulatedParticipant(SimOptions options = {});
  session::Viewport viewport() const override;
  Status train(const session::TaskSetSpec& set) override;  // free exploration: nothing measured, nothing rendered
  Result<session::TrialOutcome> run_trial(const session::TrialSpec& trial) override;
  Result<std::vector<session::QuestionAnswer>> answer_questionnaire(const session::QuestionnaireSpec& spec) override;
  const TrialTrace& last_trace() const { return trace_; }  // the trace of the last run_trial

 private:
  SimOptions options_;
  TrialTrace trace_;
};

}  // namespace dtlab::sim

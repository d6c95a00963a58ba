// SimulatedParticipant (sim.h): traits from the agent seed, one renderer per
// trial scene, the task's strategy (detail/abstract.cpp, detail/walkthrough.cpp).
// Per-trial randomness comes from mix64(agent seed, trial seed) alone, so a
// trial's outcome never depends on what ran before it in this process.
#include "study/sim/sim.h"

#include <algorithm>
#include <cmath>

#include "study/design/seeds.h"
#include "study/sim/detail/agent.h"

namespace dtlab::sim {

std::uint64_t agent_seed(std::uint64_t master_seed, int enrollment_index, std::uint64_t sim_seed) {
  return mix64(design::participant_seed(master_seed, static_cast<std::uint64_t>(enrollment_index)), mix64(sim_seed));
}

Traits draw_traits(std::uint64_t seed) {
  Stream r(mix64(seed, 0x747261697473ULL));  // "traits"
  Traits t;
  t.speed = std::exp(r.normal(0.0, 0.30));
  t.attention = std::clamp(r.normal(0.95, 0.03), 0.8, 1.0);
  t.memory = std::clamp(r.normal(0.985, 0.008), 0.9, 0.999);
  t.patience = r.chance(0.5) ? 2 : 3;
  t.patience_rooms = 3 + static_cast<int>(r.below(3));
  t.legibility = std::clamp(r.normal(0.6, 0.08), 0.4, 0.95);
  t.map_error = std::exp(r.normal(0.0, 0.25));
  t.rating_bias = r.normal(0.0, 0.3);
  return t;
}

SimulatedParticipant::SimulatedParticipant(SimOptions options) : options_(std::move(options)) {
  if (options_.width < 16 || options_.height < 16)
    throw std::invalid_argument("SimulatedParticipant: the viewport must be at least 16 x 16 pixels");
}

session::Viewport SimulatedParticipant::viewport() const { return {options_.width, options_.height}; }

Status SimulatedParticipant::train(const session::TaskSetSpec&) { return {}; }

Result<session::TrialOutcome> SimulatedParticipant::run_trial(const session::TrialSpec& spec) {
  if (!spec.scene || !spec.protocol) throw std::invalid_argument("SimulatedParticipant::run_trial: spec without scene or protocol");
  auto renderer = render::Renderer::create(*spec.scene);
  if (!renderer) return renderer.error();
  const std::uint64_t seed = agent_seed(spec.protocol->master_seed, spec.enrollment_index, options_.seed);
  const Traits traits = draw_traits(seed);
  detail::TrialRun run(spec, options_.model, traits, mix64(seed, spec.planned.seed), *renderer.value(), options_.width,
                       options_.height);
  switch (spec.scene->task) {
    case scene::Task::T1: detail::run_count_targets(run); break;
    case scene::Task::T2: detail::run_identify_letter(run); break;
    case scene::Task::T3: detail::run_find_unique(run); break;
    case scene::Task::T4: detail::run_count_kind(run); break;
  }
  trace_ = run.trace;
  if (run.failure) return *run.failure;
  return std::move(run.out);
}

}  // namespace dtlab::sim

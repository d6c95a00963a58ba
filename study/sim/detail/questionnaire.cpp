// The simulated participant's questionnaires (docs/sim.md, "Questionnaire"):
// the depth test from what the renderer shows of each pair (apparent size
// against the model's known size); every other answer from its item type's
// (or instrument's) model in study/questionnaire, fed with the agent's own
// recorded trials, its traits, and how sure the depth test felt. Randomness:
// one stream per occasion, mix64(agent seed, "quest") at the end (as before
// occasions existed) and mixed with the occasion's scope elsewhere. Never
// reads the depth test's key (the session scores the answers).
#include <algorithm>
#include <cmath>
#include <map>

#include "study/scene/models.h"
#include "study/sim/detail/agent.h"

namespace dtlab::sim {

namespace {

struct Judgement {
  std::uint32_t closer = 0;
  double margin = 0;  // |log ratio| of the two distance estimates
};

// The stream of one occasion: the end's is the one the reference study's answers were drawn
// from before questionnaires had occasions; every other occasion's is its own, so an answer never
// depends on which occasions this process asked before.
std::uint64_t occasion_seed(std::uint64_t agent, const questionnaire::Occasion& o) {
  const std::uint64_t end = mix64(agent, 0x7175657374ULL);  // "quest"
  if (o.scope.empty()) return end;
  std::uint64_t h = 0xcbf29ce484222325ULL;  // FNV-1a of the occasion's scope
  for (unsigned char c : o.scope) h = (h ^ c) * 0x100000001b3ULL;
  return mix64(end, h);
}

}  // namespace

Result<std::vector<session::QuestionAnswer>> SimulatedParticipant::answer_questionnaire(
    const session::QuestionnaireSpec& spec) {
  const std::uint64_t seed = agent_seed(spec.protocol->master_seed, spec.enrollment_index, options_.seed);
  const Traits traits = draw_traits(seed);
  Stream rng(occasion_seed(seed, spec.occasion));
  const ModelParams& m = options_.model;

  // Depth tests first: self-reported depth perception draws on how they felt.
  std::map<std::pair<std::string, int>, Judgement> judged;  // (item, pair) -> judgement
  double margin_sum = 0;
  int margins = 0;
  for (const session::DepthTestView& dt : spec.depth_tests) {
    auto renderer = render::Renderer::create(dt.scene);
    if (!renderer) return renderer.error();
    const auto bounds = object_bounds(dt.scene);
    const render::Camera cam =
        render::camera_from_start(dt.camera, static_cast<float>(options_.width) / static_cast<float>(options_.height));
    std::vector<std::uint32_t> shown;
    std::vector<const session::Question*> pairs;
    for (const session::Question& q : spec.questions) {
      if (q.item->id != dt.item || q.pair == 0) continue;
      pairs.push_back(&q);
      for (std::uint32_t id : {q.object_a, q.object_b}) shown.push_back(id - 1);  // Object::id is index + 1
    }
    const auto looked = look(*renderer.value(), cam, dt.frame, options_.width, options_.height, shown, bounds);
    if (!looked) return looked.error();
    const View& v = looked.value();
    // Distance estimate: a model of known size (footprint x height) covering A pixels is about
    // sqrt(size / A) away, times lognormal noise; an object not seen at all is taken as farthest.
    auto estimate = [&](const Seen& s) {
      const scene::ModelInfo* info = scene::find_model(dt.scene.objects[s.index].kind);
      const double size = info ? 2.0 * info->footprint_radius * info->height : 1.0;
      if (s.visible_px <= 0) return 1e9;
      return std::sqrt(size / static_cast<double>(s.visible_px)) * std::exp(rng.normal(0.0, m.depth_noise));
    };
    for (std::size_t k = 0; k < pairs.size(); ++k) {
      const double da = estimate(v.seen[2 * k]), db = estimate(v.seen[2 * k + 1]);
      Judgement j{da <= db ? pairs[k]->object_a : pairs[k]->object_b, std::abs(std::log(da / db))};
      judged[{dt.item, pairs[k]->pair}] = j;
      margin_sum += std::min(1.0, j.margin / (2.0 * m.depth_noise));
      ++margins;
    }
  }

  // Every question through its item type's (or instrument's) model, in order, with what the
  // participant did so far and what it answered before at this occasion.
  const questionnaire::DesignNames names = protocol::design_names(*spec.protocol);
  questionnaire::Experience e;
  e.design = &names;
  e.occasion = &spec.occasion;
  for (const session::RecordedTrial& t : spec.history)
    e.history.push_back({t.planned.position, t.planned.block, t.planned.task, t.planned.levels, t.completion_s,
                         t.answered, t.planned.practice});
  e.seed = seed;
  e.rating_bias = traits.rating_bias;
  e.rating_gain = m.rating_gain;
  e.rating_noise = m.rating_noise;
  if (margins > 0) e.depth_confidence = margin_sum / margins;
  e.depth_choice = [&](const session::Question& q) -> std::optional<std::uint32_t> {
    const auto it = judged.find({q.item->id, q.pair});
    if (it == judged.end()) return std::nullopt;
    return it->second.closer;
  };
  e.rng = &rng;
  std::vector<session::QuestionAnswer> answers;
  for (const session::Question& q : spec.questions) {
    answers.push_back(questionnaire::simulate(q, e));
    e.given.emplace_back(&q, answers.back());
  }
  return answers;
}

}  // namespace dtlab::sim

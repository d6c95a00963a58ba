// The simulated participant's post-test questionnaire (docs/sim.md,
// "Questionnaire"): ratings from its own recorded completion times per
// condition, the preferred level from its own ratings, the depth test from
// what the renderer shows of each pair (apparent size against the model's
// known size), self-reported depth perception from how sure the depth test
// felt. Randomness: mix64(agent seed, "questionnaire"). Never reads the
// depth test's key (the session scores the answers).
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

// The rendering factor's name, or "".
std::string rendering_factor(const protocol::Protocol& p) {
  const protocol::Factor* f = protocol::factor_with_role(p, protocol::FactorRole::rendering);
  return f ? f->name : "";
}

bool matches(const design::PlannedTrial& t, const std::vector<std::pair<std::string, std::string>>& levels,
             const std::string& except) {
  for (const auto& [factor, level] : levels) {
    if (factor == except) continue;
    const auto it = std::find_if(t.levels.begin(), t.levels.end(), [&](const auto& l) { return l.first == factor; });
    if (it == t.levels.end() || it->second != level) return false;
  }
  return true;
}

struct CellTimes {
  double mean = 0;
  double unanswered = 0;  // share of trials without an answer
  int n = 0;
};

CellTimes cell_times(const std::vector<session::RecordedTrial>& history,
                     const std::vector<std::pair<std::string, std::string>>& levels, const std::string& except) {
  CellTimes c;
  int none = 0;
  for (const auto& t : history) {
    if (t.planned.practice || !matches(t.planned, levels, except)) continue;
    c.mean += t.completion_s;
    none += !t.answered;
    ++c.n;
  }
  if (c.n > 0) {
    c.mean /= c.n;
    c.unanswered = static_cast<double>(none) / c.n;
  }
  return c;
}

}  // namespace

Result<std::vector<session::QuestionAnswer>> SimulatedParticipant::answer_questionnaire(
    const session::QuestionnaireSpec& spec) {
  const std::uint64_t seed = agent_seed(spec.protocol->master_seed, spec.enrollment_index, options_.seed);
  const Traits traits = draw_traits(seed);
  detail::Stream rng(mix64(seed, 0x7175657374ULL));  // "quest"
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
    const View v = look(*renderer.value(), cam, dt.frame, options_.width, options_.height, shown, bounds);
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

  const std::string rendering = rendering_factor(*spec.protocol);
  std::vector<session::QuestionAnswer> answers;
  std::map<std::string, std::vector<double>> rating_of_level;  // level of the rendering factor -> ratings given
  for (const session::Question& q : spec.questions) {
    const protocol::QuestionnaireItem& item = *q.item;
    switch (item.type) {
      case protocol::ItemType::rating: {
        const double lo = item.scale_min, hi = item.scale_max, mid = 0.5 * (lo + hi), unit = (hi - lo) / 4.0;
        double raw = mid;
        if (!q.levels.empty()) {
          // Ease of a condition: its mean time against the same scenario under every rendering.
          const CellTimes cell = cell_times(spec.history, q.levels, "");
          const CellTimes ref = cell_times(spec.history, q.levels, rendering);
          if (cell.n > 0 && ref.n > 0 && cell.mean > 0 && ref.mean > 0)
            raw = mid + unit * (m.rating_gain * std::log2(ref.mean / cell.mean) - 2.0 * cell.unanswered);
        } else if (margins > 0) {
          raw = lo + (hi - lo) * margin_sum / margins;  // how sure the depth judgements felt
        }
        const double r = std::clamp(std::round(raw + unit * (traits.rating_bias + rng.normal(0.0, m.rating_noise))), lo, hi);
        for (const auto& [factor, level] : q.levels)
          if (factor == rendering) rating_of_level[level].push_back(r);
        answers.emplace_back(r);
        break;
      }
      case protocol::ItemType::choice: {
        // The option it rated best on average; without ratings, the one it was fastest with. Two
        // options that score exactly alike (equal mean ratings) leave no preference: the neutral
        // option, where the item has one.
        std::string best;
        double best_score = -1e300;
        bool tied = false;
        for (const std::string& o : q.options) {
          if (o == item.neutral) continue;
          double score = -1e300;
          if (auto it = rating_of_level.find(o); it != rating_of_level.end() && !it->second.empty()) {
            score = 0;
            for (double r : it->second) score += r;
            score /= static_cast<double>(it->second.size());
          } else if (!rendering.empty()) {
            const CellTimes c = cell_times(spec.history, {{rendering, o}}, "");
            if (c.n > 0) score = -c.mean;
          }
          if (score > best_score) {
            best_score = score;
            best = o;
            tied = false;
          } else if (score == best_score && score != -1e300) {
            tied = true;
          }
        }
        if (tied && !item.neutral.empty()) best = item.neutral;
        else if (best.empty() || best_score == -1e300) best = q.options[rng.below(q.options.size())];
        answers.emplace_back(best);
        break;
      }
      case protocol::ItemType::depth_test: {
        const auto it = judged.find({item.id, q.pair});
        answers.emplace_back(static_cast<double>(it != judged.end() ? it->second.closer : q.object_a));
        break;
      }
    }
  }
  return answers;
}

}  // namespace dtlab::sim

// Item type "rating": an integer on [scale min, max], asked once, or (at the
// end) once per combination of the `per` factors' levels, first factor
// slowest. Stored: the integer. Simulated: the reference study's model
// (docs/sim.md): easier than its own average rates higher; a rating without
// a condition after a depth test reports how sure the judgements felt.
// Never: changes the draws of the reference study's simulated answers.
#include <algorithm>
#include <cmath>

#include "study/questionnaire/detail/items.h"

namespace dtlab::questionnaire {
namespace {

void check_item(Item& item, const DesignNames& design, Problems& problems) {
  const auto& per = item.strings("per");
  std::vector<std::string> names;
  for (const auto& f : design.factors) names.push_back(f.name);
  for (std::size_t i = 0; i < per.size(); ++i)
    if (!design.factor(per[i]))
      problems.error_at("per", i, "no factor named '" + per[i] + "' (factors: " + detail::quoted_list(names) + ")");
  if (!per.empty() && item.when.kind != When::Kind::end)
    problems.error("per", "applies only to when = \"end\"; an item asked at \"" + to_string(item.when) +
                              "\" is already about that occasion's condition");
}

std::vector<Question> expand_item(const Item& item, const DesignNames& design) {
  std::vector<const DesignNames::Factor*> per;
  std::size_t combinations = 1;
  for (const auto& name : item.strings("per")) {
    const DesignNames::Factor* f = design.factor(name);
    if (!f) continue;  // the reader checked the names; a hand-built item may not have
    per.push_back(f);
    combinations *= f->levels.size();
  }
  std::vector<Question> out;
  for (std::size_t c = 0; c < combinations; ++c) {
    Question q;
    q.item = &item;
    std::size_t rest = c, stride = combinations;
    for (const DesignNames::Factor* f : per) {
      stride /= f->levels.size();
      const std::string& level = f->levels[rest / stride];
      rest %= stride;
      q.levels.emplace_back(f->name, level);
      q.scope += (q.scope.empty() ? "" : ";") + f->name + "=" + level;
    }
    out.push_back(std::move(q));
  }
  return out;
}

Result<StoredValue> encode_answer(const Question& q, const Answer& a, const EncodeContext&) {
  const NumberPair s = q.item->range("scale");
  const double* v = std::get_if<double>(&a);
  if (!v || *v != std::floor(*v) || *v < s.min || *v > s.max)
    return detail::answer_error(q, "expected an integer rating in [" + std::to_string(static_cast<int>(s.min)) + ", " +
                                       std::to_string(static_cast<int>(s.max)) + "]");
  return StoredValue{*v};
}

// The reference study's rating (docs/sim.md): kept draw for draw as it was before the seam.
Answer simulate_answer(const Question& q, Experience& e) {
  const NumberPair s = q.item->range("scale");
  const double lo = s.min, hi = s.max, mid = 0.5 * (lo + hi), unit = (hi - lo) / 4.0;
  double raw = mid;
  const detail::Levels levels = detail::condition_of(q, e);
  if (!levels.empty()) {
    if (const auto st = detail::strain_of(levels, e))
      raw = mid + unit * (-e.rating_gain * st->strain - 2.0 * st->unanswered);
  } else if (e.depth_confidence) {
    raw = lo + (hi - lo) * *e.depth_confidence;  // how sure the depth judgements felt
  }
  return std::clamp(std::round(raw + unit * (e.rating_bias + e.rng->normal(0.0, e.rating_noise))), lo, hi);
}

NumberPair scale_bounds(const Item& item) { return item.range("scale"); }

}  // namespace

const ItemType& item_type_rating() {
  static const ItemType t = [] {
    ItemType t;
    t.name = "rating";
    t.summary = "an integer on a scale (buttons or digit keys), once or per combination of factors' levels";
    t.keys = {
        KeySpec::of("scale", KeyKind::int_range).within(-100, 100).strictly().or_else(NumberPair{0, 4}),
        KeySpec::of("per", KeyKind::strings).within(0, 8).or_else(std::vector<std::string>{}),
    };
    t.measure = Measure::ordinal;
    t.check = check_item;
    t.expand = expand_item;
    t.encode = encode_answer;
    t.simulate = simulate_answer;
    t.bounds = scale_bounds;
    return t;
  }();
  return t;
}

}  // namespace dtlab::questionnaire

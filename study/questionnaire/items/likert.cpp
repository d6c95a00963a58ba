// Item type "likert": one of `points` labelled points (2 to 11), labelled
// one by one (`labels` has `points` entries) or at the two ends (2 entries);
// the first point's stored value is `first` (default 1: 1..points). Stored:
// the point's value. Simulated: like a rating, from how easy the occasion's
// condition felt (docs/sim.md), on the points' scale.
#include <cmath>

#include "study/questionnaire/detail/items.h"

namespace dtlab::questionnaire {
namespace {

void check_item(Item& item, const DesignNames&, Problems& problems) {
  const auto points = static_cast<std::size_t>(item.integer("points"));
  const auto labels = item.strings("labels").size();
  if (labels != points && labels != 2)
    problems.error("labels", "has " + std::to_string(labels) + " entries; expected one per point (" +
                                 std::to_string(points) + ") or two (the ends)");
}

NumberPair scale_bounds(const Item& item) {
  const double first = static_cast<double>(item.integer("first"));
  return {first, first + static_cast<double>(item.integer("points")) - 1};
}

Result<StoredValue> encode_answer(const Question& q, const Answer& a, const EncodeContext&) {
  const NumberPair b = scale_bounds(*q.item);
  const double* v = std::get_if<double>(&a);
  if (!v || *v != std::floor(*v) || *v < b.min || *v > b.max)
    return detail::answer_error(q, "expected a point in [" + detail::num(b.min) + ", " + detail::num(b.max) + "]");
  return StoredValue{*v};
}

Answer simulate_answer(const Question& q, Experience& e) {
  const NumberPair b = scale_bounds(*q.item);
  return detail::ease_point(b.min, b.max, 1.0, q, e);
}

std::string value_text(const Item& item, const StoredValue& v) {
  const double* x = std::get_if<double>(&v);
  if (!x) return "";
  const NumberPair b = scale_bounds(item);
  const auto& labels = item.strings("labels");
  const auto points = static_cast<std::size_t>(item.integer("points"));
  const double k = *x - b.min;
  if (k < 0 || k > b.max - b.min) return "";
  const auto i = static_cast<std::size_t>(k);
  if (labels.size() == points) return labels[i];
  if (i == 0) return labels.front();
  return i + 1 == points ? labels.back() : "";
}

}  // namespace

const ItemType& item_type_likert() {
  static const ItemType t = [] {
    ItemType t;
    t.name = "likert";
    t.summary = "one of a row of labelled points (buttons or digit keys)";
    t.keys = {
        KeySpec::of("points", KeyKind::integer).needed().within(2, 11),
        KeySpec::of("labels", KeyKind::strings).needed().within(2, 11).shown_only(),
        KeySpec::of("first", KeyKind::integer).within(-100, 100).or_else(std::int64_t{1}),
    };
    t.measure = Measure::ordinal;
    t.check = check_item;
    t.encode = encode_answer;
    t.simulate = simulate_answer;
    t.bounds = scale_bounds;
    t.label = value_text;
    return t;
  }();
  return t;
}

}  // namespace dtlab::questionnaire

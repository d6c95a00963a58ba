// Item type "slider": a visual analogue scale, a number on `range` (default
// [0, 100]) in steps of `step` from its lower end (default 1), with an
// optional label at each end (`anchors`). Stored: the number. Simulated: from
// how easy the occasion's condition felt (docs/sim.md), on the slider's scale.
#include <cmath>

#include "study/questionnaire/detail/items.h"

namespace dtlab::questionnaire {
namespace {

void check_item(Item& item, const DesignNames&, Problems& problems) {
  const NumberPair r = item.range("range");
  const double step = item.number("step");
  if (step > r.max - r.min)
    problems.error("step", "step " + detail::num(step) + " is wider than the range [" + detail::num(r.min) + ", " +
                               detail::num(r.max) + "]");
  if (item.written.count("anchors") && item.strings("anchors").size() != 2)
    problems.error("anchors", "expected two labels: the left end's and the right end's");
}

// Whether v lies on the slider's grid: min + k x step (to 1e-9 of a step).
bool on_grid(double v, const NumberPair& r, double step) {
  const double k = (v - r.min) / step;
  return std::abs(k - std::round(k)) <= 1e-9;
}

Result<StoredValue> encode_answer(const Question& q, const Answer& a, const EncodeContext&) {
  const NumberPair r = q.item->range("range");
  const double step = q.item->number("step");
  const std::string expected = "a number in [" + detail::num(r.min) + ", " + detail::num(r.max) + "] in steps of " +
                               detail::num(step);
  auto v = detail::number_answer(q, a, expected);
  if (!v) return v.error();
  if (*v < r.min || *v > r.max || !on_grid(*v, r, step)) return detail::answer_error(q, "expected " + expected);
  return StoredValue{*v};
}

Answer simulate_answer(const Question& q, Experience& e) {
  const NumberPair r = q.item->range("range");
  return detail::ease_point(r.min, r.max, q.item->number("step"), q, e);
}

NumberPair scale_bounds(const Item& item) { return item.range("range"); }

}  // namespace

const ItemType& item_type_slider() {
  static const ItemType t = [] {
    ItemType t;
    t.name = "slider";
    t.summary = "a number on a visual analogue scale (drag, arrow keys, or type the value)";
    t.keys = {
        KeySpec::of("range", KeyKind::number_range).within(-1e6, 1e6).strictly().or_else(NumberPair{0, 100}),
        KeySpec::of("step", KeyKind::number).within(1e-6, 1e6).or_else(1.0),
        KeySpec::of("anchors", KeyKind::strings).within(2, 2).shown_only(),
    };
    t.measure = Measure::interval;
    t.check = check_item;
    t.encode = encode_answer;
    t.simulate = simulate_answer;
    t.bounds = scale_bounds;
    return t;
  }();
  return t;
}

}  // namespace dtlab::questionnaire

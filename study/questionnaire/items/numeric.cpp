// Item type "numeric": a typed number in `range` with at most `decimals`
// decimals (default 0: an integer), and an optional `unit` shown beside the
// field. Stored: the number. Simulated: a value around the middle of the
// range (sd a sixth of it), rounded to the decimals: the item says nothing
// the agent could know, so it answers like someone estimating.
#include <algorithm>
#include <cmath>

#include "study/questionnaire/detail/items.h"

namespace dtlab::questionnaire {
namespace {

double scale_of(const Item& item) { return std::pow(10.0, static_cast<double>(item.integer("decimals"))); }

// The range's ends on the decimals' grid (lo > hi: no number fits).
NumberPair grid_ends(const Item& item) {
  const NumberPair r = item.range("range");
  const double s = scale_of(item);
  return {std::ceil(r.min * s - 1e-9) / s, std::floor(r.max * s + 1e-9) / s};
}

void check_item(Item& item, const DesignNames&, Problems& problems) {
  const NumberPair g = grid_ends(item);
  if (g.min > g.max)
    problems.error("range", "holds no number with " + std::to_string(item.integer("decimals")) + " decimals");
}

Result<StoredValue> encode_answer(const Question& q, const Answer& a, const EncodeContext&) {
  const NumberPair r = q.item->range("range");
  const auto decimals = q.item->integer("decimals");
  const std::string expected = "a number in [" + detail::num(r.min) + ", " + detail::num(r.max) + "] with at most " +
                               std::to_string(decimals) + " decimal" + (decimals == 1 ? "" : "s");
  auto v = detail::number_answer(q, a, expected);
  if (!v) return v.error();
  const double scaled = *v * scale_of(*q.item);
  if (*v < r.min || *v > r.max || std::abs(scaled - std::round(scaled)) > 1e-6 * std::max(1.0, std::abs(scaled)))
    return detail::answer_error(q, "expected " + expected);
  return StoredValue{*v};
}

Answer simulate_answer(const Question& q, Experience& e) {
  const NumberPair r = q.item->range("range");
  const double x = e.rng->normal(0.5 * (r.min + r.max), (r.max - r.min) / 6.0);
  const double s = scale_of(*q.item);
  const NumberPair g = grid_ends(*q.item);
  return std::clamp(std::round(x * s) / s, g.min, g.max);
}

NumberPair scale_bounds(const Item& item) { return item.range("range"); }

}  // namespace

const ItemType& item_type_numeric() {
  static const ItemType t = [] {
    ItemType t;
    t.name = "numeric";
    t.summary = "a typed number in a range";
    t.keys = {
        KeySpec::of("range", KeyKind::number_range).needed().within(-1e9, 1e9).strictly(),
        KeySpec::of("decimals", KeyKind::integer).within(0, 6).or_else(std::int64_t{0}),
        KeySpec::of("unit", KeyKind::text).or_else(std::string()).shown_only(),
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

// Item type "multiple-choice": any of `options` (toggles, number keys), at
// least and at most `select` = [min, max] of them (default: any number,
// none included); `labels` are what the participant reads. Stored: the
// chosen options joined by "\n" in option order ("" for none). Simulated:
// each option with probability 0.35, redrawn into the allowed count: the
// options mean nothing the agent could know.
#include <algorithm>

#include "study/questionnaire/detail/items.h"

namespace dtlab::questionnaire {
namespace {

// [min, max] of the selection, max capped at the number of options.
std::pair<std::size_t, std::size_t> selection(const Item& item) {
  const NumberPair s = item.range("select");
  const std::size_t n = item.strings("options").size();
  return {static_cast<std::size_t>(s.min), std::min(n, static_cast<std::size_t>(s.max))};
}

void check_item(Item& item, const DesignNames&, Problems& problems) {
  const std::size_t n = item.strings("options").size();
  if (item.written.count("labels") && item.strings("labels").size() != n)
    problems.error("labels", "has " + std::to_string(item.strings("labels").size()) + " entries; expected one per option (" +
                                 std::to_string(n) + ")");
  if (item.written.count("select") && item.range("select").min > static_cast<double>(n))
    problems.error("select", "asks for at least " + detail::num(item.range("select").min) + " of " + std::to_string(n) +
                                 " options");
}

std::vector<Question> expand_item(const Item& item, const DesignNames&) {
  Question q;
  q.item = &item;
  q.options = item.strings("options");
  return {q};
}

Result<StoredValue> encode_answer(const Question& q, const Answer& a, const EncodeContext&) {
  std::vector<std::string> chosen;
  if (const auto* list = std::get_if<std::vector<std::string>>(&a)) chosen = *list;
  else if (const auto* one = std::get_if<std::string>(&a)) chosen = {*one};
  else return detail::answer_error(q, "expected a list of the item's options");
  const auto [lo, hi] = selection(*q.item);
  std::string stored;
  std::size_t count = 0;
  for (const std::string& o : q.options) {
    const auto n = std::count(chosen.begin(), chosen.end(), o);
    if (n > 1) return detail::answer_error(q, "option \"" + o + "\" is chosen twice");
    if (n == 1) stored += (count++ ? "\n" : "") + o;
  }
  if (count != chosen.size()) return detail::answer_error(q, "expected options of the item only");
  if (count < lo || count > hi)
    return detail::answer_error(q, "expected " + std::to_string(lo) + " to " + std::to_string(hi) + " options, got " +
                                       std::to_string(count));
  return StoredValue{stored};
}

Answer simulate_answer(const Question& q, Experience& e) {
  const auto [lo, hi] = selection(*q.item);
  std::vector<std::string> chosen;
  for (int attempt = 0; attempt < 16; ++attempt) {
    chosen.clear();
    for (const std::string& o : q.options)
      if (e.rng->uniform() < 0.35) chosen.push_back(o);
    if (chosen.size() >= lo && chosen.size() <= hi) return chosen;
  }
  // Still outside after 16 draws: the first lo options (a rare, narrow `select`).
  chosen.assign(q.options.begin(), q.options.begin() + static_cast<long>(std::min(lo, q.options.size())));
  return chosen;
}

}  // namespace

const ItemType& item_type_multiple_choice() {
  static const ItemType t = [] {
    ItemType t;
    t.name = "multiple-choice";
    t.summary = "any number of options (toggles or number keys), then Next";
    t.keys = {
        KeySpec::of("options", KeyKind::strings).needed().within(2, 32),
        KeySpec::of("labels", KeyKind::strings).within(2, 32).shown_only(),
        KeySpec::of("select", KeyKind::int_range).within(0, 32).or_else(NumberPair{0, 32}),
    };
    t.measure = Measure::multiple;
    t.check = check_item;
    t.expand = expand_item;
    t.encode = encode_answer;
    t.simulate = simulate_answer;
    return t;
  }();
  return t;
}

}  // namespace dtlab::questionnaire

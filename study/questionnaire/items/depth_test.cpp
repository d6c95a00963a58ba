// Item type "depth-test": `pairs` object pairs in one static WALKTHROUGH
// view of `scenario` drawn with `rendering` (the session prepares the view
// and the key: session::depth_test_view); which of each pair is closer?
// Stored per pair ("pair=k"): 1 if the answer names the closer object, else
// 0. Simulated: the judgement the participant made by looking at the view
// (study/sim renders it and hands it in as Experience::depth_choice).
#include <algorithm>

#include "study/questionnaire/detail/items.h"

namespace dtlab::questionnaire {
namespace {

void check_item(Item& item, const DesignNames& design, Problems& problems) {
  const auto known = [&](const char* key, const std::vector<std::string>& names, const char* what) {
    const std::string& name = item.text(key);
    if (!item.written.count(key) || std::find(names.begin(), names.end(), name) != names.end()) return;
    problems.error(key, std::string("no ") + what + " named '" + name + "' (declared: " + detail::quoted_list(names) + ")");
    item.keys[key] = std::string();
  };
  known("scenario", design.scenarios, "scenario");
  known("rendering", design.renderings, "rendering");
}

std::vector<Question> expand_item(const Item& item, const DesignNames&) {
  std::vector<Question> out;
  for (int k = 1; k <= static_cast<int>(item.integer("pairs")); ++k) {
    Question q;
    q.item = &item;
    q.pair = k;
    q.scope = "pair=" + std::to_string(k);
    out.push_back(std::move(q));
  }
  return out;
}

Result<StoredValue> encode_answer(const Question& q, const Answer& a, const EncodeContext& ctx) {
  const double* num = std::get_if<double>(&a);
  if (!num || (*num != q.object_a && *num != q.object_b))
    return detail::answer_error(q, "expected the Object::id of one of the pair (" + std::to_string(q.object_a) + " or " +
                                       std::to_string(q.object_b) + ")");
  const auto closer = ctx.closer ? ctx.closer(q) : std::nullopt;
  if (!closer) return detail::answer_error(q, "no depth-test key for this pair");
  return StoredValue{static_cast<std::uint32_t>(*num) == *closer ? 1.0 : 0.0};
}

Answer simulate_answer(const Question& q, Experience& e) {
  const auto judged = e.depth_choice ? e.depth_choice(q) : std::nullopt;
  return static_cast<double>(judged ? *judged : q.object_a);
}

NumberPair scale_bounds(const Item&) { return {0, 1}; }

}  // namespace

const ItemType& item_type_depth_test() {
  static const ItemType t = [] {
    ItemType t;
    t.name = "depth-test";
    t.summary = "which object of each marked pair in a static view is closer (click A or B, or press the key)";
    t.keys = {
        KeySpec::of("scenario", KeyKind::text).needed(),
        KeySpec::of("rendering", KeyKind::text).needed(),
        KeySpec::of("pairs", KeyKind::integer).within(1, 20).or_else(std::int64_t{3}),
    };
    t.measure = Measure::correct;
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

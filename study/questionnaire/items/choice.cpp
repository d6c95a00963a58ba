// Item type "choice": one of `options`, or of the levels of `factor`, with an
// optional `neutral` option ("no preference") shown last and stored like the
// others; `labels` (parallel to options) are what the participant reads.
// Stored: the chosen option (text). Simulated: the option it rated best at
// this occasion, else the rendering level it was fastest with; equal ratings
// of the best two leave no preference (the neutral option, where there is one).
#include <algorithm>

#include "study/questionnaire/detail/items.h"

namespace dtlab::questionnaire {
namespace {

void check_item(Item& item, const DesignNames& design, Problems& problems) {
  const bool factor = item.written.count("factor") > 0, options = item.written.count("options") > 0;
  if (!factor && !options)
    problems.error("", "a choice needs factor = \"<factor>\" (its levels are the options) or options = [...]");
  else if (factor && options)
    problems.error("options", "give either factor or options, not both");
  if (factor) {
    const std::string& name = item.text("factor");
    std::vector<std::string> names;
    for (const auto& f : design.factors) names.push_back(f.name);
    if (const DesignNames::Factor* f = design.factor(name)) item.keys["options"] = f->levels;
    else problems.error("factor", "no factor named '" + name + "' (declared: " + detail::quoted_list(names) + ")");
    if (item.written.count("labels"))
      problems.error("labels", "the options of a factor are its levels; label them with the factor's labels");
  }
  auto opts = item.strings("options");
  if (item.written.count("labels") && !factor && item.strings("labels").size() != opts.size())
    problems.error("labels", "has " + std::to_string(item.strings("labels").size()) + " entries; expected one per option (" +
                                 std::to_string(opts.size()) + ")");
  if (item.written.count("neutral")) {
    const std::string& neutral = item.text("neutral");
    if (std::find(opts.begin(), opts.end(), neutral) != opts.end()) {
      problems.error("neutral", "\"" + neutral + "\" is already one of the options; the neutral option must differ");
      item.keys["neutral"] = std::string();
    } else {
      opts.push_back(neutral);
      item.keys["options"] = opts;
    }
  }
}

std::vector<Question> expand_item(const Item& item, const DesignNames&) {
  Question q;
  q.item = &item;
  q.options = item.strings("options");  // a factor's levels (the check copied them), then the neutral one
  return {q};
}

Result<StoredValue> encode_answer(const Question& q, const Answer& a, const EncodeContext&) {
  const std::string* text = std::get_if<std::string>(&a);
  if (!text || std::find(q.options.begin(), q.options.end(), *text) == q.options.end())
    return detail::answer_error(q, "expected one of the item's options");
  return StoredValue{*text};
}

// The reference study's preference (docs/sim.md), kept draw for draw.
Answer simulate_answer(const Question& q, Experience& e) {
  const std::string rendering = e.design ? e.design->rendering_factor : "";
  const std::string& neutral = q.item->text("neutral");
  // The ratings given so far at this occasion, per level of the rendering factor.
  std::map<std::string, std::vector<double>> rating_of_level;
  for (const auto& [gq, answer] : e.given) {
    if (gq->item->type->measure != Measure::ordinal || !std::holds_alternative<double>(answer)) continue;
    for (const auto& [factor, level] : gq->levels)
      if (factor == rendering) rating_of_level[level].push_back(std::get<double>(answer));
  }
  std::string best;
  double best_score = -1e300;
  bool tied = false;
  for (const std::string& o : q.options) {
    if (o == neutral) continue;
    double score = -1e300;
    if (auto it = rating_of_level.find(o); it != rating_of_level.end() && !it->second.empty()) {
      score = 0;
      for (double r : it->second) score += r;
      score /= static_cast<double>(it->second.size());
    } else if (!rendering.empty()) {
      const detail::CellTimes c = detail::cell_times(e.history, {{rendering, o}}, "");
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
  if (tied && !neutral.empty()) best = neutral;
  else if (best.empty() || best_score == -1e300) best = q.options[e.rng->below(q.options.size())];
  return best;
}

std::string value_text(const Item& item, const StoredValue& v) {
  const std::string* text = std::get_if<std::string>(&v);
  if (!text) return "";
  const auto& options = item.strings("options");
  const auto& labels = item.strings("labels");
  const auto it = std::find(options.begin(), options.end(), *text);
  const auto i = static_cast<std::size_t>(it - options.begin());
  return it != options.end() && i < labels.size() ? labels[i] : "";
}

}  // namespace

const ItemType& item_type_choice() {
  static const ItemType t = [] {
    ItemType t;
    t.name = "choice";
    t.summary = "one option (buttons or number keys), the neutral one included";
    t.keys = {
        KeySpec::of("factor", KeyKind::text),
        KeySpec::of("options", KeyKind::strings).within(2, 32),
        KeySpec::of("neutral", KeyKind::text).or_else(std::string()),
        KeySpec::of("labels", KeyKind::strings).within(2, 32).shown_only(),
    };
    t.measure = Measure::nominal;
    t.check = check_item;
    t.expand = expand_item;
    t.encode = encode_answer;
    t.simulate = simulate_answer;
    t.label = value_text;
    return t;
  }();
  return t;
}

}  // namespace dtlab::questionnaire

// Item type "text": free text in any script (UTF-8), at most `max_length`
// characters (Unicode code points), in a box of `lines` lines; empty unless
// `required`. Stored: the text as typed (line breaks kept). Simulated: a
// short comment about the conditions it did best and worst in, or nothing,
// by the participant's talkativeness (docs/sim.md).
#include <algorithm>

#include "study/common/text.h"
#include "study/questionnaire/detail/items.h"

namespace dtlab::questionnaire {
namespace {

// Code points of valid UTF-8 without control characters other than line breaks and tabs; nullopt otherwise.
std::optional<std::size_t> code_points(const std::string& s) {
  const auto decoded = utf8_decode(s);
  if (!decoded) return std::nullopt;
  for (const char32_t c : *decoded)
    if (c < 0x20 && c != U'\n' && c != U'\t') return std::nullopt;
  return decoded->size();
}

Result<StoredValue> encode_answer(const Question& q, const Answer& a, const EncodeContext&) {
  const std::string* text = std::get_if<std::string>(&a);
  const auto max = static_cast<std::size_t>(q.item->integer("max_length"));
  if (!text) return detail::answer_error(q, "expected a text");
  const auto n = code_points(*text);
  if (!n) return detail::answer_error(q, "expected UTF-8 text without control characters (line breaks and tabs are kept)");
  if (*n > max)
    return detail::answer_error(q, "the text has " + std::to_string(*n) + " characters; at most " + std::to_string(max) +
                                       " are allowed");
  if (q.item->boolean("required") && text->find_first_not_of(" \t\n") == std::string::npos)
    return detail::answer_error(q, "an answer is required");
  return StoredValue{*text};
}

// The compared factor's levels it was fastest and slowest with, from its own trials so far.
std::pair<std::string, std::string> best_and_worst(const Experience& e) {
  const std::string factor = e.design ? e.design->rendering_factor : "";
  const DesignNames::Factor* f = e.design && !factor.empty() ? e.design->factor(factor) : nullptr;
  if (!f && e.design && !e.design->factors.empty()) f = &e.design->factors.front();
  if (!f) return {};
  std::string best, worst;
  double lo = 1e300, hi = -1e300;
  for (const std::string& level : f->levels) {
    const detail::CellTimes c = detail::cell_times(e.history, {{f->name, level}}, "");
    if (c.n == 0) continue;
    if (c.mean < lo) lo = c.mean, best = level;
    if (c.mean > hi) hi = c.mean, worst = level;
  }
  return {best, worst == best ? "" : worst};
}

Answer simulate_answer(const Question& q, Experience& e) {
  // Talkativeness: a participant constant (from its seed); about a third leave the box empty.
  Stream traits(mix64(e.seed, 0x74616c6bULL));  // "talk"
  const bool talks = traits.uniform() < 0.65 || q.item->boolean("required");
  const double u = e.rng->uniform();
  if (!talks) return std::string();
  const auto [best, worst] = best_and_worst(e);
  std::string text;
  if (best.empty()) text = u < 0.5 ? "No comments." : "It was fine.";
  else if (worst.empty()) text = "It went well with " + best + ".";
  else if (u < 0.5) text = "Easiest with " + best + "; " + worst + " took me longer.";
  else text = "I found things faster with " + best + " than with " + worst + ".";
  const auto max = static_cast<std::size_t>(q.item->integer("max_length"));
  if (text.size() > max) text.resize(max);  // ASCII: bytes are characters
  return text;
}

}  // namespace

const ItemType& item_type_text() {
  static const ItemType t = [] {
    ItemType t;
    t.name = "text";
    t.summary = "free text typed into a box (any script), then Next";
    t.keys = {
        KeySpec::of("max_length", KeyKind::integer).within(1, 10000).or_else(std::int64_t{500}),
        KeySpec::of("lines", KeyKind::integer).within(1, 20).or_else(std::int64_t{3}).shown_only(),
        KeySpec::of("required", KeyKind::boolean).or_else(false),
    };
    t.measure = Measure::text;
    t.encode = encode_answer;
    t.simulate = simulate_answer;
    return t;
  }();
  return t;
}

}  // namespace dtlab::questionnaire

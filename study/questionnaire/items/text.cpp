// Item type "text": free text in any script (UTF-8), at most `max_length`
// characters (Unicode code points), in a box of `lines` lines; empty unless
// `required`. Stored: the text as typed (line breaks kept). Simulated: a
// short comment about the conditions it did best and worst in, or nothing,
// by the participant's talkativeness (docs/sim.md).
#include <algorithm>

#include "study/questionnaire/detail/items.h"

namespace dtlab::questionnaire {
namespace {

// Code points of valid UTF-8 (no overlongs, surrogates or values past U+10FFFF); nullopt if invalid.
std::optional<std::size_t> code_points(const std::string& s) {
  std::size_t n = 0;
  for (std::size_t i = 0; i < s.size(); ++n) {
    const auto c = static_cast<unsigned char>(s[i]);
    std::size_t len = c < 0x80 ? 1 : (c >> 5) == 0x6 ? 2 : (c >> 4) == 0xE ? 3 : (c >> 3) == 0x1E ? 4 : 0;
    if (len == 0 || i + len > s.size()) return std::nullopt;
    std::uint32_t cp = len == 1 ? c : len == 2 ? c & 0x1F : len == 3 ? c & 0x0F : c & 0x07;
    for (std::size_t k = 1; k < len; ++k) {
      const auto cc = static_cast<unsigned char>(s[i + k]);
      if ((cc >> 6) != 0x2) return std::nullopt;
      cp = (cp << 6) | (cc & 0x3F);
    }
    const std::uint32_t least[] = {0, 0, 0x80, 0x800, 0x10000};
    if (cp < least[len] || cp > 0x10FFFF || (cp >= 0xD800 && cp <= 0xDFFF)) return std::nullopt;
    if (cp < 0x20 && cp != '\n' && cp != '\t') return std::nullopt;  // control characters other than line breaks, tabs
    i += len;
  }
  return n;
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

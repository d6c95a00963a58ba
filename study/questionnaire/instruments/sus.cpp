// Instrument "sus": the System Usability Scale (Brooke 1996): ten statements
// in Brooke's wording, each a five-point Likert item from 1 "Strongly
// disagree" to 5 "Strongly agree" (only the ends labelled, as on the form).
// Scale: the SUS score 0..100: odd (positive) items contribute the answer
// minus 1, even (negative) items 5 minus the answer, and the sum of the ten
// contributions (0..40) is multiplied by 2.5 (Brooke 1996, "Scoring SUS").
#include <algorithm>
#include <array>
#include <cmath>

#include "study/questionnaire/detail/items.h"

namespace dtlab::questionnaire {
namespace {

// Brooke (1996), Figure 1.
constexpr std::array<const char*, 10> kStatements{
    "I think that I would like to use this system frequently.",
    "I found the system unnecessarily complex.",
    "I thought the system was easy to use.",
    "I think that I would need the support of a technical person to be able to use this system.",
    "I found the various functions in this system were well integrated.",
    "I thought there was too much inconsistency in this system.",
    "I would imagine that most people would learn to use this system very quickly.",
    "I found the system very cumbersome to use.",
    "I felt very confident using the system.",
    "I needed to learn a lot of things before I could get going with this system.",
};

std::string sub(std::size_t i) { return "q" + std::to_string(i + 1); }

std::vector<Item> items(const Keys&) {
  std::vector<Item> out;
  for (std::size_t i = 0; i < kStatements.size(); ++i) {
    Item it;
    it.sub = sub(i);
    it.type = find_item_type("likert");
    it.prompt = kStatements[i];
    it.keys = {{"points", std::int64_t{5}},
               {"labels", std::vector<std::string>{"Strongly disagree", "Strongly agree"}},
               {"first", std::int64_t{1}}};
    out.push_back(std::move(it));
  }
  return out;
}

std::vector<Scale> scales(const Keys&) { return {{"score", "SUS score", 0, 100}}; }

std::vector<std::optional<double>> score(const Keys&, const SubAnswers& answers) {
  double sum = 0;
  for (std::size_t i = 0; i < kStatements.size(); ++i) {
    const auto it = answers.find(sub(i));
    const double* v = it == answers.end() ? nullptr : std::get_if<double>(&it->second);
    if (!v || *v != std::floor(*v) || *v < 1 || *v > 5) return {std::nullopt};
    sum += i % 2 == 0 ? *v - 1 : 5 - *v;  // items 1, 3, 5, 7, 9 are positive; 2, 4, 6, 8, 10 negative
  }
  return {sum * 2.5};
}

// docs/sim.md, "Instruments": how usable the system felt falls with how much slower than its
// own average the participant was in the occasion's condition and with the trials it left
// unanswered; agreement with positive statements rises with it, with negative ones falls.
Answer simulate_answer(const Item& item, const Question& q, Experience& e) {
  Stream traits(mix64(e.seed, 0x737573ULL));  // "sus": a participant's leniency
  const double leniency = traits.normal(0.0, 0.3);
  const auto s = detail::strain_of(detail::condition_of(q, e), e);
  const double usability = -std::tanh(1.5 * (s ? s->strain : 0.0)) - (s ? s->unanswered : 0.0) + leniency;
  const int index = std::atoi(item.sub.c_str() + 1) - 1;  // "q3" -> 2
  const double agree = 3.0 + (index % 2 == 0 ? 1.6 : -1.6) * usability + e.rng->normal(0.0, 0.7);
  return std::clamp(std::round(agree), 1.0, 5.0);
}

}  // namespace

const Instrument& instrument_sus() {
  static const Instrument i = [] {
    Instrument i;
    i.name = "sus";
    i.title = "System Usability Scale (SUS)";
    i.citation = "Brooke (1996), SUS: a \"quick and dirty\" usability scale";
    i.items = items;
    i.scales = scales;
    i.score = score;
    i.simulate = simulate_answer;
    return i;
  }();
  return i;
}

}  // namespace dtlab::questionnaire

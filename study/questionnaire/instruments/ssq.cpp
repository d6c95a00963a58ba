// Instrument "ssq": the Simulator Sickness Questionnaire (Kennedy, Lane,
// Berbaum & Lilienthal 1993): 16 symptoms, each rated 0 None, 1 Slight,
// 2 Moderate, 3 Severe ("how much is each symptom affecting you right
// now?"). Scales (Kennedy et al. 1993, Table 1 and its scoring): the raw sum
// of each subscale's seven symptoms times its weight: Nausea x 9.54,
// Oculomotor x 7.58, Disorientation x 13.92, and the Total Score: the sum of
// the three raw sums x 3.74 (a symptom in two subscales counts in both).
#include <algorithm>
#include <array>
#include <cmath>

#include "study/questionnaire/detail/items.h"

namespace dtlab::questionnaire {
namespace {

struct Symptom {
  const char* sub;
  const char* name;
  bool n, o, d;      // subscale membership: nausea, oculomotor, disorientation
  double base_rate;  // simulation: how often a susceptible participant reports it (docs/sim.md)
};

// Kennedy et al. (1993), in the questionnaire's order, with the subscales each symptom is scored in.
constexpr std::array<Symptom, 16> kSymptoms{{
    {"general_discomfort", "General discomfort", true, true, false, 0.30},
    {"fatigue", "Fatigue", false, true, false, 0.35},
    {"headache", "Headache", false, true, false, 0.15},
    {"eyestrain", "Eye strain", false, true, false, 0.40},
    {"difficulty_focusing", "Difficulty focusing", false, true, true, 0.20},
    {"increased_salivation", "Increased salivation", true, false, false, 0.05},
    {"sweating", "Sweating", true, false, false, 0.10},
    {"nausea", "Nausea", true, false, true, 0.08},
    {"difficulty_concentrating", "Difficulty concentrating", true, true, false, 0.20},
    {"fullness_of_head", "Fullness of head", false, false, true, 0.12},
    {"blurred_vision", "Blurred vision", false, true, true, 0.12},
    {"dizzy_eyes_open", "Dizzy (eyes open)", false, false, true, 0.10},
    {"dizzy_eyes_closed", "Dizzy (eyes closed)", false, false, true, 0.06},
    {"vertigo", "Vertigo", false, false, true, 0.05},
    {"stomach_awareness", "Stomach awareness", true, false, false, 0.08},
    {"burping", "Burping", true, false, false, 0.03},
}};

constexpr double kNausea = 9.54, kOculomotor = 7.58, kDisorientation = 13.92, kTotal = 3.74;

std::vector<Item> items(const Keys&) {
  std::vector<Item> out;
  for (const Symptom& s : kSymptoms) {
    Item it;
    it.sub = s.sub;
    it.type = find_item_type("likert");
    it.prompt = std::string(s.name) + "\nHow much is this symptom affecting you right now?";
    it.keys = {{"points", std::int64_t{4}},
               {"labels", std::vector<std::string>{"None", "Slight", "Moderate", "Severe"}},
               {"first", std::int64_t{0}}};
    out.push_back(std::move(it));
  }
  return out;
}

std::vector<Scale> scales(const Keys&) {
  // Maxima: every symptom "Severe" (3): 7 x 3 x weight, and 21 x 3 x 3.74 for the total.
  return {{"nausea", "Nausea (N)", 0, 21 * kNausea},
          {"oculomotor", "Oculomotor (O)", 0, 21 * kOculomotor},
          {"disorientation", "Disorientation (D)", 0, 21 * kDisorientation},
          {"total", "Total Score (TS)", 0, 63 * kTotal}};
}

std::vector<std::optional<double>> score(const Keys&, const SubAnswers& answers) {
  double n = 0, o = 0, d = 0;
  for (const Symptom& s : kSymptoms) {
    const auto it = answers.find(s.sub);
    const double* v = it == answers.end() ? nullptr : std::get_if<double>(&it->second);
    if (!v || *v != std::floor(*v) || *v < 0 || *v > 3) return {std::nullopt, std::nullopt, std::nullopt, std::nullopt};
    n += s.n ? *v : 0;
    o += s.o ? *v : 0;
    d += s.d ? *v : 0;
  }
  return {n * kNausea, o * kOculomotor, d * kDisorientation, (n + o + d) * kTotal};
}

// docs/sim.md, "Instruments": symptoms are rare and mild on a desktop display; a participant's
// susceptibility (lognormal, a constant of theirs) times the symptom's base rate times the time
// spent in the scenes so far (a quarter of an hour doubles it) gives the chance of "Slight", and
// a fifth of those (a tenth of those again) are "Moderate" ("Severe").
Answer simulate_answer(const Item& item, const Question&, Experience& e) {
  Stream traits(mix64(e.seed, 0x737371ULL));  // "ssq"
  const double susceptibility = std::exp(traits.normal(-0.7, 0.8));
  double minutes = 0;
  for (const PastTrial& t : e.history) minutes += t.completion_s / 60.0;
  const double u = e.rng->uniform();
  for (const Symptom& s : kSymptoms) {
    if (item.sub != s.sub) continue;
    const double p = 1.0 - std::exp(-susceptibility * s.base_rate * (0.5 + minutes / 15.0));
    return u < p * 0.02 ? 3.0 : u < p * 0.2 ? 2.0 : u < p ? 1.0 : 0.0;
  }
  return 0.0;
}

}  // namespace

const Instrument& instrument_ssq() {
  static const Instrument i = [] {
    Instrument i;
    i.name = "ssq";
    i.title = "Simulator Sickness Questionnaire (SSQ)";
    i.citation = "Kennedy, Lane, Berbaum & Lilienthal (1993), International Journal of Aviation Psychology 3(3)";
    i.items = items;
    i.scales = scales;
    i.score = score;
    i.simulate = simulate_answer;
    return i;
  }();
  return i;
}

}  // namespace dtlab::questionnaire

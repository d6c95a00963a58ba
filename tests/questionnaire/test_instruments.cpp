// The standard instruments (study/questionnaire/instrument.h): their items
// as published (count, order, subscale membership), their scoring against
// worked examples computed by hand from the published scoring rules (the
// arithmetic is written above each expected value, with its source), and
// incomplete or malformed answers giving no score. Then the simulated
// participant's answers: in range, plausible (more workload and less
// usability where it was slower; sickness mostly absent, varying between
// people).
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <numeric>

#include "study/questionnaire/instrument.h"
#include "study/questionnaire/table.h"

namespace dtlab::questionnaire {
namespace {

InstrumentUse use_of(const char* name, Keys keys = {}) {
  InstrumentUse u;
  u.id = "x";
  u.instrument = find_instrument(name);
  EXPECT_NE(u.instrument, nullptr) << name;
  for (const KeySpec& k : u.instrument->keys)
    if (!keys.count(k.name)) keys[k.name] = k.fallback;
  u.keys = std::move(keys);
  return u;
}

std::vector<std::optional<double>> score(const InstrumentUse& u, const SubAnswers& a) { return score_occasion(u, a); }

// --- NASA-TLX -------------------------------------------------------------------------------------

SubAnswers tlx_ratings(std::array<double, 6> r) {
  const char* dims[] = {"mental", "physical", "temporal", "performance", "effort", "frustration"};
  SubAnswers a;
  for (int i = 0; i < 6; ++i) a[dims[i]] = r[static_cast<std::size_t>(i)];
  return a;
}

TEST(NasaTlx, ItemsAreTheSixSubscalesThenTheFifteenPairs) {
  const auto plain = instrument_items(use_of("nasa-tlx"));
  ASSERT_EQ(plain.size(), 6u);
  const auto weighted = instrument_items(use_of("nasa-tlx", {{"weights", true}}));
  ASSERT_EQ(weighted.size(), 21u);
  std::vector<std::string> subs;
  for (const Item& i : weighted) subs.push_back(i.sub);
  EXPECT_EQ(subs[0], "mental");
  EXPECT_EQ(subs[5], "frustration");
  EXPECT_EQ(subs[6], "w.mental-physical");
  EXPECT_EQ(subs[20], "w.effort-frustration");
  for (int i = 0; i < 6; ++i) {
    EXPECT_EQ(weighted[i].type->name, "slider");
    // 21 gradations: 0..100 in steps of 5 (Hart & Staveland 1988).
    EXPECT_EQ(weighted[i].range("range"), (NumberPair{0, 100}));
    EXPECT_EQ(weighted[i].number("step"), 5.0);
    EXPECT_EQ(weighted[i].id, "x." + weighted[i].sub);
  }
  // The performance scale runs from "Perfect" to "Failure" (the official rating sheet).
  EXPECT_EQ(weighted[3].strings("anchors"), (std::vector<std::string>{"Perfect", "Failure"}));
  for (int i = 6; i < 21; ++i) EXPECT_EQ(weighted[i].type->name, "choice");
}

struct TlxCase {
  const char* what;
  std::array<double, 6> ratings;  // mental, physical, temporal, performance, effort, frustration
  std::map<std::string, std::string> won;  // pair sub -> the dimension chosen
  double raw, weighted;
};

// The 15 pairs won so that the weights are mental 5, physical 0, temporal 3, performance 2,
// effort 4, frustration 1 (a consistent ranking: mental > effort > temporal > performance >
// frustration > physical).
std::map<std::string, std::string> ranked_pairs() {
  const std::vector<std::string> dims = {"mental", "physical", "temporal", "performance", "effort", "frustration"};
  const std::map<std::string, int> rank = {{"mental", 6}, {"effort", 5}, {"temporal", 4}, {"performance", 3},
                                           {"frustration", 2}, {"physical", 1}};
  std::map<std::string, std::string> won;
  for (std::size_t a = 0; a < dims.size(); ++a)
    for (std::size_t b = a + 1; b < dims.size(); ++b)
      won["w." + dims[a] + "-" + dims[b]] = rank.at(dims[a]) > rank.at(dims[b]) ? dims[a] : dims[b];
  return won;
}

TEST(NasaTlx, RawAndWeightedScoresFollowThePublishedProcedure) {
  const auto ranked = ranked_pairs();
  const std::vector<TlxCase> cases = {
      // Raw TLX (Hart 2006): the mean of the six ratings: (70 + 10 + 40 + 30 + 60 + 20) / 6 = 230 / 6.
      // Weighted (Hart & Staveland 1988; NASA TLX manual, "weighted rating"): weights = comparisons
      // won: mental 5, physical 0, temporal 3, performance 2, effort 4, frustration 1 (sum 15);
      // (5 x 70 + 0 x 10 + 3 x 40 + 2 x 30 + 4 x 60 + 1 x 20) / 15 = (350 + 0 + 120 + 60 + 240 + 20) / 15 = 790 / 15.
      {"a ranked participant", {70, 10, 40, 30, 60, 20}, ranked, 230.0 / 6.0, 790.0 / 15.0},
      // Every rating 0 and every rating 100: the ends of both scales whatever the weights.
      {"all zero", {0, 0, 0, 0, 0, 0}, ranked, 0.0, 0.0},
      {"all hundred", {100, 100, 100, 100, 100, 100}, ranked, 100.0, 100.0},
      // A subscale that won no comparison does not count: only physical rated high, and it weighs 0:
      // raw (0 + 100 + 0 + 0 + 0 + 0) / 6 = 16.67; weighted (0 x 5 + 100 x 0 + ...) / 15 = 0.
      {"weightless subscale", {0, 100, 0, 0, 0, 0}, ranked, 100.0 / 6.0, 0.0},
      // Only mental (weight 5) at 90: weighted 5 x 90 / 15 = 30; raw 90 / 6 = 15.
      {"heaviest subscale", {90, 0, 0, 0, 0, 0}, ranked, 15.0, 30.0},
  };
  const InstrumentUse u = use_of("nasa-tlx", {{"weights", true}});
  for (const TlxCase& c : cases) {
    SubAnswers a = tlx_ratings(c.ratings);
    for (const auto& [pair, won] : c.won) a[pair] = won;
    const auto s = score(u, a);
    ASSERT_EQ(s.size(), 2u) << c.what;
    ASSERT_TRUE(s[0] && s[1]) << c.what;
    EXPECT_NEAR(*s[0], c.raw, 1e-12) << c.what;
    EXPECT_NEAR(*s[1], c.weighted, 1e-12) << c.what;
  }
}

TEST(NasaTlx, IncompleteOrMalformedAnswersScoreNothing) {
  const InstrumentUse u = use_of("nasa-tlx", {{"weights", true}});
  SubAnswers full = tlx_ratings({50, 50, 50, 50, 50, 50});
  for (const auto& [pair, won] : ranked_pairs()) full[pair] = won;
  const auto missing_rating = [&] { SubAnswers a = full; a.erase("effort"); return a; }();
  const auto missing_pair = [&] { SubAnswers a = full; a.erase("w.mental-effort"); return a; }();
  const auto foreign_winner = [&] { SubAnswers a = full; a["w.mental-effort"] = std::string("physical"); return a; }();
  const auto out_of_range = [&] { SubAnswers a = full; a["mental"] = 105.0; return a; }();
  const auto text_rating = [&] { SubAnswers a = full; a["mental"] = std::string("50"); return a; }();
  EXPECT_FALSE(score(u, missing_rating)[0]);
  EXPECT_FALSE(score(u, missing_rating)[1]);
  EXPECT_TRUE(score(u, missing_pair)[0]) << "the raw TLX needs the ratings only";
  EXPECT_FALSE(score(u, missing_pair)[1]);
  EXPECT_FALSE(score(u, foreign_winner)[1]) << "a pair won by a subscale not in it";
  EXPECT_FALSE(score(u, out_of_range)[0]);
  EXPECT_FALSE(score(u, text_rating)[0]);
  // Without weights the instrument has one scale.
  EXPECT_EQ(score(use_of("nasa-tlx"), full).size(), 1u);
}

// --- SUS ----------------------------------------------------------------------------------------------

SubAnswers sus(std::array<double, 10> v) {
  SubAnswers a;
  for (int i = 0; i < 10; ++i) a["q" + std::to_string(i + 1)] = v[static_cast<std::size_t>(i)];
  return a;
}

TEST(Sus, ItemsAreBrookesTenStatementsOnFivePoints) {
  const auto items = instrument_items(use_of("sus"));
  ASSERT_EQ(items.size(), 10u);
  EXPECT_EQ(items[0].prompt, "I think that I would like to use this system frequently.");
  EXPECT_EQ(items[9].prompt, "I needed to learn a lot of things before I could get going with this system.");
  for (const Item& i : items) {
    EXPECT_EQ(i.type->name, "likert");
    EXPECT_EQ(i.integer("points"), 5);
    EXPECT_EQ(i.integer("first"), 1);
    EXPECT_EQ(i.strings("labels"), (std::vector<std::string>{"Strongly disagree", "Strongly agree"}));
  }
}

TEST(Sus, ScoresFollowBrookesScoring) {
  // Brooke (1996), "Scoring SUS": odd items contribute (answer - 1), even items (5 - answer);
  // the sum (0..40) times 2.5.
  const InstrumentUse u = use_of("sus");
  struct Case {
    const char* what;
    std::array<double, 10> answers;
    double expected;
  };
  const std::vector<Case> cases = {
      // Best: odd 5, even 1: 5 x 4 + 5 x 4 = 40 -> 40 x 2.5 = 100.
      {"best", {5, 1, 5, 1, 5, 1, 5, 1, 5, 1}, 100.0},
      // Worst: odd 1, even 5: 0 -> 0.
      {"worst", {1, 5, 1, 5, 1, 5, 1, 5, 1, 5}, 0.0},
      // Neutral throughout: each item contributes 2: 20 x 2.5 = 50.
      {"neutral", {3, 3, 3, 3, 3, 3, 3, 3, 3, 3}, 50.0},
      // Agreeing with everything: odd 5 x 4 = 20, even 5 x 0 = 0: 20 x 2.5 = 50.
      {"acquiescent", {5, 5, 5, 5, 5, 5, 5, 5, 5, 5}, 50.0},
      // A mixed form: odd 4, 3, 5, 4, 4 -> 3 + 2 + 4 + 3 + 3 = 15; even 2, 1, 2, 3, 1 -> 3 + 4 + 3 + 2 + 4 = 16;
      // (15 + 16) x 2.5 = 77.5.
      {"mixed", {4, 2, 3, 1, 5, 2, 4, 3, 4, 1}, 77.5},
  };
  for (const Case& c : cases) {
    const auto s = score(u, sus(c.answers));
    ASSERT_EQ(s.size(), 1u);
    ASSERT_TRUE(s[0]) << c.what;
    EXPECT_EQ(*s[0], c.expected) << c.what;
  }
  auto missing = sus({3, 3, 3, 3, 3, 3, 3, 3, 3, 3});
  missing.erase("q7");
  EXPECT_FALSE(score(u, missing)[0]);
  EXPECT_FALSE(score(u, sus({3, 3, 3, 3, 3, 3, 3, 3, 3, 6}))[0]) << "6 is not a point of the scale";
  EXPECT_FALSE(score(u, sus({3, 3, 3, 3, 3, 3, 3, 3, 3, 2.5}))[0]);
}

// --- SSQ ----------------------------------------------------------------------------------------------

const std::vector<std::string> kSymptoms = {
    "general_discomfort", "fatigue",    "headache",       "eyestrain",       "difficulty_focusing", "increased_salivation",
    "sweating",           "nausea",     "difficulty_concentrating", "fullness_of_head", "blurred_vision",
    "dizzy_eyes_open",    "dizzy_eyes_closed", "vertigo", "stomach_awareness", "burping"};

SubAnswers ssq(const std::map<std::string, double>& set) {
  SubAnswers a;
  for (const auto& s : kSymptoms) a[s] = set.count(s) ? set.at(s) : 0.0;
  return a;
}

TEST(Ssq, ItemsAreTheSixteenSymptomsRatedNoneToSevere) {
  const auto items = instrument_items(use_of("ssq"));
  ASSERT_EQ(items.size(), 16u);
  for (std::size_t i = 0; i < items.size(); ++i) {
    EXPECT_EQ(items[i].sub, kSymptoms[i]);
    EXPECT_EQ(items[i].integer("points"), 4);
    EXPECT_EQ(items[i].integer("first"), 0);
    EXPECT_EQ(items[i].strings("labels"), (std::vector<std::string>{"None", "Slight", "Moderate", "Severe"}));
  }
}

TEST(Ssq, ScoresFollowKennedyEtAl1993) {
  // Kennedy, Lane, Berbaum & Lilienthal (1993), Table 1 and its scoring: N = 9.54 x the raw sum of
  // general discomfort, increased salivation, sweating, nausea, difficulty concentrating, stomach
  // awareness, burping; O = 7.58 x the sum of general discomfort, fatigue, headache, eyestrain,
  // difficulty focusing, difficulty concentrating, blurred vision; D = 13.92 x the sum of difficulty
  // focusing, nausea, fullness of head, blurred vision, dizzy (eyes open), dizzy (eyes closed),
  // vertigo; TS = 3.74 x (N raw + O raw + D raw).
  const InstrumentUse u = use_of("ssq");
  struct Case {
    const char* what;
    std::map<std::string, double> set;
    double n, o, d, ts;
  };
  const std::vector<Case> cases = {
      {"no symptom", {}, 0, 0, 0, 0},
      // General discomfort slight (1) counts in N and O: N 9.54, O 7.58, D 0, TS 3.74 x (1 + 1 + 0) = 7.48.
      {"general discomfort slight", {{"general_discomfort", 1}}, 9.54, 7.58, 0, 7.48},
      // Nausea moderate (2) counts in N and D: N 19.08, D 27.84, TS 3.74 x 4 = 14.96.
      {"nausea moderate", {{"nausea", 2}}, 19.08, 0, 27.84, 14.96},
      // Eyestrain slight (O), vertigo slight (D), burping severe (N):
      // N 3 x 9.54 = 28.62, O 7.58, D 13.92, TS 3.74 x (3 + 1 + 1) = 18.7.
      {"three subscales", {{"eyestrain", 1}, {"vertigo", 1}, {"burping", 3}}, 28.62, 7.58, 13.92, 18.7},
      // Every symptom severe: the published maxima: N 7 x 3 x 9.54 = 200.34, O 7 x 3 x 7.58 = 159.18,
      // D 7 x 3 x 13.92 = 292.32, TS 3.74 x 63 = 235.62.
      {"every symptom severe", [] { std::map<std::string, double> m; for (const auto& s : kSymptoms) m[s] = 3; return m; }(),
       200.34, 159.18, 292.32, 235.62},
  };
  for (const Case& c : cases) {
    const auto s = score(u, ssq(c.set));
    ASSERT_EQ(s.size(), 4u);
    for (const auto& v : s) ASSERT_TRUE(v) << c.what;
    EXPECT_NEAR(*s[0], c.n, 1e-9) << c.what;
    EXPECT_NEAR(*s[1], c.o, 1e-9) << c.what;
    EXPECT_NEAR(*s[2], c.d, 1e-9) << c.what;
    EXPECT_NEAR(*s[3], c.ts, 1e-9) << c.what;
  }
  // The scales' declared maxima are the same numbers.
  const auto scales = u.instrument->scales(u.keys);
  EXPECT_NEAR(scales[0].max, 200.34, 1e-9);
  EXPECT_NEAR(scales[3].max, 235.62, 1e-9);
  auto missing = ssq({});
  missing.erase("vertigo");
  EXPECT_FALSE(score(u, missing)[3]);
  EXPECT_FALSE(score(u, ssq({{"fatigue", 4}}))[0]) << "4 is not a rating";
}

}  // namespace
}  // namespace dtlab::questionnaire

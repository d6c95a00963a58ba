// Simulated answers (questionnaire::simulate, docs/sim.md "Questionnaire"):
// for every item type and instrument, over many participants, each answer is
// one its own type stores (encode takes it); and they are plausible: after a
// condition in which the participant was slower than its own average, NASA-
// TLX demands are higher and SUS lower; the SSQ is mostly "None" with
// participants differing. (That a resumed session answers as an uninterrupted
// one is tests/session/test_occasions.cpp.)
#include <gtest/gtest.h>

#include <map>

#include "study/questionnaire/instrument.h"
#include "study/questionnaire/table.h"

namespace dtlab::questionnaire {
namespace {

const DesignNames kDesign{{{"technique", {"standard", "lens"}}}, {"abstract"}, {"standard", "lens"}, "technique"};

// 8 trials under each technique; `slow` takes `factor` times as long.
std::vector<PastTrial> history(const std::string& slow, double factor) {
  std::vector<PastTrial> h;
  int pos = 0;
  for (int b = 1; b <= 2; ++b)
    for (int k = 0; k < 8; ++k) {
      const std::string level = b == 1 ? "standard" : "lens";
      h.push_back({++pos, b, "T1", {{"technique", level}}, level == slow ? 30.0 * factor : 30.0, true, false});
    }
  return h;
}

Occasion after(const std::string& level) {
  return Occasion{When::Kind::level, "technique", "technique=" + level, 0, "", {{"technique", level}}, 16};
}

// Every answer of participant `seed` to the items of `items` at `o`.
std::vector<Answer> answers(const std::vector<Item>& items, const Occasion& o, std::uint64_t seed,
                            const std::vector<PastTrial>& h) {
  Stream rng(seed * 7919 + 1);
  Experience e;
  e.design = &kDesign;
  e.occasion = &o;
  e.history = h;
  e.seed = seed;
  e.rng = &rng;
  std::vector<Question> qs;
  for (const Item& i : items)
    for (Question& q : expand(i, kDesign)) qs.push_back(std::move(q));
  std::vector<Answer> out;
  for (const Question& q : qs) {
    out.push_back(simulate(q, e));
    e.given.emplace_back(&q, out.back());
    EXPECT_TRUE(encode(q, out.back()).ok()) << q.item->id << ": " << encode(q, out.back()).error().to_string();
  }
  return out;
}

std::vector<Item> instrument(const char* name, Keys keys = {}) {
  InstrumentUse u;
  u.id = name;
  u.instrument = find_instrument(name);
  for (const KeySpec& k : u.instrument->keys)
    if (!keys.count(k.name)) keys[k.name] = k.fallback;
  u.keys = keys;
  u.when = When{When::Kind::level, "technique"};
  return instrument_items(u);
}

Item plain(const char* type, Keys keys) {
  Item i;
  i.id = type;
  i.type = find_item_type(type);
  for (const KeySpec& k : i.type->keys)
    if (!keys.count(k.name)) keys[k.name] = k.fallback;
  i.keys = std::move(keys);
  i.when = When{When::Kind::level, "technique"};
  return i;
}

TEST(SimulatedAnswers, EveryTypeAnswersWhatItStores) {
  using S = std::vector<std::string>;
  std::vector<Item> items = {
      plain("rating", {{"scale", NumberPair{1, 7}}}),
      plain("likert", {{"points", std::int64_t{7}}, {"labels", S{"no", "yes"}}}),
      plain("slider", {{"range", NumberPair{-5, 5}}, {"step", 0.5}}),
      plain("choice", {{"options", S{"a", "b", "c"}}}),
      plain("multiple-choice", {{"options", S{"a", "b", "c", "d"}}, {"select", NumberPair{2, 3}}}),
      plain("numeric", {{"range", NumberPair{0.05, 0.95}}, {"decimals", std::int64_t{1}}}),
      plain("text", {{"max_length", std::int64_t{20}}}),
  };
  for (const char* name : {"nasa-tlx", "sus", "ssq"})
    for (Item& i : instrument(name, std::string(name) == "nasa-tlx" ? Keys{{"weights", true}} : Keys{})) items.push_back(i);
  std::size_t questions = 0;
  for (const Item& i : items) questions += expand(i, kDesign).size();
  ASSERT_EQ(questions, 7u + 6 + 15 + 10 + 16);  // the plain items, then the TLX with weights, SUS, SSQ
  // answers() holds each answer to the item type's own check (encode); every question gets one.
  for (std::uint64_t p = 0; p < 40; ++p)
    for (const char* level : {"standard", "lens"})
      EXPECT_EQ(answers(items, after(level), p, history("lens", 1.5)).size(), questions) << "participant " << p;
}

double mean_tlx(std::uint64_t p, const std::string& level, const std::vector<PastTrial>& h) {
  const auto items = instrument("nasa-tlx");
  const auto a = answers(items, after(level), p, h);
  double sum = 0;
  for (const Answer& x : a) sum += std::get<double>(x);
  return sum / 6;
}

TEST(SimulatedAnswers, WorkloadIsHigherAndUsabilityLowerWhereTheParticipantWasSlower) {
  const auto h = history("lens", 2.0);  // twice as long with the lens
  const auto sus_items = instrument("sus");
  const InstrumentUse sus{"sus", find_instrument("sus"), {}, {}, {}};
  int tlx_higher = 0, sus_lower = 0;
  const int n = 40;
  for (std::uint64_t p = 0; p < n; ++p) {
    tlx_higher += mean_tlx(p, "lens", h) > mean_tlx(p, "standard", h);
    std::map<std::string, double> score;
    for (const char* level : {"standard", "lens"}) {
      const auto a = answers(sus_items, after(level), p, h);
      SubAnswers subs;
      for (std::size_t i = 0; i < a.size(); ++i) subs[sus_items[i].sub] = std::get<double>(a[i]);
      score[level] = *score_occasion(sus, subs)[0];
    }
    sus_lower += score["lens"] < score["standard"];
  }
  // Each participant's own noise may reverse a difference; most must follow it.
  EXPECT_GE(tlx_higher, n * 9 / 10);
  EXPECT_GE(sus_lower, n * 8 / 10);
}

TEST(SimulatedAnswers, SicknessIsMostlyAbsentAndVariesBetweenParticipants) {
  const auto items = instrument("ssq");
  const InstrumentUse ssq{"ssq", find_instrument("ssq"), {}, {}, {}};
  Occasion end;
  end.after_position = 16;
  int none = 0, total = 0;
  std::map<double, int> totals;
  for (std::uint64_t p = 0; p < 60; ++p) {
    const auto a = answers(items, end, p, history("lens", 1.0));
    SubAnswers subs;
    for (std::size_t i = 0; i < a.size(); ++i) {
      const double v = std::get<double>(a[i]);
      none += v == 0;
      ++total;
      subs[items[i].sub] = v;
    }
    ++totals[*score_occasion(ssq, subs)[3]];
  }
  EXPECT_GT(none, total * 7 / 10) << "most symptoms are absent";
  EXPECT_LT(none, total) << "some are reported";
  EXPECT_GE(totals.size(), 4u) << "participants differ";
}

}  // namespace
}  // namespace dtlab::questionnaire

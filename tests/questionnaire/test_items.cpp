// The item types (study/questionnaire/questionnaire.h) through their one
// registration each: every answer a type takes is stored as the docs say and
// every answer it refuses names the item's field (table-driven per type);
// the occasions of a plan (after each task set, block, level and at the end,
// in that order); stored scopes round-trip; the tidy answer table puts
// answers under the condition their occasion followed and adds the scores.
#include <gtest/gtest.h>

#include <map>

#include "study/questionnaire/instrument.h"
#include "study/questionnaire/table.h"

namespace dtlab::questionnaire {
namespace {

Item make(const char* type, Keys keys = {}, When when = {}) {
  Item i;
  i.id = "i";
  i.type = find_item_type(type);
  EXPECT_NE(i.type, nullptr) << type;
  for (const auto& [k, v] : keys) i.written.insert(k);
  for (const KeySpec& k : i.type->keys)
    if (!keys.count(k.name)) keys[k.name] = k.fallback;
  i.keys = std::move(keys);
  i.when = std::move(when);
  return i;
}

const DesignNames kDesign{{{"technique", {"standard", "lens"}}, {"scenario", {"abstract", "walkthrough"}}},
                          {"abstract", "walkthrough"},
                          {"standard", "lens"},
                          "technique"};

struct EncodeCase {
  const char* what;
  Item item;
  Answer answer;
  std::optional<StoredValue> stored;  // nullopt: refused
  const char* message = "";           // part of the refusal's message
};

TEST(ItemTypes, EachTypeStoresWhatItTakesAndNamesTheFieldOfWhatItRefuses) {
  using S = std::vector<std::string>;
  const Item likert = make("likert", {{"points", std::int64_t{5}}, {"labels", S{"no", "yes"}}});
  const Item ssq_like = make("likert", {{"points", std::int64_t{4}}, {"labels", S{"None", "Slight", "Moderate", "Severe"}},
                                        {"first", std::int64_t{0}}});
  const Item slider = make("slider", {{"range", NumberPair{0, 100}}, {"step", 5.0}});
  const Item vas = make("slider");  // 0..100 in steps of 1
  const Item multi = make("multiple-choice", {{"options", S{"a", "b", "c"}}, {"select", NumberPair{1, 2}}});
  const Item numeric = make("numeric", {{"range", NumberPair{0, 168}}, {"decimals", std::int64_t{1}}});
  const Item text = make("text", {{"max_length", std::int64_t{5}}});
  const Item required = make("text", {{"required", true}});
  const Item rating = make("rating", {{"scale", NumberPair{1, 7}}});
  const std::vector<EncodeCase> cases = {
      {"likert point", likert, 4.0, StoredValue{4.0}},
      {"likert below", likert, 0.0, std::nullopt, "[1, 5]"},
      {"likert fraction", likert, 2.5, std::nullopt, "point"},
      {"likert text", likert, std::string("4"), std::nullopt, "point"},
      {"likert from 0", ssq_like, 0.0, StoredValue{0.0}},
      {"likert from 0, past the end", ssq_like, 4.0, std::nullopt, "[0, 3]"},
      {"slider on its grid", slider, 35.0, StoredValue{35.0}},
      {"slider between steps", slider, 37.0, std::nullopt, "steps of 5"},
      {"slider past its end", slider, 105.0, std::nullopt, "[0, 100]"},
      {"slider not finite", slider, std::nan(""), std::nullopt, "[0, 100]"},
      {"visual analogue scale", vas, 73.0, StoredValue{73.0}},
      {"multiple choice, two", multi, S{"c", "a"}, StoredValue{std::string("a\nc")}},  // option order
      {"multiple choice, one as text", multi, std::string("b"), StoredValue{std::string("b")}},
      {"multiple choice, none", multi, S{}, std::nullopt, "1 to 2 options, got 0"},
      {"multiple choice, three", multi, S{"a", "b", "c"}, std::nullopt, "1 to 2 options, got 3"},
      {"multiple choice, twice", multi, S{"a", "a"}, std::nullopt, "chosen twice"},
      {"multiple choice, foreign", multi, S{"d"}, std::nullopt, "options of the item only"},
      {"numeric", numeric, 12.5, StoredValue{12.5}},
      {"numeric, too many decimals", numeric, 12.25, std::nullopt, "at most 1 decimal"},
      {"numeric, out of range", numeric, 169.0, std::nullopt, "[0, 168]"},
      {"text, Greek", text, std::string("καλό"), StoredValue{std::string("καλό")}},  // 4 characters, 8 bytes
      {"text, Cyrillic 5", text, std::string("добро"), StoredValue{std::string("добро")}},
      {"text, 6 characters", text, std::string("zażółć"), std::nullopt, "6 characters; at most 5"},
      {"text, empty", text, std::string(), StoredValue{std::string()}},
      {"text, invalid UTF-8", text, std::string("\xc3\x28"), std::nullopt, "UTF-8"},
      {"text, overlong UTF-8", text, std::string("\xc0\xaf"), std::nullopt, "UTF-8"},
      {"text, a control character", text, std::string("a\x07"), std::nullopt, "control"},
      {"text, line breaks kept", required, std::string("a\nb"), StoredValue{std::string("a\nb")}},
      {"text, required but blank", required, std::string(" \n"), std::nullopt, "required"},
      {"rating", rating, 7.0, StoredValue{7.0}},
      {"rating below", rating, 0.0, std::nullopt, "[1, 7]"},
  };
  for (const EncodeCase& c : cases) {
    std::vector<Question> qs = expand(c.item, kDesign);
    ASSERT_EQ(qs.size(), 1u) << c.what;
    auto stored = encode(qs[0], c.answer);
    if (c.stored) {
      ASSERT_TRUE(stored.ok()) << c.what << ": " << stored.error().to_string();
      EXPECT_EQ(stored.value(), *c.stored) << c.what;
    } else {
      ASSERT_FALSE(stored.ok()) << c.what;
      EXPECT_EQ(stored.error().field, "questionnaire.i") << c.what;
      EXPECT_NE(stored.error().message.find(c.message), std::string::npos) << c.what << ": " << stored.error().message;
    }
  }
}

TEST(ItemTypes, LabelsForTheExport) {
  using S = std::vector<std::string>;
  const Item ends = make("likert", {{"points", std::int64_t{5}}, {"labels", S{"no", "yes"}}});
  EXPECT_EQ(value_label(ends, 1.0), "no");
  EXPECT_EQ(value_label(ends, 3.0), "");
  EXPECT_EQ(value_label(ends, 5.0), "yes");
  const Item each = make("likert", {{"points", std::int64_t{3}}, {"labels", S{"a", "b", "c"}}, {"first", std::int64_t{0}}});
  EXPECT_EQ(value_label(each, 1.0), "b");
  EXPECT_EQ(value_label(each, 7.0), "");
  const Item choice = make("choice", {{"options", S{"mental", "effort"}}, {"labels", S{"Mental Demand", "Effort"}}});
  EXPECT_EQ(value_label(choice, std::string("effort")), "Effort");
  EXPECT_EQ(value_label(make("slider"), 50.0), "");
}

// A plan of 2 blocks x 2 tasks x 2 trials under technique (blocks) and scenario.
std::vector<PlanPoint> plan() {
  std::vector<PlanPoint> p;
  int pos = 0;
  for (int b = 1; b <= 2; ++b)
    for (const char* task : {"T1", "T2"})
      for (int k = 0; k < 2; ++k)
        p.push_back({++pos, b, task, {{"technique", b == 1 ? "lens" : "standard"}, {"scenario", "abstract"}}});
  return p;
}

TEST(Occasions, ComeAfterTheirTaskSetsBlocksLevelsAndTheEndInOrder) {
  const std::vector<Item> items = {make("slider", {}, When{When::Kind::task, ""}), make("slider", {}, When{When::Kind::block, ""}),
                                   make("slider", {}, When{When::Kind::level, "technique"}), make("slider")};
  const auto got = occasions(items, plan(), {"technique", "scenario"});
  std::vector<std::string> seen;
  for (const Occasion& o : got) seen.push_back(std::to_string(o.after_position) + " " + to_string(When{o.kind, o.factor}) + " " + o.scope);
  EXPECT_EQ(seen, (std::vector<std::string>{
                      "2 task block=1;task=T1", "4 task block=1;task=T2", "4 block block=1", "4 level:technique technique=lens",
                      "6 task block=2;task=T1", "8 task block=2;task=T2", "8 block block=2",
                      "8 level:technique technique=standard", "8 end "}));
  // A block's occasion carries its condition; a level's only its factor's level.
  EXPECT_EQ(got[2].levels, (std::vector<std::pair<std::string, std::string>>{{"technique", "lens"}, {"scenario", "abstract"}}));
  EXPECT_EQ(got[3].levels, (std::vector<std::pair<std::string, std::string>>{{"technique", "lens"}}));
  EXPECT_EQ(got[0].task, "T1");
  // Only the kinds some item asks at.
  EXPECT_EQ(occasions(std::vector<Item>{make("slider")}, plan(), {"technique"}).size(), 1u);
  EXPECT_TRUE(occasions(std::vector<Item>{}, plan(), {"technique"}).empty());
}

TEST(Occasions, ScopesJoinAndSplitBack) {
  Item rating = make("rating", {{"per", std::vector<std::string>{"scenario"}}});
  const auto qs = expand(rating, kDesign);
  ASSERT_EQ(qs.size(), 2u);
  EXPECT_EQ(stored_scope(Occasion{}, qs[1]), "scenario=walkthrough");
  Item depth = make("depth-test", {{"scenario", std::string("walkthrough")}, {"rendering", std::string("lens")}},
                    When{When::Kind::task, ""});
  const auto pairs = expand(depth, kDesign);
  ASSERT_EQ(pairs.size(), 3u);
  Occasion task{When::Kind::task, "", "block=2;task=T1", 2, "T1", {}, 6};
  const std::string s = stored_scope(task, pairs[2]);
  EXPECT_EQ(s, "block=2;task=T1;pair=3");
  EXPECT_EQ(split_scope(depth, s), (std::pair<std::string, std::string>{"block=2;task=T1", "pair=3"}));
  Item block = make("slider", {}, When{When::Kind::block, ""});
  EXPECT_EQ(split_scope(block, "block=12"), (std::pair<std::string, std::string>{"block=12", ""}));
  EXPECT_EQ(split_scope(rating, "scenario=abstract"), (std::pair<std::string, std::string>{"", "scenario=abstract"}));
  EXPECT_EQ(parse_when("level:technique"), (std::optional<When>{When{When::Kind::level, "technique"}}));
  EXPECT_EQ(parse_when("level:"), std::nullopt);
  EXPECT_EQ(parse_when("Block"), std::nullopt);
}

TEST(AnswerTable, RowsFollowTheirOccasionsConditionsWithScoresAfterTheInstrument) {
  InstrumentUse sus;
  sus.id = "sus";
  sus.instrument = find_instrument("sus");
  sus.when = When{When::Kind::level, "technique"};
  std::vector<Item> items = instrument_items(sus);
  for (const Item& i : items) sus.items.push_back(i.id);
  items.push_back(make("text", {}, When{}));
  items.back().id = "comment";
  std::vector<StoredAnswer> answers;
  for (int q = 1; q <= 10; ++q) {
    answers.push_back({"P1", "sus.q" + std::to_string(q), "technique=standard", 3.0, "t"});
    answers.push_back({"P1", "sus.q" + std::to_string(q), "technique=lens", q % 2 ? 5.0 : 1.0, "t"});
  }
  answers.push_back({"P1", "comment", "", std::string("fine"), "t"});
  answers.push_back({"P1", "old_item", "", 2.0, "t"});  // an item the protocol no longer has
  const std::vector<ParticipantPlan> plans = {{"P1", plan()}};
  const Table t = answer_table(items, std::vector<InstrumentUse>{sus}, {"technique", "scenario"}, plans, answers);
  // 20 answers, 2 scores, the comment, the old item.
  ASSERT_EQ(t.rows.size(), 24u);
  // Lens came first in the plan (block 1): its occasion's rows first, its score after its items.
  EXPECT_EQ(t.rows[0].item, "sus.q1");
  EXPECT_EQ(t.rows[0].occasion_scope, "technique=lens");
  EXPECT_EQ(t.rows[0].levels, (std::vector<std::string>{"lens", ""}));
  EXPECT_EQ(t.rows[0].label, "Strongly agree");
  EXPECT_EQ(t.rows[10].item, "sus:score");
  EXPECT_EQ(t.rows[10].type, "score");
  EXPECT_EQ(t.rows[10].number, 100.0);  // all answers the positive extreme: 40 x 2.5
  EXPECT_EQ(t.rows[21].item, "sus:score");
  EXPECT_EQ(t.rows[21].number, 50.0);   // all 3: 20 x 2.5
  EXPECT_EQ(t.rows[21].levels, (std::vector<std::string>{"standard", ""}));
  EXPECT_EQ(t.rows[22].item, "comment");
  EXPECT_EQ(t.rows[22].occasion, "end");
  EXPECT_EQ(t.rows[22].text, std::optional<std::string>("fine"));
  EXPECT_EQ(t.rows[23].item, "old_item");
  EXPECT_EQ(t.rows[23].type, "");
  // An occasion without every item scores nothing.
  answers.erase(answers.begin());  // sus.q1 at technique=standard
  const Table partial = answer_table(items, std::vector<InstrumentUse>{sus}, {"technique", "scenario"}, plans, answers);
  int scores = 0;
  for (const auto& r : partial.rows) scores += r.type == "score";
  EXPECT_EQ(scores, 1);
}

}  // namespace
}  // namespace dtlab::questionnaire

// Trial plans: the reference protocol's 24 trials per participant and 384 for
// 16, each condition equally often at every position; seeds follow the
// documented hash (values computed independently, see below), change with the
// master seed and never with the order row; blocks of one factor with another
// nested, fixed, random and full-permutation orderings; practice trials.
#include <gtest/gtest.h>

#include <map>
#include <set>
#include <stdexcept>
#include <string>

#include "study/design/design.h"
#include "study/design/seeds.h"
#include "study/protocol/protocol.h"

namespace {

using namespace dtlab;
using namespace dtlab::design;

protocol::Protocol load(const std::string& path) {
  auto p = protocol::load_protocol(path);
  if (!p.ok()) throw std::runtime_error(p.error().to_string());
  return *p;
}

protocol::Protocol reference() { return load(DTLAB_SOURCE_DIR "/protocols/elmqvist2008.toml"); }

protocol::Protocol from_text(const std::string& text) {
  auto p = protocol::load_protocol_text(text, "test.toml");
  if (!p.ok()) throw std::runtime_error(p.error().to_string());
  return *p;
}

std::string condition_of(const PlannedTrial& t) {
  std::string s;
  for (const auto& [f, l] : t.levels) s += (s.empty() ? "" : "/") + l;
  return s;
}

TEST(ReferencePlan, HasTwentyFourTrialsInFourBlocksOfSix) {
  const auto p = reference();
  EXPECT_EQ(order_rows(p), 4);
  const Plan plan = make_plan(p, 0);
  EXPECT_EQ(plan.protocol_id, "elmqvist2008");
  EXPECT_EQ(plan.index, 0);
  EXPECT_EQ(plan.order_row, 0);
  ASSERT_EQ(plan.trials.size(), 24u);
  for (int i = 0; i < 24; ++i) {
    const PlannedTrial& t = plan.trials[i];
    EXPECT_EQ(t.position, i + 1);
    EXPECT_EQ(t.block, i / 6 + 1);
    EXPECT_EQ(t.trial, i % 3 + 1);
    EXPECT_FALSE(t.practice);
    ASSERT_EQ(t.levels.size(), 2u);
    EXPECT_EQ(t.levels[0].first, "transparency");
    EXPECT_EQ(t.levels[1].first, "scenario");
    // Within a block: the scenario's two tasks in order, 3 trials each.
    const bool abstract = t.levels[1].second == "abstract";
    EXPECT_EQ(t.task, (i % 6 < 3) ? (abstract ? "T1" : "T3") : (abstract ? "T2" : "T4"));
    // The rendering method follows the transparency level.
    EXPECT_EQ(t.method, t.levels[0].second == "on" ? "dt-seed" : "standard");
    // Every trial of a block has the block's condition.
    EXPECT_EQ(condition_of(t), condition_of(plan.trials[(i / 6) * 6]));
  }
}

TEST(ReferencePlan, SixteenParticipantsBalanceConditionsOverPositions) {
  const auto p = reference();
  std::map<std::pair<int, std::string>, int> at_position;  // (trial position, condition) -> count
  std::map<std::pair<int, std::string>, int> at_block;     // (block position, condition) -> count
  std::map<int, int> rows;
  std::set<std::uint64_t> seeds;
  int total = 0;
  for (int k = 0; k < 16; ++k) {
    const Plan plan = make_plan(p, k);
    EXPECT_EQ(plan.order_row, k % 4);
    ++rows[plan.order_row];
    for (const auto& t : plan.trials) {
      ++at_position[{t.position, condition_of(t)}];
      if ((t.position - 1) % 6 == 0) ++at_block[{t.block, condition_of(t)}];
      seeds.insert(t.seed);
      ++total;
    }
  }
  EXPECT_EQ(total, 384);                  // 16 x 2 x 2 x 2 x 3 (STUDY.md)
  EXPECT_EQ(seeds.size(), 384u);          // every trial its own seed
  for (const auto& [row, n] : rows) EXPECT_EQ(n, 4) << "row " << row;
  ASSERT_EQ(at_position.size(), 24u * 4u);  // every condition occurs at every position
  for (const auto& [key, n] : at_position) EXPECT_EQ(n, 4) << "position " << key.first << " " << key.second;
  ASSERT_EQ(at_block.size(), 16u);
  for (const auto& [key, n] : at_block) EXPECT_EQ(n, 4) << "block " << key.first << " " << key.second;
}

TEST(ReferencePlan, EachOrderRowIsALatinSquareRow) {
  const auto p = reference();
  const OrderTable t = order_table(p);
  EXPECT_TRUE(is_latin_square(t));
  EXPECT_TRUE(positions_balanced(t));
  // Each level of each factor equally often in every position (VI.6).
  for (std::size_t f = 0; f < p.factors.size(); ++f)
    for (int pos = 0; pos < 4; ++pos) {
      std::map<int, int> count;
      for (const auto& row : t) ++count[p.conditions[row[pos]].levels[f]];
      for (const auto& [level, n] : count) EXPECT_EQ(n, 2);
    }
}

TEST(Seeds, FollowTheDocumentedHash) {
  // Expected values computed outside dtlab (Python, SplitMix64 finaliser):
  //   mix(z): z += 0x9e3779b97f4a7c15; z = (z ^ z>>30) * 0xbf58476d1ce4e5b9;
  //           z = (z ^ z>>27) * 0x94d049bb133111eb; return z ^ z>>31   (all mod 2^64)
  //   mix2(s, v) = mix(s ^ mix(v));  seed = mix2(mix2(mix(M), k), position)
  EXPECT_EQ(trial_seed(20080401, 0, 1), 13947942700548049222ULL);
  EXPECT_EQ(trial_seed(20080401, 0, 24), 16161111821191113536ULL);
  EXPECT_EQ(trial_seed(20080401, 15, 7), 10535650152387789735ULL);
  EXPECT_EQ(trial_seed(0, 0, 1), 15204172177749531820ULL);
  static_assert(trial_seed(1, 2, 3) == mix64(mix64(mix64(1), 2), 3));  // usable at compile time
  const auto p = reference();
  const Plan plan = make_plan(p, 15);
  for (const auto& t : plan.trials) EXPECT_EQ(t.seed, trial_seed(p.master_seed, 15, t.position));
}

// The practice scenes' and the depth test's seeds, moved into seeds.h from the window and the
// session (issue 26): the same streams as before. Expected values computed outside dtlab with the
// Python of FollowTheDocumentedHash:
//   mix2(mix2(mix(20080401), 3), 2**61 + 0x747261696e + 64 * 2 + 1)   block 2, task index 1
//   mix2(mix2(mix(20080401), 1), 2**62 + 0x6465707468 + 5)            questionnaire position 5
TEST(Seeds, PracticeAndDepthTestSeedsFollowTheDocumentedHash) {
  EXPECT_EQ(training_seed(20080401, 3, 2, 1), 17979032487613094384ULL);
  EXPECT_EQ(depth_test_seed(20080401, 1, 5), 14838250802174397229ULL);
  // No derivation reaches another's domain: a trial position is an int, the domains start at 2^61.
  static_assert(kTrainingDomain > (1ULL << 61) && kDepthTestDomain > (1ULL << 62) && kOrderDomain > (1ULL << 63));
}

TEST(Seeds, AChangedMasterSeedChangesEveryTrialSeed) {
  const auto p = reference();
  auto q = p;
  q.master_seed = p.master_seed + 1;
  for (int k = 0; k < 16; ++k) {
    const Plan a = make_plan(p, k), b = make_plan(q, k);
    ASSERT_EQ(a.trials.size(), b.trials.size());
    for (std::size_t i = 0; i < a.trials.size(); ++i) {
      EXPECT_NE(a.trials[i].seed, b.trials[i].seed) << "participant " << k << " position " << i + 1;
      EXPECT_EQ(condition_of(a.trials[i]), condition_of(b.trials[i]));  // the order does not depend on the seed
    }
  }
}

TEST(Seeds, DependOnPositionNotOnOrderRow) {
  const auto p = reference();
  const Plan a = make_plan(p, 5), b = make_plan(p, 5, 3);
  EXPECT_EQ(a.order_row, 1);
  EXPECT_EQ(b.order_row, 3);  // a row assigned by the ledger after a released slot
  for (std::size_t i = 0; i < a.trials.size(); ++i) EXPECT_EQ(a.trials[i].seed, b.trials[i].seed);
  EXPECT_NE(condition_of(a.trials[0]), condition_of(b.trials[0]));
}

TEST(Plans, AreDeterministicAndValidateTheirArguments) {
  const auto p = reference();
  const Plan a = make_plan(p, 7), b = make_plan(p, 7);
  ASSERT_EQ(a.trials.size(), b.trials.size());
  for (std::size_t i = 0; i < a.trials.size(); ++i) {
    EXPECT_EQ(a.trials[i].seed, b.trials[i].seed);
    EXPECT_EQ(a.trials[i].levels, b.trials[i].levels);
  }
  EXPECT_THROW(make_plan(p, -1), std::invalid_argument);
  EXPECT_THROW(make_plan(p, 0, 4), std::invalid_argument);
  EXPECT_THROW(make_plan(p, 0, -1), std::invalid_argument);
  EXPECT_THROW(make_plan(protocol::Protocol{}, 0), std::invalid_argument);
}

// A 2 x 3 design with scenario blocks and the transparency order nested.
const char* kBlocks = R"(id = "blocks"
title = "Blocks"
participants = 12
master_seed = 3
[factors.scenario]
role = "scenario"
levels = ["abstract", "walkthrough"]
[factors.transparency]
role = "rendering"
levels = ["off", "on", "fast"]
[order]
unit = "blocks"
block_factor = "scenario"
scheme = "latin-square"
nested_scheme = "williams"
[training]
practice_trials = 1
[scenarios.abstract]
kind = "abstract"
[scenarios.abstract.tasks.T1]
type = "count-targets"
trials = 2
[scenarios.walkthrough]
kind = "walkthrough"
[scenarios.walkthrough.tasks.T3]
type = "find-unique"
trials = 1
[rendering.off]
method = "standard"
[rendering.on]
method = "dt-seed"
[rendering.fast]
method = "dt-fast"
)";

TEST(BlockOrdering, KeepsBlocksTogetherAndCountersBalanceBothLevels) {
  const auto p = from_text(kBlocks);
  EXPECT_EQ(order_rows(p), 2 * 6);  // latin square of 2 blocks x williams of 3 (6 rows)
  const OrderTable t = order_table(p);
  EXPECT_TRUE(is_permutation_table(t));
  EXPECT_TRUE(positions_balanced(t));
  for (const auto& row : t) {
    // The first three conditions share one scenario level, the last three the other.
    for (int i = 1; i < 3; ++i) EXPECT_EQ(p.conditions[row[i]].levels[0], p.conditions[row[0]].levels[0]);
    for (int i = 4; i < 6; ++i) EXPECT_EQ(p.conditions[row[i]].levels[0], p.conditions[row[3]].levels[0]);
    EXPECT_NE(p.conditions[row[0]].levels[0], p.conditions[row[3]].levels[0]);
  }
  // Practice trials come first in each task set and are flagged.
  const Plan plan = make_plan(p, 0);
  const bool abstract_first = plan.trials[0].levels[0].second == "abstract";
  const std::size_t per_participant = 3 * (1 + 2) + 3 * (1 + 1);
  ASSERT_EQ(plan.trials.size(), per_participant);
  EXPECT_TRUE(plan.trials[0].practice);
  EXPECT_EQ(plan.trials[0].trial, 1);
  EXPECT_FALSE(plan.trials[1].practice);
  EXPECT_EQ(plan.trials[1].task, abstract_first ? "T1" : "T3");
  int practice = 0;
  for (const auto& tr : plan.trials) practice += tr.practice;
  EXPECT_EQ(practice, 6);  // one per task set: 6 blocks x 1 task
}

TEST(OtherSchemes, FixedRandomAndFullPermutation) {
  std::string text = kBlocks;
  const auto replace = [&](const std::string& from, const std::string& to) {
    const auto at = text.find(from);
    ASSERT_NE(at, std::string::npos) << from;
    text.replace(at, from.size(), to);
  };
  replace("unit = \"blocks\"\nblock_factor = \"scenario\"\nscheme = \"latin-square\"\nnested_scheme = \"williams\"",
          "scheme = \"fixed\"\norder = [{scenario = \"walkthrough\", transparency = \"on\"}, "
          "{scenario = \"abstract\", transparency = \"fast\"}, {scenario = \"abstract\", transparency = \"off\"}, "
          "{scenario = \"walkthrough\", transparency = \"off\"}, {scenario = \"abstract\", transparency = \"on\"}, "
          "{scenario = \"walkthrough\", transparency = \"fast\"}]");
  const auto fixed = from_text(text);
  EXPECT_EQ(order_rows(fixed), 1);
  const Plan plan = make_plan(fixed, 9);
  EXPECT_EQ(plan.order_row, 0);
  EXPECT_EQ(condition_of(plan.trials[0]), "walkthrough/on");
  EXPECT_EQ(plan.trials[0].method, "dt-seed");

  std::string random_text = kBlocks;
  random_text.replace(random_text.find("unit = \"blocks\""), std::string("unit = \"blocks\"").size(), "");
  random_text.replace(random_text.find("block_factor = \"scenario\""), 25, "");
  random_text.replace(random_text.find("nested_scheme = \"williams\""), 26, "");
  random_text.replace(random_text.find("scheme = \"latin-square\""), 23, "scheme = \"random\"\nrows = 30");
  const auto random = from_text(random_text);
  EXPECT_EQ(order_rows(random), 30);
  const OrderTable rt = order_table(random);
  EXPECT_TRUE(is_permutation_table(rt));
  EXPECT_EQ(rt, order_table(from_text(random_text)));  // seeded by the master seed: reproducible
  EXPECT_EQ(rt, random_orders(6, 30, order_seed(random.master_seed, 0)));

  std::string perm_text = random_text;
  perm_text.replace(perm_text.find("scheme = \"random\"\nrows = 30"), 27, "scheme = \"full-permutation\"");
  const auto perm = from_text(perm_text);
  EXPECT_EQ(order_rows(perm), 720);
  EXPECT_EQ(order_table(perm), all_permutations(6));
}

}  // namespace

// `dtlab simulate` answers every questionnaire item type and instrument at
// every kind of occasion (the lighter pilot with NASA-TLX after every block,
// SUS and a Likert item after each transparency level, a slider after every
// task set, and at the end the SSQ, a multiple choice, a number and free
// text), then `dtlab export --questionnaires` holds each simulated
// participant's answer to every question of every occasion, each one its
// item type takes, and every instrument's scores.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <set>

#include "analysis/stats/csv.h"
#include "tests/common/light_pilot.h"
#include "tests/common/run_cli.h"

namespace {

namespace fs = std::filesystem;

const char* kItems = R"(
[questionnaire.tlx]
instrument = "nasa-tlx"
when = "block"
weights = true

[questionnaire.effort]
type = "slider"
prompt = "How much effort did that task take?"
anchors = ["none", "a lot"]
when = "task"

[questionnaire.sus]
instrument = "sus"
when = "level:transparency"

[questionnaire.liked]
type = "likert"
prompt = "I liked this view."
points = 7
labels = ["Strongly disagree", "Strongly agree"]
when = "level:transparency"

[questionnaire.ssq]
instrument = "ssq"

[questionnaire.games]
type = "multiple-choice"
prompt = "Which do you play?"
options = ["shooters", "puzzles", "none"]
select = [1, 2]

[questionnaire.hours]
type = "numeric"
prompt = "Hours a week?"
range = [0, 60]
decimals = 1

[questionnaire.comment]
type = "text"
prompt = "Anything else?"
max_length = 200
)";

TEST(SimulateQuestionnaires, EveryItemAndInstrumentIsAnsweredAtEveryOccasion) {
  const std::string base = dtlab::test::light_pilot_text();
  ASSERT_FALSE(base.empty());
  const fs::path d = fs::temp_directory_path() / ("dtlab_simulate_q_" + std::to_string(::getpid()));
  fs::remove_all(d);
  fs::create_directories(d);
  { std::ofstream(d / "q.toml") << base << kItems; }
  const auto sim = dtlab::test::run_dtlab("simulate '" + (d / "q.toml").string() + "' --participants 2 --db '" +
                                          (d / "q.sqlite").string() + "'");
  ASSERT_EQ(sim.rc, 0) << sim.err;
  const auto exp = dtlab::test::run_dtlab("export '" + (d / "q.sqlite").string() + "' --questionnaires '" +
                                          (d / "answers.csv").string() + "'");
  ASSERT_EQ(exp.rc, 0) << exp.err;
  auto csv = dtlab::stats::read_csv_file((d / "answers.csv").string());
  ASSERT_TRUE(csv.ok()) << csv.error().to_string();
  const auto col = [&](const char* name) { return static_cast<std::size_t>(csv->column(name)); };
  // participant -> item -> the occasions it was answered at
  std::map<std::string, std::map<std::string, std::multiset<std::string>>> seen;
  for (const auto& r : csv->rows) {
    seen[r[col("participant")]][r[col("item")]].insert(r[col("occasion_scope")]);
    if (r[col("type")] == "score") {
      const double v = std::stod(r[col("value")]);
      EXPECT_GE(v, 0) << r[col("item")];
      EXPECT_LE(v, r[col("item")].rfind("ssq:", 0) == 0 ? 292.32 : 100.0) << r[col("item")];
    }
  }
  ASSERT_EQ(seen.size(), 2u);
  for (const auto& [who, items] : seen) {
    SCOPED_TRACE(who);
    // 4 blocks x 2 tasks x 1 trial in the pilot: 8 task sets, 4 blocks, 2 levels.
    EXPECT_EQ(items.at("effort").size(), 8u);
    for (const char* sub : {"tlx.mental", "tlx.frustration", "tlx.w.mental-physical", "tlx.w.effort-frustration"})
      EXPECT_EQ(items.at(sub).size(), 4u) << sub;
    EXPECT_EQ(items.at("tlx:raw").size(), 4u);
    EXPECT_EQ(items.at("tlx:weighted").size(), 4u);
    EXPECT_EQ(items.at("sus.q10").size(), 2u);
    EXPECT_EQ(items.at("sus:score"), (std::multiset<std::string>{"transparency=off", "transparency=on"}));
    EXPECT_EQ(items.at("liked").size(), 2u);
    for (const char* end : {"ssq.vertigo", "ssq:nausea", "ssq:oculomotor", "ssq:disorientation", "ssq:total", "games",
                            "hours", "comment", "preference", "depth_self", "depth_test"})
      EXPECT_EQ(items.count(end), 1u) << end;
  }
  fs::remove_all(d);
}

}  // namespace

// `dtlab export --questionnaires` (session::export_questionnaire_csv): a
// session with items of every occasion kind, a free text holding a comma, a
// quote, a line break and non-Latin letters, and a multiple choice, exported
// and read back by a CSV parser (as R's read.csv reads it): one row per stored
// answer with its occasion's block, task and factor levels from the plan,
// values and texts as stored, labels, and one raw-TLX score row per block
// after the block's TLX items; the same through the command line.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <map>
#include <sstream>

#include "analysis/stats/csv.h"
#include "study/session/questionnaire_export.h"
#include "study/session/session.h"
#include "study/store/read.h"
#include "tests/common/run_cli.h"

namespace dtlab::session {
namespace {

const char* kItems = R"(
[questionnaire.tlx]
instrument = "nasa-tlx"
when = "block"

[questionnaire.games]
type = "multiple-choice"
prompt = "Which do you play?"
options = ["shooters", "puzzles", "none"]
labels = ["Shooters", "Puzzles", "None"]
when = "level:transparency"

[questionnaire.comment]
type = "text"
prompt = "Anything else?"
)";

const std::string kComment = "Die Linse, \"langsam\"\nκαλό, но медленно";

class Answering : public Responder {
 public:
  Viewport viewport() const override { return {320, 240}; }
  Status train(const TaskSetSpec&) override { return {}; }
  Result<TrialOutcome> run_trial(const TrialSpec& spec) override {
    TrialOutcome o;
    o.completion_s = spec.planned.position;
    o.started_at = o.ended_at = std::chrono::system_clock::now();
    return o;
  }
  Result<std::vector<QuestionAnswer>> answer_questionnaire(const QuestionnaireSpec& spec) override {
    std::vector<QuestionAnswer> out;
    for (const Question& q : spec.questions) {
      const std::string& type = q.item->type->name;
      if (type == "slider") out.emplace_back(spec.occasion.block * 10.0 + (q.item->sub == "mental" ? 5.0 : 0.0));
      else if (type == "multiple-choice") out.emplace_back(std::vector<std::string>{"puzzles", "shooters"});
      else if (type == "text") out.emplace_back(kComment);
      else if (type == "choice") out.emplace_back(q.options.front());
      else if (type == "depth-test") out.emplace_back(static_cast<double>(q.object_a));
      else out.emplace_back(q.item->type->bounds(*q.item).min);
    }
    return out;
  }
};

std::string temp_db(const std::string& name) {
  const auto dir = std::filesystem::temp_directory_path() / ("dtlab_qexport_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const auto path = dir / name;
  for (const char* suffix : {"", "-wal", "-shm"}) std::filesystem::remove(path.string() + suffix);
  return path.string();
}

TEST(QuestionnaireExport, EveryAnswerWithItsOccasionsConditionAndTheScoresReadBack) {
  auto p = protocol::load_protocol_text(test::read_text(DTLAB_SOURCE_DIR "/protocols/pilot.toml") + kItems, "x.toml");
  ASSERT_TRUE(p.ok()) << p.error().to_string();
  const std::string db = temp_db("export.sqlite");
  design::Plan plan;
  {
    auto store = store::Store::open(db, study_info(p.value()));
    ASSERT_TRUE(store.ok());
    Answering who;
    auto sum = run_session(store.value(), p.value(), "P01", who);
    ASSERT_TRUE(sum.ok()) << sum.error().to_string();
    plan = sum->plan;
  }
  auto reader = store::StudyReader::open(db);
  ASSERT_TRUE(reader.ok());
  std::ostringstream out;
  auto sum = export_questionnaire_csv(reader.value(), out);
  ASSERT_TRUE(sum.ok()) << sum.error().to_string();
  auto stored = reader->questionnaire();
  ASSERT_TRUE(stored.ok());
  auto csv = stats::parse_csv(out.str(), "answers.csv");
  ASSERT_TRUE(csv.ok()) << csv.error().to_string();
  EXPECT_EQ(csv->header, sum->columns);
  EXPECT_EQ(csv->header, questionnaire_export_columns({"transparency", "scenario"}));
  EXPECT_EQ(sum->answers, static_cast<long long>(stored->size()));
  EXPECT_EQ(sum->scores, 4) << "one raw TLX per block (no weights)";
  ASSERT_EQ(csv->rows.size(), stored->size() + 4);

  const auto col = [&](const char* name) { return static_cast<std::size_t>(csv->column(name)); };
  // The block each condition ran in, from the plan (not from the export).
  std::map<int, std::pair<std::string, std::string>> block_levels;
  for (const auto& t : plan.trials) block_levels[t.block] = {t.levels[0].second, t.levels[1].second};
  int scores_seen = 0;
  std::string previous_item;
  for (const auto& r : csv->rows) {
    const std::string& item = r[col("item")];
    SCOPED_TRACE(item + " " + r[col("occasion_scope")]);
    if (r[col("occasion")] == "block") {
      const int block = std::stoi(r[col("block")]);
      EXPECT_EQ(r[col("occasion_scope")], "block=" + std::to_string(block));
      EXPECT_EQ(r[col("transparency")], block_levels[block].first);
      EXPECT_EQ(r[col("scenario")], block_levels[block].second);
      EXPECT_EQ(r[col("task")], "NA");
      if (item == "tlx:raw") {
        ++scores_seen;
        EXPECT_EQ(r[col("type")], "score");
        EXPECT_EQ(previous_item, "tlx.frustration") << "the score follows its block's items";
        // mental = 10 b + 5, the other five 10 b: (60 b + 5) / 6.
        EXPECT_DOUBLE_EQ(std::stod(r[col("value")]), (60.0 * block + 5) / 6);
        EXPECT_EQ(r[col("answered_at")], "NA");
      } else {
        EXPECT_EQ(r[col("instrument")], "nasa-tlx");
        EXPECT_EQ(r[col("type")], "slider");
      }
    }
    if (item == "games") {
      EXPECT_EQ(r[col("occasion")], "level:transparency");
      EXPECT_EQ(r[col("transparency")], r[col("occasion_scope")].substr(std::string("transparency=").size()));
      EXPECT_EQ(r[col("scenario")], "NA");
      EXPECT_EQ(r[col("text")], "shooters\npuzzles") << "option order, one per line";
      EXPECT_EQ(r[col("value")], "NA");
    }
    if (item == "comment") {
      EXPECT_EQ(r[col("occasion")], "end");
      EXPECT_EQ(r[col("text")], kComment);
      EXPECT_EQ(r[col("occasion_scope")], "NA");
    }
    if (item == "depth_test") EXPECT_EQ(r[col("scope")].rfind("pair=", 0), 0u);
    if (item == "preference") EXPECT_EQ(r[col("label")], "NA");
    EXPECT_EQ(r[col("participant")], "P01");
    EXPECT_EQ(r[col("excluded")], "NA");
    previous_item = item;
  }
  EXPECT_EQ(scores_seen, 4);

  // The command line writes the same file and says what it wrote.
  const std::string file = temp_db("answers.csv");
  const auto run = test::run_dtlab("export '" + db + "' --questionnaires '" + file + "' --json");
  ASSERT_EQ(run.rc, 0) << run.err;
  EXPECT_NE(run.out.find("\"scores\": 4"), std::string::npos) << run.out;
  EXPECT_EQ(test::read_text(file), out.str());
  const auto none = test::run_dtlab("export '" + db + "'");
  EXPECT_EQ(none.rc, 2) << "nothing asked for";
  EXPECT_NE(none.err.find("--questionnaires"), std::string::npos) << none.err;
}

}  // namespace
}  // namespace dtlab::session

// Questionnaire occasions in the session runner: items asked after each task
// set, block and level and at the end are asked right after the trial their
// occasion follows (the order checked against the plan, derived here from the
// plan's own blocks, task sets and levels), each occasion stored in one
// transaction under its scope; an interrupted occasion stores nothing and is
// asked again on resume, a stored one never is, and the resumed file equals
// an uninterrupted run's.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <map>

#include "study/design/design.h"
#include "study/session/session.h"
#include "study/store/read.h"
#include "tests/common/run_cli.h"

namespace dtlab::session {
namespace {

// The pilot with an item per occasion kind (the pilot's own items stay at the end).
const char* kItems = R"(
[questionnaire.effort]
type = "slider"
prompt = "How much effort did that task take?"
when = "task"

[questionnaire.tlx]
instrument = "nasa-tlx"
when = "block"

[questionnaire.liked]
type = "likert"
prompt = "I liked this view."
points = 5
labels = ["no", "yes"]
when = "level:transparency"
)";

protocol::Protocol load() {
  auto p = protocol::load_protocol_text(test::read_text(DTLAB_SOURCE_DIR "/protocols/pilot.toml") + kItems, "occ.toml");
  EXPECT_TRUE(p.ok()) << (p.ok() ? "" : p.error().to_string());
  return p.value();
}

std::string temp_db(const std::string& name) {
  const auto dir = std::filesystem::temp_directory_path() / ("dtlab_occasions_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const auto path = dir / name;
  for (const char* suffix : {"", "-wal", "-shm"}) std::filesystem::remove(path.string() + suffix);
  return path.string();
}

// Logs "trial N" and "ask <scope>" in call order; answers every item type with a valid value.
class Logging : public Responder {
 public:
  std::vector<std::string> log;
  std::string fail_at = "-";        // an occasion scope: return an Error there ("-": nowhere)
  std::string bad_answer_at = "-";  // an occasion scope: its last question gets an answer its type refuses
  Viewport viewport() const override { return {320, 240}; }
  Status train(const TaskSetSpec&) override { return {}; }
  Result<TrialOutcome> run_trial(const TrialSpec& spec) override {
    log.push_back("trial " + std::to_string(spec.planned.position));
    TrialOutcome o;
    o.completion_s = 10 + spec.planned.position;
    o.started_at = o.ended_at = std::chrono::system_clock::now();
    return o;
  }
  Result<std::vector<QuestionAnswer>> answer_questionnaire(const QuestionnaireSpec& spec) override {
    log.push_back("ask " + (spec.occasion.scope.empty() ? std::string("end") : spec.occasion.scope));
    if (spec.occasion.scope == fail_at) return Error{"", 0, 0, "logging", "the window was closed"};
    std::vector<QuestionAnswer> out;
    for (const Question& q : spec.questions) {
      const std::string& type = q.item->type->name;
      if (type == "choice") out.emplace_back(q.options.front());
      else if (type == "depth-test") out.emplace_back(static_cast<double>(q.object_b));
      else out.emplace_back(q.item->type->bounds(*q.item).max);  // slider, Likert, rating: the scale's top
    }
    if (spec.occasion.scope == bad_answer_at) out.back() = std::string("not a number");
    return out;
  }
};

// What the plan says must happen: each trial, then the occasions it ends, in the documented order.
std::vector<std::string> expected_log(const design::Plan& plan) {
  std::map<std::string, int> last_of_level;
  for (const auto& t : plan.trials) last_of_level[t.levels[0].second] = t.position;  // transparency
  std::vector<std::string> out;
  for (std::size_t i = 0; i < plan.trials.size(); ++i) {
    const auto& t = plan.trials[i];
    out.push_back("trial " + std::to_string(t.position));
    const bool last = i + 1 == plan.trials.size();
    const bool block_ends = last || plan.trials[i + 1].block != t.block;
    if (block_ends || plan.trials[i + 1].task != t.task)
      out.push_back("ask block=" + std::to_string(t.block) + ";task=" + t.task);
    if (block_ends) out.push_back("ask block=" + std::to_string(t.block));
    if (last_of_level[t.levels[0].second] == t.position) out.push_back("ask transparency=" + t.levels[0].second);
  }
  out.push_back("ask end");
  return out;
}

// Every stored answer: "item|scope" -> value.
std::map<std::string, std::string> stored(const std::string& db) {
  auto r = store::StudyReader::open(db);
  EXPECT_TRUE(r.ok());
  std::map<std::string, std::string> out;
  auto answers = r->questionnaire();
  for (const auto& a : *answers)
    out[a.item + "|" + a.scope] =
        std::holds_alternative<double>(a.value) ? std::to_string(std::get<double>(a.value)) : std::get<std::string>(a.value);
  return out;
}

TEST(Occasions, EachIsAskedRightAfterTheTrialItFollowsAndStoredUnderItsScope) {
  const protocol::Protocol p = load();
  const std::string db = temp_db("order.sqlite");
  auto store = store::Store::open(db, study_info(p));
  ASSERT_TRUE(store.ok());
  Logging who;
  auto sum = run_session(store.value(), p, "P", who);
  ASSERT_TRUE(sum.ok()) << sum.error().to_string();
  EXPECT_TRUE(sum->finished);
  EXPECT_EQ(who.log, expected_log(sum->plan));
  // 8 task sets, 4 blocks, 2 levels, the end.
  EXPECT_EQ(sum->occasions_recorded, 8 + 4 + 2 + 1);
  const auto q = stored(db);
  // Per task set one slider, per block the six TLX subscales, per level the Likert, at the end
  // the pilot's 4 ratings, preference, depth_self and 3 depth pairs.
  EXPECT_EQ(q.size(), 8u + 4 * 6 + 2 + (4 + 1 + 1 + 3));
  EXPECT_EQ(q.at("effort|block=1;task=" + sum->plan.trials.front().task), "100.000000");
  EXPECT_EQ(q.at("tlx.frustration|block=4"), "100.000000");
  EXPECT_EQ(q.at("liked|transparency=on"), "5.000000");
  EXPECT_EQ(q.count("depth_test|pair=3"), 1u);
  EXPECT_EQ(q.count("preference|"), 1u);
}

TEST(Occasions, AnInterruptedOccasionStoresNothingAndIsAskedAgainOnResumeOthersNever) {
  const protocol::Protocol p = load();
  const std::string ref_db = temp_db("reference.sqlite"), db = temp_db("interrupted.sqlite");
  {
    auto store = store::Store::open(ref_db, study_info(p));
    ASSERT_TRUE(store.ok());
    Logging who;
    ASSERT_TRUE(run_session(store.value(), p, "P", who).ok());
  }
  {
    auto store = store::Store::open(db, study_info(p));
    ASSERT_TRUE(store.ok());
    Logging who;
    who.fail_at = "block=2";  // the window closes on block 2's questionnaire
    auto r = run_session(store.value(), p, "P", who);
    ASSERT_FALSE(r.ok());
    EXPECT_EQ(who.log.back(), "ask block=2");
    const auto q = stored(db);
    EXPECT_EQ(q.count("tlx.mental|block=1"), 1u);
    EXPECT_EQ(q.count("tlx.mental|block=2"), 0u);
  }
  {
    auto store = store::Store::open(db, study_info(p));
    ASSERT_TRUE(store.ok());
    Logging who;
    who.bad_answer_at = "block=2";  // now a refused answer on its last page: nothing of it is stored either
    auto r = run_session(store.value(), p, "P", who);
    ASSERT_FALSE(r.ok());
    EXPECT_EQ(r.error().field, "questionnaire.tlx.frustration");
    EXPECT_EQ(stored(db).count("tlx.mental|block=2"), 0u) << "one transaction per occasion";
    EXPECT_EQ(who.log, (std::vector<std::string>{"ask block=2"})) << "the missed occasion before any trial";
  }
  {
    auto store = store::Store::open(db, study_info(p));
    ASSERT_TRUE(store.ok());
    Logging who;
    auto r = run_session(store.value(), p, "P", who);
    ASSERT_TRUE(r.ok()) << r.error().to_string();
    ASSERT_FALSE(who.log.empty());
    EXPECT_EQ(who.log.front(), "ask block=2");
    for (const std::string& line : who.log) EXPECT_NE(line, "ask block=1") << "a stored occasion is never asked again";
  }
  EXPECT_EQ(stored(db), stored(ref_db));
}

}  // namespace
}  // namespace dtlab::session

// The session runner (study/session/session.h) with a scripted, deterministic
// Responder (no GL): all planned trials recorded in plan order with the scene's
// answer key and store::score()'s scores, the questionnaire stored with the
// protocol's ids and scopes, the session finished; interruptions at every
// stage resume to the same file contents as an uninterrupted run.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <map>
#include <sstream>

#include "analysis/stats/csv.h"
#include "study/design/design.h"
#include "study/session/session.h"
#include "study/store/export.h"
#include "study/store/read.h"

namespace dtlab::session {
namespace {

protocol::Protocol load(const char* name) {
  auto p = protocol::load_protocol(std::string(DTLAB_SOURCE_DIR) + "/protocols/" + name);
  EXPECT_TRUE(p.ok()) << (p.ok() ? "" : p.error().to_string());
  return p.value();
}

std::string temp_db(const std::string& name) {
  const auto dir = std::filesystem::temp_directory_path() / ("dtlab_session_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const auto path = dir / name;
  std::filesystem::remove(path);
  std::filesystem::remove(path.string() + "-wal");
  std::filesystem::remove(path.string() + "-shm");
  return path.string();
}

// Answers from the position: odd positions right (the key), even positions off by a known amount;
// position 5 gives no answer. Completion time = position seconds. Fails on demand.
class Scripted : public Responder {
 public:
  int fail_at = 0;              // run_trial of this position returns an Error
  bool fail_questionnaire = false;
  std::vector<int> ran;         // positions run, in order
  std::vector<std::pair<int, std::string>> trained;  // (block, task)
  std::vector<std::uint32_t> depth_pairs;            // object ids shown in the depth test

  Viewport viewport() const override { return {320, 240}; }
  Status train(const TaskSetSpec& set) override {
    trained.emplace_back(set.block, set.task);
    return {};
  }
  Result<TrialOutcome> run_trial(const TrialSpec& spec) override {
    const int pos = spec.planned.position;
    if (pos == fail_at) return Error{"", 0, 0, "scripted", "failing at trial " + std::to_string(pos)};
    ran.push_back(pos);
    TrialOutcome o;
    const scene::Answer& key = spec.scene->answer;
    const bool right = pos % 2 == 1;
    if (pos != 5) {
      switch (key.task) {
        case scene::Task::T1:
        case scene::Task::T4: o.answer = store::Count{key.count + (right ? 0 : 2)}; break;
        case scene::Task::T2: o.answer = store::Letter{right ? std::string(1, key.letter) : std::string("Q")}; break;
        case scene::Task::T3: o.answer = store::Position{key.position.x + (right ? 0.0 : 3.0), key.position.y + (right ? 0.0 : 4.0)}; break;
      }
    }
    o.completion_s = pos;
    o.started_at = std::chrono::system_clock::now();
    o.ended_at = o.started_at;
    for (int f = 0; f < 3; ++f) {
      o.frame_ms.push_back(10.0 + f);
      o.poses.push_back(store::CameraPose{0.1 * f, 1, 2, 3, 0.5, 0.25});
    }
    o.events.push_back({0.0, store::InputEvent::Kind::key_down, "Up", 0, 0});
    return o;
  }
  Result<std::vector<QuestionAnswer>> answer_questionnaire(const QuestionnaireSpec& spec) override {
    if (fail_questionnaire) return Error{"", 0, 0, "scripted", "no questionnaire today"};
    std::vector<QuestionAnswer> out;
    for (const Question& q : spec.questions) {
      const std::string& type = q.item->type->name;
      if (type == "rating") {
        out.emplace_back(static_cast<double>(q.scope.size() % 5));
      } else if (type == "choice") {
        out.emplace_back(q.options.back());  // the neutral one, if any
      } else if (type == "depth-test") {
        depth_pairs.push_back(q.object_a);
        depth_pairs.push_back(q.object_b);
        out.emplace_back(static_cast<double>(q.object_a));  // always the first of the pair
      } else {
        ADD_FAILURE() << "no scripted answer for type " << type;
        out.emplace_back(0.0);
      }
    }
    return out;
  }
};

struct Row {
  std::map<std::string, std::string> cells;
  const std::string& operator[](const std::string& c) const { return cells.at(c); }
};

std::vector<Row> exported(const std::string& db) {
  std::ostringstream csv;
  auto sum = store::export_trials_csv(db, csv);
  EXPECT_TRUE(sum.ok()) << (sum.ok() ? "" : sum.error().to_string());
  auto t = stats::parse_csv(csv.str(), db);
  EXPECT_TRUE(t.ok());
  std::vector<Row> rows;
  for (const auto& r : t->rows) {
    Row row;
    for (std::size_t c = 0; c < t->header.size(); ++c) row.cells[t->header[c]] = r[c];
    rows.push_back(row);
  }
  return rows;
}

// Every questionnaire row: "item|scope" -> value (number or text), read through the store's reader.
std::map<std::string, std::string> questionnaire(const std::string& db) {
  auto r = store::StudyReader::open(db);
  EXPECT_TRUE(r.ok()) << (r.ok() ? "" : r.error().to_string());
  std::map<std::string, std::string> out;
  if (!r) return out;
  auto answers = r->questionnaire();
  EXPECT_TRUE(answers.ok());
  for (const auto& a : *answers) {
    char buf[40];
    if (const double* v = std::get_if<double>(&a.value)) std::snprintf(buf, sizeof buf, "%.17g", *v);
    out[a.item + "|" + a.scope] = std::holds_alternative<double>(a.value) ? std::string(buf) : std::get<std::string>(a.value);
  }
  return out;
}

Result<store::Store> open(const std::string& db, const protocol::Protocol& p) { return store::Store::open(db, study_info(p)); }

TEST(Runner, RecordsEveryTrialInPlanOrderWithScoresQuestionnaireAndFinish) {
  const protocol::Protocol p = load("elmqvist2008.toml");
  const std::string db = temp_db("full.sqlite");
  auto store = open(db, p);
  ASSERT_TRUE(store.ok()) << store.error().to_string();
  Scripted who;
  std::vector<int> recorded;
  Hooks hooks;
  hooks.on_trial_recorded = [&](const TrialSpec& s, const store::TrialRecord& r) {
    EXPECT_EQ(s.planned.position, r.position);
    recorded.push_back(r.position);
  };
  auto sum = run_session(store.value(), p, "P01", who, hooks);
  ASSERT_TRUE(sum.ok()) << sum.error().to_string();
  EXPECT_TRUE(sum->finished);
  EXPECT_TRUE(sum->questionnaire_recorded);
  EXPECT_FALSE(sum->resumed);
  EXPECT_EQ(sum->trials_run, 24);
  EXPECT_EQ(sum->enrollment.index, 0);
  std::vector<int> all(24);
  for (int i = 0; i < 24; ++i) all[static_cast<std::size_t>(i)] = i + 1;
  EXPECT_EQ(who.ran, all);
  EXPECT_EQ(recorded, all);
  // Training once per task set: 4 blocks x 2 tasks.
  ASSERT_EQ(who.trained.size(), 8u);
  EXPECT_EQ(who.trained[0], std::make_pair(1, std::string(sum->plan.trials[0].task)));

  const auto rows = exported(db);
  ASSERT_EQ(rows.size(), 24u);
  const design::Plan plan = design::make_plan(p, 0, 0);
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const Row& r = rows[i];
    const design::PlannedTrial& t = plan.trials[i];
    const int pos = static_cast<int>(i) + 1;
    SCOPED_TRACE("position " + std::to_string(pos) + " " + t.task);
    EXPECT_EQ(r["position"], std::to_string(pos));
    EXPECT_EQ(r["task"], t.task);
    EXPECT_EQ(r["trial_seed"], std::to_string(t.seed));
    EXPECT_EQ(std::stod(r["completion_time_s"]), pos);
    EXPECT_EQ(r["frame_count"], "3");
    EXPECT_EQ(std::stod(r["frame_ms_mean"]), 11.0);
    // The key is the generated scene's.
    auto setup = trial_setup(p, t);
    ASSERT_TRUE(setup.ok());
    auto sc = trial_scene(setup.value(), t);
    ASSERT_TRUE(sc.ok());
    EXPECT_EQ(r["scene_hash"], sc->hash);
    const bool right = pos % 2 == 1, none = pos == 5;
    if (t.task == "T1" || t.task == "T4") {
      EXPECT_EQ(r["truth_count"], std::to_string(sc->answer.count));
      if (none) {
        EXPECT_EQ(r["answer_count"], "NA");
        EXPECT_EQ(r["rel_error"], "NA");
      } else {
        EXPECT_EQ(std::stod(r["rel_error"]), right ? 0.0 : 2.0 / sc->answer.count);
        EXPECT_EQ(r["signed_error"], right ? "0" : "2");
      }
    } else if (t.task == "T2") {
      EXPECT_EQ(r["truth_letter"], std::string(1, sc->answer.letter));
      EXPECT_EQ(r["correct"], none ? "NA" : right ? "1" : "0");
    } else {
      EXPECT_NEAR(std::stod(r["truth_x"]), sc->answer.position.x, 1e-4);
      if (!none) {
        EXPECT_NEAR(std::stod(r["distance"]), right ? 0.0 : 5.0, 1e-9);
      }
    }
  }

  // Questionnaire: 4 ratings (scenario x transparency), the preference, depth_self, 3 depth-test pairs.
  const auto q = questionnaire(db);
  EXPECT_EQ(q.size(), 4u + 1 + 1 + 3);
  for (const char* scope : {"scenario=abstract;transparency=off", "scenario=abstract;transparency=on",
                            "scenario=walkthrough;transparency=off", "scenario=walkthrough;transparency=on"})
    EXPECT_TRUE(q.count(std::string("rating|") + scope)) << scope;
  EXPECT_EQ(q.at("preference|"), "no preference");  // the neutral option, shown and stored
  EXPECT_TRUE(q.count("depth_self|"));
  for (const char* pair : {"pair=1", "pair=2", "pair=3"}) {
    ASSERT_TRUE(q.count(std::string("depth_test|") + pair)) << pair;
    const std::string v = q.at(std::string("depth_test|") + pair);
    EXPECT_TRUE(v == "0.0" || v == "1.0" || v == "0" || v == "1") << v;
  }
  ASSERT_EQ(who.depth_pairs.size(), 6u);
  for (std::uint32_t id : who.depth_pairs) EXPECT_GT(id, 0u);

  auto s = store->session("P01");
  ASSERT_TRUE(s.ok());
  EXPECT_EQ(s->status, store::SessionStatus::finished);

  // A second call finds the session finished and leaves it alone.
  Scripted again;
  auto second = run_session(store.value(), p, "P01", again);
  ASSERT_TRUE(second.ok()) << second.error().to_string();
  EXPECT_TRUE(second->already_finished);
  EXPECT_TRUE(again.ran.empty());
}

// The depth-test key is geometry: the scripted responder always names the first object, so the
// stored 0/1 must equal "first object is closer to the depth-test eye".
TEST(Runner, DepthTestIsScoredAgainstDistanceFromTheEye) {
  const protocol::Protocol p = load("elmqvist2008.toml");
  const auto& item = p.questionnaire.back();
  ASSERT_EQ(item.type->name, "depth-test");
  for (int k = 0; k < 6; ++k) {
    std::vector<Question> qs = expand_questionnaire(p);
    auto key = depth_test_view(p, item, k, {320, 240}, qs);
    ASSERT_TRUE(key.ok()) << key.error().to_string();
    const scene::Scene& sc = key->view.scene;
    const glm::vec3 eye = key->view.camera.position;
    int pairs = 0;
    for (const Question& q : qs) {
      if (q.item != &item) continue;
      ++pairs;
      auto dist = [&](std::uint32_t id) {
        const glm::vec4 c = sc.objects[id - 1].transform[3];
        return std::hypot(c.x - eye.x, c.z - eye.z);
      };
      const double da = dist(q.object_a), db = dist(q.object_b);
      const double ratio = std::max(da, db) / std::min(da, db);
      EXPECT_GE(ratio, 1.05);
      EXPECT_LE(ratio, 3.0);
      EXPECT_EQ(key->closer[static_cast<std::size_t>(q.pair - 1)], da < db ? q.object_a : q.object_b);
    }
    EXPECT_EQ(pairs, 3);
    // Deterministic: the same index gives the same view.
    std::vector<Question> again = expand_questionnaire(p);
    auto key2 = depth_test_view(p, item, k, {320, 240}, again);
    ASSERT_TRUE(key2.ok());
    EXPECT_EQ(key2->closer, key->closer);
    EXPECT_EQ(key2->view.camera.yaw, key->view.camera.yaw);
  }
}

// The A and B markers of every pair lie inside the window, for every participant of the pilot's
// first two Latin-square cycles and the window sizes people use. Regression: the window drew them
// through the scene's start camera instead of the test's own view, and for the second participant
// both lay off screen (the depth test could not be answered by mouse, and a script hung there).
TEST(Runner, DepthTestMarkersLieInsideTheWindowForEveryParticipant) {
  const protocol::Protocol p = load("pilot.toml");
  const auto& item = p.questionnaire.back();
  ASSERT_EQ(item.type->name, "depth-test");
  for (const Viewport vp : {Viewport{640, 480}, Viewport{800, 600}, Viewport{1280, 800}, Viewport{1920, 1080}})
    for (int k = 0; k < 8; ++k) {
      std::vector<Question> qs = expand_questionnaire(p);
      auto key = depth_test_view(p, item, k, vp, qs);
      ASSERT_TRUE(key.ok()) << key.error().to_string();
      for (const Question& q : qs) {
        if (q.item != &item) continue;
        const auto a = depth_test_marker(key->view, q.object_a, vp), b = depth_test_marker(key->view, q.object_b, vp);
        ASSERT_TRUE(a && b) << "index " << k << " pair " << q.pair;
        for (const glm::vec2 m : {*a, *b}) {
          EXPECT_GT(m.x, 0.0f) << "index " << k << " pair " << q.pair << " at " << vp.width << "x" << vp.height;
          EXPECT_LT(m.x, static_cast<float>(vp.width)) << "index " << k << " pair " << q.pair;
          EXPECT_GT(m.y, 0.0f) << "index " << k << " pair " << q.pair;
          EXPECT_LT(m.y, static_cast<float>(vp.height)) << "index " << k << " pair " << q.pair;
        }
        // The two markers of a pair are apart.
        EXPECT_NE(*a, *b);
      }
    }
  EXPECT_FALSE(depth_test_marker(DepthTestView{}, 1, Viewport{}).has_value()) << "no such object";
}

// Interrupted at a trial, at the questionnaire, and after the questionnaire: each rerun resumes,
// runs exactly the remaining trials, and ends with the file of an uninterrupted run.
TEST(Runner, InterruptionsResumeToTheSameFile) {
  const protocol::Protocol p = load("pilot.toml");
  const std::string ref_db = temp_db("reference.sqlite");
  {
    auto store = open(ref_db, p);
    ASSERT_TRUE(store.ok());
    Scripted who;
    ASSERT_TRUE(run_session(store.value(), p, "P", who).ok());
  }
  const std::string db = temp_db("interrupted.sqlite");
  {
    auto store = open(db, p);
    ASSERT_TRUE(store.ok());
    Scripted who;
    who.fail_at = 4;  // a crash in trial 4
    auto r = run_session(store.value(), p, "P", who);
    ASSERT_FALSE(r.ok());
    EXPECT_EQ(r.error().field, "scripted");
    EXPECT_EQ(who.ran, (std::vector<int>{1, 2, 3}));
  }
  {
    auto store = open(db, p);  // a new process would open the file again
    ASSERT_TRUE(store.ok());
    Scripted who;
    int calls = 0;
    Hooks hooks;
    hooks.stop_requested = [&] { return ++calls > 3; };  // Ctrl-C after three more trials
    auto r = run_session(store.value(), p, "P", who, hooks);
    ASSERT_TRUE(r.ok()) << r.error().to_string();
    EXPECT_TRUE(r->stopped);
    EXPECT_TRUE(r->resumed);
    EXPECT_EQ(who.ran, (std::vector<int>{4, 5, 6}));
    // Resuming mid task set: training again, flagged as resumed.
    ASSERT_FALSE(who.trained.empty());
  }
  {
    auto store = open(db, p);
    ASSERT_TRUE(store.ok());
    Scripted who;
    who.fail_questionnaire = true;  // every trial done, the questionnaire fails
    auto r = run_session(store.value(), p, "P", who);
    ASSERT_FALSE(r.ok());
    EXPECT_EQ(who.ran, (std::vector<int>{7, 8}));
    auto s = store->session("P");
    ASSERT_TRUE(s.ok());
    EXPECT_EQ(s->status, store::SessionStatus::running);
  }
  {
    // The questionnaire committed, then the process died before finish_session: the rerun must
    // see the questionnaire as done and finish. The answers committed are the uninterrupted
    // run's (as scored by the runner: depth tests stored as right or wrong).
    auto store = open(db, p);
    ASSERT_TRUE(store.ok());
    Scripted who;
    auto s = store->session("P");
    ASSERT_TRUE(s.ok());
    auto ref = store::StudyReader::open(ref_db);
    ASSERT_TRUE(ref.ok());
    auto ref_answers = ref->questionnaire("P");
    ASSERT_TRUE(ref_answers.ok());
    ASSERT_FALSE(ref_answers->empty());
    std::vector<store::QuestionnaireAnswer> stored;
    for (const auto& a : *ref_answers) stored.push_back({a.item, a.scope, a.value});
    ASSERT_TRUE(store->record_questionnaire(s.value(), stored).ok());
    auto r = run_session(store.value(), p, "P", who);
    ASSERT_TRUE(r.ok()) << r.error().to_string();
    EXPECT_TRUE(r->finished);
    EXPECT_FALSE(r->questionnaire_recorded);
    EXPECT_TRUE(who.ran.empty());
  }
  // Same rows as the uninterrupted run, but for wall-clock stamps.
  auto a = exported(ref_db), b = exported(db);
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i)
    for (const auto& [col, v] : a[i].cells) {
      if (col == "started_at" || col == "ended_at") continue;
      EXPECT_EQ(b[i][col], v) << "row " << i << " column " << col;
    }
  EXPECT_EQ(questionnaire(ref_db), questionnaire(db));
}

TEST(Runner, QuestionnaireExpansion) {
  const protocol::Protocol p = load("elmqvist2008.toml");
  const auto qs = expand_questionnaire(p);  // the end's: every item of the reference study
  std::vector<std::string> got;
  for (const auto& q : qs) got.push_back(q.item->id + "|" + q.scope);
  EXPECT_EQ(got, (std::vector<std::string>{
                     "rating|scenario=abstract;transparency=off", "rating|scenario=abstract;transparency=on",
                     "rating|scenario=walkthrough;transparency=off", "rating|scenario=walkthrough;transparency=on",
                     "preference|", "depth_self|", "depth_test|pair=1", "depth_test|pair=2", "depth_test|pair=3"}));
  // The factor's levels, then the neutral option (regression: it was dropped, and the preference
  // question silently became a forced choice).
  EXPECT_EQ(qs[4].options, (std::vector<std::string>{"off", "on", "no preference"}));
  EXPECT_EQ(qs[1].levels, (std::vector<std::pair<std::string, std::string>>{{"scenario", "abstract"}, {"transparency", "on"}}));
}

// A responder that breaks its contract is an Error, and nothing of that trial is stored.
TEST(Runner, ResponderContractViolationsAreErrors) {
  const protocol::Protocol p = load("pilot.toml");
  struct Bad : Scripted {
    int mode = 0;
    Result<TrialOutcome> run_trial(const TrialSpec& spec) override {
      auto o = Scripted::run_trial(spec);
      if (mode == 0) o->poses.pop_back();                  // frames != poses
      if (mode == 1) o->answer = store::Letter{"C"};       // a letter to a count task (pilot starts with T1 or T3)
      if (mode == 1 && spec.planned.task == "T2") o->answer = store::Count{1};
      if (mode == 1 && spec.planned.task == "T3") o->answer = store::Count{1};
      if (mode == 2) o->frame_ms[0] = -1;
      return o;
    }
  };
  for (int mode = 0; mode < 3; ++mode) {
    const std::string db = temp_db("bad" + std::to_string(mode) + ".sqlite");
    auto store = open(db, p);
    ASSERT_TRUE(store.ok());
    Bad who;
    who.mode = mode;
    auto r = run_session(store.value(), p, "P", who);
    ASSERT_FALSE(r.ok()) << mode;
    EXPECT_EQ(r.error().field.rfind("trial 1.", 0), 0u) << r.error().to_string();
    EXPECT_TRUE(exported(db).empty()) << mode;
  }
}

}  // namespace
}  // namespace dtlab::session

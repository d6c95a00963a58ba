// The session's sequence around the trials (docs/session.md, "The sequence")
// with a responder that records every page it is shown (no GL): consent
// first, a decline stores only the refusal and counts as a withdrawal, the
// start pages, announcements, level instructions and breaks in their places,
// practice feedback with the key, the end pages after the questionnaire, and
// every page in the screen log in the order shown. A session stopped and
// resumed shows the same pages at the same places as one run straight through.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "study/session/session.h"
#include "study/store/read.h"

namespace dtlab::session {
namespace {

std::string pilot_text() {
  std::ifstream in(std::string(DTLAB_SOURCE_DIR) + "/protocols/pilot.toml");
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

void replace(std::string& text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  ASSERT_NE(at, std::string::npos) << from;
  text.replace(at, from.size(), to);
}

// The pilot (4 blocks of one condition each, 2 trials per block) with the whole sequence declared.
protocol::Protocol sequenced(int practice_trials = 0) {
  std::string t = pilot_text();
  replace(t, "[session]\n", "[session]\nannounce_blocks = true\ntrial_counter = true\n");
  replace(t, "practice_trials = 0\n",
          "practice_trials = " + std::to_string(practice_trials) + "\nfeedback = true\n");
  replace(t, "levels = [\"off\", \"on\"]\n",
          "levels = [\"off\", \"on\"]\nlabels = [\"Normal view\", \"X-ray view\"]\n"
          "instructions = [\"\", \"You can see through walls.\"]\n");
  t += R"(
[consent]
title = "Consent"
text = "I agree to take part."

[pages.hello]
when = "start"
title = "Welcome"
text = "Thank you for coming."

[pages.bye]
when = "end"
title = "Thank you"
text = "That was all."

[breaks]
after_blocks = true
every_trials = 1
min_s = 2
max_s = 30
skippable = false
)";
  auto p = protocol::load_protocol_text(t, "sequenced.toml");
  EXPECT_TRUE(p.ok()) << (p.ok() ? "" : p.error().to_string());
  return p.value();
}

std::string temp_db(const std::string& name) {
  const auto dir = std::filesystem::temp_directory_path() / ("dtlab_sequence_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const auto path = dir / name;
  for (const char* suffix : {"", "-wal", "-shm"}) std::filesystem::remove(path.string() + suffix);
  return path.string();
}

// Answers every trial with the key, declines consent on demand, and records the pages shown.
class PageRecorder : public Responder {
 public:
  bool decline = false;
  int stop_after = 0;  // trials; 0 = never
  int trials = 0;
  std::vector<PageSpec> pages;

  Viewport viewport() const override { return {320, 240}; }
  Status train(const TaskSetSpec&) override { return {}; }
  Result<PageOutcome> show_page(const PageSpec& page) override {
    pages.push_back(page);
    const auto now = std::chrono::system_clock::now();
    std::string answer = page.kind == PageSpec::Kind::consent ? (decline ? "decline" : "agree") : "continue";
    return PageOutcome{answer, now, now + std::chrono::milliseconds(250)};
  }
  Result<TrialOutcome> run_trial(const TrialSpec& spec) override {
    ++trials;
    TrialOutcome o;
    o.answer = answer_key(spec.scene->answer);
    o.completion_s = 1;
    o.started_at = o.ended_at = std::chrono::system_clock::now();
    return o;
  }
  Result<std::vector<QuestionAnswer>> answer_questionnaire(const QuestionnaireSpec& spec) override {
    std::vector<QuestionAnswer> out;
    for (const Question& q : spec.questions) {
      const std::string& type = q.item->type->name;
      if (type == "rating") out.emplace_back(1.0);
      else if (type == "choice") out.emplace_back(q.options.front());
      else out.emplace_back(static_cast<double>(q.object_a));  // the pilot asks nothing else
    }
    pages.push_back(PageSpec{PageSpec::Kind::information, nullptr, "questionnaire", "", "", ""});
    return out;
  }
  std::vector<std::string> names() const {
    std::vector<std::string> out;
    for (const PageSpec& p : pages) out.push_back(p.screen);
    return out;
  }
};

std::vector<store::ScreenRow> screens(const std::string& db, const std::string& participant) {
  auto r = store::StudyReader::open(db);
  EXPECT_TRUE(r.ok()) << (r.ok() ? "" : r.error().to_string());
  auto s = r->screens(participant);
  EXPECT_TRUE(s.ok()) << (s.ok() ? "" : s.error().to_string());
  return s.ok() ? s.value() : std::vector<store::ScreenRow>{};
}

TEST(Sequence, PagesComeInTheirPlacesAndEveryOneIsInTheScreenLog) {
  const protocol::Protocol p = sequenced();
  const std::string db = temp_db("order.sqlite");
  auto store = store::Store::open(db, study_info(p));
  ASSERT_TRUE(store.ok()) << store.error().to_string();
  PageRecorder who;
  auto sum = run_session(store.value(), p, "P01", who);
  ASSERT_TRUE(sum.ok()) << sum.error().to_string();
  EXPECT_TRUE(sum->finished);
  EXPECT_FALSE(sum->declined);

  // Participant 0 meets transparency off first or on first depending on the Latin-square row;
  // the instructions of "on" come before the first block of "on", once, and "off" has none.
  std::vector<std::string> expected{"consent", "page hello"};
  bool met_on = false;
  for (int block = 1; block <= 4; ++block) {
    if (block > 1) expected.push_back("break");
    expected.push_back("announce " + std::to_string(block));
    const auto first = std::find_if(sum->plan.trials.begin(), sum->plan.trials.end(),
                                    [&](const design::PlannedTrial& t) { return t.block == block; });
    ASSERT_NE(first, sum->plan.trials.end());
    const bool on = first->levels[0].second == "on";
    if (on && !met_on) expected.push_back("level transparency=on");
    met_on = met_on || on;
    expected.push_back("break");  // every_trials = 1: between the block's two trials
  }
  expected.push_back("questionnaire");
  expected.push_back("page bye");
  EXPECT_EQ(who.names(), expected);

  // The pause is as the protocol says; the announcement names the block's level labels.
  for (const PageSpec& page : who.pages) {
    if (page.kind == PageSpec::Kind::pause) {
      EXPECT_EQ(page.min_s, 2);
      EXPECT_EQ(page.max_s, 30);
      EXPECT_FALSE(page.skippable);
    }
    if (page.screen == "announce 1") {
      EXPECT_TRUE(page.text.find("view") != std::string::npos) << page.text;
    }
  }

  // Every page but the questionnaire (stored as answers) is in the screen log, in order, with its
  // answer and the time it was shown; the consent's hash is the one stored with the consent.
  const auto log = screens(db, "P01");
  std::vector<std::string> logged;
  for (const auto& s : log) logged.push_back(s.screen);
  std::vector<std::string> shown = expected;
  shown.erase(std::find(shown.begin(), shown.end(), "questionnaire"));
  EXPECT_EQ(logged, shown);
  ASSERT_FALSE(log.empty());
  EXPECT_EQ(log.front().answer, std::optional<std::string>("agree"));
  EXPECT_NEAR(log.front().duration_s, 0.25, 1e-3);
  for (std::size_t i = 0; i < log.size(); ++i) EXPECT_EQ(log[i].seq, static_cast<int>(i) + 1);
  auto r = store::StudyReader::open(db);
  auto consents = r->consents();
  ASSERT_TRUE(consents.ok());
  ASSERT_EQ(consents->size(), 1u);
  EXPECT_TRUE(consents->front().agreed);
  EXPECT_EQ(consents->front().text_sha256, log.front().shown);
  EXPECT_EQ(consents->front().text_sha256.size(), 64u);
}

TEST(Sequence, DecliningConsentStoresOnlyTheRefusalAndCountsAsWithdrawn) {
  const protocol::Protocol p = sequenced();
  const std::string db = temp_db("decline.sqlite");
  auto store = store::Store::open(db, study_info(p));
  ASSERT_TRUE(store.ok()) << store.error().to_string();
  PageRecorder who;
  who.decline = true;
  auto sum = run_session(store.value(), p, "P01", who);
  ASSERT_TRUE(sum.ok()) << sum.error().to_string();
  EXPECT_TRUE(sum->declined);
  EXPECT_FALSE(sum->finished);
  EXPECT_EQ(who.trials, 0);
  EXPECT_EQ(who.names(), std::vector<std::string>{"consent"});

  auto r = store::StudyReader::open(db);
  ASSERT_TRUE(r.ok());
  auto consents = r->consents();
  ASSERT_TRUE(consents.ok());
  ASSERT_EQ(consents->size(), 1u);
  EXPECT_FALSE(consents->front().agreed);
  auto withdrawals = r->withdrawals();
  ASSERT_TRUE(withdrawals.ok());
  ASSERT_EQ(withdrawals->size(), 1u);
  EXPECT_EQ(withdrawals->front().participant, "P01");
  auto trials = r->trials();
  ASSERT_TRUE(trials.ok());
  EXPECT_TRUE(trials->empty());

  // Asked again, the refusal stands: no page, no trial.
  PageRecorder again;
  auto second = run_session(store.value(), p, "P01", again);
  ASSERT_TRUE(second.ok()) << second.error().to_string();
  EXPECT_TRUE(second->declined);
  EXPECT_TRUE(again.pages.empty());
  EXPECT_EQ(again.trials, 0);

  // The next participant runs the order row the refusal freed.
  PageRecorder next;
  auto third = run_session(store.value(), p, "P02", next);
  ASSERT_TRUE(third.ok()) << third.error().to_string();
  EXPECT_TRUE(third->finished);
  EXPECT_EQ(third->enrollment.order_row, 0);
}

TEST(Sequence, AResumedSessionShowsThePagesAnUninterruptedOneWould) {
  const protocol::Protocol p = sequenced();
  const std::string straight_db = temp_db("straight.sqlite");
  const std::string resumed_db = temp_db("resumed.sqlite");
  {
    auto store = store::Store::open(straight_db, study_info(p));
    ASSERT_TRUE(store.ok());
    PageRecorder who;
    ASSERT_TRUE(run_session(store.value(), p, "P01", who).ok());
  }
  for (int stop_at : {1, 2, 5}) {
    const std::string db = temp_db("resumed" + std::to_string(stop_at) + ".sqlite");
    auto store = store::Store::open(db, study_info(p));
    ASSERT_TRUE(store.ok());
    PageRecorder first;
    Hooks hooks;
    hooks.stop_requested = [&] { return first.trials >= stop_at; };
    auto sum = run_session(store.value(), p, "P01", first, hooks);
    ASSERT_TRUE(sum.ok()) << sum.error().to_string();
    ASSERT_TRUE(sum->stopped);
    PageRecorder rest;
    auto done = run_session(store.value(), p, "P01", rest);
    ASSERT_TRUE(done.ok()) << done.error().to_string();
    ASSERT_TRUE(done->finished);
    std::vector<std::string> a, b;
    for (const auto& s : screens(straight_db, "P01")) a.push_back(s.screen);
    for (const auto& s : screens(db, "P01")) b.push_back(s.screen);
    EXPECT_EQ(a, b) << "stopped after " << stop_at << " trials";
  }
}

TEST(Sequence, PracticeTrialsAreFollowedByTheirCorrectAnswer) {
  const protocol::Protocol p = sequenced(1);
  const std::string db = temp_db("practice.sqlite");
  auto store = store::Store::open(db, study_info(p));
  ASSERT_TRUE(store.ok()) << store.error().to_string();
  PageRecorder who;
  auto sum = run_session(store.value(), p, "P01", who);
  ASSERT_TRUE(sum.ok()) << sum.error().to_string();
  int practice = 0;
  for (const design::PlannedTrial& t : sum->plan.trials) practice += t.practice ? 1 : 0;
  ASSERT_GT(practice, 0);
  int feedback = 0;
  for (const PageSpec& page : who.pages)
    if (page.kind == PageSpec::Kind::feedback) {
      ++feedback;
      EXPECT_FALSE(page.text.empty());
    }
  EXPECT_EQ(feedback, practice);
}

}  // namespace
}  // namespace dtlab::session

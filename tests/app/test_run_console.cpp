// The experimenter console in its own window (`dtlab run --console-monitor 1`),
// through the real app on an X server with two monitors (two_monitors.sh:
// Xorg's dummy driver). A scripted session of one trial: the participant's
// window never shows the answer key or any of the console's items (not even
// on Ctrl+Shift+E), the console's window shows the key; a pause, an invalid
// trial, a note and the abort made in the console's window are stored. Also: --list-monitors
// lists both monitors, and a console monitor that does not exist or is the
// participant's is refused with exit 2, naming the monitors.
#include <gtest/gtest.h>
#include <stb_image.h>

#include "study/store/read.h"
#include "tests/app/console_session.h"
#include "tests/common/run_cli.h"

namespace dtlab::run {
namespace {

namespace fs = std::filesystem;
using test::Shown;

// The participant enrols, opens trial 1 and presses Ctrl+Shift+E in their own window (the chord
// that would open the overlay on one monitor); the experimenter pauses, resumes, saves a note and
// marks the trial invalid in the console's window; the participant answers; on the next screen the
// experimenter aborts.
constexpr const char* kScript = R"(
[start]
wait 0.3
click_item "Participant ID"
type "con-01"
click_item "age"
type "30"
click_item "Start session"

[instructions]
wait 0.2
click_item "Continue"

[training]
key Enter

[trial T1]
wait 0.3
key_down LeftControl
key_down LeftShift
key E
key_up LeftShift
key_up LeftControl
wait 0.3
window console
click_item "Pause"
wait 0.4
click_item "Resume"
click_item "Note"
type "seen in the console window"
click_item "Save note"
click_item "Trial 1 invalid..."
click_item "Reason"
type "looked away"
click_item "Record as invalid"
window participant
key Enter

[answer T1]
type "12"
key Enter

[instructions T2]
wait 0.2
window console
click_item "Abort the session..."
click_item "Abort: the session is abandoned"

[end]
wait 0.3
click_item "Close"
)";

// The console's items (any of them in the participant's window means the console was drawn there).
const char* const kConsoleItems[] = {"Answer key", "Answer key hidden", "Pause", "Resume", "Save note", "Note",
                                     "End training", "Abort the session..."};

class ConsoleWindow : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir = new fs::path(test::fresh_dir("window"));
    { std::ofstream(*dir / "console.script") << kScript; }
    // Killed at 50 s, under the script's 60 s idle limit: a click that is lost fails the test.
    rc = test::run_pilot(*dir / "c.sqlite", *dir / "log.txt", *dir / "items.jsonl",
                         {"--console-monitor", "1", "--script", (*dir / "console.script").string(), "--screenshots",
                          (*dir / "shots").string()},
                         50);
    shown = new std::vector<Shown>(test::read_items_log(*dir / "items.jsonl"));
  }
  static void TearDownTestSuite() {
    if (!::testing::Test::HasFailure() && !std::getenv("DTLAB_KEEP_TEST_DIRS")) fs::remove_all(*dir);
    delete shown;
    delete dir;
  }
  static std::string log() { return test::read_text(*dir / "log.txt"); }
  static fs::path* dir;
  static int rc;
  static std::vector<Shown>* shown;
};
fs::path* ConsoleWindow::dir = nullptr;
int ConsoleWindow::rc = -1;
std::vector<Shown>* ConsoleWindow::shown = nullptr;

TEST_F(ConsoleWindow, TheParticipantsWindowNeverShowsTheAnswerKeyOrTheConsole) {
  EXPECT_EQ(rc, 0) << log();  // what was shown is checked whatever the run's end
  int participant_lines = 0;
  bool trial_seen = false;
  for (const Shown& s : *shown) {
    if (s.window != "participant") continue;
    ++participant_lines;
    trial_seen = trial_seen || s.screen == "trial T1";
    for (const char* item : kConsoleItems) EXPECT_FALSE(s.has(item)) << item << " on the participant's " << s.screen;
  }
  EXPECT_GT(participant_lines, 5);
  EXPECT_TRUE(trial_seen) << "the trial ran in the participant's window";
}

TEST_F(ConsoleWindow, TheConsolesWindowShowsTheAnswerKeyDuringTheTrial) {
  ASSERT_EQ(rc, 0) << log();
  bool key = false, hidden = false;
  for (const Shown& s : *shown)
    if (s.window == "console") {
      key = key || (s.screen == "trial T1" && s.has("Answer key"));
      hidden = hidden || s.has("Answer key hidden");
    }
  EXPECT_TRUE(key) << "its own window shows the key without a held chord";
  EXPECT_FALSE(hidden);
  // Its picture (the gallery's): the console window's size, not the participant's 640 x 480.
  fs::path png;
  for (const auto& e : fs::directory_iterator(*dir / "shots"))
    if (e.path().filename().string().find("console-window") != std::string::npos) png = e.path();
  ASSERT_FALSE(png.empty());
  int w = 0, h = 0, n = 0;
  ASSERT_TRUE(stbi_info(png.c_str(), &w, &h, &n));
  EXPECT_GT(w, 640);
  EXPECT_GT(h, 480);
}

TEST_F(ConsoleWindow, ThePauseTheInvalidTrialTheNoteAndTheAbortMadeThereAreStored) {
  ASSERT_EQ(rc, 0) << log();
  auto r = store::StudyReader::open((*dir / "c.sqlite").string());
  ASSERT_TRUE(r) << r.error().to_string();
  const auto sessions = r->sessions();
  ASSERT_TRUE(sessions);
  ASSERT_EQ(sessions->size(), 1u);
  const auto& s = (*sessions)[0];
  EXPECT_EQ(s.status, store::SessionStatus::abandoned);
  EXPECT_EQ(s.recorded, 1);
  ASSERT_EQ(s.pauses.size(), 1u);
  EXPECT_EQ(s.pauses[0].position, 1);
  EXPECT_GE(s.pauses[0].duration_s, 0.3);  // `wait 0.4` between the clicks
  const auto notes = r->notes();
  ASSERT_TRUE(notes);
  ASSERT_EQ(notes->size(), 2u);
  EXPECT_EQ((*notes)[0].text, "seen in the console window");
  EXPECT_EQ((*notes)[0].position, 1);
  EXPECT_EQ((*notes)[1].text, "session aborted from the console");
  const auto exclusions = r->exclusions();
  ASSERT_TRUE(exclusions);
  ASSERT_EQ(exclusions->size(), 1u);
  EXPECT_EQ((*exclusions)[0].participant, "con-01");
  EXPECT_EQ((*exclusions)[0].position, 1) << "the trial running when it was marked";
  EXPECT_TRUE((*exclusions)[0].exclude);
  EXPECT_EQ((*exclusions)[0].reason, "looked away");
  // The paused time is not completion time: the trial's wall-clock span less its completion time is
  // the pause (to the millisecond the wall-clock stamps keep).
  const auto trials = r->trials("con-01");
  ASSERT_TRUE(trials);
  ASSERT_EQ(trials->size(), 1u);
  const auto& t = (*trials)[0];
  EXPECT_EQ(std::get<store::Count>(*t.answer).n, 12);
  auto seconds_of_day = [](const std::string& iso) {  // "2026-12-03T12:16:52.639Z"
    return std::stod(iso.substr(11, 2)) * 3600 + std::stod(iso.substr(14, 2)) * 60 + std::stod(iso.substr(17, 6));
  };
  double wall = seconds_of_day(t.ended_at) - seconds_of_day(t.started_at);
  if (wall < 0) wall += 86400;  // over midnight
  EXPECT_NEAR(wall - t.completion_s, s.pauses[0].duration_s, 0.01);
  EXPECT_NE(log().find("aborted from the console"), std::string::npos) << log();
}

TEST(ConsoleMonitors, ListedAndABadOneRefusedNamingThem) {
  const auto list = test::run_dtlab("run --list-monitors");
  ASSERT_EQ(list.rc, 0) << list.err;
  EXPECT_NE(list.out.find("0  DUMMY0  1280x1024 at 0,0"), std::string::npos) << list.out;
  EXPECT_NE(list.out.find("1  DUMMY1  1280x1024 at 1280,0"), std::string::npos) << list.out;
  const fs::path d = test::fresh_dir("bad");
  const std::string pilot = std::string(DTLAB_SOURCE_DIR) + "/protocols/pilot.toml";
  for (const char* n : {"2", "0"}) {
    SCOPED_TRACE(n);
    const auto bad = test::run_dtlab("run '" + pilot + "' --db '" + (d / "x.sqlite").string() + "' --console-monitor " + n);
    EXPECT_EQ(bad.rc, 2) << bad.err;
    EXPECT_NE(bad.err.find(std::string("--console-monitor ") + n), std::string::npos) << bad.err;
    if (std::string(n) == "2") EXPECT_NE(bad.err.find("0: DUMMY0, 1280x1024 at 0,0"), std::string::npos) << bad.err;
    else EXPECT_NE(bad.err.find("the participant's window is on that monitor"), std::string::npos) << bad.err;
    EXPECT_FALSE(fs::exists(d / "x.sqlite")) << "refused before anything was opened";
  }
  fs::remove_all(d);
}

}  // namespace
}  // namespace dtlab::run

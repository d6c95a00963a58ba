// The experimenter console on one monitor (`dtlab run` without
// --console-monitor; this program runs under xvfb-run): the overlay over the
// participant's screen hides the answer key, saying to hold Ctrl+Shift+K,
// and shows it only while the chord is held; the chord's K never reaches a
// participant screen (on the T2 answer screen K is an answer); the pause,
// the invalid trial, the note and the abort made in the overlay are stored
// as with the console's own window. Also: a --font that is not a whole font
// is refused with exit 1 naming it (Dear ImGui would abort on it), before
// any screen is shown.
#include <gtest/gtest.h>

#include "study/store/read.h"
#include "tests/app/console_session.h"
#include "tests/common/run_cli.h"

namespace dtlab::run {
namespace {

namespace fs = std::filesystem;
using test::Shown;

// Trial 1: the experimenter opens the console, waits, holds Ctrl+Shift+K for a moment, lets go,
// pauses, resumes, saves a note, marks the trial invalid and closes it. On the T2 answer screen
// they press Ctrl+Shift+K (which must not answer "K"), then the participant answers C. At the
// break they abort.
constexpr const char* kScript = R"(
[start]
wait 0.3
click_item "Participant ID"
type "ovl-01"
click_item "age"
type "31"
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
wait 0.4
key_down LeftControl
key_down LeftShift
key_down K
wait 0.4
key_up K
key_up LeftShift
key_up LeftControl
wait 0.4
window console
click_item "Pause"
wait 0.3
click_item "Resume"
click_item "Note"
type "seen in the overlay"
click_item "Save note"
click_item "Trial 1 invalid..."
click_item "Reason"
type "looked away"
click_item "Record as invalid"
key_down LeftControl
key_down LeftShift
key E
key_up LeftShift
key_up LeftControl
window participant
key Enter

[answer T1]
type "12"
key Enter

[trial T2]
wait 0.3
key Enter

[answer T2]
wait 0.2
key_down LeftControl
key_down LeftShift
key K
key_up LeftShift
key_up LeftControl
wait 0.5
click_item "C"

[break]
wait 0.2
key_down LeftControl
key_down LeftShift
key E
key_up LeftShift
key_up LeftControl
click_item "Abort the session..."
click_item "Abort: the session is abandoned"

[end]
wait 0.3
click_item "Close"
)";

class ConsoleOverlay : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir = new fs::path(test::fresh_dir("overlay"));
    { std::ofstream(*dir / "overlay.script") << kScript; }
    // Killed at 50 s, under the script's 60 s idle limit: a click that is lost fails the test.
    rc = test::run_pilot(*dir / "o.sqlite", *dir / "log.txt", *dir / "items.jsonl",
                         {"--script", (*dir / "overlay.script").string()}, 50);
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
fs::path* ConsoleOverlay::dir = nullptr;
int ConsoleOverlay::rc = -1;
std::vector<Shown>* ConsoleOverlay::shown = nullptr;

// What the overlay showed of the key during trial 1, in order, one entry per change:
// 'h' hidden (with the hint), 'k' the key; nothing while the console was closed.
std::string key_states(const std::vector<Shown>& shown) {
  std::string states;
  for (const Shown& s : shown) {
    if (s.window != "participant" || s.screen != "trial T1" || !s.has("Pause")) continue;
    EXPECT_NE(s.has("Answer key"), s.has("Answer key hidden")) << "the key or the hint, never both or neither";
    const char c = s.has("Answer key") ? 'k' : 'h';
    if (states.empty() || states.back() != c) states += c;
  }
  return states;
}

TEST_F(ConsoleOverlay, TheKeyIsHiddenUnlessCtrlShiftKIsHeld) {
  EXPECT_EQ(rc, 0) << log();  // what was shown is checked whatever the run's end
  // Opened: hidden; held: shown; let go: hidden again (through the pause and the note).
  EXPECT_EQ(key_states(*shown), "hkh");
  for (const Shown& s : *shown) {
    if (s.screen != "trial T1") {
      EXPECT_FALSE(s.has("Answer key")) << s.screen;
    }
  }
}

TEST_F(ConsoleOverlay, TheChordsKIsNoAnswer) {
  ASSERT_EQ(rc, 0) << log();
  auto r = store::StudyReader::open((*dir / "o.sqlite").string());
  ASSERT_TRUE(r) << r.error().to_string();
  const auto trials = r->trials("ovl-01");
  ASSERT_TRUE(trials);
  ASSERT_EQ(trials->size(), 2u);
  EXPECT_EQ(std::get<store::Count>(*(*trials)[0].answer).n, 12);
  EXPECT_EQ(std::get<store::Letter>(*(*trials)[1].answer).letter, "C") << "Ctrl+Shift+K answered K";
}

TEST_F(ConsoleOverlay, ThePauseTheInvalidTrialTheNoteAndTheAbortAreStored) {
  ASSERT_EQ(rc, 0) << log();
  auto r = store::StudyReader::open((*dir / "o.sqlite").string());
  ASSERT_TRUE(r) << r.error().to_string();
  const auto sessions = r->sessions();
  ASSERT_TRUE(sessions);
  ASSERT_EQ(sessions->size(), 1u);
  EXPECT_EQ((*sessions)[0].status, store::SessionStatus::abandoned);
  ASSERT_EQ((*sessions)[0].pauses.size(), 1u);
  EXPECT_EQ((*sessions)[0].pauses[0].position, 1);
  const auto notes = r->notes();
  ASSERT_TRUE(notes);
  ASSERT_EQ(notes->size(), 2u);
  EXPECT_EQ((*notes)[0].text, "seen in the overlay");
  EXPECT_EQ((*notes)[1].text, "session aborted from the console");
  EXPECT_FALSE((*notes)[1].position.has_value()) << "aborted between trials";
  const auto exclusions = r->exclusions();
  ASSERT_TRUE(exclusions);
  ASSERT_EQ(exclusions->size(), 1u);
  EXPECT_EQ((*exclusions)[0].participant, "ovl-01");
  EXPECT_EQ((*exclusions)[0].position, 1) << "the trial running when it was marked";
  EXPECT_TRUE((*exclusions)[0].exclude);
  EXPECT_EQ((*exclusions)[0].reason, "looked away");
}

// Regression: `--font /etc/passwd` aborted the program in ImGui's atlas build (an assertion in
// Debian's libimgui); a truncated font would read past its end. Each is now an error naming the file.
TEST(RunFont, AFileThatIsNotAWholeFontIsRefusedNamingIt) {
  const fs::path d = test::fresh_dir("font");
  const std::string pilot = std::string(DTLAB_SOURCE_DIR) + "/protocols/pilot.toml";
  { std::ofstream(d / "notes.ttf") << "these are notes, not a font\n"; }
  std::vector<std::pair<std::string, std::string>> cases{{"notes.ttf", "no font signature"}};
  const fs::path dejavu = "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf";
  if (fs::exists(dejavu)) {
    const std::string whole = test::read_text(dejavu);
    ASSERT_GT(whole.size(), 4000u);
    { std::ofstream(d / "head.ttf", std::ios::binary) << whole.substr(0, 100); }   // its directory: 12 + 16 x 20 bytes
    { std::ofstream(d / "part.ttf", std::ios::binary) << whole.substr(0, 4000); }  // directory whole, tables not
    cases.emplace_back("head.ttf", "its table directory is cut off");
    cases.emplace_back("part.ttf", "a table lies past the end of the file");
  }
  for (const auto& [file, why] : cases) {
    SCOPED_TRACE(file);
    const auto r = test::run_dtlab("run '" + pilot + "' --db '" + (d / "f.sqlite").string() + "' --size 640x480 --font '" +
                                   (d / file).string() + "'");
    EXPECT_EQ(r.rc, 1) << r.err;
    EXPECT_NE(r.err.find((d / file).string() + ": font: not a TrueType or OpenType font (" + why), std::string::npos)
        << r.err;
  }
  fs::remove_all(d);
}

}  // namespace
}  // namespace dtlab::run

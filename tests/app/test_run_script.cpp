// Scripts for `dtlab run --script` (app/run/script.h): what parses, what is
// refused with file:line, and which section serves which screen. No window:
// the player is exercised end to end by the window tests (test_run.cpp).
#include <gtest/gtest.h>

#include <memory>

#include "app/run/script.h"

namespace dtlab::run {
namespace {

TEST(Script, ParsesSectionsAndSteps) {
  const auto s = parse_script_text(
      "# a comment\n"
      "[start]\n"
      "click_item \"Participant ID\"   # trailing comment\n"
      "type \"P \"\"7\"\"\"\n"
      "key Enter\n"
      "[trial T1]\n"
      "drag 10 20 30.5 40 0.5\n"
      "hold Up 1.25\n"
      "click_item \"floor plan\" 0.25 0.75\n"
      "[trial]\n"
      "turn -150 0.4\n",
      "s.script");
  ASSERT_TRUE(s) << s.error().to_string();
  ASSERT_EQ(s->sections.size(), 3u);
  const auto& start = s->sections[0].steps;
  ASSERT_EQ(start.size(), 3u);
  EXPECT_EQ(start[0].op, ScriptStep::Op::click_item);
  EXPECT_EQ(start[0].text, "Participant ID");
  EXPECT_EQ(start[1].text, "P \"7\"");
  EXPECT_EQ(start[2].key, Input::key_code("Enter"));
  const auto& t1 = s->sections[1].steps;
  EXPECT_EQ(t1[0].x1, 30.5);
  EXPECT_EQ(t1[0].seconds, 0.5);
  EXPECT_EQ(t1[1].seconds, 1.25);
  EXPECT_EQ(t1[2].x0, 0.25);
  EXPECT_EQ(t1[2].y0, 0.75);
  EXPECT_EQ(t1[2].line, 9);
  // Sections: the exact screen first, then its first word.
  EXPECT_EQ(s->for_screen("trial T1"), &s->sections[1]);
  EXPECT_EQ(s->for_screen("trial T3"), &s->sections[2]);
  EXPECT_EQ(s->for_screen("start"), &s->sections[0]);
  EXPECT_EQ(s->for_screen("answer T1"), nullptr);
}

struct Bad {
  const char* name;
  const char* text;
  int line;
  const char* says;
};

class ScriptErrors : public ::testing::TestWithParam<Bad> {};

TEST_P(ScriptErrors, NameTheLineAndWhatWasExpected) {
  const auto s = parse_script_text(GetParam().text, "bad.script");
  ASSERT_FALSE(s);
  EXPECT_EQ(s.error().file, "bad.script");
  EXPECT_EQ(s.error().line, GetParam().line) << s.error().to_string();
  EXPECT_NE(s.error().to_string().find(GetParam().says), std::string::npos) << s.error().to_string();
}

INSTANTIATE_TEST_SUITE_P(
    Table, ScriptErrors,
    ::testing::Values(Bad{"empty", "", 0, "no [screen] section"},
                      Bad{"step_before_section", "key Enter\n", 1, "before any [screen]"},
                      Bad{"unknown_step", "[start]\njump 3\n", 2, "unknown step"},
                      Bad{"unknown_key", "[start]\nkey Hyper\n", 2, "unknown key \"Hyper\""},
                      Bad{"missing_argument", "[start]\nwait\n", 2, "expected: wait SECONDS"},
                      Bad{"not_a_number", "[start]\nwait soon\n", 2, "is not a number"},
                      Bad{"negative_wait", "[start]\nwait -1\n", 2, "within 0..3600"},
                      Bad{"open_quote", "[start]\ntype \"abc\n", 2, "not closed"},
                      Bad{"bad_button", "[start]\nclick 1 2 thumb\n", 2, "left, right or middle"},
                      Bad{"one_fraction", "[start]\nclick_item \"x\" 0.5\n", 2, "both fractions"},
                      Bad{"duplicate_section", "[start]\nwait 1\n[start]\n", 3, "already defined at line 1"},
                      Bad{"bad_header", "[start\n", 1, "expected [SCREEN]"}),
    [](const auto& info) { return std::string(info.param.name); });

// An instrument's items share its section ("questionnaire tlx" serves "questionnaire tlx.mental");
// a section of its own wins, the most specific first ("questionnaire tlx.w" for the pairs).
TEST(Script, AnInstrumentsItemsShareItsSection) {
  const auto s = parse_script_text("[questionnaire tlx]\nkey Enter\n[questionnaire tlx.w]\nkey 1\n"
                                   "[questionnaire tlx.effort]\nkey 2\n[questionnaire]\nkey 3\n",
                                   "s.script");
  ASSERT_TRUE(s) << s.error().to_string();
  EXPECT_EQ(s->for_screen("questionnaire tlx.mental"), &s->sections[0]);
  EXPECT_EQ(s->for_screen("questionnaire tlx.w.mental-physical"), &s->sections[1]);
  EXPECT_EQ(s->for_screen("questionnaire tlx.effort"), &s->sections[2]);
  EXPECT_EQ(s->for_screen("questionnaire sus.q1"), &s->sections[3]);
  EXPECT_EQ(s->for_screen("questionnaire"), &s->sections[3]);
}

// `type` takes any script as UTF-8 (each code point one character); bytes that are not UTF-8 are
// refused at the step's line before anything runs.
TEST(Script, TypeTakesUtf8AndRefusesOtherBytes) {
  EXPECT_TRUE(parse_script_text("[s]\ntype \"καλό, добро, żółć\"\n", "s.script"));
  const auto bad = parse_script_text("[s]\nwait 1\ntype \"ab\xff\"\n", "s.script");
  ASSERT_FALSE(bad);
  EXPECT_EQ(bad.error().line, 3);
  EXPECT_NE(bad.error().message.find("not UTF-8"), std::string::npos) << bad.error().message;
}

TEST(Script, ANulByteIsRefused) {
  const auto s = parse_script_text(std::string("[start]\nwa\0it 1\n", 16), "nul.script");
  ASSERT_FALSE(s);
  EXPECT_EQ(s.error().line, 2);
  EXPECT_NE(s.error().message.find("NUL"), std::string::npos);
}

TEST(Script, KeyNamesRoundTrip) {
  for (const char* name : {"A", "Z", "0", "9", "F1", "F12", "Enter", "Space", "Escape", "Up", "LeftShift"})
    EXPECT_EQ(Input::key_name(Input::key_code(name)), name);
  EXPECT_EQ(Input::key_code("a"), Input::key_code("A"));
  EXPECT_EQ(Input::key_code("F13"), -1);
  EXPECT_EQ(Input::key_code(""), -1);
}

TEST(Script, TheShippedPilotScriptParses) {
  const auto s = parse_script(std::string(DTLAB_SOURCE_DIR) + "/protocols/pilot-session.script");
  ASSERT_TRUE(s) << s.error().to_string();
  for (const char* screen : {"start", "instructions T1", "training T3", "trial T1", "answer T2", "answer T3", "break",
                             "questionnaire rating", "questionnaire preference", "questionnaire depth_self",
                             "depth_test", "end"})
    EXPECT_NE(s->for_screen(screen), nullptr) << screen;
}


// The player against a fake clock (no window: Input takes events only through its entry points).
// Regression: a click_item whose item was drawn off the window "clicked" it and finished, and the
// depth test then waited forever with the script played out (issue: a second participant's
// session hung at the depth test). Every step now gives up after its documented timeout.
struct Played {
  Script script;
  Input input{nullptr};
  std::unique_ptr<ScriptPlayer> player;
  Clock::time_point t0 = Clock::now();
  explicit Played(const std::string& text) {
    auto s = parse_script_text(text, "t.script");
    EXPECT_TRUE(s) << s.error().to_string();
    script = std::move(*s);
    player = std::make_unique<ScriptPlayer>(script, input);
  }
  // Ticks screen `screen` every 0.1 s up to `seconds`; the first error, or success.
  Status run(const std::string& screen, const ItemBoxes& items, double seconds, double from = 0) {
    for (double t = from; t <= seconds; t += 0.1) {
      const auto now = t0 + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(t));
      if (Status st = player->tick(screen, 1, items, {}, now); !st) return st;
    }
    return {};
  }
};

TEST(ScriptPlayer, ClickItemThatNeverAppearsFailsAfterItsTimeoutNamingTheLine) {
  Played p("[depth_test]\nwait 0.2\nclick_item \"A\"\n");
  EXPECT_TRUE(p.run("depth_test", {{"B", ItemBox{10, 10, 20, 20}}}, kItemTimeoutS - 1));
  const Status st = p.run("depth_test", {{"B", ItemBox{10, 10, 20, 20}}}, kItemTimeoutS + 2, kItemTimeoutS - 1);
  ASSERT_FALSE(st);
  EXPECT_EQ(st.error().file, "t.script");
  EXPECT_EQ(st.error().line, 3);
  EXPECT_NE(st.error().message.find("no UI item \"A\" appeared on screen"), std::string::npos) << st.error().message;
  EXPECT_NE(st.error().message.find("\"B\""), std::string::npos) << "it lists what was on screen";
}

TEST(ScriptPlayer, ClickItemWhoseBoxNeverHoldsStillFailsAfterItsTimeout) {
  Played p("[s]\nclick_item \"A\"\n");
  Status st;
  for (double t = 0; t <= kItemTimeoutS + 2 && st; t += 0.1) {
    const auto now = p.t0 + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(t));
    st = p.player->tick("s", 1, {{"A", ItemBox{static_cast<float>(t * 10), 0, 20, 20}}}, {}, now);
  }
  ASSERT_FALSE(st);
  EXPECT_EQ(st.error().line, 2);
  EXPECT_NE(st.error().message.find("did not hold still"), std::string::npos) << st.error().message;
}

TEST(ScriptPlayer, ClickItemPressesAndReleasesAtTheBoxCentre) {
  Played p("[s]\nclick_item \"A\"\n");
  const ItemBoxes items{{"A", ItemBox{100, 50, 40, 20}}};
  bool pressed = false;
  for (double t = 0; t < 1.0; t += 0.1) {
    p.input.new_frame();
    const auto now = p.t0 + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(t));
    ASSERT_TRUE(p.player->tick("s", 1, items, {}, now));
    if (p.input.button_pressed(0)) {
      pressed = true;
      EXPECT_EQ(p.input.cursor(), glm::dvec2(120, 60));
    }
  }
  EXPECT_TRUE(pressed);
  EXPECT_TRUE(p.player->played_out());
}

TEST(ScriptPlayer, AScreenStillUpAfterItsSectionPlayedOutFailsNamingTheLastStep) {
  Played p("[questionnaire rating]\nwait 0.2\nkey 7\n");
  EXPECT_TRUE(p.run("questionnaire rating", {}, kIdleTimeoutS - 1)) << "within the timeout it waits";
  const Status st = p.run("questionnaire rating", {}, kIdleTimeoutS + 2, kIdleTimeoutS - 1);
  ASSERT_FALSE(st);
  EXPECT_EQ(st.error().line, 3);
  EXPECT_NE(st.error().message.find("played out"), std::string::npos) << st.error().message;
}

TEST(ScriptPlayer, AScreenWithoutASectionFailsAfterTheTimeout) {
  Played p("[start]\nkey Enter\n");
  EXPECT_TRUE(p.run("break", {}, kIdleTimeoutS - 1));
  const Status st = p.run("break", {}, kIdleTimeoutS + 2, kIdleTimeoutS - 1);
  ASSERT_FALSE(st);
  EXPECT_NE(st.error().message.find("no section for the screen \"break\""), std::string::npos) << st.error().message;
}

// `window console` sends a section's next steps to the console's own window: its click_item finds the
// console window's items (not the participant's), its keys reach the console's input only, a key
// it holds is released there when the screen goes, and the next screen's section starts in the
// participant's window again.
TEST(ScriptPlayer, WindowConsoleStepsActInTheConsolesWindowOnly) {
  Played p("[trial]\nwindow console\nkey_down LeftShift\nclick_item \"Pause\"\nwindow participant\nkey Enter\n"
           "[answer]\nkey 5\n");
  Input console{nullptr};
  p.player = std::make_unique<ScriptPlayer>(p.script, p.input, &console);
  const ItemBoxes participant_items{{"Answer", ItemBox{0, 0, 10, 10}}};
  const ItemBoxes console_items{{"Pause", ItemBox{200, 100, 40, 20}}};
  bool console_clicked = false, participant_enter = false;
  for (double t = 0; t < 1.0; t += 0.05) {
    p.input.new_frame();
    console.new_frame();
    const auto now = p.t0 + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(t));
    ASSERT_TRUE(p.player->tick("trial T1", 1, participant_items, console_items, now));
    p.player->console_drew();  // here the console window draws a frame at every participant frame
    EXPECT_FALSE(p.input.button_pressed(0)) << "no click in the participant's window";
    if (console.button_pressed(0)) {
      console_clicked = true;
      EXPECT_EQ(console.cursor(), glm::dvec2(220, 110));
    }
    participant_enter = participant_enter || p.input.key_pressed(Input::key_code("Enter"));
    EXPECT_FALSE(console.key_pressed(Input::key_code("Enter")));
  }
  EXPECT_TRUE(console_clicked);
  EXPECT_TRUE(participant_enter);
  EXPECT_TRUE(console.shift()) << "held in the console's window";
  EXPECT_FALSE(p.input.shift());
  p.player->leave();
  EXPECT_FALSE(console.shift()) << "released where it was held when the screen went";
  p.input.new_frame();
  ASSERT_TRUE(p.player->tick("answer T1", 2, {}, console_items, p.t0 + std::chrono::seconds(2)));
  ASSERT_TRUE(p.player->tick("answer T1", 2, {}, console_items, p.t0 + std::chrono::seconds(2)));
  EXPECT_TRUE(p.input.key_down(Input::key_code("5")) || p.input.key_pressed(Input::key_code("5")))
      << "a new section starts in the participant's window";
}

// The console window draws in the participant's spare time, so fewer frames: a step acting there waits
// for one console frame after each of its phases. Regression: a click's release and the next click's
// press fell into one console frame, ImGui saw the button held while the cursor jumped, and "Resume"
// was never clicked (the session stayed paused).
TEST(ScriptPlayer, ConsoleStepsWaitForAConsoleFrameAfterEachPhase) {
  Played p("[trial]\nwindow console\nclick_item \"Resume\"\nclick_item \"Save note\"\n");
  Input console{nullptr};
  p.player = std::make_unique<ScriptPlayer>(p.script, p.input, &console);
  const ItemBoxes console_items{{"Resume", ItemBox{0, 0, 40, 20}}, {"Save note", ItemBox{0, 100, 40, 20}}};
  // Console frames at every third participant frame; what each console frame sees of the mouse.
  std::vector<std::pair<bool, glm::dvec2>> seen;  // (button down or pressed since the last console frame, cursor)
  for (int frame = 0; frame < 60; ++frame) {
    p.input.new_frame();
    const auto now = p.t0 + std::chrono::milliseconds(16 * frame);
    ASSERT_TRUE(p.player->tick("trial T1", 1, {}, console_items, now));
    if (frame % 3 == 2) {
      seen.emplace_back(console.button_down(0) || console.button_pressed(0), console.cursor());
      console.new_frame();
      p.player->console_drew();
    }
  }
  // Each click is down in one console frame and up in the next, at its own item.
  std::vector<glm::dvec2> clicks;
  for (std::size_t i = 0; i + 1 < seen.size(); ++i)
    if (seen[i].first && !seen[i + 1].first) clicks.push_back(seen[i].second);
  ASSERT_EQ(clicks.size(), 2u);
  EXPECT_EQ(clicks[0], glm::dvec2(20, 10));
  EXPECT_EQ(clicks[1], glm::dvec2(20, 110));
  EXPECT_TRUE(p.player->played_out());
}

// On one monitor there is no console window: `window console` steps act in the participant's window,
// where the console is drawn.
TEST(ScriptPlayer, WindowConsoleWithoutAConsoleWindowActsInTheParticipantsWindow) {
  Played p("[trial]\nwindow console\nclick_item \"Pause\"\n");
  const ItemBoxes items{{"Pause", ItemBox{200, 100, 40, 20}}};
  bool clicked = false;
  for (double t = 0; t < 0.5; t += 0.05) {
    p.input.new_frame();
    const auto now = p.t0 + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(t));
    ASSERT_TRUE(p.player->tick("trial T1", 1, items, {}, now));
    clicked = clicked || p.input.button_pressed(0);
  }
  EXPECT_TRUE(clicked);
}

// Ctrl+Shift+E with the console in its own window lends the participant's pointer to it: free of a
// WALKTHROUGH capture, its motion turns nothing (no delta), until it is given back or a click in the
// participant's window takes it back; coming back does not make the view jump.
TEST(InputLendPointer, ALentPointerTurnsNothingAndAClickTakesItBack) {
  Input in{nullptr};
  in.capture_cursor(true);
  in.on_cursor(100, 100);
  in.new_frame();
  in.on_cursor(110, 100);
  EXPECT_EQ(in.cursor_delta(), glm::dvec2(10, 0));
  in.lend_pointer(true);
  in.new_frame();
  in.on_cursor(900, 400);
  in.on_cursor(950, 420);
  EXPECT_EQ(in.cursor_delta(), glm::dvec2(0, 0)) << "the experimenter's mouse travel turns nothing";
  EXPECT_TRUE(in.cursor_captured()) << "the capture resumes when the pointer comes back";
  in.on_mouse_button(0, 1 /* GLFW_PRESS */, 0);
  EXPECT_FALSE(in.pointer_lent());
  EXPECT_TRUE(in.button_pressed(0)) << "the click that takes it back is a click";
  EXPECT_EQ(in.cursor(), glm::dvec2(950, 420)) << "where the pointer is";
  in.new_frame();
  in.on_cursor(-3000, 7000);  // the captured cursor's own origin
  EXPECT_EQ(in.cursor_delta(), glm::dvec2(0, 0)) << "no jump on the first position after the return";
  in.on_cursor(-2995, 7000);
  EXPECT_EQ(in.cursor_delta(), glm::dvec2(5, 0));
}

TEST(ScriptParse, WindowTakesConsoleOrParticipant) {
  EXPECT_TRUE(parse_script_text("[trial]\nwindow console\nwindow participant\n", "w.script"));
  const auto bad = parse_script_text("[trial]\nwindow experimenter\n", "w.script");
  ASSERT_FALSE(bad);
  EXPECT_EQ(bad.error().line, 2);
  EXPECT_NE(bad.error().message.find("expected console or participant"), std::string::npos) << bad.error().message;
}

}  // namespace
}  // namespace dtlab::run

// Scripts for `dtlab run --script` (app/run/script.h): what parses, what is
// refused with file:line, and which section serves which screen. No window:
// the player is exercised end to end by the window tests (test_run.cpp).
#include <gtest/gtest.h>

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

}  // namespace
}  // namespace dtlab::run

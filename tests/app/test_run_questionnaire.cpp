// The questionnaire's screens in the real window (this program runs under
// xvfb-run): `dtlab run` with tests/app/data/questionnaire-screens.toml and
// its script answers a page of every item type the window draws (sliders of
// NASA-TLX after each block, set by typing and by the arrow keys; a Likert
// item after each level, by a point's number and by its label; a multiple
// choice, a typed number, a choice with its neutral option, free text with
// Greek letters) and the stored answers are exactly what the script chose.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <map>

#include "study/store/read.h"
#include "tests/common/run_cli.h"

namespace dtlab::run {
namespace {

namespace fs = std::filesystem;

const std::string kData = std::string(DTLAB_SOURCE_DIR) + "/tests/app/data/";

// `dtlab run` of the screens study and its script; the exit code, or -1 after `seconds` (killed).
int run_screens(const fs::path& db, const fs::path& log, double seconds) {
  return test::run_dtlab_for({"run", kData + "questionnaire-screens.toml", "--db", db.string(), "--size", "640x480",
                              "--script", kData + "questionnaire-screens.script"},
                             log, seconds);
}

TEST(RunQuestionnaire, EveryItemScreenTakesTheScriptsAnswer) {
  const fs::path d = fs::temp_directory_path() / ("dtlab_run_questionnaire_" + std::to_string(::getpid()));
  fs::remove_all(d);
  fs::create_directories(d);
  const int rc = run_screens(d / "screens.sqlite", d / "log.txt", 240);
  ASSERT_EQ(rc, 0) << test::read_text(d / "log.txt");
  auto r = store::StudyReader::open((d / "screens.sqlite").string());
  ASSERT_TRUE(r.ok()) << r.error().to_string();
  std::map<std::string, std::string> got;
  const auto answers = r->questionnaire("screens-01");
  ASSERT_TRUE(answers.ok());
  for (const auto& a : *answers) {
    if (const double* v = std::get_if<double>(&a.value)) {
      char buf[32];
      std::snprintf(buf, sizeof buf, "%g", *v);
      got[a.item + "[" + a.scope + "]"] = buf;
    } else {
      got[a.item + "[" + a.scope + "]"] = std::get<std::string>(a.value);
    }
  }
  const std::map<std::string, std::string> expected = {
      {"tlx.mental[block=1]", "35"},       {"tlx.physical[block=1]", "35"},    {"tlx.temporal[block=1]", "35"},
      {"tlx.performance[block=1]", "35"},  {"tlx.effort[block=1]", "35"},      {"tlx.frustration[block=1]", "60"},
      {"tlx.mental[block=2]", "35"},       {"tlx.physical[block=2]", "35"},    {"tlx.temporal[block=2]", "35"},
      {"tlx.performance[block=2]", "35"},  {"tlx.effort[block=2]", "35"},      {"tlx.frustration[block=2]", "60"},
      {"liked[transparency=off]", "4"},    {"liked[transparency=on]", "4"},    {"symptom[]", "1"},
      {"games[]", "shooters\npuzzles"},    {"hours[]", "12.5"},                {"view[]", "either"},
      {"comment[]", "Gut, aber καλό: 5/5."},
  };
  EXPECT_EQ(got, expected);
  const auto sessions = r->sessions();
  ASSERT_TRUE(sessions.ok());
  ASSERT_EQ(sessions->size(), 1u);
  EXPECT_EQ((*sessions)[0].status, store::SessionStatus::finished);
  if (!::testing::Test::HasFailure()) fs::remove_all(d);
}

}  // namespace
}  // namespace dtlab::run

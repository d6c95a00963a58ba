// The shipped comparison protocols/screen-door-vs-dt.toml end to end as a
// researcher runs it: `dtlab simulate` (every participant, headless at a
// small size, the simulated participant looking through each method's own
// frames) and `dtlab analyze`: every trial of the three techniques recorded,
// and the report's JSON carries the technique factor with its three levels.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <nlohmann/json.hpp>

#include "tests/common/run_cli.h"

namespace {

namespace fs = std::filesystem;

TEST(ScreenDoorStudy, SimulatesAndAnalyses) {
  const fs::path dir = fs::temp_directory_path() / ("dtlab_sd_study_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  const fs::path db = dir / "study.sqlite", out = dir / "report";
  const auto sim = dtlab::test::run_dtlab("simulate '" + std::string(DTLAB_SOURCE_DIR) +
                                          "/protocols/screen-door-vs-dt.toml' --participants 6 --db '" + db.string() +
                                          "' --width 96 --height 72 --json");
  ASSERT_EQ(sim.rc, 0) << sim.err;
  const auto rep = dtlab::test::run_dtlab("analyze '" + db.string() + "' --out '" + out.string() + "' --quiet --json");
  ASSERT_EQ(rep.rc, 0) << rep.err;
  const std::string text = rep.out + dtlab::test::read_text(out / "report.json");
  // 6 participants x 3 techniques x 2 trials, every level named in the analysis.
  const auto summary = nlohmann::json::parse(sim.out);
  EXPECT_EQ(summary.at("trials_run"), 36) << sim.out;
  EXPECT_TRUE(summary.at("failed").empty()) << sim.out;
  for (const char* level : {"\"off\"", "\"dt\"", "\"screen-door\""}) EXPECT_NE(text.find(level), std::string::npos) << level;
  fs::remove_all(dir);
}

}  // namespace

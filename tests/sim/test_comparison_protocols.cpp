// The shipped comparison protocol protocols/vdt-vs-dt.toml end to end, as a
// researcher runs it: `dtlab simulate` (every condition through the real
// renderer, the simulated participant seeing through vdt like through any
// method), then `dtlab export` and `dtlab analyze` on the database. At the
// pilot tests' size: one participant per Latin-square row, 96 x 72 frames.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <string>

#include "tests/common/run_cli.h"

namespace {

namespace fs = std::filesystem;
using dtlab::test::read_text;
using dtlab::test::run_dtlab;

TEST(ComparisonProtocols, VdtVsDtSimulatesExportsAndAnalyses) {
  const fs::path dir = fs::temp_directory_path() / ("dtlab_vdt_vs_dt_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  const fs::path db = dir / "study.sqlite", csv = dir / "trials.csv", report = dir / "report";
  const auto sim = run_dtlab("simulate '" + std::string(DTLAB_SOURCE_DIR) + "/protocols/vdt-vs-dt.toml' " +
                             "--participants 3 --width 96 --height 72 --db '" + db.string() + "'");
  ASSERT_EQ(sim.rc, 0) << sim.err;
  const auto exp = run_dtlab("export '" + db.string() + "' --csv '" + csv.string() + "'");
  ASSERT_EQ(exp.rc, 0) << exp.err;
  const std::string rows = read_text(csv);
  std::size_t vdt = 0, seed = 0, standard = 0;
  for (std::size_t i = rows.find('\n'); i != std::string::npos; i = rows.find('\n', i + 1)) {
    const std::string line = rows.substr(i + 1, rows.find('\n', i + 1) - i - 1);
    vdt += line.find(",vdt,") != std::string::npos;
    seed += line.find(",dt-seed,") != std::string::npos;
    standard += line.find(",standard,") != std::string::npos;
  }
  // 3 participants x 2 trials per condition.
  EXPECT_EQ(vdt, 6u) << rows.substr(0, 400);
  EXPECT_EQ(seed, 6u);
  EXPECT_EQ(standard, 6u);
  const auto an = run_dtlab("analyze '" + db.string() + "' --out '" + report.string() + "' --quiet");
  ASSERT_EQ(an.rc, 0) << an.err;
  const std::string html = read_text(report / "index.html");
  EXPECT_NE(html.find("vdt"), std::string::npos);
  fs::remove_all(dir);
}

}  // namespace

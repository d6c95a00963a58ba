// The shipped comparison protocols (protocols/*-vs-dt.toml: another source
// paper's technique against dynamic transparency in the reference design),
// each simulated end to end as a user runs it: `dtlab simulate` with one
// participant per row of its ordering (a pilot's size), then `dtlab analyze`.
// Every protocol of that name is found by listing the folder, so a new one is
// tested without editing this file. Asserts: every participant's every
// planned trial is stored under its own condition, each condition has trials
// and answers, the report is written, and it never speaks of "the article"
// (these protocols declare no published results).
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <unistd.h>

#include "analysis/stats/csv.h"
#include "study/design/design.h"
#include "study/protocol/protocol.h"
#include "study/store/export.h"
#include "tests/common/run_cli.h"

namespace {

namespace fs = std::filesystem;

std::vector<std::string> comparison_protocols() {
  std::vector<std::string> out;
  for (const auto& e : fs::directory_iterator(fs::path(DTLAB_SOURCE_DIR) / "protocols")) {
    const std::string name = e.path().filename().string();
    if (name.size() > 11 && name.substr(name.size() - 11) == "-vs-dt.toml") out.push_back(name);
  }
  std::sort(out.begin(), out.end());
  return out;
}

TEST(ComparisonProtocols, AtLeastTheLensProtocolIsShipped) {
  const auto names = comparison_protocols();
  EXPECT_NE(std::find(names.begin(), names.end(), "lens-vs-dt.toml"), names.end());
}

class ComparisonProtocol : public ::testing::TestWithParam<std::string> {};

TEST_P(ComparisonProtocol, SimulatesAndAnalysesEndToEnd) {
  const std::string path = std::string(DTLAB_SOURCE_DIR) + "/protocols/" + GetParam();
  auto p = dtlab::protocol::load_protocol(path);
  ASSERT_TRUE(p.ok()) << p.error().to_string();
  const int participants = dtlab::design::order_rows(*p);
  ASSERT_GE(participants, 2);

  const fs::path dir = fs::temp_directory_path() / ("dtlab_compare_" + std::to_string(::getpid()) + "_" +
                                                   GetParam().substr(0, GetParam().find('.')));
  fs::remove_all(dir);
  fs::create_directories(dir);
  const fs::path db = dir / "study.sqlite", report = dir / "report";
  const auto sim = dtlab::test::run_dtlab("simulate '" + path + "' --participants " + std::to_string(participants) +
                                          " --db '" + db.string() + "' --width 96 --height 72");
  ASSERT_EQ(sim.rc, 0) << sim.out << sim.err;

  // Every planned trial of every participant, under the condition its plan names.
  std::ostringstream csv;
  auto sum = dtlab::store::export_trials_csv(db.string(), csv);
  ASSERT_TRUE(sum.ok()) << sum.error().to_string();
  auto t = dtlab::stats::parse_csv(csv.str(), db.string());
  ASSERT_TRUE(t.ok());
  std::size_t planned = 0;
  for (int k = 0; k < participants; ++k) planned += dtlab::design::make_plan(*p, k).trials.size();
  EXPECT_EQ(t->rows.size(), planned);
  const auto col = [&](const char* name) { return static_cast<std::size_t>(t->column(name)); };
  std::map<std::string, int> per_method, answered;
  std::set<std::string> people;
  for (const auto& row : t->rows) {
    ++per_method[row[col("method")]];
    answered[row[col("method")]] +=
        row[col("answer_count")] != "NA" || row[col("answer_letter")] != "NA" || row[col("answer_x")] != "NA";
    people.insert(row[col("participant")]);
  }
  EXPECT_EQ(people.size(), static_cast<std::size_t>(participants));
  for (const auto& r : p->renderings) {
    EXPECT_GT(per_method[r.method], 0) << r.name << " (" << r.method << ") has no trials";
    EXPECT_GT(answered[r.method], 0) << r.name << " (" << r.method << ") has no answers";
  }

  const auto analyze = dtlab::test::run_dtlab("analyze '" + db.string() + "' --out '" + report.string() + "'");
  ASSERT_EQ(analyze.rc, 0) << analyze.out << analyze.err;
  const std::string md = dtlab::test::read_text(report / "report.md");
  ASSERT_FALSE(md.empty());
  EXPECT_NE(md.find("Completion time"), std::string::npos);
  EXPECT_EQ(md.find("article"), std::string::npos) << "a protocol without [reference_results] cites no article";
  fs::remove_all(dir);
}

INSTANTIATE_TEST_SUITE_P(Shipped, ComparisonProtocol, ::testing::ValuesIn(comparison_protocols()),
                         [](const auto& info) {
                           std::string n = info.param.substr(0, info.param.find('.'));
                           std::replace(n.begin(), n.end(), '-', '_');
                           return n;
                         });

}  // namespace

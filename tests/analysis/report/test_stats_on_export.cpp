// `dtlab stats` on the CSV `dtlab export` writes of a database with practice
// trials: practice rows are left out by default (it is a dtlab export), and
// one task's test with --aggregate mean then gives the report's F and p;
// keeping the practice rows changes F; repeated rows without --aggregate and
// an unknown --where column are errors that say what to do.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "tests/analysis/report/studies.h"
#include "tests/common/run_cli.h"

namespace dtlab::report::testing {
namespace {

using nlohmann::json;

double number(const json& j) { return j.is_number() ? j.get<double>() : std::nan(""); }

// A protocol with one practice trial per task set: `dtlab stats` on `dtlab export`'s CSV leaves the practice
// rows out by default (it is a dtlab export) and then gives the report's F and p; keeping them changes F.
TEST(StatsOnExport, PracticeRowsLeftOutByDefaultGiveTheReportsTest) {
  TempDir dir;
  StudySpec s;
  s.protocol_text = source_file("protocols/elmqvist2008.toml");
  const std::string from = "practice_trials = 0", to = "practice_trials = 1";
  const auto at = s.protocol_text.find(from);
  ASSERT_NE(at, std::string::npos);
  s.protocol_text.replace(at, from.size(), to);
  for (int i = 1; i <= 6; ++i) s.participants.push_back("P" + std::to_string(i));
  s.trial = [](size_t p, const design::PlannedTrial& t) -> std::optional<Outcome> {
    Outcome o;
    const bool off = level(t, "transparency") == "off";
    o.time_s = 20.0 + static_cast<double>(p) + (off ? 3.0 + 0.7 * static_cast<double>(p % 3) : 0.0) +
               0.25 * t.trial + (t.practice ? 40.0 * static_cast<double>(p % 2) * (off ? 1 : -0.5) : 0.0);
    return o;
  };
  const std::string db = dir.file("s.sqlite"), csv = dir.file("trials.csv");
  build_study(db, s);
  const json report = run_report(db, dir.file("out"));
  const json& effect = find_effect(find_test(report, "completion_time", "T1"), "transparency");

  ASSERT_EQ(test::run_dtlab("export " + db + " --csv " + csv).rc, 0);
  const std::string stats = "stats rm-anova --data " + csv +
                            " --dv completion_time_s --subject participant --within transparency --where task=T1";
  const auto by_default = test::run_dtlab(stats + " --aggregate mean --json");
  ASSERT_EQ(by_default.rc, 0) << by_default.err;
  const json d = json::parse(by_default.out);
  EXPECT_GT(d.at("rows").at("practice_left_out"), 0);
  const json& e = d.at("effects")[0];
  EXPECT_NEAR(number(e.at("F")), number(effect.at("F")), 1e-9 * number(effect.at("F")));
  EXPECT_NEAR(number(e.at("p")), number(effect.at("p")), 1e-9 * number(effect.at("p")));
  const auto asked = test::run_dtlab(stats + " --aggregate mean --exclude-practice --json");
  ASSERT_EQ(asked.rc, 0) << asked.err;
  EXPECT_EQ(json::parse(asked.out).at("effects")[0].at("F"), e.at("F"));
  const auto text = test::run_dtlab(stats + " --aggregate mean");
  EXPECT_NE(text.out.find("of practice trials left out (the default for a dtlab export; --include-practice keeps them)"),
            std::string::npos) << text.out;
  const auto with_practice = test::run_dtlab(stats + " --aggregate mean --include-practice --json");
  ASSERT_EQ(with_practice.rc, 0) << with_practice.err;
  EXPECT_GT(std::abs(number(json::parse(with_practice.out).at("effects")[0].at("F")) - number(effect.at("F"))), 0.01)
      << "practice trials would change the test";
  // Several trials per participant and cell: an error naming the lines unless --aggregate reduces them.
  const auto repeated = test::run_dtlab(stats);
  EXPECT_EQ(repeated.rc, 1);
  EXPECT_NE(repeated.err.find(csv), std::string::npos) << repeated.err;
  EXPECT_NE(repeated.err.find("--aggregate"), std::string::npos) << repeated.err;
  // --where naming a column that does not exist lists the columns.
  const auto unknown = test::run_dtlab(stats + " --where taks=T1 --aggregate mean");
  EXPECT_EQ(unknown.rc, 1);
  EXPECT_NE(unknown.err.find("taks: no such column for --where; the header has: participant, "), std::string::npos)
      << unknown.err;
}

}  // namespace
}  // namespace dtlab::report::testing

// Power planning from a pilot database (analysis/report/planning.h,
// `dtlab power`, the report's "Planning the next study"): the analytic power
// of an observed effect against R's power.t.test, the resampling's
// determinism whatever the thread count, errors and exit codes.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <fstream>
#include <string>

#include "analysis/report/planning.h"
#include "study/protocol/protocol.h"
#include "study/store/read.h"
#include "tests/analysis/report/studies.h"
#include "tests/common/run_cli.h"

namespace dtlab::report::testing {
namespace {

using nlohmann::json;

double number(const json& j) { return j.is_number() ? j.get<double>() : std::nan(""); }

const json& planned(const json& effects, const std::string& scope, const std::string& measure, const std::string& effect) {
  for (const auto& e : effects)
    if (e.at("scope") == scope && e.at("measure") == measure && e.at("effect") == effect) return e;
  ADD_FAILURE() << "no planned effect " << scope << " / " << measure << " / " << effect;
  static const json none = json::object();
  return none;
}

Result<PowerPlan> plan(const std::string& db, const PlanningOptions& o) {
  store::ReadOptions ro;
  ro.design_hash_of = &protocol::design_sha256_of_text;
  auto reader = store::StudyReader::open(db, ro);
  if (!reader) return reader.error();
  return plan_power(*reader, o);
}

// The T1 row of build_statsmodels_t1 is F(1, 7) = 22.4 (ezANOVA), so d_z = sqrt(22.4 / 8). R 4.2.2:
//   power.t.test(n = n, delta = sqrt(22.4 / 8), sd = 1, type = "paired", strict = TRUE)$power
//   n = 8 -> 0.980315824401141, n = 12 -> 0.999480804653524, n = 5 -> 0.79618, n = 6 -> 0.9009394
//   (so the smallest n for 80% and for 90% is 6).
TEST(Planning, TheReportSectionGivesTheAnalyticPowerOfTheObservedEffect) {
  TempDir dir;
  build_statsmodels_t1(dir.file("s.sqlite"));
  const json report = run_report(dir.file("s.sqlite"), dir.file("out"));
  ASSERT_TRUE(report.contains("planning"));
  const json& p = report.at("planning");
  EXPECT_EQ(p.at("method"), "analytic");
  const json& t1 = planned(p.at("effects"), "T1", "completion time", "transparency");
  EXPECT_EQ(t1.at("pilot_n"), 8);
  EXPECT_NEAR(number(t1.at("dz")), std::sqrt(22.4 / 8), 1e-9);
  const json& at = t1.at("power");
  ASSERT_EQ(at.size(), 5u);
  EXPECT_EQ(at[0].at("n"), 8);
  EXPECT_NEAR(number(at[0].at("analytic")), 0.980315824401141, 1e-6);
  EXPECT_EQ(at[1].at("n"), 12);
  EXPECT_NEAR(number(at[1].at("analytic")), 0.999480804653524, 1e-6);
  EXPECT_TRUE(at[0].at("resampled").is_null()) << "the report does not resample";
  EXPECT_EQ(number(t1.at("n_for_80")), 6);
  EXPECT_EQ(number(t1.at("n_for_90")), 6);
  const std::string md = read_text(dir.file("out/report.md"));
  EXPECT_NE(md.find("## Planning the next study"), std::string::npos);
  EXPECT_NE(md.find("dtlab power " + dir.file("s.sqlite") + " --participants 8,12,16,24,32"), std::string::npos);
}

TEST(Planning, ResamplingIsSeededAndIndependentOfTheThreadCount) {
  TempDir dir;
  build_statsmodels_2x2(dir.file("s.sqlite"));
  PlanningOptions o;
  o.sizes = {4, 16};
  o.replications = 60;
  o.seed = 5;
  o.threads = 1;
  std::size_t calls = 0, last_total = 0;
  o.progress = [&](std::size_t done, std::size_t total) {
    ++calls;
    last_total = total;
    EXPECT_LE(done, total);
  };
  const auto one = plan(dir.file("s.sqlite"), o);
  ASSERT_TRUE(one.ok()) << one.error().to_string();
  o.threads = 2;
  o.progress = nullptr;
  const auto two = plan(dir.file("s.sqlite"), o);
  ASSERT_TRUE(two.ok()) << two.error().to_string();
  ASSERT_FALSE(one->effects.empty());
  ASSERT_EQ(one->effects.size(), two->effects.size());
  EXPECT_EQ(calls, last_total);
  for (std::size_t i = 0; i < one->effects.size(); ++i)
    for (std::size_t k = 0; k < 2; ++k) {
      const auto& a = one->effects[i].at[k].resampled;
      EXPECT_EQ(a.rejections, two->effects[i].at[k].resampled.rejections) << i << " " << k;
      EXPECT_EQ(a.replications, 60u);
      if (std::isfinite(a.power)) {
        EXPECT_LE(a.ci_low, a.power);
        EXPECT_GE(a.ci_high, a.power);
      }
    }
  // The overall 2 x 2 test: three effects, each planned.
  int overall = 0;
  for (const auto& e : one->effects) overall += e.scope == "overall" && e.measure == "completion time";
  EXPECT_EQ(overall, 3);
  o.seed = 6;
  const auto other = plan(dir.file("s.sqlite"), o);
  ASSERT_TRUE(other.ok());
  std::size_t differ = 0;
  for (std::size_t i = 0; i < one->effects.size(); ++i)
    differ += other->effects[i].at[0].resampled.rejections != one->effects[i].at[0].resampled.rejections;
  EXPECT_GT(differ, 0u) << "another seed draws other participants";
}

TEST(Planning, BadOptionsAreInputErrors) {
  TempDir dir;
  build_small_reference(dir.file("s.sqlite"), 4);
  PlanningOptions o;
  o.replications = 0;
  o.sizes = {1};
  EXPECT_FALSE(plan(dir.file("s.sqlite"), o).ok());
  o.sizes = {8};
  o.alpha = 1.5;
  EXPECT_FALSE(plan(dir.file("s.sqlite"), o).ok());
  o.alpha = 0.05;
  o.revision = "all";
  EXPECT_FALSE(plan(dir.file("s.sqlite"), o).ok());
  o.revision = "7";
  const auto r = plan(dir.file("s.sqlite"), o);
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.error().kind, ErrorKind::not_found);
  o.revision = "latest";
  EXPECT_TRUE(plan(dir.file("s.sqlite"), o).ok());
}

// Broke: `dtlab power` printed the Greenhouse-Geisser p beside the uncorrected df.
// R (tests/analysis/data/stats_r_followups.R, section 8): anova(aov_car(score ~ Error(id/week), complete
// subjects of pingouin_rm_anova_wide.csv), correction = "GG") -> num Df 2.08298799390625,
// den Df 16.66390395125, Pr(>F) 0.0166993073368505.
TEST(PowerCli, ThePrintedDfAreThoseOfTheP) {
  TempDir dir;
  build_pingouin_wide(dir.file("w.sqlite"));
  const auto r = test::run_dtlab("power " + dir.file("w.sqlite") + " --replications 0 --json");
  ASSERT_EQ(r.rc, 0) << r.err;
  const json j = json::parse(r.out);
  const json& week = planned(j.at("effects"), "T1", "completion time", "week");
  EXPECT_NEAR(number(week.at("p_df1")), 2.08298799390625, 1e-9);
  EXPECT_NEAR(number(week.at("p_df2")), 16.66390395125, 1e-9);
  EXPECT_NEAR(number(week.at("p")), 0.0166993073368505, 1e-10);
  EXPECT_EQ(number(week.at("df1")), 3);
  const auto text = test::run_dtlab("power " + dir.file("w.sqlite") + " --replications 0 --quiet");
  EXPECT_NE(text.out.find("F(2.08, 16.66) = 5.20, p = 0.0167 (Greenhouse-Geisser)"), std::string::npos) << text.out;
}

TEST(PowerCli, JsonTextAndExitCodes) {
  TempDir dir;
  build_statsmodels_t1(dir.file("s.sqlite"));
  const std::string db = dir.file("s.sqlite");
  const auto r = test::run_dtlab("power " + db + " --participants 6,10 --replications 40 --jobs 2 --json");
  ASSERT_EQ(r.rc, 0) << r.err;
  const json j = json::parse(r.out);
  EXPECT_EQ(j.at("sizes"), json({6, 10}));
  EXPECT_EQ(j.at("replications"), 40);
  EXPECT_EQ(j.at("participants"), 8);
  const json& t1 = planned(j.at("effects"), "T1", "completion time", "transparency");
  // R 4.2.2: power.t.test(n = 6, delta = sqrt(22.4 / 8), sd = 1, type = "paired", strict = TRUE)$power -> 0.9009394
  EXPECT_NEAR(number(t1.at("power")[0].at("analytic")), 0.9009394, 1e-6);
  const double resampled = number(t1.at("power")[0].at("resampled"));
  EXPECT_GE(resampled, 0.0);
  EXPECT_LE(resampled, 1.0);
  EXPECT_LE(number(t1.at("power")[0].at("resampled_ci95_low")), resampled);
  EXPECT_NE(r.err.find("dtlab power: resampled"), std::string::npos) << "progress on stderr";
  const auto same = test::run_dtlab("power " + db + " --participants 6,10 --replications 40 --jobs 1 --json --quiet");
  ASSERT_EQ(same.rc, 0) << same.err;
  EXPECT_EQ(json::parse(same.out).at("effects"), j.at("effects")) << "the thread count changes nothing";
  EXPECT_TRUE(same.err.empty()) << same.err;

  const auto text = test::run_dtlab("power " + db + " --replications 20 --quiet");
  ASSERT_EQ(text.rc, 0) << text.err;
  EXPECT_NE(text.out.find("T1, completion time: transparency"), std::string::npos) << text.out;
  // The reference protocol's 4 x 4 Latin square: 6 leaves two rows used once more than the others.
  EXPECT_NE(text.out.find("smallest n for 80% power: 6 (analytic; 8 keeps the 4 order rows of the latin-square balanced)"),
            std::string::npos) << text.out;
  EXPECT_EQ(j.at("order_rows"), 4);
  EXPECT_EQ(j.at("order_scheme"), "latin-square");
  EXPECT_EQ(number(t1.at("n_for_80")), 6);
  EXPECT_EQ(number(t1.at("n_for_80_balanced")), 8);
  EXPECT_EQ(number(t1.at("p_df1")), 1);  // a 1-df effect: its p is uncorrected
  const auto sizes = test::run_dtlab("power " + db + " --participants 6,8 --replications 0 --quiet");
  EXPECT_NE(sizes.out.find("6 (next balanced: 8) is not a multiple"), std::string::npos) << sizes.out;

  EXPECT_EQ(test::run_dtlab("power " + db + " --participants 1").rc, 2);
  EXPECT_EQ(test::run_dtlab("power " + db + " --alpha 2").rc, 2);
  EXPECT_EQ(test::run_dtlab("power " + dir.file("missing.sqlite")).rc, 2);
  std::ofstream(dir.file("text.txt")) << "not a database\n";
  const auto bad = test::run_dtlab("power " + dir.file("text.txt"));
  EXPECT_EQ(bad.rc, 1) << bad.err;
  EXPECT_NE(bad.err.find("text.txt"), std::string::npos) << bad.err;
  const auto revision = test::run_dtlab("power " + db + " --revision 3");
  EXPECT_NE(revision.rc, 0);
  EXPECT_NE(revision.err.find("revision"), std::string::npos) << revision.err;
}

}  // namespace
}  // namespace dtlab::report::testing

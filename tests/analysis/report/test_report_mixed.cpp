// The report's mixed-model section (mixed_models.cpp computes, layout_models.cpp lays out) on the statsmodels
// 2 x 2 study (studies.h: 8 participants, times = statsmodels' anova-rm DV,
// both tasks of a scenario the same times, letter answers as studies.cpp
// sets them): its models equal lme4 / lmerTest / emmeans fitted in R on the
// report's own trials.csv (the R calls above the values), the section is in
// report.md with the lme4 calls a reader can paste, and report.json has every fit.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <string>

#include "analysis/report/planning.h"
#include "study/protocol/protocol.h"
#include "study/store/read.h"
#include "tests/analysis/report/studies.h"
#include "tests/analysis/stats/test_util.h"

namespace dtlab::report::testing {
namespace {

using nlohmann::json;

class ReportMixed : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir = new TempDir;
    build_statsmodels_2x2(dir->file("s.sqlite"));
    report = new json(run_report(dir->file("s.sqlite"), dir->file("out")));
    md = new std::string(read_text(dir->file("out/report.md")));
  }
  static void TearDownTestSuite() {
    delete md;
    delete report;
    delete dir;
  }
  static const json& model(const std::string& section, const std::string& scope) {
    for (const auto& m : (*report)["mixed_models"])
      if (m["section"] == section && m["scope"] == scope) return m;
    ADD_FAILURE() << "no mixed model " << section << " " << scope;
    static const json none;
    return none;
  }
  static TempDir* dir;
  static json* report;
  static std::string* md;
};
TempDir* ReportMixed::dir = nullptr;
json* ReportMixed::report = nullptr;
std::string* ReportMixed::md = nullptr;

// R (lme4 1.1-31, lmerTest 3.1-3, emmeans 1.8.4) on the report's trials.csv:
//   options(contrasts = c("contr.sum", "contr.poly"))
//   d <- subset(read.csv("trials.csv"), practice == 0 & is.na(excluded))
//   m <- lmer(log(completion_time_s) ~ transparency + (1 | participant), data = subset(d, task == "T1"))
//   REMLcrit(m); anova(m); confint(pairs(emmeans(m, ~ transparency, lmer.df = "satterthwaite",
//                                                type = "response"), reverse = TRUE))
//   (lme4: boundary (singular) fit: these times have no participant variance)
TEST_F(ReportMixed, TimeModelOfATaskEqualsLmerTest) {
  const json& m = model("time", "T1");
  ASSERT_TRUE(m.contains("fit")) << m.dump();
  const json& f = m["fit"];
  EXPECT_EQ(f["formula"], "log(completion_time_s) ~ transparency + (1 | participant)");
  EXPECT_TRUE(stats::test::near_rel(f["reml_criterion"].get<double>(), 53.430483750489145, 1e-6));
  EXPECT_TRUE(stats::test::near_rel(f["anova"][0]["F"].get<double>(), 16.577682902512308, 1e-6));
  EXPECT_TRUE(stats::test::near_rel(f["anova"][0]["den_df"].get<double>(), 45.999999999459071, 1e-4));
  const json& c = m["primary"]["contrasts"][0];  // off - on; the table shows on / off
  EXPECT_TRUE(stats::test::near_rel(1 / c["ratio"].get<double>(), 1.5957025915436063, 1e-6));
  EXPECT_TRUE(stats::test::near_rel(1 / c["ratio_ci_high"].get<double>(), 1.2665342098919945, 1e-6));
}

// R: m <- lmer(log(completion_time_s) ~ transparency * task + (1 | participant), data = d); anova(m)
TEST_F(ReportMixed, TimeModelOverAllTasksHasTheTaskAsAFactor) {
  const json& f = model("time", "overall")["fit"];
  EXPECT_EQ(f["formula"], "log(completion_time_s) ~ transparency * task + (1 | participant)");
  ASSERT_EQ(f["anova"].size(), 3u);
  EXPECT_TRUE(stats::test::near_rel(f["anova"][0]["F"].get<double>(), 8.5519629387074136, 1e-6));
  EXPECT_TRUE(stats::test::near_rel(f["anova"][2]["F"].get<double>(), 1.0522649234690018, 1e-6));
}

// R: ctl <- glmerControl(tolPwrss = 1e-13, optimizer = "nloptwrap",
//                        optCtrl = list(xtol_abs = 1e-14, ftol_abs = 1e-15, xtol_rel = 1e-14))
//    afex::mixed(correct ~ transparency + (1 | participant), data = subset(d, task == "T2"),
//                family = binomial, method = "LRT", control = ctl)
TEST_F(ReportMixed, LetterTaskGetsABinomialGlmmWithItsLrt) {
  const json& m = model("accuracy", "T2");
  ASSERT_TRUE(m.contains("fit")) << m.dump();
  EXPECT_EQ(m["fit"]["family"], "binomial");
  EXPECT_EQ(m["fit"]["formula"], "correct ~ transparency + (1 | participant)");
  EXPECT_NEAR(m["fit"]["lrt"][0]["chisq"].get<double>(), 5.9093163478087511, 1e-5);
}

TEST_F(ReportMixed, SectionIsInTheReportWithPasteableCalls) {
  EXPECT_NE(md->find("## Mixed models on trial-level data"), std::string::npos);
  EXPECT_NE(md->find("`lmer(log(completion_time_s) ~ transparency + (1 | participant), data = subset(d, task == "
                     "\"T1\"))`"),
            std::string::npos);
  EXPECT_NE(md->find("`glmer(correct ~ transparency + (1 | participant), data = subset(d, task == \"T2\"), "
                     "family = binomial, control = ctl)`"),
            std::string::npos);
  EXPECT_NE(md->find("T1: on trials took "), std::string::npos);
  // every model is compared with the report's test by decision at .05
  for (const auto& m : (*report)["mixed_models"]) {
    if (m.contains("fit")) {
      EXPECT_FALSE(m["decisions"].empty()) << m["scope"];
    }
  }
}

// dtlab power --mixed: every fitted mixed model's primary factor planned by simulation
// (stats::lmm_power, checked against the paired t's power in test_lmm_power.cpp),
// one row per size, the same numbers for the same seed.
TEST_F(ReportMixed, PowerPlansTheMixedModelsBySimulation) {
  auto plan_with = [&](std::uint64_t seed) {
    store::ReadOptions ro;
    ro.design_hash_of = &protocol::design_sha256_of_text;
    auto reader = store::StudyReader::open(dir->file("s.sqlite"), ro);
    EXPECT_TRUE(reader.ok());
    PlanningOptions o;
    o.sizes = {4, 12};
    o.replications = 0;
    o.mixed = true;
    o.mixed_replications = 40;
    o.seed = seed;
    auto plan = plan_power(*reader, o);
    EXPECT_TRUE(plan.ok()) << (plan.ok() ? "" : plan.error().to_string());
    return *plan;
  };
  const PowerPlan a = plan_with(5), b = plan_with(5);
  ASSERT_EQ(a.mixed.size(), (*report)["mixed_models"].size());
  for (size_t i = 0; i < a.mixed.size(); ++i) {
    const auto& m = a.mixed[i];
    SCOPED_TRACE(m.section + " " + m.scope);
    EXPECT_EQ(m.term, "transparency");
    ASSERT_EQ(m.at.size(), 2u) << m.not_planned;
    for (size_t k = 0; k < 2; ++k) {
      EXPECT_EQ(m.at[k].power.replications, 40u);
      EXPECT_EQ(m.at[k].power.rejections, b.mixed[i].at[k].power.rejections);
      EXPECT_GE(m.at[k].power.power, 0.0);
      EXPECT_LE(m.at[k].power.power, 1.0);
    }
  }
}

}  // namespace
}  // namespace dtlab::report::testing

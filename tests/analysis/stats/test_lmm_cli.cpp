// `dtlab stats lmm` run as a user runs it: the JSON equals the library's
// reference case (lme4 values from data/lmm/lmm_reference.json), every field
// the docs promise is there, lme4's singular message reaches stderr, and bad
// input gives file:line messages with exit codes 1 and 2.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <fstream>
#include <set>
#include <string>

#include "test_util.h"
#include "tests/common/run_cli.h"

namespace dtlab::stats {
namespace {

using nlohmann::json;

std::string data(const std::string& name) { return test::data_path("lmm/" + name); }

json case_named(const std::string& name) {
  std::ifstream in(test::data_path("lmm/lmm_reference.json"));
  const json ref = json::parse(in);
  for (const auto& c : ref["cases"])
    if (c["name"] == name) return c;
  ADD_FAILURE() << "no case " << name;
  return {};
}

// R: lmerTest::lmer(log(time) ~ A * B + (1 | s), data = d, REML = TRUE) on balanced_2x2.csv
//    (REMLcrit(m), coef(summary(m)), anova(m); case "balanced_intercepts")
TEST(LmmCli, JsonEqualsLmerTestAndHasEveryField) {
  const json ref = case_named("balanced_intercepts");
  const auto r = dtlab::test::run_dtlab("stats lmm --data " + data("balanced_2x2.csv") +
                                        " --dv time --subject s --within A,B --transform log --emmeans A,A:B --json");
  ASSERT_EQ(r.rc, 0) << r.err;
  const json j = json::parse(r.out);
  for (const char* key : {"test", "formula", "family", "method", "ddf", "n", "groups", "random", "fallback",
                          "coefficients", "anova", "lrt", "variances", "correlations", "sigma", "theta",
                          "reml_criterion", "deviance", "loglik", "df", "aic", "bic", "singular", "messages",
                          "warnings", "r_code", "emmeans", "rows"})
    EXPECT_TRUE(j.contains(key)) << key;
  EXPECT_EQ(j["formula"], ref["formula"]);
  EXPECT_TRUE(test::near_rel(j["reml_criterion"].get<double>(), ref["criterion"].get<double>(), 1e-6));
  EXPECT_TRUE(test::near_rel(j["coefficients"][1]["se"].get<double>(), ref["se"][1].get<double>(), 1e-6));
  EXPECT_TRUE(test::near_rel(j["anova"][0]["den_df"].get<double>(), ref["den_df"][0].get<double>(), 1e-4));
  ASSERT_EQ(j["emmeans"].size(), 2u);
  EXPECT_EQ(j["emmeans"][1]["means"].size(), 4u);
  EXPECT_EQ(j["emmeans"][0]["scale"], "log");
  // a log model's contrast is a ratio with a sentence
  const std::string apa = j["emmeans"][0]["apa"][0];
  EXPECT_NE(apa.find("a1 trials took"), std::string::npos) << apa;
  EXPECT_NE(apa.find("times as long as a2 trials, 95% CI ["), std::string::npos) << apa;
  EXPECT_NE(j["r_code"].get<std::string>().find("lmer(log(time) ~ A * B + (1 | s), data = d, REML = TRUE)"),
            std::string::npos);
}

// R: lme4 messages "boundary (singular) fit: see help('isSingular')" for
//    lmer(y ~ A + (1 + A | s), d) on one_factor_3.csv (case "one_factor_slopes")
TEST(LmmCli, SingularMessageOnStderrAndInJson) {
  const auto r = dtlab::test::run_dtlab("stats lmm --data " + data("one_factor_3.csv") +
                                        " --dv y --subject s --within A --random slopes --json");
  ASSERT_EQ(r.rc, 0) << r.err;
  EXPECT_NE(r.err.find("boundary (singular) fit: see help('isSingular')"), std::string::npos) << r.err;
  EXPECT_TRUE(json::parse(r.out)["singular"].get<bool>());
}

TEST(LmmCli, BadDataAndBadOptions) {
  const std::string path = ::testing::TempDir() + "/lmm_bad.csv";
  std::ofstream(path) << "s,A,time\ns1,a1,1.2\ns1,a2,-3\ns2,a1,1\ns2,a2,2\n";
  auto r = dtlab::test::run_dtlab("stats lmm --data " + path + " --dv time --subject s --within A --transform log");
  EXPECT_EQ(r.rc, 1);
  EXPECT_NE(r.err.find("lmm_bad.csv:3"), std::string::npos) << r.err;
  r = dtlab::test::run_dtlab("stats lmm --data " + path + " --dv time --subject s --within A --random everything");
  EXPECT_EQ(r.rc, 2);
  EXPECT_NE(r.err.find("--random must be intercepts, slopes or max"), std::string::npos) << r.err;
  r = dtlab::test::run_dtlab("stats lmm --data " + path + " --dv time --subject s --within A --reml --ml");
  EXPECT_EQ(r.rc, 2);
  r = dtlab::test::run_dtlab("stats lmm --data " + path + " --dv nope --subject s --within A");
  EXPECT_EQ(r.rc, 1);
  EXPECT_NE(r.err.find("nope"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace dtlab::stats

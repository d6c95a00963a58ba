// The report's "Instruments and questions per condition" (questionnaire_results.cpp, layout_instruments.cpp):
// NASA-TLX asked after every block is scored (raw TLX) and compared across the
// conditions with a repeated-measures ANOVA, a Likert item asked after each
// transparency level with Friedman's test, both checked against R on the same
// answers (tests/analysis/data/instruments_r_references.R, its output in
// instruments_r_references.Rout); free-text answers are listed as typed, the
// empty ones left out; the scores reach instrument_scores.csv.
#include <gtest/gtest.h>

#include <filesystem>

#include "analysis/stats/csv.h"
#include "tests/analysis/report/studies.h"

namespace dtlab::report::testing {
namespace {

const nlohmann::json& measure(const nlohmann::json& report, const std::string& id) {
  for (const auto& m : report.at("instruments").at("measures"))
    if (m.at("id") == id) return m;
  ADD_FAILURE() << "no measure " << id;
  throw std::runtime_error("measure not found");
}

class Instruments : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new TempDir;
    build_instruments(dir_->file("instruments.sqlite"));
    report_ = new nlohmann::json(run_report(dir_->file("instruments.sqlite"), dir_->file("report")));
  }
  static void TearDownTestSuite() {
    delete report_;
    delete dir_;
  }
  static TempDir* dir_;
  static nlohmann::json* report_;
};
TempDir* Instruments::dir_ = nullptr;
nlohmann::json* Instruments::report_ = nullptr;

TEST_F(Instruments, RawTlxPerConditionAndItsAnovaEqualR) {
  const auto& m = measure(*report_, "tlx:raw");
  EXPECT_EQ(m.at("occasion"), "block");
  const auto& t = m.at("test");
  EXPECT_EQ(t.at("test"), "rm-anova");
  EXPECT_EQ(t.at("n"), 8);
  // R: aggregate(raw ~ transparency + scenario, tlx, function(x) c(mean = mean(x), sd = sd(x)))
  const std::map<std::string, std::pair<double, double>> cells = {{"off/abstract", {47.60416666666666, 3.19466010314136}},
                                                                  {"off/walkthrough", {49.89583333333333, 4.25938506255435}},
                                                                  {"on/abstract", {35.10416666666666, 5.89991760771096}},
                                                                  {"on/walkthrough", {38.85416666666667, 4.93886232963737}}};
  ASSERT_EQ(t.at("cells").size(), 4u);
  for (const auto& c : t.at("cells")) {
    const auto& [mean, sd] = cells.at(c.at("cell").get<std::string>());
    EXPECT_NEAR(c.at("mean").get<double>(), mean, 1e-12) << c.at("cell");
    EXPECT_NEAR(c.at("sd").get<double>(), sd, 1e-12) << c.at("cell");
  }
  // R: afex::aov_ez(id = "participant", dv = "raw", data = tlx, within = c("transparency", "scenario"),
  //                 anova_table = list(correction = "none", es = "pes"))
  struct Row {
    const char* effect;
    double F, p, pes;
  };
  for (const Row& r : {Row{"transparency", 33.166233766233795, 0.0006919798150378, 0.825724262803932},
                       Row{"scenario", 2.619937694704056, 0.1495611015872537, 0.272344559585493},
                       Row{"transparency:scenario", 0.859649122807012, 0.3846904554039170, 0.109374999999999}}) {
    const auto& e = find_effect(t, r.effect);
    EXPECT_EQ(e.at("df1").get<double>(), 1) << r.effect;
    EXPECT_EQ(e.at("df2").get<double>(), 7) << r.effect;
    EXPECT_NEAR(e.at("F").get<double>(), r.F, 1e-9 * r.F) << r.effect;
    EXPECT_NEAR(e.at("p").get<double>(), r.p, 1e-9 * r.p) << r.effect;
    EXPECT_NEAR(e.at("eta_p2").get<double>(), r.pes, 1e-9) << r.effect;
  }
}

TEST_F(Instruments, LikertPerLevelAndItsFriedmanTestEqualR) {
  const auto& m = measure(*report_, "ease");
  EXPECT_EQ(m.at("occasion"), "level:transparency");
  EXPECT_EQ(m.at("min"), 1);
  EXPECT_EQ(m.at("max"), 7);
  const auto& t = m.at("test");
  EXPECT_EQ(t.at("test"), "friedman");
  // R: aggregate(ease ~ transparency, e, function(x) c(mean = mean(x), sd = sd(x)))
  EXPECT_NEAR(t.at("cells")[0].at("mean").get<double>(), 4.375, 1e-12);
  EXPECT_NEAR(t.at("cells")[0].at("sd").get<double>(), 1.18773493916542, 1e-12);
  EXPECT_NEAR(t.at("cells")[1].at("sd").get<double>(), 1.59798980865694, 1e-12);
  // R: friedman.test(ease ~ transparency | participant, data = e)
  const auto& f = t.at("friedman");
  EXPECT_NEAR(f.at("Q").get<double>(), 1.285714285714286, 1e-12);
  EXPECT_EQ(f.at("df").get<double>(), 1);
  EXPECT_NEAR(f.at("p").get<double>(), 0.256839257957857, 1e-12);
}

TEST_F(Instruments, FreeTextIsListedAsTypedAndScoresReachTheirCsv) {
  const auto& texts = report_->at("instruments").at("free_text");
  ASSERT_EQ(texts.size(), 3u) << "P1, P4 and P7 wrote something; empty answers are left out";
  EXPECT_EQ(texts[0].at("participant"), "P1");
  EXPECT_EQ(texts[0].at("text"), "Participant P1 found the lens \"slow\"; für mich gut.");
  EXPECT_EQ(texts[0].at("condition"), "");
  const std::string md = read_text(dir_->file("report/report.md"));
  EXPECT_NE(md.find("für mich gut"), std::string::npos);
  EXPECT_NE(md.find("Instruments and questions per condition"), std::string::npos);
  auto csv = stats::read_csv_file(dir_->file("report/instrument_scores.csv"));
  ASSERT_TRUE(csv.ok()) << csv.error().to_string();
  EXPECT_EQ(csv->rows.size(), 32u) << "8 participants x 4 blocks, one raw TLX each";
  const int scale = csv->column("scale"), value = csv->column("value");
  double sum = 0;
  for (const auto& r : csv->rows) {
    EXPECT_EQ(r[static_cast<size_t>(scale)], "tlx:raw");
    sum += std::stod(r[static_cast<size_t>(value)]);
  }
  // The grand mean of the raw TLX: the mean of R's four cell means (every participant in every cell).
  EXPECT_NEAR(sum / 32, (47.60416666666666 + 49.89583333333333 + 35.10416666666666 + 38.85416666666667) / 4, 1e-9);
}

}  // namespace
}  // namespace dtlab::report::testing

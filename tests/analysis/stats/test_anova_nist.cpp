// One-way ANOVA against NIST StRD certified values (all 11 datasets, as CSV
// converted by data/nist/convert_nist.py with the decimal text unchanged),
// against R's aov on PlantGrowth, and the documented results for degenerate
// data.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "analysis/stats/anova.h"
#include "analysis/stats/csv.h"
#include "analysis/stats/posthoc.h"
#include "test_util.h"

namespace dtlab::stats {
namespace {

using test::data_path;
using test::lre;
using test::near_rel;

struct Certified {
  std::string name;
  double df_between, ss_between, F, df_within, ss_within, r_squared, residual_sd;
};

std::vector<Certified> certified() {
  auto t = read_csv_file(data_path("nist/certified.csv"));
  EXPECT_TRUE(t.ok());
  std::vector<Certified> out;
  for (const auto& r : t->rows)
    out.push_back({r[0], std::strtod(r[1].c_str(), nullptr), std::strtod(r[2].c_str(), nullptr),
                   std::strtod(r[4].c_str(), nullptr), std::strtod(r[5].c_str(), nullptr),
                   std::strtod(r[6].c_str(), nullptr), std::strtod(r[8].c_str(), nullptr),
                   std::strtod(r[9].c_str(), nullptr)});
  return out;
}

TEST(AnovaNist, EveryDatasetHasLreOfAtLeast12) {
  const auto cert = certified();
  ASSERT_EQ(cert.size(), 11u);
  for (const auto& c : cert) {
    SCOPED_TRACE(c.name);
    const LongData d = test::load_long("nist/" + c.name + ".csv", {"response", "", {}, {"treatment"}});
    auto r = one_way_anova(d);
    ASSERT_TRUE(r.ok()) << r.error().to_string();
    const Effect& e = r->effect;
    EXPECT_EQ(e.df1, c.df_between);
    EXPECT_EQ(e.df2, c.df_within);
    EXPECT_GE(lre(e.ss, c.ss_between), 12.0) << "SS between " << e.ss;
    EXPECT_GE(lre(e.ss_error, c.ss_within), 12.0) << "SS within " << e.ss_error;
    EXPECT_GE(lre(e.F, c.F), 12.0) << "F " << e.F;
    EXPECT_GE(lre(e.eta_p2, c.r_squared), 12.0) << "R^2 " << e.eta_p2;
    EXPECT_GE(lre(std::sqrt(e.ss_error / e.df2), c.residual_sd), 12.0);
  }
}

// The plain method (strtod, then two-pass sums in double) on the same file:
// shows the test data really is hard, so the LRE test above can fail.
TEST(AnovaNist, PlainDoublesLoseAccuracyOnSmLs09) {
  auto t = read_csv_file(data_path("nist/SmLs09.csv"));
  ASSERT_TRUE(t.ok());
  std::vector<std::string> g;
  std::vector<double> y;
  for (const auto& r : t->rows) {
    g.push_back(r[0]);
    y.push_back(std::strtod(r[1].c_str(), nullptr));
  }
  std::vector<double> sum(10, 0.0), n(10, 0.0);
  for (size_t i = 0; i < y.size(); ++i) {
    const int k = std::atoi(g[i].c_str());
    sum[k] += y[i];
    n[k] += 1;
  }
  double ssw = 0;
  for (size_t i = 0; i < y.size(); ++i) {
    const int k = std::atoi(g[i].c_str());
    ssw += (y[i] - sum[k] / n[k]) * (y[i] - sum[k] / n[k]);
  }
  EXPECT_LT(lre(ssw, 1.8e2), 8.0) << "plain doubles should not reach 8 digits on SmLs09";
}

// R 4.x: summary(aov(weight ~ group, data = PlantGrowth))
//   group 2 3.766 1.8832 4.846 0.0159; Residuals 27 10.492 0.3886
// R 4.x: anova(lm(weight ~ group, PlantGrowth)): Sum Sq 3.7663 10.4921, F 4.8461, Pr(>F) 0.01591
TEST(AnovaR, PlantGrowthMatchesAov) {
  const std::vector<double> y{4.17, 5.58, 5.18, 6.11, 4.50, 4.61, 5.17, 4.53, 5.33, 5.14,
                              4.81, 4.17, 4.41, 3.59, 5.87, 3.83, 6.03, 4.89, 4.32, 4.69,
                              6.31, 5.12, 5.54, 5.50, 5.37, 5.29, 4.92, 6.15, 5.80, 5.26};
  std::vector<std::string> g;
  for (const char* level : {"ctrl", "trt1", "trt2"})
    for (int i = 0; i < 10; ++i) g.push_back(level);
  const OneWayResult r = one_way_anova(g, y).value();
  EXPECT_EQ(r.effect.df1, 2);
  EXPECT_EQ(r.effect.df2, 27);
  EXPECT_TRUE(near_rel(r.effect.ss, 3.76634, 1e-5));
  EXPECT_TRUE(near_rel(r.effect.ss_error, 10.49209, 1e-6));
  EXPECT_TRUE(near_rel(r.effect.F, 4.8461, 1e-4));
  EXPECT_TRUE(near_rel(r.effect.p, 0.01591, 3e-4));
  ASSERT_EQ(r.groups.size(), 3u);
  // R: tapply(weight, group, mean) = 5.032 4.661 5.526; sd = 0.583 0.794 0.443 (3 digits)
  EXPECT_NEAR(r.groups[0].d.mean, 5.032, 1e-12);
  EXPECT_NEAR(r.groups[2].d.mean, 5.526, 1e-12);
  EXPECT_NEAR(r.groups[1].d.sd, 0.794, 5e-4);

  // R 4.x: pairwise.t.test(PlantGrowth$weight, PlantGrowth$group, p.adjust.method = "bonferroni")
  //   trt1-ctrl 0.583, trt2-ctrl 0.263, trt2-trt1 0.013 (pooled SD, printed to 3 digits)
  LongData d;
  d.between.push_back({"group", g});
  d.dv = Measurements::from_doubles(y);
  auto pc = pairwise_between(d);
  ASSERT_TRUE(pc.ok());
  ASSERT_EQ(pc->size(), 3u);
  EXPECT_NEAR(std::min(1.0, 3 * (*pc)[0].p), 0.583, 5e-4);
  EXPECT_NEAR(std::min(1.0, 3 * (*pc)[1].p), 0.263, 5e-4);
  EXPECT_NEAR(std::min(1.0, 3 * (*pc)[2].p), 0.013, 5e-4);
  EXPECT_EQ((*pc)[0].df, 27);
  // R 4.2.2: pairwise.t.test(PlantGrowth$weight, PlantGrowth$group, p.adjust.method = "holm")$p.value
  //   trt1-ctrl 0.194387880054301, trt2-ctrl 0.175363350125367, trt2-trt1 0.0133777078146164
  EXPECT_NEAR((*pc)[0].p_holm, 0.194387880054301, 1e-12);
  EXPECT_NEAR((*pc)[1].p_holm, 0.175363350125367, 1e-12);
  EXPECT_NEAR((*pc)[2].p_holm, 0.0133777078146164, 1e-12);
  // The rows describe ctrl - trt1 with the pooled SE: 0.371, SE 0.27878160840555 (s_pooled sqrt(2/10)),
  // CI 0.371 -+ qt(.975, 27) SE = -0.201012611559963 0.943012611559964
  EXPECT_NEAR((*pc)[0].estimate, 0.371, 1e-13);
  EXPECT_NEAR((*pc)[0].se, 0.27878160840555, 1e-12);
  EXPECT_NEAR((*pc)[0].ci_low, -0.201012611559963, 1e-12);
  EXPECT_NEAR((*pc)[0].ci_high, 0.943012611559964, 1e-12);
}

struct Degenerate {
  const char* what;
  std::vector<std::string> g;
  std::vector<double> y;
  double F, p;     // expected; NaN = undefined
  const char* warning;
};

TEST(AnovaHardCases, DegenerateDataGiveDocumentedResults) {
  const double nan = std::nan(""), inf = INFINITY;
  const std::vector<Degenerate> cases{
      {"zero within-group variance", {"a", "a", "b", "b"}, {0.1, 0.1, 0.3, 0.3}, inf, 0.0, "zero within-group variance"},
      {"zero variance, equal means (0/0)", {"a", "a", "b", "b"}, {2, 2, 2, 2}, nan, nan, "0/0"},
      {"one group", {"a", "a", "a"}, {1, 2, 3}, nan, nan, "only one group"},
      {"one observation per group", {"a", "b", "c"}, {1, 2, 3}, nan, nan, "one observation per group"},
  };
  for (const auto& c : cases) {
    SCOPED_TRACE(c.what);
    const OneWayResult r = one_way_anova(c.g, c.y).value();
    if (std::isnan(c.F)) {
      EXPECT_TRUE(std::isnan(r.effect.F));
      EXPECT_TRUE(std::isnan(r.effect.p));
    } else {
      EXPECT_EQ(r.effect.F, c.F);
      EXPECT_EQ(r.effect.p, c.p);
      EXPECT_EQ(r.effect.log10_p, -inf);
    }
    ASSERT_FALSE(r.warnings.empty());
    EXPECT_NE(r.warnings.back().find(c.warning), std::string::npos) << r.warnings.back();
  }
}

TEST(AnovaHardCases, MissingValuesAreLeftOutWithAWarning) {
  // Same as a 2 x 3 design without the missing row.
  const OneWayResult full = one_way_anova({"a", "a", "b", "b", "b"}, {1, 2, 4, 5, 7}).value();
  const OneWayResult with_na = one_way_anova({"a", "a", "a", "b", "b", "b"}, {1, 2, std::nan(""), 4, 5, 7}).value();
  EXPECT_EQ(with_na.n, 5u);
  EXPECT_DOUBLE_EQ(with_na.effect.F, full.effect.F);
  ASSERT_EQ(with_na.warnings.size(), 1u);
  EXPECT_NE(with_na.warnings[0].find("1 row with a missing value left out"), std::string::npos);
}

TEST(AnovaHardCases, LargeOffsetFromDoublesStaysAccurate) {
  // Values 1e9 + {0.1, 0.2, 0.3 | 0.4, 0.5, 0.6} as doubles: SS between = 0.135 +- double input error.
  std::vector<double> y;
  for (double v : {0.1, 0.2, 0.3, 0.4, 0.5, 0.6}) y.push_back(1e9 + v);
  const OneWayResult r = one_way_anova({"a", "a", "a", "b", "b", "b"}, y).value();
  EXPECT_NEAR(r.effect.ss, 0.135, 1e-6);
  EXPECT_NEAR(r.effect.ss_error, 0.04, 1e-6);
}

}  // namespace
}  // namespace dtlab::stats

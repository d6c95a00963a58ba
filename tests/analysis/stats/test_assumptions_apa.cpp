// Shapiro-Wilk and ANOVA residuals, the eta_p2 confidence interval, the new
// ANOVA columns (MSE, corrected df) and APA text, against R 4.2.2 and
// published values (the call above each value).
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "analysis/stats/apa.h"
#include "analysis/stats/assumptions.h"
#include "analysis/stats/effect_size.h"
#include "analysis/stats/rm_anova.h"
#include "test_util.h"

namespace dtlab::stats {
namespace {

using test::near_rel;

struct SwCase {
  const char* what;
  std::vector<double> x;
  double W, p;
};

std::vector<double> generated(int n, int mult, int mod, bool square) {
  // R: ((1:n * mult) %% mod)^2 / 7   or   ((1:n * mult) %% mod) - 504
  std::vector<double> x;
  for (int i = 1; i <= n; ++i) {
    const double v = static_cast<double>((static_cast<long long>(i) * mult) % mod);
    x.push_back(square ? v * v / 7.0 : v - 504.0);
  }
  return x;
}

TEST(ShapiroWilk, MatchesRShapiroTest) {
  const std::vector<SwCase> cases{
      // Shapiro & Wilk (1965), weights of 11 men: published W = 0.79 (p < .01).
      // R: shapiro.test(c(148, 154, 158, 160, 161, 162, 166, 170, 182, 195, 236))
      {"Shapiro & Wilk 1965", {148, 154, 158, 160, 161, 162, 166, 170, 182, 195, 236}, 0.788814694835387, 0.00670381405650293},
      // R: shapiro.test(sleep$extra)
      {"sleep", {0.7, -1.6, -0.2, -1.2, -0.1, 3.4, 3.7, 0.8, 0.0, 2.0, 1.9, 0.8, 1.1, 0.1, -0.1, 4.4, 5.5, 1.6, 4.6, 3.4},
       0.946072762509969, 0.311375416723224},
      // R: shapiro.test(PlantGrowth$weight)
      {"PlantGrowth", {4.17, 5.58, 5.18, 6.11, 4.50, 4.61, 5.17, 4.53, 5.33, 5.14, 4.81, 4.17, 4.41, 3.59, 5.87,
                       3.83, 6.03, 4.89, 4.32, 4.69, 6.31, 5.12, 5.54, 5.50, 5.37, 5.29, 4.92, 6.15, 5.80, 5.26},
       0.982683016098587, 0.891507368227399},
      {"n = 3 (exact p)", {1, 2, 4}, 0.964285714285714, 0.636886845028963},     // shapiro.test(c(1, 2, 4))
      {"n = 4", {1, 2, 4, 9}, 0.894686270839335, 0.40514721117389},             // shapiro.test(c(1, 2, 4, 9))
      {"n = 5", {2.1, 3.5, 1.0, 7.7, 4.4}, 0.951091235244266, 0.744982168958853},
      {"n = 6", generated(6, 37, 101, true), 0.875814266411489, 0.25038092463348},
      {"n = 11", generated(11, 37, 101, true), 0.902155532348409, 0.19636939784674},
      {"n = 12", generated(12, 37, 101, true), 0.893176751952686, 0.129500372288158},
      {"n = 50", generated(50, 37, 101, true), 0.892791732773102, 0.000280136998242666},
      {"n = 200", generated(200, 37, 101, true), 0.893367214587596, 9.69726506645187e-11},
      {"n = 5000", generated(5000, 37, 101, true), 0.893918302326902, 3.29346965596549e-50},
      {"uniform-like n = 20", generated(20, 7919, 1009, false), 0.955493094391412, 0.458175853255494},
      {"uniform-like n = 1000", generated(1000, 7919, 1009, false), 0.954960260471123, 5.77828648635425e-17},
      {"outlier", {1, 1, 1, 1, 1, 1, 1, 1, 1, 100}, 0.365720627414263, 1.00369281388907e-07},
  };
  for (const auto& c : cases) {
    SCOPED_TRACE(c.what);
    const ShapiroWilkResult r = shapiro_wilk(c.x);
    EXPECT_EQ(r.n, c.x.size());
    EXPECT_TRUE(near_rel(r.W, c.W, 1e-9));
    EXPECT_TRUE(near_rel(r.p, c.p, 1e-6));
    EXPECT_TRUE(r.warnings.empty());
  }
}

TEST(ShapiroWilk, DegenerateSamplesAreUndefinedWithAWarning) {
  // R: shapiro.test(c(1, 2)) -> "sample size must be between 3 and 5000"; c(2, 2, 2) -> "all 'x' values are identical"
  for (const auto& x : {std::vector<double>{1, 2}, std::vector<double>{2, 2, 2}, std::vector<double>(5001, 1.0)}) {
    const ShapiroWilkResult r = shapiro_wilk(x);
    EXPECT_TRUE(std::isnan(r.W));
    EXPECT_TRUE(std::isnan(r.p));
    EXPECT_EQ(r.warnings.size(), 1u);
  }
  EXPECT_EQ(shapiro_wilk({1, std::nan(""), 2, 4}).n, 3u) << "NaN dropped";
}

// R 4.2.2: Y <- subject x cell matrix of md_12.1;
//   E <- Y - rowMeans(Y) - colMeans(Y) (by column) + mean(Y); E[1, ] -> -3 -51 -9 27 -21 57
//   shapiro.test(as.vector(t(E))) -> W = 0.971873411127596, p = 0.180074681114414
TEST(AnovaResiduals, ValueMinusSubjectAndCellMeansPlusGrandMean) {
  auto r = anova_residuals(test::load_long("md_12.1.csv", {"rt", "id", {"noise", "angle"}, {}}));
  ASSERT_TRUE(r.ok()) << r.error().to_string();
  ASSERT_EQ(r->residuals.size(), 60u);
  const double first[] = {-3, -51, -9, 27, -21, 57};
  for (size_t c = 0; c < 6; ++c) EXPECT_NEAR(r->residuals[c].value, first[c], 1e-11);
  EXPECT_EQ(r->residuals[0].subject, "1");
  EXPECT_EQ(r->residuals[0].cell, "noise=absent, angle=0");
  std::vector<double> e;
  for (const auto& x : r->residuals) e.push_back(x.value);
  const ShapiroWilkResult sw = shapiro_wilk(e);
  EXPECT_TRUE(near_rel(sw.W, 0.971873411127596, 1e-9));
  EXPECT_TRUE(near_rel(sw.p, 0.180074681114414, 1e-6));
}

// 90% CI of partial eta squared (Steiger 2004). Reference: R 4.2.2 with an independent noncentral F
// (pf, AS 226 / R84):  g <- function(t) uniroot(function(l) pf(F, df1, df2, ncp = l) - t, c(0, 10 F df1), tol = 1e-13)$root
//   bounds g(0.95), g(0.05) (0 when pf(F, df1, df2) <= t), eta = l / (l + df1 + df2 + 1), as
//   apaTables::get.ci.partial.eta.squared (MBESS::conf.limits.ncf) converts them.
struct CiCase {
  double F, df1, df2, lambda_low, lambda_high, low, high;
};

TEST(EffectSize, EtaP2IntervalFromTheNoncentralF) {
  const std::vector<CiCase> cases{
      {20.09, 1, 15, 5.3254304071474, 42.8195384409479, 0.238536516879087, 0.715811916255725},
      {40.72, 2, 18, 35.0056520459702, 140.724921762101, 0.625037844702479, 0.870149883078062},
      {1.2, 2, 30, 0, 8.8659180876651, 0, 0.211769345869839},
      {0.3, 3, 40, 0, 3.03275286066427, 0, 0.0644817212730217},
      {5.72, 2, 114, 2.13007203284398, 24.3919992084306, 0.0178802211439671, 0.172513291734941},
  };
  for (const auto& c : cases) {
    SCOPED_TRACE(c.F);
    EXPECT_NEAR(f_noncentrality_for_cdf(c.F, c.df1, c.df2, 0.95), c.lambda_low, 1e-8 * (1 + c.lambda_low));
    EXPECT_NEAR(f_noncentrality_for_cdf(c.F, c.df1, c.df2, 0.05), c.lambda_high, 1e-8 * c.lambda_high);
    const Interval ci = eta_p2_interval(c.F, c.df1, c.df2);
    // R's pnbeta stops at an error of 1e-9 (errmax), so eta agrees to about 1e-9.
    EXPECT_NEAR(ci.low, c.low, 2e-9);
    EXPECT_NEAR(ci.high, c.high, 2e-9);
  }
  // Huge F: bounds from the large-lambda limit, close to 1 and ordered; infinite F: undefined.
  const Interval huge = eta_p2_interval(1.38e28, 2, 6);
  EXPECT_GT(huge.low, 1 - 1e-9);
  EXPECT_LE(huge.low, huge.high);
  EXPECT_TRUE(std::isnan(eta_p2_interval(INFINITY, 1, 5).low));
}

// MSE and the corrected df of Maxwell & Delaney Table 12.1 (angle: SS_error 64080 / 18 df;
// car: GG 0.961637, HF 1.217564 -> df_gg = 2 x 0.961637, df_hf = df as min(1, HF) = 1).
TEST(EffectSize, AnovaRowsCarryMseAndCorrectedDf) {
  auto r = rm_anova(test::load_long("md_12.1.csv", {"rt", "id", {"angle", "noise"}, {}}));
  ASSERT_TRUE(r.ok());
  const Effect& angle = r->effects[0];
  ASSERT_EQ(angle.name, "angle");
  EXPECT_TRUE(near_rel(angle.mse, 64080.0 / 18.0, 1e-13));
  EXPECT_DOUBLE_EQ(angle.df1_gg, 2 * angle.gg_epsilon);
  EXPECT_DOUBLE_EQ(angle.df2_gg, 18 * angle.gg_epsilon);
  EXPECT_TRUE(test::printed(angle.df1_gg, "1.92327"));  // 2 x 0.961637 (car), rounded
  EXPECT_EQ(angle.df1_hf, 2.0);
  EXPECT_EQ(angle.df2_hf, 18.0);
  EXPECT_EQ(r->effects[1].df1_gg, 1.0) << "1-df effect: epsilon 1";
  EXPECT_GT(angle.eta_p2_ci_low, 0.0);
  EXPECT_LT(angle.eta_p2_ci_low, angle.eta_p2);
  EXPECT_GT(angle.eta_p2_ci_high, angle.eta_p2);
}

TEST(Apa, NumbersAndSentences) {
  EXPECT_EQ(apa_p(0.0017), "p = .002");
  EXPECT_EQ(apa_p(0.0004), "p < .001");
  EXPECT_EQ(apa_p(0.0), "p < .001");
  EXPECT_EQ(apa_p(0.04999), "p = .050");
  EXPECT_EQ(apa_p(0.9999), "p > .999");
  EXPECT_EQ(apa_p(std::nan("")), "p = NA");
  EXPECT_EQ(apa_bounded(0.5712), ".57");
  EXPECT_EQ(apa_bounded(1.0), "1.00");
  EXPECT_EQ(apa_bounded(-0.001), ".00") << "never -0.00";
  EXPECT_EQ(apa_number(-1.284), "-1.28");
  EXPECT_EQ(apa_number(INFINITY), "∞");
  EXPECT_EQ(apa_df(15), "15");
  EXPECT_EQ(apa_df(5.1349), "5.13");
  Effect e;
  e.name = "transparency:scenario";
  e.within = true;
  e.df1 = 1;
  e.df2 = 15;
  e.F = 20.0912;
  e.p = 0.00044;
  e.eta_p2 = 0.5725;
  e.gg_epsilon = 1;
  complete_effect(e);
  EXPECT_EQ(apa_effect(e).rfind("F(1, 15) = 20.09, p < .001, ηp² = .57", 0), 0u) << apa_effect(e);
  EXPECT_NE(apa_effect(e).find(", 90% CI [.24, .72]"), std::string::npos) << apa_effect(e);
  Effect g = e;  // a 3-level effect with GG 0.5135: corrected df in the sentence
  g.df1 = 2;
  g.df2 = 10;
  g.F = 6.14;
  g.gg_epsilon = 0.5135;
  g.hf_epsilon = 0.6;
  g.p_gg = 0.0543;
  g.mauchly_p = 0.2;
  complete_effect(g);
  EXPECT_EQ(apa_effect(g).rfind("F(1.03, 5.13) = 6.14, p = .054, ε = .51, ηp²", 0), 0u) << apa_effect(g);
  EXPECT_EQ(apa_effect(g, Correction::automatic).substr(0, 24), "F(2, 10) = 6.14, p < .00") << "Mauchly p .2: uncorrected";
}

}  // namespace
}  // namespace dtlab::stats

// Follow-ups of mixed designs as emmeans gives them on the afex fit (post-hoc
// contrasts of a within factor: groups weighted equally, pooled error with
// N - g df; simple effects as joint_tests / pairs(emmeans(fit, ~ A | B))),
// afex's MSE beside Greenhouse-Geisser df, and how our 90% CI of eta_p2
// relates to the effectsize package's. Every expected value comes from
// tests/analysis/data/stats_r_followups.R (output in .Rout beside it).
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "analysis/stats/effect_size.h"
#include "analysis/stats/followup.h"
#include "analysis/stats/posthoc.h"
#include "analysis/stats/rm_anova.h"
#include "test_util.h"

namespace dtlab::stats {
namespace {

using test::near_rel;
using test::printed;

LongData mixed_posthoc() { return test::load_long("mixed_posthoc.csv", {"time", "id", {"task"}, {"group"}}); }
LongData obk() {
  return test::load_long("obk_long.csv", {"value", "id", {"phase", "hour"}, {"treatment", "gender"}});
}

const SimpleEffect& row(const SimpleEffects& s, const std::string& factor, const std::string& at_level) {
  for (const auto& r : s.rows)
    if (r.factor == factor && r.at_level == at_level) return r;
  ADD_FAILURE() << "no simple effect of " << factor << " at " << at_level;
  static const SimpleEffect none{};
  return none;
}

// Broke: --posthoc on a mixed design ran paired t tests over all subjects,
// ignoring the groups (search - locate: p = .0237 unadjusted, where emmeans
// gives .0555, and .1109 after Holm: a changed conclusion).
// R: fit <- aov_car(time ~ group + Error(id/task), mixed_posthoc.csv)
//    pairs(emmeans(fit, ~ task), adjust = "none" / "holm"); confint(pairs(..., adjust = "none"))
TEST(MixedPosthoc, WithinFactorFollowsEmmeansOnTheAfexFit) {
  auto r = pairwise_within(mixed_posthoc(), "task", PairwiseTest::paired_t);
  ASSERT_TRUE(r.ok()) << r.error().to_string();
  ASSERT_EQ(r->size(), 3u);
  const Comparison& sl = (*r)[1];
  EXPECT_EQ(sl.a, "search");
  EXPECT_EQ(sl.b, "locate");
  EXPECT_EQ(sl.test, "emmeans t");
  EXPECT_EQ(sl.df, 10.0);  // N - g = 12 - 2
  EXPECT_TRUE(near_rel(sl.estimate, -0.3624999999999989, 1e-12));
  EXPECT_TRUE(near_rel(sl.se, 0.167285310173966, 1e-12));
  EXPECT_TRUE(near_rel(sl.ci_low, -0.735234898965187, 1e-12));
  EXPECT_TRUE(near_rel(sl.ci_high, 0.0102348989651892, 1e-10));
  EXPECT_TRUE(printed(sl.statistic, "-2.167"));
  EXPECT_TRUE(printed(sl.p, "0.0555"));
  EXPECT_TRUE(printed(sl.p_holm, "0.1109"));
  EXPECT_GT(sl.p, 0.05) << "paired t over all subjects gave 0.0237428183988271";
  // search - count: 0.0437500000000011, SE 0.122043153228684, p 0.7274 (Holm 0.7274)
  EXPECT_TRUE(near_rel((*r)[0].estimate, 0.0437500000000011, 1e-12));
  EXPECT_TRUE(near_rel((*r)[0].se, 0.122043153228684, 1e-12));
  EXPECT_TRUE(printed((*r)[0].p_holm, "0.7274"));
  // count - locate: -0.40625, SE 0.118930783441462, t -3.416, p 0.0066 (Holm 0.0198)
  EXPECT_TRUE(near_rel((*r)[2].se, 0.118930783441462, 1e-12));
  EXPECT_TRUE(printed((*r)[2].statistic, "-3.416"));
  EXPECT_TRUE(printed((*r)[2].p, "0.0066"));
  EXPECT_TRUE(printed((*r)[2].p_holm, "0.0198"));
}

// R: fo <- aov_car(value ~ treatment * gender + Error(id/(phase * hour)), obk_long.csv)
//    pairs(emmeans(fo, ~ phase), adjust = "holm"): averaged over treatment, gender (6 cells of 2-3) and hour.
TEST(MixedPosthoc, ObrienKaiserPhaseAveragedOverFourFactors) {
  auto r = pairwise_within(obk(), "phase", PairwiseTest::paired_t);
  ASSERT_TRUE(r.ok()) << r.error().to_string();
  ASSERT_EQ(r->size(), 3u);
  // pre - post -1.264 0.402 10 -3.143 0.0209; pre - fup -1.819 0.289 -6.302 0.0003; post - fup -0.556 0.280 -1.985 0.0752
  const char* est[] = {"-1.264", "-1.819", "-0.556"};
  const char* se[] = {"0.402", "0.289", "0.280"};
  const char* t[] = {"-3.143", "-6.302", "-1.985"};
  const char* p[] = {"0.0209", "0.0003", "0.0752"};
  for (int i = 0; i < 3; ++i) {
    EXPECT_EQ((*r)[i].df, 10.0);  // 16 subjects - 6 between cells
    EXPECT_TRUE(printed((*r)[i].estimate, est[i]));
    EXPECT_TRUE(printed((*r)[i].se, se[i]));
    EXPECT_TRUE(printed((*r)[i].statistic, t[i]));
    EXPECT_TRUE(printed((*r)[i].p_holm, p[i]));
  }
}

// Broke: --simple-effects exited 1 ("all-within designs only") for any between factor.
// R: joint_tests(fit, by = "group"): task expert F(2, 10) = 19.081 p = 0.000385880698961599,
//    task novice 16.623 p = 0.000661135971654593;
//    pairs(emmeans(fit, ~ group | task)) (emmeans orders expert before novice; the file has novice first):
//    search expert - novice -0.763 SE 0.595 t -1.282 p 0.2288; count -2.475 0.638 -3.877 0.0031;
//    locate -1.588 0.691 -2.296 0.0445 (joint_tests by task: F = t^2, p 0.22882924540612407,
//    0.00307395906168371, 0.04454253064717599).
TEST(MixedSimpleEffects, BetweenAndWithinFactorFollowJointTests) {
  auto s = simple_effects(mixed_posthoc(), "group", "task");
  ASSERT_TRUE(s.ok()) << s.error().to_string();
  ASSERT_EQ(s->rows.size(), 5u);  // group at 3 tasks, task at 2 groups
  const SimpleEffect& novice = row(*s, "task", "novice");
  EXPECT_EQ(novice.test, "emmeans F");
  EXPECT_EQ(novice.anova.df1, 2.0);
  EXPECT_EQ(novice.anova.df2, 10.0);
  EXPECT_TRUE(printed(novice.anova.F, "16.623"));
  EXPECT_TRUE(near_rel(novice.p, 0.000661135971654593, 1e-9));
  EXPECT_TRUE(near_rel(row(*s, "task", "expert").p, 0.000385880698961599, 1e-9));
  const SimpleEffect& count = row(*s, "group", "count");
  EXPECT_EQ(count.test, "emmeans t");
  EXPECT_EQ(count.contrast.a, "novice");
  EXPECT_TRUE(printed(count.contrast.estimate, "2.475"));
  EXPECT_TRUE(printed(count.contrast.se, "0.638"));
  EXPECT_TRUE(printed(count.contrast.statistic, "3.877"));
  EXPECT_TRUE(near_rel(count.p, 0.00307395906168371, 1e-9));
  EXPECT_TRUE(near_rel(row(*s, "group", "search").p, 0.22882924540612407, 1e-9));
  EXPECT_TRUE(near_rel(row(*s, "group", "locate").p, 0.04454253064717599, 1e-9));
  // Holm within the family "group at each task" (p.adjust(c(.2288, .0031, .0445), "holm")).
  EXPECT_TRUE(near_rel(count.p_holm, 3 * 0.00307395906168371, 1e-9));
  EXPECT_TRUE(near_rel(row(*s, "group", "search").p_holm, 0.22882924540612407, 1e-9));
}

// R: joint_tests(fo, by = "treatment"): phase A F(2, 10) = 9.119 p 5.57037519209157e-03, B 28.272
//    7.66445287151185e-05, control 0.142 8.69344857581268e-01; hour A F(4, 10) = 11.202 p 1.02862491923794e-03;
//    gender A F(1, 10) = 8.057 p 1.75927117397454e-02; pairs(emmeans(fo, ~ gender | treatment)): A F - M -3.500 SE 1.233.
//    joint_tests(fo, by = "phase"): treatment pre F(2, 10) = 0.341 p 0.71901867384071472, fup 9.886 0.00427594440268615.
TEST(MixedSimpleEffects, ObrienKaiserWithinAtBetweenAndBetweenAtWithin) {
  const LongData d = obk();
  auto tp = simple_effects(d, "treatment", "phase");
  ASSERT_TRUE(tp.ok()) << tp.error().to_string();
  EXPECT_TRUE(near_rel(row(*tp, "phase", "A").p, 5.57037519209157e-03, 1e-9));
  EXPECT_TRUE(near_rel(row(*tp, "phase", "B").p, 7.66445287151185e-05, 1e-9));
  EXPECT_TRUE(near_rel(row(*tp, "phase", "control").p, 8.69344857581268e-01, 1e-9));
  EXPECT_TRUE(printed(row(*tp, "phase", "B").anova.F, "28.272"));
  EXPECT_TRUE(near_rel(row(*tp, "treatment", "pre").p, 0.71901867384071472, 1e-9));
  EXPECT_TRUE(near_rel(row(*tp, "treatment", "fup").p, 0.00427594440268615, 1e-9));
  auto th = simple_effects(d, "treatment", "hour");
  ASSERT_TRUE(th.ok());
  EXPECT_EQ(row(*th, "hour", "A").anova.df1, 4.0);
  EXPECT_TRUE(near_rel(row(*th, "hour", "A").p, 1.02862491923794e-03, 1e-9));
  auto tg = simple_effects(d, "treatment", "gender");
  ASSERT_TRUE(tg.ok());
  const SimpleEffect& ga = row(*tg, "gender", "A");
  EXPECT_EQ(ga.test, "emmeans t");
  EXPECT_EQ(ga.contrast.a, "M");  // first in the file; emmeans prints F - M = -3.500
  EXPECT_TRUE(printed(ga.contrast.estimate, "3.500"));
  EXPECT_TRUE(printed(ga.contrast.se, "1.233"));
  EXPECT_TRUE(near_rel(ga.p, 1.75927117397454e-02, 1e-9));
  EXPECT_TRUE(printed(ga.contrast.statistic * ga.contrast.statistic, "8.057"));
}

// afex's MSE beside corrected df: SS_error / den Df (GG).
// R: anova(aov_car(rt ~ Error(id/(angle * noise)), md_12.1)): angle den Df 17.30945732670, MSE 3702.022471910;
//    angle:noise 16.27158724472, 1283.218390805; noise 9, 8460; anova(..., correction = "none"): 3560, 8460, 1160.
TEST(MixedFollowups, MseBesideGreenhouseGeisserDfIsAfexs) {
  auto r = rm_anova(test::load_long("md_12.1.csv", {"rt", "id", {"angle", "noise"}, {}}));
  ASSERT_TRUE(r.ok());
  const Effect& angle = r->effects[0];
  const Effect& noise = r->effects[1];
  const Effect& inter = r->effects[2];
  EXPECT_TRUE(near_rel(angle.df2_gg, 17.30945732670, 1e-11));
  EXPECT_TRUE(near_rel(angle.mse_gg, 3702.022471910, 1e-11));
  EXPECT_TRUE(near_rel(inter.mse_gg, 1283.218390805, 1e-11));
  EXPECT_TRUE(near_rel(noise.mse_gg, 8460, 1e-12));
  EXPECT_TRUE(near_rel(angle.mse, 3560, 1e-12));
  EXPECT_TRUE(near_rel(inter.mse, 1160, 1e-12));
  // HF > 1 is treated as 1 (afex warns "HF eps > 1 treated as 1"): the uncorrected MSE.
  EXPECT_TRUE(near_rel(angle.mse_hf, 3560, 1e-12));
}

// Our interval converts the noncentrality bounds as lambda / (lambda + df1 + df2 + 1) (MBESS,
// apaTables); effectsize converts the same bounds as lambda / (lambda + df2).
// R: F_to_eta2(F, df, df_error, ci = 0.9, alternative = "two.sided") (effectsize 0.8.3):
//    angle F(2, 18) = 40.7191011235955: [0.66040767191289, 0.886594182519282]
//    noise F(1, 9) = 33.7659574468085: [0.492187307126857, 0.888700257629392]
//    angle:noise F(2, 18) = 45.3103448275862: [0.688044057073511, 0.896263693246394]
TEST(MixedFollowups, EtaP2IntervalDiffersFromEffectsizeOnlyByTheConversion) {
  struct Case {
    double F, df1, df2, low, high;
  } cases[] = {{40.7191011235955, 2, 18, 0.66040767191289, 0.886594182519282},
               {33.7659574468085, 1, 9, 0.492187307126857, 0.888700257629392},
               {45.3103448275862, 2, 18, 0.688044057073511, 0.896263693246394}};
  for (const auto& c : cases) {
    const double lo = f_noncentrality_for_cdf(c.F, c.df1, c.df2, 0.95);
    const double hi = f_noncentrality_for_cdf(c.F, c.df1, c.df2, 0.05);
    EXPECT_TRUE(near_rel(lo / (lo + c.df2), c.low, 1e-6)) << c.F;
    EXPECT_TRUE(near_rel(hi / (hi + c.df2), c.high, 1e-6)) << c.F;
    const Interval ours = eta_p2_interval(c.F, c.df1, c.df2);
    EXPECT_LT(ours.low, c.low);
    EXPECT_LT(ours.high, c.high);
    EXPECT_TRUE(near_rel(ours.high, hi / (hi + c.df1 + c.df2 + 1), 1e-12));
  }
}

}  // namespace
}  // namespace dtlab::stats

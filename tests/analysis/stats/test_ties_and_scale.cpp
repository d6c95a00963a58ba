// Hard cases found by probing `dtlab stats`, each checked against R
// (tests/analysis/data/stats_r_followups.R, output in .Rout beside it):
// means that are equal as decimals stay equal under --aggregate mean and in a
// factor's marginal means (so ranks tie and zero differences are dropped),
// values near the smallest double keep F and p (scale invariance), and a
// within factor with thousands of levels is analysed in O(N C) plus the
// smaller Gram matrix, with a documented bound above which rm-anova refuses.
#include <gtest/gtest.h>

#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include "analysis/stats/anova.h"
#include "analysis/stats/friedman.h"
#include "analysis/stats/paired.h"
#include "analysis/stats/rm_anova.h"
#include "test_util.h"

namespace dtlab::stats {
namespace {

using test::near_rel;
using test::printed;

LongData aggregated(const std::string& where_not) {
  LongData d = test::load_long("aggregate_ties.csv", {"time", "participant", {"condition"}, {}});
  d.aggregate = Aggregate::mean;
  if (where_not.empty()) return d;
  LongData kept;  // the rows whose condition is not `where_not` (as --where condition!=C)
  kept.source = d.source;
  kept.dv_name = d.dv_name;
  kept.aggregate = d.aggregate;
  kept.within.push_back({"condition", {}});
  std::vector<std::optional<Decimal>> values;
  for (size_t i = 0; i < d.rows(); ++i) {
    if (d.within[0].level[i] == where_not) continue;
    kept.subject.push_back(d.subject[i]);
    kept.within[0].level.push_back(d.within[0].level[i]);
    values.push_back(d.dv.decimal[i]);
  }
  kept.dv = Measurements::from_decimals(values);
  return kept;
}

TEST(DecimalMean, EqualDecimalMeansAreEqualDoubles) {
  auto mean = [](std::initializer_list<const char*> xs) {
    std::vector<Decimal> d;
    for (const char* x : xs) d.push_back(*parse_decimal(x));
    return *decimal_mean(d);
  };
  // (0.1 + 0.2 + 0.3) / 3 in doubles is 0.19999999999999998; the decimal mean is 0.2.
  EXPECT_EQ(mean({"0.1", "0.2", "0.3"}).value, 0.2);
  EXPECT_TRUE(mean({"0.1", "0.2", "0.3"}).exact);
  EXPECT_EQ(mean({"0.7", "0.1"}).value, mean({"0.4", "0.4"}).value);
  EXPECT_EQ(mean({"1000000000000.4", "1000000000000.2"}).value, 1000000000000.3);
  // 1/3 has no finite decimal: 37 digits and a sticky digit, the same whatever the inputs' spelling.
  const Decimal third = mean({"1", "0", "0"});
  EXPECT_FALSE(third.exact);
  EXPECT_EQ(third.value, 1.0 / 3.0);
  const Decimal same = mean({"2", "0", "0", "0", "0", "0"});
  EXPECT_EQ(same.magnitude, third.magnitude);
  EXPECT_EQ(same.exponent, third.exponent);
  EXPECT_EQ(mean({"-0.1", "-0.2", "-0.3"}).value, -0.2);
  EXPECT_FALSE(decimal_mean({*parse_decimal("1e30"), *parse_decimal("1e-30")}).has_value())
      << "digits that cannot be aligned in 128 bits: the caller averages the doubles";
  EXPECT_EQ(decimal_median({*parse_decimal("0.3"), *parse_decimal("0.1"), *parse_decimal("0.2"),
                            *parse_decimal("0.4")})->value, 0.25);
}

// Broke: --aggregate mean summed the doubles and divided, so mean(0.1, 0.2, 0.3)
// = 0.19999999999999998 ranked below mean(0.2, 0.2, 0.2) = 0.2: Q = 4.45455
// where R gives 1.333, and Wilcoxon ranked four differences of -2.8e-17 (p = .059, R .371).
// R: a <- aggregate(time ~ participant + condition, aggregate_ties.csv, mean)
//    friedman.test(time ~ condition | participant, a): chi-squared = 1.333333333333, df = 2, p = 0.513417119033
//    wilcox.test(A, B, paired = TRUE): V = 0, p = 0.371093369523 (zeros dropped; "cannot compute exact p-value with zeroes")
TEST(AggregateTies, FriedmanAndWilcoxonOnCellMeansAgreeWithR) {
  auto f = friedman(aggregated(""));
  ASSERT_TRUE(f.ok()) << f.error().to_string();
  EXPECT_TRUE(near_rel(f->Q, 1.333333333333, 1e-12));
  EXPECT_TRUE(near_rel(f->p, 0.513417119033, 1e-11));
  EXPECT_TRUE(f->ties);
  auto w = paired_tests(aggregated("C"));
  ASSERT_TRUE(w.ok()) << w.error().to_string();
  EXPECT_EQ(w->wilcoxon.pairs, 6u);
  EXPECT_EQ(w->wilcoxon.zeros, 4u);
  EXPECT_EQ(w->wilcoxon.n, 2u);
  EXPECT_EQ(w->wilcoxon.V, 0.0);
  EXPECT_TRUE(near_rel(w->wilcoxon.p, 0.371093369523, 1e-11));
  // R: mean(w$time.A - w$time.B) -> -0.116666666666667 (0 + 0 + 0 - 0.4 + 0 - 0.3) / 6
  EXPECT_TRUE(near_rel(w->t.mean_difference, -0.116666666666667, 1e-13));
}

// A factor's marginal means (wilcoxon --factor A, B averaged): s1 (0.1, 0.3) vs (0.2, 0.2) and
// s2 (0.7, 0.1) vs (0.4, 0.4) are equal as decimals. R's mean(c(0.7, 0.1)) is one ulp below 0.4,
// so R on its own means ranks a difference of -5.6e-17 (V = 3); on the decimal means (round(, 12)):
// R: wilcox.test(a1, a2, paired = TRUE) -> differences 0 0 0.5 -0.05 0, V = 2, p-value = 1.
TEST(AggregateTies, FactorMarginalMeansAreTakenOnTheDigits) {
  const LongData d = test::long_from_text(
      "id,A,B,y\n"
      "s1,a1,b1,0.1\ns1,a1,b2,0.3\ns1,a2,b1,0.2\ns1,a2,b2,0.2\n"
      "s2,a1,b1,0.7\ns2,a1,b2,0.1\ns2,a2,b1,0.4\ns2,a2,b2,0.4\n"
      "s3,a1,b1,1.5\ns3,a1,b2,0.9\ns3,a2,b1,0.6\ns3,a2,b2,0.8\n"
      "s4,a1,b1,0.3\ns4,a1,b2,0.6\ns4,a2,b1,0.9\ns4,a2,b2,0.1\n"
      "s5,a1,b1,2.2\ns5,a1,b2,2.4\ns5,a2,b1,2.3\ns5,a2,b2,2.3\n",
      {"y", "id", {"A", "B"}, {}});
  auto w = paired_tests(d, {}, "A");
  ASSERT_TRUE(w.ok()) << w.error().to_string();
  EXPECT_EQ(w->wilcoxon.zeros, 3u);
  EXPECT_EQ(w->wilcoxon.n, 2u);
  EXPECT_EQ(w->wilcoxon.V, 2.0);  // ranks: |0.5| = 2 (+), |-0.05| = 1 (-)
  EXPECT_EQ(w->wilcoxon.p, 1.0);
}

// Broke: rm-anova on values near 1e-310 printed F and p as NA (the sums of
// squares, near 1e-618, underflowed to 0/0) with no warning, while anova worked.
// R: summary(aov(y ~ cond + Error(id/cond), tiny_values.csv)): Sum Sq 0, F NaN;
//    the same data times 1e310, anova(aov_car(y ~ Error(id/cond), t), correction = "none" / "GG"):
//    F = 44.5708154506434, p = 1.04404617271353e-05; den Df (GG) 7.79320145847095, p 8.15477960052817e-05.
TEST(TinyValues, RmAnovaScalesAndWarnsLikeAnova) {
  auto r = rm_anova(test::load_long("tiny_values.csv", {"y", "id", {"cond"}, {}}));
  ASSERT_TRUE(r.ok()) << r.error().to_string();
  const Effect& e = r->effects[0];
  EXPECT_TRUE(near_rel(e.F, 44.5708154506434, 1e-12));
  EXPECT_TRUE(near_rel(e.p, 1.04404617271353e-05, 1e-10));
  EXPECT_TRUE(near_rel(e.df2_gg, 7.79320145847095, 1e-12));
  EXPECT_TRUE(near_rel(e.p_gg, 8.15477960052817e-05, 1e-10));
  EXPECT_EQ(e.ss_error, 0.0) << "1e-618 is below the double range: printed as 0";
  bool warned = false;
  for (const auto& w : r->warnings) warned = warned || w.find("below the smallest normal double") != std::string::npos;
  EXPECT_TRUE(warned);
}

// Broke: rm-anova formed the p x p contrast matrices and E^2, O(C^3) and more
// (3 subjects x 3000 levels did not finish in 120 s). Now 3000 levels take 0.2 s.
// Data: y = ((s 7919 + c 104729) mod 1000) / 10 for subjects s = 0..2, levels c = 0..L-1.
// R: summary(aov(y ~ cond + Error(id/cond), mk(300))): cond F(299, 598) = 3.2497, SS 465754.805556,
//    Residuals 286644.444444; one_way_within(mk(300)): F 3.24970404682534, p 1.04365536064730e-34;
//    one_way_within(mk(3000)): SS 4653652.5, SS_error 2846340, F 3.2699203187251, p 0 (R underflows),
//    log10_p -331.1677112627310.
TEST(ManyLevels, ThreeSubjectsByThreeThousandLevels) {
  for (int L : {300, 3000}) {
    LongData d;
    d.within.push_back({"cond", {}});
    std::vector<double> y;
    for (int s = 0; s < 3; ++s)
      for (int c = 0; c < L; ++c) {
        d.subject.push_back("s" + std::to_string(s));
        d.within[0].level.push_back("c" + std::to_string(c));
        y.push_back(static_cast<double>((s * 7919 + c * 104729) % 1000) / 10);
      }
    d.dv = Measurements::from_doubles(y);
    auto r = rm_anova(d);
    ASSERT_TRUE(r.ok()) << r.error().to_string();
    const Effect& e = r->effects[0];
    EXPECT_EQ(e.df1, L - 1.0);
    EXPECT_EQ(e.df2, 2.0 * (L - 1));
    if (L == 300) {
      EXPECT_TRUE(near_rel(e.ss, 465754.805556, 1e-11));
      EXPECT_TRUE(near_rel(e.ss_error, 286644.444444, 1e-11));
      EXPECT_TRUE(near_rel(e.F, 3.24970404682534, 1e-12));
      EXPECT_TRUE(near_rel(e.p, 1.04365536064730e-34, 1e-9));
    } else {
      EXPECT_TRUE(near_rel(e.ss, 4653652.5, 1e-12));
      EXPECT_TRUE(near_rel(e.ss_error, 2846340, 1e-12));
      EXPECT_TRUE(near_rel(e.F, 3.2699203187251, 1e-12));
      EXPECT_TRUE(near_rel(e.log10_p, -331.1677112627310, 1e-9));
    }
    EXPECT_TRUE(std::isnan(e.mauchly_p)) << "2 error df < " << L - 1 << " contrasts";
  }
}

// The bound: N p min(N, p) summed over the within terms, at most 4e9.
TEST(ManyLevels, WorkBeyondTheBoundIsRefusedWithTheReason) {
  EXPECT_EQ(rm_anova_work(3, {3000}), 3.0 + 3.0 * 2999 * 3);  // the between stratum (p = 1) and cond
  EXPECT_LT(rm_anova_work(1500, {1000}), kRmAnovaWorkBound);
  EXPECT_GT(rm_anova_work(2000, {2000}), kRmAnovaWorkBound);  // about 20 s of CPU when it ran
  // 2 x 60 x 60 within: the interaction alone has 3481 contrasts.
  EXPECT_EQ(rm_anova_work(10, {60, 60}), 10.0 * 59 * 10 * 2 + 10.0 * 3481 * 10 + 10.0 * 1 * 1);
}

}  // namespace
}  // namespace dtlab::stats

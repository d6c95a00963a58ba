// Wilcoxon signed-rank, sign test and paired t against R's own example
// outputs (tests/Examples/stats-Ex.Rout.save, R-devel 2024) and closed forms.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "analysis/stats/paired.h"
#include "test_util.h"

namespace dtlab::stats {
namespace {

using test::near_rel;
using test::printed;

// Hollander & Wolfe (1973), 29f: Hamilton depression scale, first (x) and second (y) visit.
const std::vector<double> kX{1.83, 0.50, 1.62, 2.48, 1.68, 1.88, 1.55, 3.06, 1.30};
const std::vector<double> kY{0.878, 0.647, 0.598, 2.05, 1.06, 1.29, 1.06, 3.14, 1.29};

WilcoxonOptions alt(Alternative a, bool exact = true, bool correct = true) {
  WilcoxonOptions o;
  o.alternative = a;
  o.correct = correct;
  if (!exact) o.exact.mode = ExactMode::never;
  return o;
}

TEST(Wilcoxon, RDepressionExample) {
  // R: wilcox.test(x, y, paired = TRUE, alternative = "greater") -> V = 40, p-value = 0.01953
  const WilcoxonResult g = wilcoxon_signed_rank(kX, kY, alt(Alternative::greater));
  EXPECT_EQ(g.V, 40);
  EXPECT_EQ(g.method, "exact");
  EXPECT_TRUE(printed(g.p, "0.01953"));
  EXPECT_DOUBLE_EQ(g.p, 10.0 / 512.0) << "psignrank: 10 of the 2^9 sign patterns have V >= 40";
  // R: wilcox.test(Pair(first, second) ~ 1, data = depression) -> V = 40, p-value = 0.03906
  const WilcoxonResult two = wilcoxon_signed_rank(kX, kY);
  EXPECT_EQ(two.V, 40);
  EXPECT_TRUE(printed(two.p, "0.03906"));
  EXPECT_DOUBLE_EQ(two.p_exact, two.p);
  // R: wilcox.test(y - x, alternative = "less") -> V = 5, p-value = 0.01953
  const std::vector<double> zero(9, 0.0);
  std::vector<double> d(9);
  for (int i = 0; i < 9; ++i) d[i] = kY[i] - kX[i];
  const WilcoxonResult less = wilcoxon_signed_rank(d, zero, alt(Alternative::less));
  EXPECT_EQ(less.V, 5);
  EXPECT_TRUE(printed(less.p, "0.01953"));
  // R: wilcox.test(y - x, alternative = "less", exact = FALSE, correct = FALSE) -> V = 5, p-value = 0.01908
  const WilcoxonResult normal = wilcoxon_signed_rank(d, zero, alt(Alternative::less, false, false));
  EXPECT_EQ(normal.method, "normal");
  EXPECT_TRUE(printed(normal.p, "0.01908"));
  EXPECT_TRUE(std::isnan(normal.p_exact)) << "exact never: no p_exact";
}

TEST(Wilcoxon, RTiesAreDecidedOnTheDoublesAsR) {
  // R: wilcox.test(4:2, 3:1, paired = TRUE) -> V = 6, p-value = 0.1489 (ties: normal, continuity correction)
  const WilcoxonResult tied = wilcoxon_signed_rank({4, 3, 2}, {3, 2, 1});
  EXPECT_EQ(tied.V, 6);
  EXPECT_TRUE(tied.ties);
  EXPECT_EQ(tied.method, "normal");
  EXPECT_TRUE(printed(tied.p, "0.1489"));
  EXPECT_FALSE(tied.warnings.empty());
  // R: wilcox.test((4:2)/10, (3:1)/10, paired = TRUE) -> V = 6, p-value = 0.25 (no ties in double)
  const WilcoxonResult untied = wilcoxon_signed_rank({4.0 / 10, 3.0 / 10, 2.0 / 10}, {3.0 / 10, 2.0 / 10, 1.0 / 10});
  EXPECT_EQ(untied.V, 6);
  EXPECT_FALSE(untied.ties);
  EXPECT_EQ(untied.method, "exact");
  EXPECT_DOUBLE_EQ(untied.p, 0.25);
  // With ties the exact conditional p is still reported: all 3 differences equal, V = 6 is the max, P = 1/8 each side.
  EXPECT_DOUBLE_EQ(tied.p_exact, 0.25);
}

TEST(Wilcoxon, ZerosAreDroppedAndAllZerosIsUndefined) {
  // One zero difference: n = 8 after dropping; R uses the normal approximation (ZEROES).
  std::vector<double> x = kX, y = kY;
  x.push_back(1.0);
  y.push_back(1.0);
  const WilcoxonResult r = wilcoxon_signed_rank(x, y);
  EXPECT_EQ(r.zeros, 1u);
  EXPECT_EQ(r.n, 9u);
  EXPECT_EQ(r.method, "normal");
  const WilcoxonResult none = wilcoxon_signed_rank({1, 2, 3}, {1, 2, 3});
  EXPECT_EQ(none.V, 0);
  EXPECT_TRUE(std::isnan(none.p));
  EXPECT_FALSE(none.warnings.empty());
}

TEST(Wilcoxon, NormalApproximationMatchesItsFormula) {
  // 60 untied pairs: R uses the normal approximation (n >= 50); z from the formula in paired.h.
  std::vector<double> x, y;
  for (int i = 1; i <= 60; ++i) {
    x.push_back(i * 1.01 + ((i * 37) % 11));
    y.push_back(i);
  }
  const WilcoxonResult r = wilcoxon_signed_rank(x, y);
  EXPECT_EQ(r.method, "normal");
  const double n = 60, mean = n * (n + 1) / 4, sd = std::sqrt(n * (n + 1) * (2 * n + 1) / 24);
  EXPECT_NEAR(r.z, (r.V - mean - 0.5) / sd, 1e-12);
  EXPECT_FALSE(std::isnan(r.p_exact)) << "auto computes p_exact when it fits";
}

TEST(SignTest, ClosedFormBinomialTails) {
  // 9 of 10 nonzero differences positive: two-sided p = 2 (1 + 10) / 2^10 (binom.test(9, 10)).
  const std::vector<double> x{2, 3, 4, 5, 6, 7, 8, 9, 10, 0, 5};
  const std::vector<double> y{1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 5};
  const SignTestResult s = sign_test(x, y);
  EXPECT_EQ(s.n, 10u);
  EXPECT_EQ(s.positive, 9u);
  EXPECT_DOUBLE_EQ(s.p, 22.0 / 1024.0);
  EXPECT_DOUBLE_EQ(sign_test(x, y, Alternative::greater).p, 11.0 / 1024.0);
  // 2000 of 2000 positive: p = 2 / 2^2000, log10 p = log10(2) - 2000 log10(2).
  const SignTestResult all = sign_test(std::vector<double>(2000, 1.0), std::vector<double>(2000, 0.0));
  EXPECT_EQ(all.p, 0.0);
  EXPECT_TRUE(near_rel(all.log10_p, -1999 * std::log10(2.0), 1e-12));
}

// R sleep data (Cushny & Peebles): extra hours of sleep with drug 1 and drug 2, 10 patients.
const std::vector<double> kDrug1{0.7, -1.6, -0.2, -1.2, -0.1, 3.4, 3.7, 0.8, 0.0, 2.0};
const std::vector<double> kDrug2{1.9, 0.8, 1.1, 0.1, -0.1, 4.4, 5.5, 1.6, 4.6, 3.4};

TEST(PairedT, RSleepExample) {
  // R: t.test(extra ~ group, data = sleep, paired = TRUE)
  //   t = -4.0621, df = 9, p-value = 0.002833; 95 percent CI -2.4598858 -0.7001142; mean difference -1.58
  const PairedTResult t = paired_t(kDrug1, kDrug2);
  EXPECT_TRUE(printed(t.t, "-4.0621"));
  EXPECT_EQ(t.df, 9);
  EXPECT_TRUE(printed(t.p, "0.002833"));
  EXPECT_TRUE(printed(t.ci_low, "-2.4598858"));
  EXPECT_TRUE(printed(t.ci_high, "-0.7001142"));
  EXPECT_NEAR(t.mean_difference, -1.58, 1e-12);
}

TEST(PairedT, ZeroVarianceIsInfiniteOrUndefined) {
  const PairedTResult shift = paired_t({2, 3, 4}, {1, 2, 3});
  EXPECT_EQ(shift.t, INFINITY);
  EXPECT_EQ(shift.p, 0.0);
  const PairedTResult same = paired_t({2, 3, 4}, {2, 3, 4});
  EXPECT_TRUE(std::isnan(same.t));
  EXPECT_TRUE(std::isnan(same.p));
  EXPECT_TRUE(std::isnan(paired_t({1}, {2}).p)) << "one pair";
}

TEST(PairedTests, LongDataWithTwoLevels) {
  LongData d = test::long_from_text(
      "id,drug,extra\n1,a,0.7\n1,b,1.9\n2,a,-1.6\n2,b,0.8\n3,a,-0.2\n3,b,1.1\n4,a,-1.2\n4,b,0.1\n5,a,-0.1\n5,b,-0.1\n"
      "6,a,3.4\n6,b,4.4\n7,a,3.7\n7,b,5.5\n8,a,0.8\n8,b,1.6\n9,a,0.0\n9,b,4.6\n10,a,2.0\n10,b,3.4\n",
      {"extra", "id", {"drug"}, {}});
  auto r = paired_tests(d);
  ASSERT_TRUE(r.ok()) << r.error().to_string();
  EXPECT_EQ(r->x_level, "a");
  EXPECT_TRUE(printed(r->t.t, "-4.0621"));
  // R: wilcox.test(extra ~ group, data = sleep, paired = TRUE) is not in the examples; the
  // structure is: one zero difference (patient 5) -> normal approximation, n = 9.
  EXPECT_EQ(r->wilcoxon.zeros, 1u);
  EXPECT_EQ(r->wilcoxon.method, "normal");
  EXPECT_EQ(r->sign.negative, 9u);
  EXPECT_DOUBLE_EQ(r->sign.p, 2.0 / 512.0);
  LongData three = test::long_from_text("id,c,y\n1,a,1\n1,b,2\n1,c,3\n", {"y", "id", {"c"}, {}});
  EXPECT_FALSE(paired_tests(three).ok());
}

}  // namespace
}  // namespace dtlab::stats

// Regression tests for the statistics' hard cases found by a hardening probe
// and a cross-check against R: each says what broke and the exact value that
// is right now. Expected values are exact rational arithmetic (derivation in
// the comment) or R 4.2.2 output (the call above the value).
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "analysis/stats/anova.h"
#include "analysis/stats/descriptives.h"
#include "analysis/stats/friedman.h"
#include "analysis/stats/paired.h"
#include "analysis/stats/rm_anova.h"
#include "test_util.h"

namespace dtlab::stats {
namespace {

using test::near_rel;

// Long CSV text "id,cond,y" from a subject x level matrix of integers written exactly.
std::string grid_csv(const std::vector<std::vector<long long>>& y) {
  std::string csv = "id,cond,y\n";
  for (size_t s = 0; s < y.size(); ++s)
    for (size_t c = 0; c < y[s].size(); ++c)
      csv += "s" + std::to_string(s + 1) + ",c" + std::to_string(c + 1) + "," + std::to_string(y[s][c]) + "\n";
  return csv;
}

const Effect& cond_effect(const RmAnovaResult& r) {
  for (const auto& e : r.effects)
    if (e.name == "cond") return e;
  ADD_FAILURE() << "no cond effect";
  static Effect none;
  return none;
}

// Broke: Mauchly's W came out 0 (p = 0) because the log-determinant treated
// Cholesky pivots below 1e-12 of the largest as singular. Now W comes from a
// Householder QR of the residual matrix, without a cut.
// Data (built for this test): 4 subjects x 3 levels, contrast scores nearly
// collinear. With contrast scores a = y1 - y2 and b = y1 + y2 - 2 y3, centred,
// S_aa, S_bb, S_ab their sums of squares and products, the orthonormal
// Helmert error matrix is E = [[S_aa/2, S_ab/sqrt(12)], [., S_bb/6]] and
//   W = det E / (tr E / 2)^2 = (S_aa S_bb/12 - S_ab^2/12) / ((S_aa/2 + S_bb/6)/2)^2,
// computed in exact rational arithmetic (Python fractions):
//   W = 27912497490000194 / 574218645000028424997840000243 = 4.860952832696474e-14.
// With p = 2 contrasts and n = 3 error df, car's chi-square approximation
// gives p = W exactly (rho = 2/3, n rho = 2, df 2: p = exp(log W)).
// R 4.2.2, car 3.1-1: summary(Anova(lm(Y ~ 1), idata = data.frame(cond = factor(1:3)),
//   idesign = ~cond, type = 3), multivariate = FALSE)$sphericity.tests -> 4.86095283406636e-14, p 4.86095283406636e-14
// (stats::mauchly.test(lm(Y ~ 1), X = ~1) prints 4.870458e-14: it takes det() of the SSD matrix in double.)
TEST(EdgeCases, MauchlyOfNearlyCollinearContrastsIsTinyNotZero) {
  const LongData d = test::long_from_text(
      grid_csv({{9999999, 20000001, 2}, {20000001, 39999997, 4}, {29999998, 60000001, 7}, {50000002, 99999997, 3}}),
      {"y", "id", {"cond"}, {}});
  auto r = rm_anova(d);
  ASSERT_TRUE(r.ok()) << r.error().to_string();
  const Effect& e = cond_effect(*r);
  EXPECT_TRUE(near_rel(e.mauchly_W, 27912497490000194.0 / 574218645000028424997840000243.0, 1e-8));
  EXPECT_TRUE(near_rel(e.mauchly_p, 27912497490000194.0 / 574218645000028424997840000243.0, 1e-8));
  // Exact: GG = 574218645000028424997840000243 / 1148437290000028937498190000292 (car: 0.500000000000012)
  EXPECT_TRUE(near_rel(e.gg_epsilon, 0.5000000000000121, 1e-12));
  // W = 0 with p = NaN stays for error df < number of contrasts (2 subjects, 2 contrasts).
  auto small = rm_anova(test::long_from_text(grid_csv({{1, 4, 2}, {3, 5, 9}}), {"y", "id", {"cond"}, {}}));
  ASSERT_TRUE(small.ok());
  EXPECT_EQ(cond_effect(*small).mauchly_W, 0.0);
  EXPECT_TRUE(std::isnan(cond_effect(*small).mauchly_p));
}

// Broke: integer data up to 2.5e14 with a real residual (exact SS_error = 163/6)
// were reported as zero error variance, F = Inf: the zero rule fired at
// 2e-28 x cells x sum of squares. Now the residual is formed in double-double
// from exact deltas and only a residual within the data's own rounding error is zero.
// Data: y_ij = s_i + c_j + e_ij with c = (0, 1.25e14, 2.5e14), s = (0, 10, 20, 30),
// e = [[-2,3,3],[2,-2,3],[-3,-3,0],[-2,2,1]]. Exact rational arithmetic:
//   SS_cond = 750000000000018000000000000109/6, SS_error = 163/6 (df 2, 6),
//   F = 2250000000000054000000000000327/163 = 1.3803680981595422e28,
//   p = (1 + F/3)^-3 (F(2, 6) closed form), log10 p = -82.98862097696326,
//   GG = 26569/49202, HF = 28537/47234, Mauchly W = p(W) = 3936/26569,
//   between-subjects error SS = 4021/3.
// R 4.2.2: pf(2250000000000054000000000000327/163, 2, 6, lower.tail = FALSE) -> 1.02654743703696e-83
// (R's aov prints SS_error 28, car 27.163411458333: both lose digits to rounding at this scale.)
TEST(EdgeCases, TinyRealResidualIsNotZeroErrorVariance) {
  const LongData d = test::long_from_text(grid_csv({{-2, 125000000000003, 250000000000003},
                                                    {12, 125000000000008, 250000000000013},
                                                    {17, 125000000000017, 250000000000020},
                                                    {28, 125000000000032, 250000000000031}}),
                                          {"y", "id", {"cond"}, {}});
  auto r = rm_anova(d);
  ASSERT_TRUE(r.ok()) << r.error().to_string();
  const Effect& e = cond_effect(*r);
  EXPECT_TRUE(near_rel(e.ss_error, 163.0 / 6.0, 1e-12));
  EXPECT_TRUE(near_rel(e.ss, 750000000000018000000000000109.0 / 6.0, 1e-14));
  EXPECT_TRUE(near_rel(e.F, 1.3803680981595422e28, 1e-12));
  EXPECT_TRUE(near_rel(e.log10_p, -82.98862097696326, 1e-12));
  EXPECT_TRUE(near_rel(e.p, 1.02654743703696e-83, 1e-10));
  EXPECT_TRUE(near_rel(e.gg_epsilon, 26569.0 / 49202.0, 1e-12));
  EXPECT_TRUE(near_rel(e.hf_epsilon, 28537.0 / 47234.0, 1e-12));
  EXPECT_TRUE(near_rel(e.mauchly_W, 3936.0 / 26569.0, 1e-12));
  EXPECT_TRUE(near_rel(e.mauchly_p, 3936.0 / 26569.0, 1e-12));
  for (const auto& w : r->warnings) EXPECT_EQ(w.find("zero error"), std::string::npos) << w;
}

// The zero rule still fires where the residual is only the rounding of the
// input: decimal data with parallel profiles (exact decimal residual 0).
TEST(EdgeCases, DecimalParallelProfilesStillHaveZeroErrorVariance) {
  const LongData d = test::long_from_text(
      "id,cond,y\na,x,1.1\na,y,3.3\na,z,8.8\nb,x,11.1\nb,y,13.3\nb,z,18.8\nc,x,26.1\nc,y,28.3\nc,z,33.8\n"
      "d,x,5.1\nd,y,7.3\nd,z,12.8\n",
      {"y", "id", {"cond"}, {}});
  auto r = rm_anova(d);
  ASSERT_TRUE(r.ok());
  EXPECT_EQ(cond_effect(*r).F, INFINITY);
  EXPECT_EQ(cond_effect(*r).ss_error, 0.0);
}

// Broke: values near the double maximum overflowed the sums silently (NA for
// SS, F and the mean); choosing the offset read past the end of the values.
TEST(EdgeCases, OverflowIsReportedNotPrintedAsNa) {
  auto t = parse_csv("g,y\na,1.7e308\na,-1.7e308\nb,1\nb,2\n", "big.csv");
  ASSERT_TRUE(t.ok());
  auto d = long_data_from_csv(*t, {"y", "", {}, {"g"}});
  ASSERT_TRUE(d.ok());
  auto r = one_way_anova(*d);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.error().message.find("overflow"), std::string::npos) << r.error().message;

  auto rm = rm_anova(test::long_from_text("id,cond,y\na,x,1.7e308\na,y,-1.7e308\nb,x,1\nb,y,2\nc,x,4\nc,y,3\n",
                                          {"y", "id", {"cond"}, {}}));
  ASSERT_FALSE(rm.ok());
  EXPECT_NE(rm.error().message.find("overflow"), std::string::npos) << rm.error().message;

  // Equal huge values: offset is one of them, deltas 0, mean exact.
  const Measurements m = Measurements::from_decimals({parse_decimal("1.7e308"), parse_decimal("1.7e308")});
  EXPECT_EQ(m.offset, 1.7e308);
  EXPECT_EQ(m.delta[0], 0.0);
  const Descriptives big = describe({1.6e308, 1.7e308});
  EXPECT_TRUE(near_rel(big.mean, 1.65e308, 1e-15));
  EXPECT_TRUE(near_rel(big.sd, 1e307 / std::sqrt(2.0), 1e-12));

  // Paired t on x - y beyond the double range: t and p from rescaled differences
  // (d = (3.4e308, 3.2e308, 3.3e308): t = mean / (sd / sqrt 3) = 3.3 / (0.1 / sqrt 3)), with a warning.
  const PairedTResult pt = paired_t({1.7e308, 1.6e308, 1.65e308}, {-1.7e308, -1.6e308, -1.65e308});
  EXPECT_TRUE(near_rel(pt.t, 3.3 / (0.1 / std::sqrt(3.0)), 1e-12));
  EXPECT_EQ(pt.mean_difference, INFINITY);
  ASSERT_FALSE(pt.warnings.empty());
  EXPECT_NE(pt.warnings.back().find("overflow"), std::string::npos);
}

// Tiny values: squares would underflow to 0 (R 4.2.2's aov prints Sum Sq 0, F NaN for
// y = c(1,2,3,4,6,8) * 1e-170). Scaling by a power of two keeps them: F does not depend on
// the scale, so it equals the F of y = c(1,2,3,4,6,8).
// R 4.2.2: summary(aov(y ~ g, data.frame(g = rep(c("a","b"), each = 3), y = c(1,2,3,4,6,8))))
//   F value 9.6
TEST(EdgeCases, TinyValuesKeepTheirF) {
  auto r = one_way_anova({"a", "a", "a", "b", "b", "b"}, {1e-170, 2e-170, 3e-170, 4e-170, 6e-170, 8e-170});
  ASSERT_TRUE(r.ok());
  auto plain = one_way_anova({"a", "a", "a", "b", "b", "b"}, {1, 2, 3, 4, 6, 8});
  ASSERT_TRUE(plain.ok());
  EXPECT_TRUE(near_rel(r->effect.F, plain->effect.F, 1e-12));
  EXPECT_TRUE(near_rel(r->effect.F, 9.6, 1e-12));
}

// Broke: constant non-zero differences gave t = Infinity, p = 0 without a word.
// R 4.2.2: t.test(c(5,6,7,8,9), c(4,5,6,7,8), paired = TRUE) -> Error: data are essentially constant
TEST(EdgeCases, ConstantDifferencesWarnAsRRefuses) {
  const PairedTResult t = paired_t({5, 6, 7, 8, 9}, {4, 5, 6, 7, 8});
  EXPECT_EQ(t.t, INFINITY);
  EXPECT_EQ(t.p, 0.0);
  ASSERT_EQ(t.warnings.size(), 1u);
  EXPECT_NE(t.warnings[0].find("essentially constant"), std::string::npos) << t.warnings[0];
  const PairedTResult zero = paired_t({1, 2, 3}, {1, 2, 3});
  ASSERT_EQ(zero.warnings.size(), 1u);
  EXPECT_NE(zero.warnings[0].find("zero"), std::string::npos);
  EXPECT_TRUE(paired_t({1, 2, 4}, {0, 0, 0}).warnings.empty());
}

// Broke: one-sided paired t reported the two-sided 95% CI.
// R 4.2.2, x = sleep$extra[1:10], y = sleep$extra[11:20]:
//   t.test(x, y, paired = TRUE, alternative = "less")$conf.int    -> -Inf -0.866994732970716
//   t.test(x, y, paired = TRUE, alternative = "greater")$conf.int -> -2.29300526702928 Inf
//   $p.value: less 0.00141644509869214, greater 0.998583554901308
TEST(EdgeCases, OneSidedPairedTHasOneSidedInterval) {
  const std::vector<double> x{0.7, -1.6, -0.2, -1.2, -0.1, 3.4, 3.7, 0.8, 0.0, 2.0};
  const std::vector<double> y{1.9, 0.8, 1.1, 0.1, -0.1, 4.4, 5.5, 1.6, 4.6, 3.4};
  const PairedTResult less = paired_t(x, y, Alternative::less);
  EXPECT_EQ(less.ci_low, -INFINITY);
  EXPECT_TRUE(near_rel(less.ci_high, -0.866994732970716, 1e-12));
  EXPECT_TRUE(near_rel(less.p, 0.00141644509869214, 1e-10));
  const PairedTResult greater = paired_t(x, y, Alternative::greater);
  EXPECT_TRUE(near_rel(greater.ci_low, -2.29300526702928, 1e-12));
  EXPECT_EQ(greater.ci_high, INFINITY);
  EXPECT_TRUE(near_rel(greater.p, 0.998583554901308, 1e-12));
}

// Broke: the default p_exact ran 100000 Monte Carlo resamples whenever the
// exact enumeration was too large (547 s at 10^6 rows). Now automatic means
// exact when cheap, else none with the reason; Monte Carlo only on request,
// with progress.
TEST(EdgeCases, FriedmanDefaultIsBoundedAndMonteCarloReportsProgress) {
  std::vector<std::vector<double>> y;
  for (int i = 0; i < 400; ++i) y.push_back({double((i * 7) % 5), double((i * 3) % 7), double((i * 11) % 13), 2.5});
  const FriedmanResult r = friedman_blocks(y);
  EXPECT_EQ(r.exact_method, "none");
  EXPECT_TRUE(std::isnan(r.p_exact));
  // The note gives the reason and the limit (the work is counted only up to it, so "more than").
  EXPECT_NE(r.exact_note.find("not enumerated: it needs more than 3e+08 state updates for n = 400, k = 4 (the limit)"),
            std::string::npos)
      << r.exact_note;
  EXPECT_NE(r.exact_note.find("monte-carlo=N"), std::string::npos) << r.exact_note;
  ExactOptions mc;
  mc.mode = ExactMode::monte_carlo;
  mc.monte_carlo_samples = 200;
  size_t calls = 0, last = 0;
  mc.progress = [&](size_t done, size_t total) {
    ++calls;
    last = done;
    EXPECT_EQ(total, 200u);
  };
  const FriedmanResult m = friedman_blocks(y, mc);
  EXPECT_EQ(m.exact_method, "monte-carlo");
  EXPECT_GT(calls, 2u);
  EXPECT_EQ(last, 200u);
}

// Broke: friedman() on data with no complete block, or a one-level factor,
// left mean_ranks shorter than treatments (the text output read past it).
TEST(EdgeCases, FriedmanWithoutBlocksOrWithOneTreatmentIsAnError) {
  auto none = friedman(test::long_from_text("id,cond,y\na,x,1\na,y,\nb,x,2\nb,y,NA\n", {"y", "id", {"cond"}, {}}));
  ASSERT_FALSE(none.ok());
  EXPECT_NE(none.error().message.find("no subject has every cell"), std::string::npos);
  auto one = friedman(test::long_from_text("id,cond,y\na,x,1\nb,x,2\n", {"y", "id", {"cond"}, {}}));
  ASSERT_FALSE(one.ok());
  EXPECT_NE(one.error().message.find("at least two treatments"), std::string::npos);
  const FriedmanResult blocks = friedman_blocks({{3}, {1}});
  EXPECT_EQ(blocks.mean_ranks.size(), 1u);
}

// Broke: a NUL byte inside an id made a second subject that printed like the first.
TEST(EdgeCases, NulByteIsACsvError) {
  const std::string text = std::string("id,cond,y\na,x,1\na") + '\0' + "b,y,2\n";
  auto t = parse_csv(text, "nul.csv");
  ASSERT_FALSE(t.ok());
  EXPECT_EQ(t.error().line, 3);
  EXPECT_EQ(t.error().column, 1);
  EXPECT_NE(t.error().message.find("NUL"), std::string::npos);
}

// Broke: a 10 MB field was echoed whole in the error message.
TEST(EdgeCases, ErrorsQuoteAtMostAShortPrefixOfAField) {
  const std::string huge(10 * 1024 * 1024, 'x');
  auto t = parse_csv("id,cond,y\na,x," + huge + "\n", "huge.csv");
  ASSERT_TRUE(t.ok());
  auto d = long_data_from_csv(*t, {"y", "id", {"cond"}, {}});
  ASSERT_FALSE(d.ok());
  const std::string msg = d.error().to_string();
  EXPECT_LT(msg.size(), 400u) << msg.substr(0, 400);
  EXPECT_NE(msg.find("(10485760 bytes)"), std::string::npos) << msg;
  EXPECT_EQ(quote_text(std::string("a\x01" "b")), "'a\\x01b'");
}

// Broke (policy change): several rows for one subject and cell were averaged
// silently-ish; now an error naming both lines unless an aggregation is asked for.
TEST(EdgeCases, RepeatedRowsNeedAnAggregation) {
  LongData twice = test::long_from_text("id,cond,y\na,x,1\na,x,3\na,y,5\nb,x,2\nb,y,4\nb,y,9\nc,x,0\nc,y,3\n",
                                        {"y", "id", {"cond"}, {}});
  auto refused = rm_anova(twice);
  ASSERT_FALSE(refused.ok());
  EXPECT_EQ(refused.error().line, 3);
  EXPECT_NE(refused.error().message.find("inline.csv:2"), std::string::npos) << refused.error().message;
  twice.aggregate = Aggregate::median;  // a: x = median(1, 3) = 2; b: y = median(4, 9) = 6.5
  auto med = rm_anova(twice);
  ASSERT_TRUE(med.ok());
  // R 4.2.2: summary(aov(y ~ cond + Error(id/cond), data.frame(id = factor(rep(c("a","b","c"), each = 2)),
  //   cond = factor(rep(c("x","y"), 3)), y = c(2, 5, 2, 6.5, 0, 3)))) -> cond F 49, Pr(>F) 0.019804
  EXPECT_TRUE(near_rel(cond_effect(*med).F, 49.0, 1e-12));
  EXPECT_TRUE(near_rel(cond_effect(*med).p, 0.0198039411804, 1e-10));
}

}  // namespace
}  // namespace dtlab::stats

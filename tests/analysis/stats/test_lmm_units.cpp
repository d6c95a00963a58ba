// The pieces of the mixed models against R's own definitions (each R call
// above its values, R 4.2.2 / lme4 1.1-31 / lmerTest 3.1-3 / numDeriv
// 2016.8-1.1), and the errors bad trial data must give (file, line, field).
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "analysis/stats/detail/lmm_design.h"
#include "analysis/stats/detail/lmm_model.h"
#include "analysis/stats/detail/numderiv.h"
#include "analysis/stats/lmm.h"
#include "test_util.h"

namespace dtlab::stats {
namespace {

using detail::code_factor;
using detail::CodedFactor;
using detail::fixed_design;

std::vector<CodedFactor> factors(const std::vector<std::pair<std::string, int>>& spec) {
  std::vector<CodedFactor> out;
  for (const auto& [name, k] : spec) {
    std::vector<std::string> labels;
    for (int l = 0; l < k; ++l) labels.push_back(name + std::to_string(l + 1));
    out.push_back(code_factor(name, labels, true));
  }
  return out;
}

// R: attr(terms(~A*B*C*D), "term.labels")
TEST(LmmDesign, TermsInRsOrder) {
  const auto d = fixed_design(factors({{"A", 2}, {"B", 2}, {"C", 2}, {"D", 2}}));
  std::vector<std::string> names;
  for (const auto& t : d.terms) names.push_back(t.name);
  EXPECT_EQ(names, (std::vector<std::string>{"A", "B", "C", "D", "A:B", "A:C", "B:C", "A:D", "B:D", "C:D", "A:B:C",
                                             "A:B:D", "A:C:D", "B:C:D", "A:B:C:D"}));
}

// R: colnames(model.matrix(~A*B, expand.grid(A = factor(1:3), B = factor(1:3)),
//                          contrasts.arg = list(A = "contr.sum", B = "contr.sum")))
TEST(LmmDesign, ContrSumColumnsAsModelMatrix) {
  const auto d = fixed_design(factors({{"A", 3}, {"B", 3}}));
  EXPECT_EQ(d.column_names, (std::vector<std::string>{"(Intercept)", "A1", "A2", "B1", "B2", "A1:B1", "A2:B1", "A1:B2",
                                                      "A2:B2"}));
  // contr.sum(3): level 3 is -1 in both columns; the interaction column A2:B1 = A2 * B1
  const Eigen::RowVectorXd r = d.cell_row({2, 0});
  EXPECT_EQ(r(1), -1);
  EXPECT_EQ(r(2), -1);
  EXPECT_EQ(r(3), 1);
  EXPECT_EQ(r(6), -1);  // A2:B1 at (a3, b1): (-1) * 1
}

// lmerTest: attr(anova(lmer(y ~ A * B + (1 | s), d)), "hypotheses") with
// options(contrasts = c("contr.sum", "contr.poly")), A with 3 levels, B with 2:
//   $A   Aa2: A1 -1, A2 1;  Aa3: A1 -2, A2 -1
//   $B   Bb2: B1 -2
//   $A:B Aa2:Bb2: A1:B1 2, A2:B1 -2;  Aa3:Bb2: A1:B1 4, A2:B1 2
TEST(LmmDesign, TypeThreeHypothesesAsLmerTest) {
  const auto d = fixed_design(factors({{"A", 3}, {"B", 2}}));
  const Eigen::MatrixXd A = detail::type3_hypothesis(d, d.terms[0]);
  const Eigen::MatrixXd B = detail::type3_hypothesis(d, d.terms[1]);
  const Eigen::MatrixXd AB = detail::type3_hypothesis(d, d.terms[2]);
  Eigen::MatrixXd eA(2, 6), eB(1, 6), eAB(2, 6);
  eA << 0, -1, 1, 0, 0, 0, 0, -2, -1, 0, 0, 0;
  eB << 0, 0, 0, -2, 0, 0;
  eAB << 0, 0, 0, 0, 2, -2, 0, 0, 0, 0, 4, 2;
  EXPECT_EQ(A, eA);
  EXPECT_EQ(B, eB);
  EXPECT_EQ(AB, eAB);
}

// R: levels(factor(c(...))) in the C locale (Sys.setlocale("LC_COLLATE", "C")),
// and read.csv's integer column sorted by value: levels(factor(c(10L, 9L, 2L))).
TEST(LmmDesign, LevelsInRsFactorOrder) {
  EXPECT_EQ(code_factor("f", {"b", "B", "10", "9", "a"}, true).levels,
            (std::vector<std::string>{"10", "9", "B", "a", "b"}));
  EXPECT_EQ(code_factor("f", {"10", "9", "2", "9"}, true).levels, (std::vector<std::string>{"2", "9", "10"}));
}

// lme4's mkReTrms: with nl = (20, 20, 50) some term has more levels than the one
// before, so ord <- rev(order(nl)) = (3, 2, 1); with (50, 20, 20) nothing moves.
TEST(LmmDesign, RandomTermsInLme4Order) {
  std::vector<detail::Grouping> g(2);
  g[0].levels.resize(20);
  g[1].levels.resize(50);
  const std::vector<detail::RandomTerm> terms{{0, {0}}, {0, {1}}, {1, {0}}};
  const auto sorted = detail::lme4_term_order(terms, g);
  EXPECT_EQ(sorted[0].grouping, 1);
  EXPECT_EQ(sorted[1].columns, std::vector<int>{1});
  EXPECT_EQ(sorted[2].columns, std::vector<int>{0});
  const std::vector<detail::RandomTerm> kept{{1, {0}}, {0, {0}}, {0, {1}}};
  EXPECT_EQ(detail::lme4_term_order(kept, g)[2].columns, std::vector<int>{1});
}

TEST(LmmDesign, RNamesGetBackticks) {
  EXPECT_EQ(detail::r_name("technique"), "technique");
  EXPECT_EQ(detail::r_name("view mode"), "`view mode`");
  EXPECT_EQ(detail::r_name("2nd"), "`2nd`");
  EXPECT_EQ(detail::r_name("if"), "`if`");
}

double f3(const std::vector<double>& x) {
  return std::exp(x[0]) * std::sin(x[1]) + x[0] * x[0] * x[1] * x[1] * x[1] + 0.1 * std::pow(x[2], 4);
}

// R: f <- function(x) exp(x[1])*sin(x[2]) + x[1]^2*x[2]^3 + 0.1*x[3]^4
//    numDeriv::hessian(f, c(0.5, 1.2, 0))   (x[3] = 0: the zero.tol step 1e-4)
TEST(NumDeriv, HessianAsNumDeriv) {
  const Eigen::MatrixXd H = detail::numderiv_hessian(f3, {0.5, 1.2, 0});
  EXPECT_TRUE(test::near_rel(H(0, 0), 4.9926726661435143, 1e-10));
  EXPECT_TRUE(test::near_rel(H(0, 1), 4.9174269374080284, 1e-10));
  EXPECT_TRUE(test::near_rel(H(1, 1), 0.26332733384263857, 1e-9));
  EXPECT_LT(std::fabs(H(0, 2)), 1e-12);  // R: -1.0848905548172412e-13
  EXPECT_LT(std::fabs(H(2, 2)), 1e-12);  // R: 0
}

// R: g <- function(x) c(sin(x[1]*x[2]), x[1]^3 + x[2]); numDeriv::jacobian(g, c(0.3, 0))
//    = [0, 0.3; 0.27000000000310392, 0.99999999999982825] (column-major "0" "0.27..." "0.3" "0.99...")
TEST(NumDeriv, JacobianAsNumDeriv) {
  const Eigen::MatrixXd J = detail::numderiv_jacobian(
      [](const std::vector<double>& x) {
        Eigen::VectorXd v(2);
        v << std::sin(x[0] * x[1]), x[0] * x[0] * x[0] + x[1];
        return v;
      },
      {0.3, 0.0});
  EXPECT_NEAR(J(0, 0), 0, 1e-15);
  EXPECT_TRUE(test::near_rel(J(1, 0), 0.27000000000310392, 1e-12));
  EXPECT_TRUE(test::near_rel(J(0, 1), 0.29999999999999993, 1e-12));
  EXPECT_TRUE(test::near_rel(J(1, 1), 0.99999999999982825, 1e-12));
}

// R: lme4:::deriv12(f, c(0.5, 1.2, 0)): gradient 3.2646726687179939 1.6774269389130403 0,
//    Hessian 4.9926726818084717 4.9174269661307335 0 / . 0.26332733035087585 0 / . . 0
TEST(NumDeriv, Deriv12AsLme4) {
  const auto d = detail::lme4_deriv12(f3, {0.5, 1.2, 0});
  EXPECT_TRUE(test::near_rel(d.gradient(0), 3.2646726687179939, 1e-10));
  EXPECT_TRUE(test::near_rel(d.gradient(1), 1.6774269389130403, 1e-10));
  EXPECT_TRUE(test::near_rel(d.hessian(0, 0), 4.9926726818084717, 1e-7));
  EXPECT_TRUE(test::near_rel(d.hessian(0, 1), 4.9174269661307335, 1e-7));
  EXPECT_TRUE(test::near_rel(d.hessian(1, 1), 0.26332733035087585, 1e-6));
}

Result<LmmFit> fit_text(const std::string& csv, const ColumnRoles& roles, LmmOptions o = {}, const std::string& item = "") {
  auto t = parse_csv(csv, "trials.csv");
  EXPECT_TRUE(t.ok());
  auto d = lmm_data_from_csv(*t, roles, item);
  if (!d) return d.error();
  return fit_lmm(*d, o);
}

std::string trials(const std::string& extra_row = "") {
  std::string s = "s,A,y\n";
  const double v[] = {1.2, 1.5, 0.9, 1.4, 1.1, 1.8, 1.0, 1.3, 1.25, 1.7, 0.95, 1.6};
  for (int i = 0; i < 12; ++i) s += "s" + std::to_string(i / 4) + "," + (i % 2 ? "a2" : "a1") + "," + std::to_string(v[i]) + "\n";
  return s + extra_row;
}

TEST(LmmErrors, LogOfANonPositiveValueNamesTheLine) {
  LmmOptions o;
  o.transform = Transform::log;
  auto r = fit_text(trials("s0,a1,0\n"), {"y", "s", {"A"}, {}}, o);
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.error().line, 14);
  EXPECT_EQ(r.error().field, "y");
  EXPECT_NE(r.error().message.find("above 0"), std::string::npos);
}

TEST(LmmErrors, BinomialNeedsZeroOrOne) {
  LmmOptions o;
  o.family = Family::binomial;
  auto r = fit_text(trials(), {"y", "s", {"A"}, {}}, o);
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.error().line, 2);
  EXPECT_NE(r.error().message.find("0 or 1"), std::string::npos);
}

TEST(LmmErrors, EmptyCellOfTheFactorialIsNamed) {
  // B = b2 only ever with A = a1: the cell a2 x b2 has no row
  std::string s = "s,A,B,y\n";
  for (int i = 0; i < 12; ++i)
    s += "s" + std::to_string(i / 3) + "," + (i % 3 == 2 ? "a1,b2" : i % 3 ? "a2,b1" : "a1,b1") + "," + std::to_string(1 + i * 0.1) + "\n";
  auto r = fit_text(s, {"y", "s", {"A", "B"}, {}});
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.error().message.find("A=a2, B=b2"), std::string::npos) << r.error().to_string();
}

TEST(LmmErrors, OneSubjectAndOneLevelAreErrors) {
  auto one_subject = fit_text("s,A,y\ns1,a1,1\ns1,a2,2\ns1,a1,1.5\n", {"y", "s", {"A"}, {}});
  ASSERT_FALSE(one_subject.ok());
  EXPECT_NE(one_subject.error().message.find("> 1 sampled level"), std::string::npos);
  auto one_level = fit_text("s,A,y\ns1,a1,1\ns2,a1,2\ns1,a1,1.5\ns2,a1,3\n", {"y", "s", {"A"}, {}});
  ASSERT_FALSE(one_level.ok());
  EXPECT_EQ(one_level.error().field, "A");
}

TEST(LmmErrors, BetweenFactorChangingWithinASubject) {
  auto r = fit_text("s,G,y\ns1,g1,1\ns1,g2,2\ns2,g1,1.5\ns2,g1,3\ns3,g2,2\n", {"y", "s", {}, {"G"}});
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.error().line, 3);
  EXPECT_NE(r.error().message.find("--within"), std::string::npos);
}

TEST(LmmErrors, MissingItemIsAnError) {
  auto r = fit_text("s,A,item,y\ns1,a1,i1,1\ns1,a2,,2\ns2,a1,i2,1.5\ns2,a2,i1,3\n", {"y", "s", {"A"}, {}}, {}, "item");
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.error().line, 3);
  EXPECT_EQ(r.error().field, "item");
}

// Missing dv values are left out as lme4's na.omit, with a warning counting them.
TEST(LmmErrors, MissingDvRowsAreLeftOutWithAWarning) {
  auto r = fit_text(trials("s1,a1,NA\ns2,a2,\n"), {"y", "s", {"A"}, {}});
  ASSERT_TRUE(r.ok()) << r.error().to_string();
  EXPECT_EQ(r->n, 12u);
  bool said = false;
  for (const auto& w : r->warnings) said = said || w.find("2 rows with a missing y left out") != std::string::npos;
  EXPECT_TRUE(said);
}

}  // namespace
}  // namespace dtlab::stats

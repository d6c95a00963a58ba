// Mixed models against lme4 1.1-31 / lmerTest 3.1-3 / pbkrtest 0.5.2 /
// emmeans 1.8.4 on the datasets of tests/analysis/data/lmm. Every expected
// value comes from data/lmm/lmm_reference.json, written by
// data/lmm/make_lmm_reference.R; each case there carries its exact R call
// ("r_call", printed with every failure), e.g.
//   options(contrasts = c("contr.sum", "contr.poly"))
//   m <- lmerTest::lmer(log(time) ~ A * B + (1 | s), data = d, REML = TRUE)
//   coef(summary(m)); anova(m); as.data.frame(VarCorr(m)); REMLcrit(m); logLik(m); AIC(m); BIC(m)
//   emmeans(m, ~ A, lmer.df = "satterthwaite", lmerTest.limit = Inf); pairs(., adjust = "holm")
//   anova(m, ddf = "Kenward-Roger")
//   lme4::glmer(correct ~ A * B + (1 | s), d, family = binomial); afex::mixed(..., method = "LRT")
// Tolerances are the issue's: estimates, SEs, variances, criteria and means
// to 1e-6 relative, df and p to 1e-4. Cases marked "path sensitive" have
// four or more variance parameters: there lme4's own BOBYQA path moves with
// the last bit of the criterion (its default stops within ~1e-4 of the
// optimum), so they are held to the optimum's criterion (1e-8) and 1e-3.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <fstream>
#include <string>
#include <vector>

#include "analysis/stats/emmeans.h"
#include "analysis/stats/lmm.h"
#include "test_util.h"

namespace dtlab::stats {
namespace {

using json = nlohmann::json;

json reference() {
  std::ifstream in(test::data_path("lmm/lmm_reference.json"));
  EXPECT_TRUE(in.good()) << "cannot read lmm_reference.json";
  return json::parse(in);
}

// jsonlite writes length-1 vectors as scalars: read both as a vector.
std::vector<double> nums(const json& v) {
  std::vector<double> out;
  auto one = [](const json& x) { return x.is_null() ? std::nan("") : x.get<double>(); };
  if (v.is_array())
    for (const auto& x : v) out.push_back(one(x));
  else
    out.push_back(one(v));
  return out;
}
std::vector<std::string> strs(const json& v) {
  std::vector<std::string> out;
  if (v.is_array())
    for (const auto& x : v) out.push_back(x.get<std::string>());
  else if (v.is_string())
    out.push_back(v.get<std::string>());
  return out;
}

::testing::AssertionResult close(double actual, double expected, double rel, const std::string& what) {
  if (std::isnan(actual) && std::isnan(expected)) return ::testing::AssertionSuccess();
  if (std::fabs(actual - expected) <= rel * std::fabs(expected)) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << what << ": " << actual << " vs R " << expected << " (relative "
                                       << std::fabs(actual - expected) / std::fabs(expected) << " > " << rel << ")";
}

struct Tolerance {
  double estimate = 1e-6, df = 1e-4, p = 1e-4, criterion = 1e-6;
  double f_ddf = 1e-4, f_p = 1e-4;  // the F tests' combined Satterthwaite df (get_Fstat_ddf)
};

Tolerance tolerance(const json& c) {
  Tolerance t;
  if (c.value("note", "").find("path sensitive") != std::string::npos) t = {1e-3, 1e-3, 1e-2, 1e-8, 1e-3, 1e-2};
  // A singular fit's theta components near 0 are arbitrary below the optimiser's
  // tolerance, and numDeriv's step switches at |x| = 1.8e-5 (zero.tol): lmerTest's
  // F ddf there changes by percents between two equally good optima.
  if (c.value("note", "").find("path sensitive") != std::string::npos && c["singular"].get<bool>()) {
    t.f_ddf = 0.1;
    t.f_p = 0.3;
  }
  return t;
}

LmmFit fit_case(const json& c, DenominatorDf ddf = DenominatorDf::satterthwaite) {
  const json& o = c["options"];
  auto table = read_csv_file(test::data_path("lmm/" + c["data"].get<std::string>()));
  EXPECT_TRUE(table.ok());
  ColumnRoles roles{o["dv"], o["subject"], strs(o["within"]), strs(o["between"])};
  auto data = lmm_data_from_csv(*table, roles, o["item"].get<std::string>());
  EXPECT_TRUE(data.ok()) << (data.ok() ? "" : data.error().to_string());
  LmmOptions opt;
  const std::string random = o["random"];
  opt.random = random == "slopes" ? RandomEffects::slopes : random == "max" ? RandomEffects::maximal : RandomEffects::intercepts;
  opt.transform = o["transform"] == "log" ? Transform::log : Transform::none;
  opt.reml = o["reml"].get<bool>();
  opt.family = o["family"] == "binomial" ? Family::binomial : Family::gaussian;
  opt.ddf = ddf;
  opt.lrt = c.contains("lrt");
  auto fit = fit_lmm(*data, opt);
  EXPECT_TRUE(fit.ok()) << (fit.ok() ? "" : fit.error().to_string());
  return fit.ok() ? *fit : LmmFit{};
}

void check_lmm(const json& c) {
  SCOPED_TRACE(c["name"].get<std::string>() + ": " + c["r_call"].get<std::string>());
  const Tolerance tol = tolerance(c);
  const LmmFit f = fit_case(c);
  EXPECT_EQ(f.formula, c["formula"].get<std::string>());
  const bool reml = c["options"]["reml"].get<bool>();
  EXPECT_TRUE(close(reml ? f.reml_criterion : f.deviance, c["criterion"], tol.criterion, "criterion"));
  EXPECT_TRUE(close(f.loglik, c["loglik"], tol.criterion, "logLik"));
  EXPECT_TRUE(close(f.aic, c["aic"], tol.criterion, "AIC"));
  EXPECT_TRUE(close(f.bic, c["bic"], tol.criterion, "BIC"));
  EXPECT_TRUE(close(f.sigma, c["sigma"], tol.estimate, "sigma"));
  EXPECT_EQ(f.singular, c["singular"].get<bool>());
  const auto names = strs(c["coef_names"]);
  ASSERT_EQ(f.coefficients.size(), names.size());
  const auto est = nums(c["estimate"]), se = nums(c["se"]), df = nums(c["df"]), t = nums(c["t"]), p = nums(c["p"]);
  for (size_t i = 0; i < names.size(); ++i) {
    EXPECT_EQ(f.coefficients[i].name, names[i]);
    EXPECT_TRUE(close(f.coefficients[i].estimate, est[i], tol.estimate, names[i] + " estimate"));
    EXPECT_TRUE(close(f.coefficients[i].se, se[i], tol.estimate, names[i] + " SE"));
    EXPECT_TRUE(close(f.coefficients[i].df, df[i], tol.df, names[i] + " df"));
    EXPECT_TRUE(close(f.coefficients[i].statistic, t[i], tol.estimate, names[i] + " t"));
    EXPECT_TRUE(close(f.coefficients[i].p, p[i], tol.p, names[i] + " p"));
  }
  const auto terms = strs(c["anova_terms"]);
  ASSERT_EQ(f.anova.size(), terms.size());
  const auto F = nums(c["F"]), ndf = nums(c["num_df"]), ddf = nums(c["den_df"]), fp = nums(c["anova_p"]);
  for (size_t i = 0; i < terms.size(); ++i) {
    EXPECT_EQ(f.anova[i].term, terms[i]);
    EXPECT_EQ(f.anova[i].num_df, ndf[i]);
    EXPECT_TRUE(close(f.anova[i].F, F[i], tol.f_ddf, terms[i] + " F"));
    EXPECT_TRUE(close(f.anova[i].den_df, ddf[i], tol.f_ddf, terms[i] + " DenDF"));
    EXPECT_TRUE(close(f.anova[i].p, fp[i], tol.f_p, terms[i] + " Pr(>F)"));
  }
  // VarCorr: variances in lme4's order, then the residual; correlations by name
  const auto grp = strs(c["vc_group"]), v1 = strs(c["vc_var1"]), v2 = strs(c["vc_var2"]);
  const auto vcov = nums(c["vc_vcov"]), sdcor = nums(c["vc_sdcor"]);
  size_t k = 0;
  for (size_t i = 0; i < grp.size(); ++i) {
    if (!v2[i].empty()) {
      bool found = false;
      for (const auto& r : f.correlations)
        if (r.a == v1[i] && r.b == v2[i]) {
          found = true;
          EXPECT_TRUE(close(r.r, sdcor[i], tol.df, "correlation " + v1[i] + " " + v2[i]));
        }
      EXPECT_TRUE(found) << "no correlation " << v1[i] << " " << v2[i];
      continue;
    }
    ASSERT_LT(k, f.variances.size());
    EXPECT_EQ(f.variances[k].name, v1[i]);
    EXPECT_TRUE(close(f.variances[k].variance, vcov[i], tol.estimate, grp[i] + " " + v1[i] + " variance"));
    ++k;
  }
  EXPECT_EQ(k, f.variances.size());
  for (const auto& e : c["emmeans"]) {
    const auto factors = strs(e["factors"]);
    auto table = marginal_means(f, factors);
    ASSERT_TRUE(table.ok());
    const auto m = nums(e["emmean"]), mse = nums(e["se"]), mdf = nums(e["df"]), lo = nums(e["lower"]);
    ASSERT_EQ(table->means.size(), m.size());
    for (size_t i = 0; i < m.size(); ++i) {
      EXPECT_TRUE(close(table->means[i].estimate, m[i], tol.estimate, "emmean"));
      EXPECT_TRUE(close(table->means[i].se, mse[i], tol.estimate, "emmean SE"));
      EXPECT_TRUE(close(table->means[i].df, mdf[i], tol.df, "emmean df"));
      EXPECT_TRUE(close(table->means[i].ci_low, lo[i], tol.df, "emmean lower.CL"));
    }
    const auto labels = strs(e["contrast"]);
    const auto ce = nums(e["c_estimate"]), cse = nums(e["c_se"]), cdf = nums(e["c_df"]);
    const auto cp = nums(e["c_p_holm"]), clo = nums(e["c_lower"]), chi = nums(e["c_upper"]);
    ASSERT_EQ(table->contrasts.size(), labels.size());
    for (size_t i = 0; i < labels.size(); ++i) {
      const auto& x = table->contrasts[i];
      EXPECT_EQ(x.a + " - " + x.b, labels[i]);
      EXPECT_TRUE(close(x.estimate, ce[i], tol.estimate, labels[i] + " estimate"));
      EXPECT_TRUE(close(x.se, cse[i], tol.estimate, labels[i] + " SE"));
      EXPECT_TRUE(close(x.df, cdf[i], tol.df, labels[i] + " df"));
      EXPECT_TRUE(close(x.p_holm, cp[i], tol.p, labels[i] + " p (holm)"));
      EXPECT_TRUE(close(x.ci_low, clo[i], tol.df, labels[i] + " lower.CL"));
      EXPECT_TRUE(close(x.ci_high, chi[i], tol.df, labels[i] + " upper.CL"));
    }
  }
  const auto messages = strs(c["messages"]);
  EXPECT_EQ(f.messages, messages);
  std::vector<std::string> lme4_warnings;  // those lme4 and lmerTest give (not dtlab's note of left-out rows)
  for (const auto& w : f.warnings)
    if (w.find("left out") == std::string::npos) lme4_warnings.push_back(w);
  EXPECT_EQ(lme4_warnings, strs(c["warnings"]));
  if (c.contains("lrt")) {  // afex::mixed(..., method = "LRT"): ML fits without each term's columns
    SCOPED_TRACE(c["lrt"]["r_call"].get<std::string>());
    const auto lterms = strs(c["lrt"]["terms"]);
    const auto chisq = nums(c["lrt"]["chisq"]), ldf = nums(c["lrt"]["df"]), lp = nums(c["lrt"]["p"]);
    ASSERT_EQ(f.lrt.size(), lterms.size());
    for (size_t i = 0; i < lterms.size(); ++i) {
      EXPECT_EQ(f.lrt[i].term, lterms[i]);
      EXPECT_EQ(f.lrt[i].df, ldf[i]);
      EXPECT_TRUE(close(f.lrt[i].chisq, chisq[i], 1e-6, lterms[i] + " Chisq"));
      EXPECT_TRUE(close(f.lrt[i].p, lp[i], 1e-4, lterms[i] + " Pr(>Chisq)"));
    }
  }
  if (c.contains("steps")) {  // --random max: the same formulas tried, for the same lme4 verdicts
    ASSERT_EQ(f.fallback.size(), c["steps"].size());
    for (size_t i = 0; i < f.fallback.size(); ++i) {
      const json& step = c["steps"][i];
      const std::string formula = step["formula"];
      EXPECT_EQ(f.fallback[i].substr(0, formula.size() + 1), formula + ":");
      const bool regular = !step["singular"].get<bool>() && step["warnings"].empty();
      EXPECT_EQ(f.fallback[i].find(": kept") != std::string::npos, regular) << f.fallback[i];
    }
  }
}

// anova(m, ddf = "Kenward-Roger") and coef(summary(m, ddf = "Kenward-Roger")) (pbkrtest 0.5.2).
void check_kenward_roger(const json& c) {
  const json& kr = c["kr"];
  SCOPED_TRACE(c["name"].get<std::string>() + ": " + c["r_call"].get<std::string>() + "; " + kr["r_call"].get<std::string>());
  const LmmFit f = fit_case(c, DenominatorDf::kenward_roger);
  EXPECT_TRUE(f.kenward_roger);
  const auto F = nums(kr["F"]), ndf = nums(kr["num_df"]), ddf = nums(kr["den_df"]), p = nums(kr["p"]);
  ASSERT_EQ(f.anova.size(), F.size());
  for (size_t i = 0; i < F.size(); ++i) {
    EXPECT_EQ(f.anova[i].num_df, ndf[i]);
    EXPECT_TRUE(close(f.anova[i].F, F[i], 1e-6, f.anova[i].term + " KR F"));
    EXPECT_TRUE(close(f.anova[i].den_df, ddf[i], 1e-4, f.anova[i].term + " KR DenDF"));
    EXPECT_TRUE(close(f.anova[i].p, p[i], 1e-4, f.anova[i].term + " KR Pr(>F)"));
  }
  const auto se = nums(kr["se"]), df = nums(kr["df"]), cp = nums(kr["coef_p"]);
  ASSERT_EQ(f.coefficients.size(), se.size());
  for (size_t i = 0; i < se.size(); ++i) {
    EXPECT_TRUE(close(f.coefficients[i].se, se[i], 1e-6, f.coefficients[i].name + " KR SE"));
    EXPECT_TRUE(close(f.coefficients[i].df, df[i], 1e-4, f.coefficients[i].name + " KR df"));
    EXPECT_TRUE(close(f.coefficients[i].p, cp[i], 1e-4, f.coefficients[i].name + " KR p"));
  }
}

// A coefficient near 0 is fixed only to the optimiser's tolerance in absolute
// terms: |difference| <= rel * max(|expected|, se).
::testing::AssertionResult close_scaled(double actual, double expected, double se, double rel, const std::string& what) {
  if (std::fabs(actual - expected) <= rel * std::max(std::fabs(expected), se)) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << what << ": " << actual << " vs R " << expected << " (difference "
                                       << std::fabs(actual - expected) << ", SE " << se << ")";
}

// glmer at the Laplace optimum (the reference's "tight" fit), lme4's default
// fit to its own tolerance, afex's LRT, emmeans on the logit scale.
void check_glmm(const json& c) {
  SCOPED_TRACE(c["name"].get<std::string>() + ": " + c["r_call"].get<std::string>());
  const LmmFit f = fit_case(c);
  EXPECT_EQ(f.formula, c["formula"].get<std::string>());
  const json& t = c["tight"];
  // se: numDeriv's Hessian; se_lme4: vcov(m), lme4's deriv12 Hessian (steps 1e-4), both at the optimum
  const auto theta = nums(t["theta"]), est = nums(t["estimate"]), se = nums(t["se"]), se_deriv12 = nums(t["se_lme4"]);
  ASSERT_EQ(f.theta.size(), theta.size());
  for (size_t i = 0; i < theta.size(); ++i) {
    if (theta[i] < 1e-4) EXPECT_LT(f.theta[i], 1e-4) << "theta " << i << " (singular in lme4)";
    else EXPECT_TRUE(close(f.theta[i], theta[i], 1e-5, "theta"));
  }
  EXPECT_EQ(f.singular, c["singular"].get<bool>());
  EXPECT_TRUE(close(f.loglik, t["loglik"], 1e-9, "logLik"));
  EXPECT_TRUE(close(f.aic, t["aic"], 1e-9, "AIC"));
  EXPECT_TRUE(close(f.bic, t["bic"], 1e-9, "BIC"));
  const auto names = strs(c["coef_names"]);
  ASSERT_EQ(f.coefficients.size(), names.size());
  const json& d = c["default"];
  const auto est_default = nums(d["estimate"]), se_lme4 = nums(d["se_lme4"]);
  for (size_t i = 0; i < names.size(); ++i) {
    EXPECT_EQ(f.coefficients[i].name, names[i]);
    EXPECT_TRUE(close_scaled(f.coefficients[i].estimate, est[i], se[i], 1e-5, names[i] + " estimate"));
    // at a singular fit deriv12's steps straddle theta = 0 from where each optimiser stopped (1e-8 apart)
    const double se_tol = c["singular"].get<bool>() ? 5e-5 : 1e-5;
    EXPECT_TRUE(close(f.coefficients[i].se, se_deriv12[i], se_tol, names[i] + " SE (deriv12)"));
    EXPECT_TRUE(close(f.coefficients[i].se, se[i], 1e-4, names[i] + " SE (numDeriv)"));
    EXPECT_TRUE(std::isinf(f.coefficients[i].df));
    // lme4's default fit (d["r_call"]) stops within its own tolerance of the optimum
    EXPECT_TRUE(close_scaled(f.coefficients[i].estimate, est_default[i], se[i], 1e-2, names[i] + " estimate vs glmer default"));
    EXPECT_TRUE(close(f.coefficients[i].se, se_lme4[i], 5e-3, names[i] + " SE vs glmer default"));
  }
  EXPECT_EQ(f.messages, strs(c["messages"]));
  if (c.contains("lrt")) {
    SCOPED_TRACE(c["lrt"]["r_call"].get<std::string>());
    const auto terms = strs(c["lrt"]["terms"]);
    const auto chisq = nums(c["lrt"]["chisq"]), df = nums(c["lrt"]["df"]), p = nums(c["lrt"]["p"]);
    ASSERT_EQ(f.lrt.size(), terms.size());
    for (size_t i = 0; i < terms.size(); ++i) {
      EXPECT_EQ(f.lrt[i].term, terms[i]);
      EXPECT_EQ(f.lrt[i].df, df[i]);
      EXPECT_NEAR(f.lrt[i].chisq, chisq[i], 1e-6 * std::max(1.0, chisq[i])) << terms[i] << " Chisq";
      EXPECT_TRUE(close(f.lrt[i].p, p[i], 1e-4, terms[i] + " Pr(>Chisq)"));
    }
  }
  for (const auto& e : c.value("emmeans", json::array())) {
    auto table = marginal_means(f, strs(e["factors"]));
    ASSERT_TRUE(table.ok());
    EXPECT_EQ(table->scale, EmmScale::logit);
    const auto m = nums(e["emmean"]), mse = nums(e["se"]);
    ASSERT_EQ(table->means.size(), m.size());
    for (size_t i = 0; i < m.size(); ++i) {
      EXPECT_TRUE(close_scaled(table->means[i].estimate, m[i], mse[i], 1e-5, "emmean"));
      EXPECT_TRUE(close(table->means[i].se, mse[i], 1e-4, "emmean SE"));
      EXPECT_TRUE(std::isinf(table->means[i].df));
    }
    const auto labels = strs(e["contrast"]);
    const auto ce = nums(e["c_estimate"]), cse = nums(e["c_se"]), cp = nums(e["c_p_holm"]);
    ASSERT_EQ(table->contrasts.size(), labels.size());
    for (size_t i = 0; i < labels.size(); ++i) {
      EXPECT_EQ(table->contrasts[i].a + " - " + table->contrasts[i].b, labels[i]);
      EXPECT_TRUE(close_scaled(table->contrasts[i].estimate, ce[i], cse[i], 1e-5, labels[i] + " estimate"));
      EXPECT_TRUE(close(table->contrasts[i].se, cse[i], 1e-4, labels[i] + " SE"));
      EXPECT_TRUE(close(table->contrasts[i].p_holm, cp[i], 1e-3, labels[i] + " p (holm)"));
    }
  }
}

// Complete separation: glmer's default fit warns (its tight fit stops with
// "Downdated VtV is not positive definite"); dtlab must finish, reach at least
// glmer's likelihood, and warn both as lme4 does and about the separation.
TEST(LmmReference, BinomialSeparationWarnsAndDoesNotCrash) {
  const json ref = reference();
  for (const auto& c : ref["cases"]) {
    if (c["name"] != "binomial_separated") continue;
    SCOPED_TRACE(c["r_call"].get<std::string>());
    EXPECT_FALSE(c["warnings"].empty());  // lme4 warns here
    const LmmFit f = fit_case(c);
    EXPECT_GE(f.loglik, c["loglik"].get<double>() - 1e-6);
    EXPECT_TRUE(close(f.theta[0], c["theta"], 1e-3, "theta"));
    bool separation = false, lme4_warning = false;
    for (const auto& w : f.warnings) {
      separation = separation || w.find("complete separation") != std::string::npos;
      lme4_warning = lme4_warning || w.find("Model is nearly unidentifiable") != std::string::npos ||
                     w.find("Model failed to converge") != std::string::npos;
    }
    EXPECT_TRUE(separation);
    EXPECT_TRUE(lme4_warning);
    return;
  }
  FAIL() << "no binomial_separated case";
}

TEST(LmmReference, BinomialCasesEqualGlmerAtTheOptimumAndAfexLrt) {
  const json ref = reference();
  int n = 0;
  for (const auto& c : ref["cases"])
    if (c["options"]["family"] == "binomial" && c.contains("tight")) {
      check_glmm(c);
      ++n;
    }
  EXPECT_GE(n, 3);
}

TEST(LmmReference, KenwardRogerEqualsPbkrtest) {
  const json ref = reference();
  int n = 0;
  for (const auto& c : ref["cases"])
    if (c.contains("kr")) {
      check_kenward_roger(c);
      ++n;
    }
  EXPECT_GE(n, 4);
}

TEST(LmmReference, GaussianCasesEqualLme4LmerTestEmmeans) {
  const json ref = reference();
  int n = 0;
  for (const auto& c : ref["cases"])
    if (c["options"]["family"] == "gaussian") {
      check_lmm(c);
      ++n;
    }
  EXPECT_GE(n, 10);
}

}  // namespace
}  // namespace dtlab::stats

// Linear and binomial mixed models on trial-level data, as R fits them with
//   options(contrasts = c("contr.sum", "contr.poly"))
//   lmerTest::lmer(dv ~ A * B * G + (1 | subject) [+ (1 | item)], data, REML = TRUE)
//   lme4::glmer(dv ~ ... , family = binomial)              (family = binomial)
// Fixed effects: the full factorial of the within and between factors with
// sum-to-zero contrasts (afex's coding). Random effects: intercepts per
// subject (and item); `slopes` adds correlated by-subject slopes for the
// within factors' main effects; `maximal` takes every fixed term whose
// factors vary within the grouping factor (Barr et al. 2013), and when that
// fit is singular or fails lme4's convergence checks falls back step by step
// (Bates et al. 2015 "Parsimonious mixed models"; Matuschek et al. 2017):
// first without correlations (the || model), then dropping the slope with the
// smallest variance until the fit is regular, recording every step.
// LMM method: lme4's relative covariance factor and profiled REML / ML
// criterion (Bates, Maechler, Bolker & Walker 2015, JSS 67(1)), NLopt BOBYQA
// with lme4's settings and starting values (detail/lmm_optimize.h);
// t tests and the type III F table by Satterthwaite (lmerTest 3.1:
// numDeriv Hessian of the deviance in (theta, sigma), Jacobian of vcov(beta);
// F tests on lmerTest's type III hypotheses for contr.sum); optionally
// Kenward-Roger (pbkrtest 0.5: adjusted vcov and ddf). GLMM: Laplace
// approximation by penalised iteratively reweighted least squares, glmer's
// two stages (nAGQ = 0, then nAGQ = 1), Wald z tests and likelihood-ratio
// tests of each term (the term's columns removed from X, ML fits: afex
// method = "LRT").
// Missing data: rows with a missing dv are left out (lme4's na.omit); every
// remaining cell of the factorial needs a row. Log transform: dv > 0 needed.
// Warnings and messages use lme4's and lmerTest's wording.
// Validated against lme4 1.1-31, lmerTest 3.1-3, pbkrtest 0.5.2, emmeans
// 1.8.4 (tests/analysis/stats/test_lmm*.cpp, reference script
// tests/analysis/data/lmm/make_lmm_reference.R).
// Example:
//   auto d = lmm_data_from_csv(table, {"time", "participant", {"technique", "task"}, {}}, "scene");
//   LmmOptions o; o.transform = Transform::log;
//   auto fit = fit_lmm(*d, o);   // fit->coefficients, fit->anova, fit->variances
#pragma once
#include <Eigen/Dense>

#include <string>
#include <utility>
#include <vector>

#include "analysis/stats/csv.h"
#include "analysis/stats/long_data.h"
#include "study/common/error.h"

namespace dtlab::stats {

// Trial-level data: LongData's roles (several rows per subject and cell are
// the point here) and an optional item column (e.g. the scene).
struct LmmData {
  LongData data;
  std::string subject_name = "subject";  // the subject column's name (the grouping factor)
  std::string item_name;          // empty: no item random effect
  std::vector<std::string> item;  // item[row] when item_name is set
};

// Reads the roles from a CSV table (rows already selected); item may be empty.
Result<LmmData> lmm_data_from_csv(const CsvTable& table, const ColumnRoles& roles, const std::string& item);

enum class RandomEffects { intercepts, slopes, maximal };
enum class Transform { none, log };
enum class Family { gaussian, binomial };
enum class DenominatorDf { satterthwaite, kenward_roger };

struct LmmOptions {
  RandomEffects random = RandomEffects::intercepts;
  Transform transform = Transform::none;
  bool reml = true;  // gaussian only; the binomial GLMM is fitted by ML (Laplace)
  Family family = Family::gaussian;
  DenominatorDf ddf = DenominatorDf::satterthwaite;
  bool lrt = false;  // likelihood-ratio test of each term (always for binomial)
};

// One row of summary(m)$coefficients.
struct LmmCoefficient {
  std::string name;  // "(Intercept)", "A1", "A1:B1"
  double estimate = 0, se = 0;
  double df = 0;         // Satterthwaite (or Kenward-Roger) df; infinity for z tests
  double statistic = 0;  // t (LMM) or z (GLMM)
  double p = 0, log10_p = 0;
};

// One row of anova(m) (type III, lmerTest columns).
struct LmmAnovaRow {
  std::string term;
  double sum_sq = 0, mean_sq = 0;
  double num_df = 0, den_df = 0;
  double F = 0, p = 0, log10_p = 0;
};

// One likelihood-ratio test: the model without the term's columns vs the full model (ML).
struct LmmLrtRow {
  std::string term;
  double df = 0, chisq = 0, p = 0, log10_p = 0;
  double deviance_full = 0, deviance_reduced = 0;
  std::vector<std::string> warnings;  // the reduced fit's warnings
};

// One row of VarCorr(m): a variance of a grouping factor's column (or the residual).
struct LmmVariance {
  std::string group;  // "subject", "item", "Residual"
  std::string name;   // "(Intercept)", "A1", ...
  double variance = 0, sd = 0;
};

struct LmmCorrelation {
  std::string group, a, b;
  double r = 0;
};

// A random-effects term as fitted: `grouping` | columns of X (0 = intercept).
struct LmmRandomTerm {
  std::string grouping;
  std::vector<std::string> columns;
  bool correlated = true;  // false: one term per column (the || form)
};

struct LmmFit {
  // The model
  Family family = Family::gaussian;
  Transform transform = Transform::none;
  bool reml = true;
  std::string dv_name;
  std::string formula;   // lme4 formula, e.g. "log(time) ~ technique * task + (1 | participant)"
  std::string r_code;    // R lines that fit the same model on the same rows
  std::vector<LmmRandomTerm> random;        // as fitted (after any fallback)
  std::vector<std::string> fallback;        // --random max: one line per fit tried and why it was left
  std::size_t n = 0;                        // rows used
  std::vector<std::pair<std::string, std::size_t>> groups;  // grouping factor, number of levels
  // Estimates
  std::vector<LmmCoefficient> coefficients;
  std::vector<LmmAnovaRow> anova;
  std::vector<LmmLrtRow> lrt;
  std::vector<LmmVariance> variances;
  std::vector<LmmCorrelation> correlations;
  std::vector<double> theta;
  double sigma = 0;           // residual SD (1 for binomial)
  double reml_criterion = 0;  // NaN for ML fits
  double deviance = 0;        // -2 logLik (ML fits; NaN for REML)
  double loglik = 0, aic = 0, bic = 0;
  int df = 0;                 // parameters counted by logLik
  bool singular = false;
  std::vector<std::string> messages;  // lme4 messages ("boundary (singular) fit: see help('isSingular')")
  std::vector<std::string> warnings;  // lme4 / lmerTest warnings and ours
  // For marginal means (emmeans.h): the fixed-effects model.
  std::vector<std::string> factor_names;
  std::vector<std::vector<std::string>> factor_levels;  // R's level order
  std::vector<std::string> column_names;
  Eigen::VectorXd beta;
  Eigen::MatrixXd vcov;                    // vcov(m) (Kenward-Roger adjusted with that option)
  std::vector<Eigen::MatrixXd> jacobian;   // lmerTest Jac_list (LMM)
  Eigen::MatrixXd vcov_varpar;             // lmerTest vcov_varpar (LMM)
  Eigen::MatrixXd vcov_unadjusted;         // vcov(m) before any Kenward-Roger adjustment
  bool kenward_roger = false;              // vcov is the Kenward-Roger adjusted one
};

// Fits the model; an Error for data it cannot fit (no rows, an empty cell of
// the factorial, a non-positive value under the log, a non-0/1 value for the
// binomial family, one subject).
Result<LmmFit> fit_lmm(const LmmData& data, const LmmOptions& options);

// Satterthwaite df of the contrast L'beta (lmerTest contest1D).
double satterthwaite_df(const LmmFit& fit, const Eigen::RowVectorXd& L);

}  // namespace dtlab::stats

// One linear mixed-model fit as lmer() makes it (starting values of
// mkLmerDevfun, optimizeLmer, checkConv), and the LmmFit it is reported as
// (summary, anova, VarCorr, logLik / AIC / BIC, lmerTest's Satterthwaite
// tests, optional Kenward-Roger). Guarantees: the response is centred
// before fitting and the centre added back to the intercept, so a constant
// offset of 1e6 costs no digits. Never prints; warnings go into the result.
#pragma once
#include <memory>
#include <vector>

#include "analysis/stats/detail/lmm_deviance.h"
#include "analysis/stats/detail/lmm_model.h"
#include "analysis/stats/detail/lmm_optimize.h"

namespace dtlab::stats::detail {

struct GaussianFit {
  std::vector<FormulaTerm> formula_terms;
  std::unique_ptr<LmmDeviance> dev;
  Optimum opt;
  ConvergenceCheck conv;
  double center = 0;  // subtracted from y before fitting

  // Not singular and without convergence warnings (what --random max keeps).
  bool regular() const { return !conv.singular && conv.warnings.empty() && opt.warnings.empty(); }
  const std::vector<RandomTerm>& lme4_terms() const { return dev->terms(); }
  std::vector<std::string> warnings;  // none beyond conv and opt (the GLMM fit has PIRLS failures)
};

// lmer(formula, REML = reml) for the given structure; X: the fixed effects
// (m.design.X, or without a term's columns for a likelihood-ratio test).
GaussianFit fit_gaussian(const PreparedModel& m, const Eigen::MatrixXd& X, const std::vector<FormulaTerm>& terms,
                         bool reml);

// The parts of an LmmFit every family shares: formula, R code, rows, groups,
// random terms, the fixed design's factors and columns.
void describe_model(LmmFit& r, const PreparedModel& m, const std::vector<FormulaTerm>& terms, const LmmOptions& o);

// VarCorr: each term's variances (scale2 T T') and correlations, in lme4's order.
void add_variances(LmmFit& r, const PreparedModel& m, const std::vector<FormulaTerm>& terms, const LmmDeviance& sys,
                   const std::vector<double>& theta, double scale2);

// X without the columns of fixed term `term` (afex's reduced model for its LRT).
Eigen::MatrixXd drop_term(const FixedDesign& design, const FixedTerm& term);

// The variance of each random-effect column at the fit (sigma^2 (T T')_jj), per lme4 term.
std::vector<std::vector<double>> column_variances(const GaussianFit& f);

// The reported fit: coefficients, anova, variances, criteria, tests.
LmmFit report_gaussian(const PreparedModel& m, GaussianFit& f, const LmmOptions& o);

}  // namespace dtlab::stats::detail

// A binomial (logit) GLMM by the Laplace approximation, as lme4's glmer
// (nAGQ = 1) defines it: for (theta, beta) penalised iteratively reweighted
// least squares finds the conditional mode u (weights mu'(eta)^2 / (mu (1 -
// mu)), step halving when the penalised deviance rises, mu clamped to [eps,
// 1 - eps] as lme4's logitinv), and the criterion is
//   -2 log L ~ log|L|^2 + ||u||^2 - 2 sum log dbinom(y | mu)
// with L L' = Lambda' Z'WZ Lambda + I at the mode. glmer's two stages: theta
// alone with (u, beta) both by PIRLS (nAGQ = 0), then (theta, beta) jointly.
// Where lme4 stops its stage 2 Nelder-Mead at FtolAbs = 1e-5 (estimates
// within about 1e-4 of the optimum), both stages here run NLopt's BOBYQA to
// the optimum (xtol_rel 1e-12); vcov(beta) is 2 H^-1 of lme4's deriv12
// Hessian of the criterion at the optimum, as vcov.merMod for a GLMM.
// Never throws; a PIRLS failure makes the criterion +inf and is reported.
#pragma once
#include <memory>
#include <string>
#include <vector>

#include "analysis/stats/detail/lmm_deviance.h"
#include "analysis/stats/detail/lmm_model.h"
#include "analysis/stats/detail/lmm_optimize.h"

namespace dtlab::stats::detail {

class BinomialLaplace {
 public:
  BinomialLaplace(const Eigen::MatrixXd& X, const Eigen::MatrixXd& Zsrc, const Eigen::VectorXd& y,
                  const std::vector<Grouping>& groupings, const std::vector<RandomTerm>& terms);

  size_t n_theta() const { return sys_.n_theta(); }
  size_t p() const { return static_cast<size_t>(X_.cols()); }
  const std::vector<double>& theta_lower() const { return sys_.lower(); }
  LmmDeviance& system() { return sys_; }

  // nAGQ = 0: the criterion at theta with (u, beta) from PIRLS; beta() after it.
  double stage1(const std::vector<double>& theta);
  // nAGQ = 1: the Laplace criterion at par = (theta..., beta...), u from PIRLS.
  double laplace(const std::vector<double>& par);

  const Eigen::VectorXd& beta() const { return beta_; }
  const Eigen::VectorXd& u() const { return u_; }
  bool failed() const { return !failure_.empty(); }
  const std::string& failure() const { return failure_; }

 private:
  struct Iterate {
    Eigen::VectorXd u, beta, eta;
    double pdev = 0;
  };
  double pirls(const std::vector<double>& theta, bool with_beta, const Eigen::VectorXd& offset);
  void set_working(const Eigen::VectorXd& eta, const Eigen::VectorXd& offset, bool fixed);
  bool step(bool with_beta, const Eigen::VectorXd& offset, const Iterate* from, Iterate& to);
  double penalised_deviance(const Eigen::VectorXd& eta, const Eigen::VectorXd& u) const;
  double aic(const Eigen::VectorXd& mu) const;

  Eigen::MatrixXd X_;
  Eigen::VectorXd y_;
  LmmDeviance sys_;
  Eigen::VectorXd u_, beta_, eta_start_;
  std::string failure_;
};

struct BinomialFit {
  std::vector<FormulaTerm> formula_terms;
  std::unique_ptr<BinomialLaplace> model;
  Optimum opt;                 // stage 2 (par = theta, beta)
  ConvergenceCheck conv;
  std::vector<std::string> warnings;

  bool regular() const { return !conv.singular && conv.warnings.empty() && opt.warnings.empty() && warnings.empty(); }
  std::vector<double> theta() const;
  const std::vector<RandomTerm>& lme4_terms() const { return model->system().terms(); }
};

// glmer(formula, family = binomial) with X (possibly without a term's columns, for the LRT).
BinomialFit fit_binomial(const PreparedModel& m, const Eigen::MatrixXd& X, const std::vector<FormulaTerm>& terms);

// The variance of each random-effect column ((T T')_jj), per lme4 term.
std::vector<std::vector<double>> column_variances(const BinomialFit& f);

// The reported fit: Wald z tests, variances, criteria, likelihood-ratio tests of each term.
LmmFit report_binomial(const PreparedModel& m, BinomialFit& f, const LmmOptions& o);

}  // namespace dtlab::stats::detail

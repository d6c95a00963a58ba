// The profiled deviance of a linear mixed model in lme4's parametrisation
// (Bates, Maechler, Bolker & Walker 2015, "Fitting linear mixed-effects
// models using lme4", JSS 67(1), sections 3.2-3.6): b = Lambda_theta u with
// Lambda_theta block diagonal (one lower-triangular T_t per level of each
// term), the sparse Cholesky L L' = P (Lambda' Z'Z Lambda + I) P' (Eigen's
// simplicial LL' with AMD ordering, pattern analysed once), R_ZX, R_X and
// the penalised residual sum of squares r^2 from the cross-products, so an
// evaluation costs O(q + nnz(L) p) whatever the number of rows. Also
// lmerTest's deviance in (theta, sigma) and vcov(beta) as functions of the
// variance parameters (lmerTest 3.1 devfun_vp, get_covbeta).
// Guarantees: the criterion equals lme4's lmer_Deviance to rounding; the
// response is taken as given (the caller centres it). Never throws for a
// theta: a factorisation failure gives +inf.
#pragma once
#include <Eigen/Dense>
#include <Eigen/SparseCholesky>

#include <vector>

#include "analysis/stats/detail/lmm_design.h"

namespace dtlab::stats::detail {

class LmmDeviance {
 public:
  // X: rows x p fixed effects; Zsrc: the columns the random terms name (the
  // full fixed design, also when X lacks a term for a likelihood-ratio test);
  // y: the response (centred by the caller); terms in lme4's order.
  LmmDeviance(Eigen::MatrixXd X, Eigen::MatrixXd Zsrc, Eigen::VectorXd y, std::vector<Grouping> groupings,
              std::vector<RandomTerm> terms, bool reml);

  // Replaces the response and the row weights (sqrt_w: square roots, empty = all 1):
  // the cross-products are formed again, in one pass over the rows (the GLMM's PIRLS);
  // with fixed = false only Z'Z and Z'y (enough for update(theta, false)).
  void set_response(const Eigen::VectorXd& y, const Eigen::VectorXd& sqrt_w = Eigen::VectorXd(), bool fixed = true);
  // Sets Lambda_theta without factorising (for random_part()).
  void set_theta(const std::vector<double>& theta);
  // Factorises at theta; with fixed = false only L and cu (enough for u_only()).
  bool update(const std::vector<double>& theta, bool fixed = true);
  // The penalised least-squares u for the current response with beta = 0 (after update).
  Eigen::VectorXd u_only() const;
  // Z Lambda u for every row, at theta (as last updated).
  Eigen::VectorXd random_part(const Eigen::VectorXd& u) const;

  size_t n_theta() const { return lower_.size(); }
  size_t q() const { return static_cast<size_t>(q_); }  // number of random effects
  const std::vector<double>& lower() const { return lower_; }  // 0 on diagonals of T, -inf elsewhere
  size_t rows() const { return static_cast<size_t>(X_.rows()); }
  size_t p() const { return static_cast<size_t>(X_.cols()); }
  bool reml() const { return reml_; }
  const std::vector<RandomTerm>& terms() const { return terms_; }
  const std::vector<Grouping>& groupings() const { return groupings_; }
  const Eigen::MatrixXd& X() const { return X_; }
  const Eigen::MatrixXd& Zsrc() const { return Zsrc_; }

  // lme4's devfun: REML criterion (or ML deviance) at theta; updates the state below.
  double operator()(const std::vector<double>& theta);
  // lmerTest's devfun_vp: the deviance at theta with sigma given (varpar = theta..., sigma).
  double deviance_vp(const std::vector<double>& varpar);
  // lmerTest's get_covbeta: sigma^2 R_X^-1 R_X^-T at varpar = (theta..., sigma).
  Eigen::MatrixXd covbeta(const std::vector<double>& varpar);

  // State after the last evaluation.
  const Eigen::VectorXd& beta() const { return beta_; }
  double pwrss() const { return pwrss_; }
  double ldL2() const { return ldL2_; }
  double ldRX2() const { return ldRX2_; }
  Eigen::MatrixXd unscaled_vcov() const;  // (R_X' R_X)^-1
  double sigma() const;                   // sqrt(pwrss / (n - p)) for REML, sqrt(pwrss / n) for ML
  Eigen::VectorXd u() const;              // the spherical random effects
  // T_t, the relative covariance factor of term t, at theta.
  Eigen::MatrixXd term_factor(size_t t, const std::vector<double>& theta) const;

 private:
  struct Pair {      // one nonzero block of Z'Z: term t1 >= t2 at levels l1, l2
    int t1, t2, l1, l2;
    size_t b;        // offset of the k1 x k2 block (column major) in zz_
    size_t idx;      // offset of the block's value indices in value_index_
  };
  void find_pairs();
  void build_pattern();
  double residual_pwrss() const;

  Eigen::MatrixXd X_, Zsrc_;
  Eigen::VectorXd y_, sqrt_w_;
  std::vector<Grouping> groupings_;
  std::vector<RandomTerm> terms_;
  bool reml_;
  std::vector<double> lower_;
  std::vector<int> k_, nl_, offset_, theta_offset_;
  int q_ = 0;
  std::vector<Pair> pairs_;
  std::vector<int> row_pairs_;      // per row, the pair of each (t1 >= t2), row-major
  std::vector<double> zz_;          // blocks of Z'Z
  std::vector<int> value_index_;    // per block entry: index into A's values, -1 above the diagonal
  std::vector<int> diagonal_index_; // index of A(i, i) in A's values
  Eigen::MatrixXd ZtX_, XtX_;
  Eigen::VectorXd Zty_, Xty_;
  double yty_ = 0;
  Eigen::SparseMatrix<double> A_;
  Eigen::SimplicialLLT<Eigen::SparseMatrix<double>, Eigen::Lower, Eigen::AMDOrdering<int>> llt_;
  std::vector<Eigen::MatrixXd> T_;
  Eigen::MatrixXd RZX_;
  Eigen::VectorXd cu_, beta_;
  Eigen::LLT<Eigen::MatrixXd> rx_;
  double ldL2_ = 0, ldRX2_ = 0, pwrss_ = 0;
};

}  // namespace dtlab::stats::detail

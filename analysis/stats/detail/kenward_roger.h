// Kenward & Roger's (1997) small-sample adjustment as pbkrtest 0.5.2
// computes it (Halekoh & Hojsgaard 2014, JSS 59(9); vcovAdj, .KR_adjust,
// Lb_ddf): Sigma = sum_r gamma_r G_r over the variance parameters (each
// element of each term's covariance, then the residual), P_r = -X'W G_r W X,
// Q_rs = X'W G_r W G_s W X, IE2_rs = tr(G_r W G_s W) - 2 tr(Phi Q_rs) +
// tr(Phi P_r Phi P_s), W = Sigma^-1, then the adjusted vcov
// Phi_A = Phi + 2 Phi (sum_rs w_rs (Q_rs - P_r Phi P_s)) Phi with w = 2 IE2^-1,
// and for L beta = 0 the scaled F and its ddf from A1, A2 (pbkrtest's
// formulas, V0 zeroed below 1e-10, .divZero). pbkrtest forms the n x n
// matrices; here every product goes through Z: W = sigma^-2 (I - Z C Z')
// with C = Lambda (Lambda'Z'Z Lambda + I)^-1 Lambda', so the work is in the
// q x q random-effects space (q <= 2000; larger models are an Error).
// Never throws; `ok` is false when the adjustment cannot be formed.
#pragma once
#include <Eigen/Dense>

#include <string>
#include <vector>

#include "analysis/stats/detail/lmm_deviance.h"
#include "analysis/stats/detail/satterthwaite.h"

namespace dtlab::stats::detail {

struct KrModel {
  bool ok = false;
  std::string error;             // why not, when !ok
  Eigen::MatrixXd vcov;          // Phi, the unadjusted vcov(beta)
  Eigen::MatrixXd vcov_adjusted; // Phi_A
  std::vector<Eigen::MatrixXd> P;
  Eigen::MatrixXd W;             // 2 IE2^-1
};

// pbkrtest::vcovAdj(model) for a REML fit at theta (vp: its vcov and sigma).
KrModel kenward_roger_model(LmmDeviance& dev, const std::vector<double>& theta, const VarparModel& vp);

struct KrTest {
  double F = 0, F_unscaled = 0, ndf = 0, ddf = 0, p = 0, log10_p = 0, scaling = 1;
};

// pbkrtest's .KR_adjust(PhiA, Phi, L, beta, 0): the F test of L beta = 0.
KrTest kenward_roger_test(const KrModel& kr, const Eigen::VectorXd& beta, const Eigen::MatrixXd& L);

}  // namespace dtlab::stats::detail

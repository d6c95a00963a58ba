// Satterthwaite's denominator df for linear mixed models, as lmerTest 3.1
// computes them (Kuznetsova, Brockhoff & Christensen 2017, JSS 82(13)):
//   A = 2 H^+ with H the numDeriv Hessian of the deviance in varpar =
//   (theta, sigma) (pseudo-inverse over eigenvalues > 1e-8, with lmerTest's
//   warnings for negative and near-zero eigenvalues); J_k = d vcov(beta) /
//   d varpar_k by numDeriv's Jacobian;
//   t test of L'beta (contest1D): df = 2 (L'VL)^2 / (g' A g), g_k = L' J_k L;
//   F test of L beta = 0 (contestMD): eigen-decompose L V L' = P D P',
//   q = #(d > sqrt(eps) d_1), F = sum (P'L beta)_m^2 / d_m / q, nu_m the t df
//   of row m of P'L, ddf = 2E / (E - q) with E = sum nu_m / (nu_m - 2)
//   (2 when any nu_m <= 2; the common value when all nu agree to 1e-8).
// Never throws; undefined quantities are NaN.
#pragma once
#include <Eigen/Dense>

#include <string>
#include <vector>

#include "analysis/stats/detail/lmm_deviance.h"

namespace dtlab::stats::detail {

struct VarparModel {
  Eigen::VectorXd beta;
  Eigen::MatrixXd vcov;                  // vcov(beta) at the optimum
  Eigen::MatrixXd vcov_varpar;           // 2 H^+
  std::vector<Eigen::MatrixXd> jacobian; // one p x p matrix per variance parameter
  double sigma = 0;
  std::vector<std::string> warnings;     // lmerTest's Hessian warnings
};

// as_lmerModLT(): the Hessian and Jacobian at (theta, sigma); leaves `dev` at theta.
VarparModel varpar_model(LmmDeviance& dev, const std::vector<double>& theta);

struct TTest {
  double estimate = 0, se = 0, df = 0, t = 0, p = 0, log10_p = 0;
};
// contest1D(model, L): estimate, SE, Satterthwaite df, t, two-sided p.
TTest satterthwaite_t(const VarparModel& m, const Eigen::RowVectorXd& L);
// The df alone for a contrast L with variance L V L'.
double satterthwaite_t_df(const Eigen::MatrixXd& vcov_varpar, const std::vector<Eigen::MatrixXd>& jacobian,
                          const Eigen::MatrixXd& vcov, const Eigen::RowVectorXd& L);

struct FTest {
  double sum_sq = 0, mean_sq = 0, num_df = 0, den_df = 0, F = 0, p = 0, log10_p = 0;
};
// contestMD(model, L): the F test of L beta = 0 with Satterthwaite ddf.
FTest satterthwaite_f(const VarparModel& m, const Eigen::MatrixXd& L);

}  // namespace dtlab::stats::detail

// lmerTest's Satterthwaite t and F tests; see satterthwaite.h.
#include "analysis/stats/detail/satterthwaite.h"

#include <cmath>
#include <cstdio>
#include <limits>

#include "analysis/stats/detail/numbers.h"
#include "analysis/stats/detail/numderiv.h"
#include "analysis/stats/distributions.h"

namespace dtlab::stats::detail {
namespace {

std::string eigen_list(const std::vector<double>& values) {
  std::string s;
  for (double v : values) {
    char b[32];
    std::snprintf(b, sizeof b, "%1.1e", v);
    s += (s.empty() ? "" : " ") + std::string(b);
  }
  return s;
}

double qform(const Eigen::RowVectorXd& x, const Eigen::MatrixXd& A) { return (x * A * x.transpose())(0, 0); }

}  // namespace

VarparModel varpar_model(LmmDeviance& dev, const std::vector<double>& theta) {
  VarparModel m;
  dev(theta);
  m.beta = dev.beta();
  m.sigma = dev.sigma();
  m.vcov = m.sigma * m.sigma * dev.unscaled_vcov();
  std::vector<double> varpar = theta;
  varpar.push_back(m.sigma);
  const Eigen::MatrixXd H =
      numderiv_hessian([&](const std::vector<double>& v) { return dev.deviance_vp(v); }, varpar);
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(H);
  const double tol = 1e-8;
  std::vector<double> negative, zero;
  // R lists eigenvalues in decreasing order
  for (Eigen::Index i = eig.eigenvalues().size() - 1; i >= 0; --i) {
    const double e = eig.eigenvalues()(i);
    if (e < -tol) negative.push_back(e);
    if (e > -tol && e < tol) zero.push_back(e);
  }
  if (!negative.empty())
    m.warnings.push_back("Model failed to converge with " + std::to_string(negative.size()) + " negative " +
                         (negative.size() > 1 ? "eigenvalues" : "eigenvalue") + ": " + eigen_list(negative));
  if (!zero.empty())
    m.warnings.push_back("Model may not have converged with " + std::to_string(zero.size()) + " " +
                         (zero.size() > 1 ? "eigenvalues" : "eigenvalue") + " close to zero: " + eigen_list(zero));
  const Eigen::Index k = H.rows();
  Eigen::MatrixXd hinv = Eigen::MatrixXd::Zero(k, k);
  for (Eigen::Index i = 0; i < k; ++i) {
    const double e = eig.eigenvalues()(i);
    if (e > tol) hinv += eig.eigenvectors().col(i) * eig.eigenvectors().col(i).transpose() / e;
  }
  m.vcov_varpar = 2.0 * hinv;
  const Eigen::Index p = m.vcov.rows();
  const Eigen::MatrixXd J = numderiv_jacobian(
      [&](const std::vector<double>& v) {
        const Eigen::MatrixXd c = dev.covbeta(v);
        return Eigen::VectorXd(Eigen::Map<const Eigen::VectorXd>(c.data(), c.size()));
      },
      varpar);
  for (Eigen::Index i = 0; i < J.cols(); ++i)
    m.jacobian.push_back(Eigen::Map<const Eigen::MatrixXd>(J.col(i).data(), p, p));
  dev(theta);
  return m;
}

double satterthwaite_t_df(const Eigen::MatrixXd& vcov_varpar, const std::vector<Eigen::MatrixXd>& jacobian,
                          const Eigen::MatrixXd& vcov, const Eigen::RowVectorXd& L) {
  const double var = qform(L, vcov);
  Eigen::RowVectorXd g(static_cast<Eigen::Index>(jacobian.size()));
  for (size_t k = 0; k < jacobian.size(); ++k) g(static_cast<Eigen::Index>(k)) = qform(L, jacobian[k]);
  return 2.0 * var * var / qform(g, vcov_varpar);
}

TTest satterthwaite_t(const VarparModel& m, const Eigen::RowVectorXd& L) {
  TTest t;
  t.estimate = L.dot(m.beta);
  t.se = std::sqrt(qform(L, m.vcov));
  t.df = satterthwaite_t_df(m.vcov_varpar, m.jacobian, m.vcov, L);
  t.t = t.estimate / t.se;
  const Tail tail = t_two_sided(t.t, t.df);
  t.p = tail.p;
  t.log10_p = tail.log10_p;
  return t;
}

FTest satterthwaite_f(const VarparModel& m, const Eigen::MatrixXd& L) {
  FTest f;
  auto finish = [&](double F, double q, double ddf) {
    f.F = F;
    f.num_df = q;
    f.den_df = ddf;
    f.mean_sq = F * m.sigma * m.sigma;
    f.sum_sq = f.mean_sq * q;
    const Tail tail = f_upper(F, q, ddf);
    f.p = tail.p;
    f.log10_p = tail.log10_p;
    return f;
  };
  if (L.rows() == 1) {
    const TTest t = satterthwaite_t(m, L.row(0));
    return finish(t.t * t.t, 1, t.df);
  }
  const Eigen::MatrixXd VL = L * m.vcov * L.transpose();
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(VL);
  // decreasing order, as R's eigen()
  const Eigen::Index r = VL.rows();
  std::vector<double> d;
  std::vector<Eigen::RowVectorXd> PtL;
  for (Eigen::Index i = r - 1; i >= 0; --i) {
    d.push_back(eig.eigenvalues()(i));
    PtL.push_back(eig.eigenvectors().col(i).transpose() * L);
  }
  const double tol = std::max(std::sqrt(std::numeric_limits<double>::epsilon()) * d[0], 0.0);
  size_t q = 0;
  while (q < d.size() && d[q] > tol) ++q;
  if (q == 0) return finish(kNaN, 0, kNaN);
  if (q == 1) {
    const TTest t = satterthwaite_t(m, PtL[0]);
    return finish(t.t * t.t, 1, t.df);
  }
  double F = 0;
  std::vector<double> nu;
  for (size_t j = 0; j < q; ++j) {
    const double e = PtL[j].dot(m.beta);
    F += e * e / d[j];
    Eigen::RowVectorXd g(static_cast<Eigen::Index>(m.jacobian.size()));
    for (size_t k = 0; k < m.jacobian.size(); ++k) g(static_cast<Eigen::Index>(k)) = qform(PtL[j], m.jacobian[k]);
    nu.push_back(2.0 * d[j] * d[j] / qform(g, m.vcov_varpar));
  }
  F /= static_cast<double>(q);
  // get_Fstat_ddf
  bool equal = true;
  for (size_t j = 1; j < nu.size(); ++j) equal = equal && std::fabs(nu[j] - nu[j - 1]) < 1e-8;
  double ddf;
  if (equal) {
    ddf = 0;
    for (double v : nu) ddf += v;
    ddf /= static_cast<double>(nu.size());
  } else {
    bool small = false;
    double E = 0;
    for (double v : nu) {
      small = small || v <= 2;
      E += v / (v - 2);
    }
    ddf = small ? 2.0 : 2.0 * E / (E - static_cast<double>(q));
  }
  return finish(F, static_cast<double>(q), ddf);
}

}  // namespace dtlab::stats::detail

// Kenward-Roger in the random-effects space; see kenward_roger.h.
#include "analysis/stats/detail/kenward_roger.h"

#include <cmath>
#include <limits>

#include "analysis/stats/distributions.h"

namespace dtlab::stats::detail {
namespace {

constexpr Eigen::Index kMaxQ = 2000;

// One random-effects variance parameter: element (i, j) of term t's covariance.
struct Param {
  int t, i, j;
};

// Products with E_r = I_levels (x) (e_i e_j' + e_j e_i') (or e_i e_i') in term t's rows.
struct Terms {
  std::vector<int> k, nl, offset;
  Eigen::MatrixXd apply(const Param& r, const Eigen::MatrixXd& M) const {
    Eigen::MatrixXd out = Eigen::MatrixXd::Zero(M.rows(), M.cols());
    const int kk = k[static_cast<size_t>(r.t)];
    for (int l = 0; l < nl[static_cast<size_t>(r.t)]; ++l) {
      const int base = offset[static_cast<size_t>(r.t)] + l * kk;
      out.row(base + r.i) += M.row(base + r.j);
      if (r.i != r.j) out.row(base + r.j) += M.row(base + r.i);
    }
    return out;
  }
};

double trace_product(const Eigen::MatrixXd& A, const Eigen::MatrixXd& B) {  // tr(A B)
  return (A.array() * B.transpose().array()).sum();
}

}  // namespace

namespace {

// The products with W = Sigma^-1 = (I - Z C Z') / sigma^2 that vcovAdj needs, in the q space.
struct WProducts {
  Eigen::MatrixXd M, N, M2, K, XW2X, XW3X;  // Z'WZ, Z'WX, Z'W^2Z, Z'W^2X, X'W^2X, X'W^3X
  double trW2 = 0;                          // tr(W^2)
};

// The terms' layout in u and the variance parameters (each element of each term's covariance).
void layout(const LmmDeviance& dev, Terms& tm, std::vector<Param>& params, int& q) {
  q = 0;
  for (size_t t = 0; t < dev.terms().size(); ++t) {
    const int k = static_cast<int>(dev.terms()[t].columns.size());
    tm.k.push_back(k);
    tm.nl.push_back(static_cast<int>(dev.groupings()[static_cast<size_t>(dev.terms()[t].grouping)].levels.size()));
    tm.offset.push_back(q);
    q += k * tm.nl.back();
    for (int j = 0; j < k; ++j)
      for (int i = j; i < k; ++i) params.push_back({static_cast<int>(t), i, j});
  }
}

// Z'Z and Z'X in one pass over the rows (dense: q <= kMaxQ).
void cross_products(const LmmDeviance& dev, const Terms& tm, int q, Eigen::MatrixXd& ZtZ, Eigen::MatrixXd& ZtX) {
  const Eigen::MatrixXd& X = dev.X();
  ZtZ = Eigen::MatrixXd::Zero(q, q);
  ZtX = Eigen::MatrixXd::Zero(q, X.cols());
  std::vector<int> idx;
  std::vector<double> val;
  for (Eigen::Index r = 0; r < X.rows(); ++r) {
    idx.clear();
    val.clear();
    for (size_t t = 0; t < dev.terms().size(); ++t) {
      const int level = dev.groupings()[static_cast<size_t>(dev.terms()[t].grouping)].index[static_cast<size_t>(r)];
      for (int a = 0; a < tm.k[t]; ++a) {
        idx.push_back(tm.offset[t] + level * tm.k[t] + a);
        val.push_back(dev.Zsrc()(r, dev.terms()[t].columns[static_cast<size_t>(a)]));
      }
    }
    for (size_t a = 0; a < idx.size(); ++a) {
      ZtX.row(idx[a]) += val[a] * X.row(r);
      for (size_t b = 0; b < idx.size(); ++b) ZtZ(idx[a], idx[b]) += val[a] * val[b];
    }
  }
}

// C = Lambda (Lambda'Z'Z Lambda + I)^-1 Lambda', then the W-products; false when A is not PD.
bool w_products(const LmmDeviance& dev, const std::vector<double>& theta, const Terms& tm, int q, double sigma,
                WProducts& w) {
  Eigen::MatrixXd ZtZ, ZtX, Lambda = Eigen::MatrixXd::Zero(q, q);
  cross_products(dev, tm, q, ZtZ, ZtX);
  for (size_t t = 0; t < dev.terms().size(); ++t) {
    const Eigen::MatrixXd T = dev.term_factor(t, theta);
    for (int l = 0; l < tm.nl[t]; ++l) Lambda.block(tm.offset[t] + l * tm.k[t], tm.offset[t] + l * tm.k[t], tm.k[t], tm.k[t]) = T;
  }
  Eigen::LLT<Eigen::MatrixXd> llt(Lambda.transpose() * ZtZ * Lambda + Eigen::MatrixXd::Identity(q, q));
  if (llt.info() != Eigen::Success) return false;
  const Eigen::MatrixXd C = Lambda * llt.solve(Lambda.transpose());
  const Eigen::MatrixXd XtX = dev.X().transpose() * dev.X();
  const double s2 = sigma * sigma;
  const Eigen::MatrixXd CH = C * ZtZ, CX = C * ZtX;  // C Z'Z, C Z'X
  w.M = (ZtZ - ZtZ * CH) / s2;
  w.N = (ZtX - ZtZ * CX) / s2;
  w.M2 = (ZtZ - 2 * ZtZ * CH + ZtZ * CH * CH) / (s2 * s2);
  w.K = (ZtX - 2 * ZtZ * CX + ZtZ * CH * CX) / (s2 * s2);
  w.XW2X = (XtX - 2 * ZtX.transpose() * CX + CX.transpose() * ZtZ * CX) / (s2 * s2);
  w.XW3X = (XtX - 3 * ZtX.transpose() * CX + 3 * CX.transpose() * ZtZ * CX - CX.transpose() * ZtZ * CH * CX) /
           (s2 * s2 * s2);
  w.trW2 = (static_cast<double>(dev.X().rows()) - 2 * CH.trace() + trace_product(CH, CH)) / (s2 * s2);
  return true;
}

// 2 IE2^-1 (MASS::ginv where IE2 is nearly singular), made symmetric.
Eigen::MatrixXd twice_inverse(const Eigen::MatrixXd& IE2) {
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(IE2);
  Eigen::MatrixXd W;
  if (eig.eigenvalues().cwiseAbs().minCoeff() > 1e-10) {
    W = 2 * IE2.inverse();
  } else {  // MASS::ginv: singular values above sqrt(eps) times the largest
    Eigen::JacobiSVD<Eigen::MatrixXd> svd(IE2, Eigen::ComputeFullU | Eigen::ComputeFullV);
    const double tol = std::sqrt(std::numeric_limits<double>::epsilon()) * svd.singularValues()(0);
    Eigen::VectorXd inv = svd.singularValues();
    for (Eigen::Index i = 0; i < inv.size(); ++i) inv(i) = inv(i) > tol ? 1 / inv(i) : 0;
    W = 2 * svd.matrixV() * inv.asDiagonal() * svd.matrixU().transpose();
  }
  return (W + W.transpose()) / 2;  // forceSymmetric
}

}  // namespace

KrModel kenward_roger_model(LmmDeviance& dev, const std::vector<double>& theta, const VarparModel& vp) {
  KrModel kr;
  if (!dev.reml()) {
    kr.error = "Kenward-Roger's method is only available for REML model fits";
    return kr;
  }
  Terms tm;
  std::vector<Param> params;
  int q = 0;
  layout(dev, tm, params, q);
  if (q > kMaxQ) {
    kr.error = "Kenward-Roger is formed with dense q x q matrices here; this model has q = " + std::to_string(q) +
               " random effects (at most " + std::to_string(kMaxQ) + ")";
    return kr;
  }
  WProducts w;
  if (!w_products(dev, theta, tm, q, vp.sigma, w)) {
    kr.error = "Lambda'Z'Z Lambda + I is not positive definite";
    return kr;
  }
  const Eigen::MatrixXd& Phi = vp.vcov;
  const Eigen::Index p = Phi.rows();
  const size_t m = params.size() + 1;  // the residual last
  std::vector<Eigen::MatrixXd> EN, EM;  // E_r N, E_r M
  for (const auto& r : params) {
    EN.push_back(tm.apply(r, w.N));
    EM.push_back(tm.apply(r, w.M));
  }
  kr.P.resize(m);
  for (size_t r = 0; r < params.size(); ++r) kr.P[r] = -w.N.transpose() * EN[r];
  kr.P[m - 1] = -w.XW2X;
  auto Q = [&](size_t r, size_t s) -> Eigen::MatrixXd {
    const bool rr = r + 1 == m, ss = s + 1 == m;
    if (!rr && !ss) return EN[r].transpose() * w.M * EN[s];
    if (!rr && ss) return EN[r].transpose() * w.K;
    if (rr && !ss) return w.K.transpose() * EN[s];
    return w.XW3X;
  };
  auto Ktrace = [&](size_t r, size_t s) -> double {
    const bool rr = r + 1 == m, ss = s + 1 == m;
    if (!rr && !ss) return trace_product(EM[r], EM[s]);
    if (rr && ss) return w.trW2;
    return tm.apply(params[rr ? s : r], w.M2).trace();
  };
  Eigen::MatrixXd IE2(m, m);
  std::vector<std::vector<Eigen::MatrixXd>> QQ(m, std::vector<Eigen::MatrixXd>(m));
  for (size_t r = 0; r < m; ++r)
    for (size_t s = r; s < m; ++s) {
      QQ[r][s] = Q(r, s);
      IE2(r, s) = IE2(s, r) = Ktrace(r, s) - 2 * (Phi.array() * QQ[r][s].array()).sum() +
                              ((Phi * kr.P[r]).array() * (kr.P[s] * Phi).array()).sum();
    }
  kr.W = twice_inverse(IE2);
  Eigen::MatrixXd UU = Eigen::MatrixXd::Zero(p, p);
  for (size_t i = 0; i + 1 < m; ++i)
    for (size_t j = i + 1; j < m; ++j) UU += kr.W(i, j) * (QQ[i][j] - kr.P[i] * Phi * kr.P[j]);
  UU = UU + UU.transpose().eval();
  for (size_t i = 0; i < m; ++i) UU += kr.W(i, i) * (QQ[i][i] - kr.P[i] * Phi * kr.P[i]);
  kr.vcov = Phi;
  kr.vcov_adjusted = Phi + 2 * Phi * UU * Phi;
  kr.ok = kr.vcov_adjusted.allFinite();
  if (!kr.ok) kr.error = "the adjusted covariance is not finite";
  return kr;
}

KrTest kenward_roger_test(const KrModel& kr, const Eigen::VectorXd& beta, const Eigen::MatrixXd& L) {
  KrTest out;
  const Eigen::MatrixXd& Phi = kr.vcov;
  const Eigen::MatrixXd Theta = L.transpose() * (L * Phi * L.transpose()).ldlt().solve(L);
  const Eigen::MatrixXd ThetaPhi = Theta * Phi;
  double A1 = 0, A2 = 0;
  const size_t m = kr.P.size();
  std::vector<Eigen::MatrixXd> u(m);
  for (size_t i = 0; i < m; ++i) u[i] = ThetaPhi * kr.P[i] * Phi;
  for (size_t i = 0; i < m; ++i)
    for (size_t j = i; j < m; ++j) {
      const double e = i == j ? 1 : 2;
      A1 += e * kr.W(i, j) * u[i].trace() * u[j].trace();
      A2 += e * kr.W(i, j) * (u[i].array() * u[j].transpose().array()).sum();
    }
  Eigen::FullPivLU<Eigen::MatrixXd> lu(L);
  const double q = static_cast<double>(lu.rank());
  const double B = (A1 + 6 * A2) / (2 * q);
  const double g = ((q + 1) * A1 - (q + 4) * A2) / ((q + 2) * A2);
  const double c1 = g / (3 * q + 2 * (1 - g)), c2 = (q - g) / (3 * q + 2 * (1 - g)),
               c3 = (q + 2 - g) / (3 * q + 2 * (1 - g));
  double V0 = 1 + c1 * B;
  const double V1 = 1 - c2 * B, V2 = 1 - c3 * B;
  if (std::fabs(V0) < 1e-10) V0 = 0;
  const double x = 1 - A2 / q;
  const double ratio = std::fabs(x) < 1e-14 && std::fabs(V1) < 1e-14 ? 1.0 : x / V1;  // .divZero
  const double rho = ratio * ratio * V0 / V2 / q;
  const double df2 = 4 + (q + 2) / (q * rho - 1);
  out.scaling = std::fabs(df2 - 2) < 0.01 ? 1.0 : df2 * (1 - A2 / q) / (df2 - 2);
  const Eigen::VectorXd Lb = L * beta;
  const double wald = Lb.dot((L * kr.vcov_adjusted * L.transpose()).ldlt().solve(Lb));
  out.ndf = q;
  out.ddf = df2;
  out.F_unscaled = wald / q;
  out.F = out.scaling * out.F_unscaled;
  const Tail tail = f_upper(out.F, q, df2);
  out.p = tail.p;
  out.log10_p = tail.log10_p;
  return out;
}

}  // namespace dtlab::stats::detail

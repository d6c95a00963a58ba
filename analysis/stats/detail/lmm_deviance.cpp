// The profiled deviance of a linear mixed model; see lmm_deviance.h.
#include "analysis/stats/detail/lmm_deviance.h"

#include <cmath>
#include <limits>
#include <numbers>
#include <unordered_map>

namespace dtlab::stats::detail {

LmmDeviance::LmmDeviance(Eigen::MatrixXd X, Eigen::MatrixXd Zsrc, Eigen::VectorXd y, std::vector<Grouping> groupings,
                         std::vector<RandomTerm> terms, bool reml)
    : X_(std::move(X)), Zsrc_(std::move(Zsrc)), groupings_(std::move(groupings)), terms_(std::move(terms)), reml_(reml) {
  for (const auto& t : terms_) {
    const int k = static_cast<int>(t.columns.size());
    k_.push_back(k);
    nl_.push_back(static_cast<int>(groupings_[static_cast<size_t>(t.grouping)].levels.size()));
    offset_.push_back(q_);
    theta_offset_.push_back(static_cast<int>(lower_.size()));
    q_ += k * nl_.back();
    for (int j = 0; j < k; ++j)  // column-major lower triangle: (j, j) first in each column
      for (int i = j; i < k; ++i) lower_.push_back(i == j ? 0.0 : -std::numeric_limits<double>::infinity());
  }
  find_pairs();
  set_response(y);
  build_pattern();
}

// Which blocks of Z'Z are nonzero: one hashing pass, remembered per row.
void LmmDeviance::find_pairs() {
  const size_t nt = terms_.size(), n = static_cast<size_t>(X_.rows());
  std::unordered_map<std::uint64_t, size_t> where;
  std::uint64_t max_levels = 1;
  for (int l : nl_) max_levels = std::max<std::uint64_t>(max_levels, static_cast<std::uint64_t>(l));
  row_pairs_.reserve(n * nt * (nt + 1) / 2);
  std::vector<int> level(nt);
  for (size_t r = 0; r < n; ++r) {
    for (size_t t = 0; t < nt; ++t) level[t] = groupings_[static_cast<size_t>(terms_[t].grouping)].index[r];
    for (size_t t1 = 0; t1 < nt; ++t1)
      for (size_t t2 = 0; t2 <= t1; ++t2) {
        const std::uint64_t key =
            ((static_cast<std::uint64_t>(t1) * nt + t2) * max_levels + static_cast<std::uint64_t>(level[t1])) *
                max_levels +
            static_cast<std::uint64_t>(level[t2]);
        auto [it, fresh] = where.try_emplace(key, pairs_.size());
        if (fresh) {
          pairs_.push_back({static_cast<int>(t1), static_cast<int>(t2), level[t1], level[t2], zz_.size(), 0});
          zz_.resize(zz_.size() + static_cast<size_t>(k_[t1] * k_[t2]), 0.0);
        }
        row_pairs_.push_back(static_cast<int>(it->second));
      }
  }
}

void LmmDeviance::set_response(const Eigen::VectorXd& y, const Eigen::VectorXd& sqrt_w, bool fixed) {
  y_ = y;
  sqrt_w_ = sqrt_w;
  const bool weighted = sqrt_w.size() > 0;
  const Eigen::Index n = X_.rows(), p = X_.cols();
  const size_t nt = terms_.size();
  if (!fixed) {
  } else if (weighted) {
    const Eigen::MatrixXd Xw = sqrt_w.asDiagonal() * X_;
    const Eigen::VectorXd yw = sqrt_w.cwiseProduct(y);
    XtX_ = Xw.transpose() * Xw;
    Xty_ = Xw.transpose() * yw;
    yty_ = yw.squaredNorm();
  } else {
    XtX_ = X_.transpose() * X_;
    Xty_ = X_.transpose() * y;
    yty_ = y.squaredNorm();
  }
  ZtX_ = Eigen::MatrixXd::Zero(q_, p);
  Zty_ = Eigen::VectorXd::Zero(q_);
  std::fill(zz_.begin(), zz_.end(), 0.0);
  std::vector<Eigen::VectorXd> z(nt);
  for (size_t t = 0; t < nt; ++t) z[t].resize(k_[t]);
  const int* pr = row_pairs_.data();
  for (Eigen::Index r = 0; r < n; ++r) {
    const double w = weighted ? sqrt_w(r) : 1.0;
    for (size_t t = 0; t < nt; ++t) {
      for (int j = 0; j < k_[t]; ++j) z[t](j) = w * Zsrc_(r, terms_[t].columns[static_cast<size_t>(j)]);
      const int row0 = offset_[t] + groupings_[static_cast<size_t>(terms_[t].grouping)].index[static_cast<size_t>(r)] * k_[t];
      if (fixed) ZtX_.middleRows(row0, k_[t]).noalias() += (w * z[t]) * X_.row(r);
      Zty_.segment(row0, k_[t]) += z[t] * (w * y(r));
    }
    for (size_t t1 = 0; t1 < nt; ++t1)
      for (size_t t2 = 0; t2 <= t1; ++t2) {
        Eigen::Map<Eigen::MatrixXd> B(zz_.data() + pairs_[static_cast<size_t>(*pr++)].b, k_[t1], k_[t2]);
        B.noalias() += z[t1] * z[t2].transpose();
      }
  }
}

// The sparsity pattern of A = Lambda' Z'Z Lambda + I (lower triangle, whole
// blocks: Lambda fills any zero inside a block), analysed once.
void LmmDeviance::build_pattern() {
  std::vector<Eigen::Triplet<double>> triplets;
  for (int i = 0; i < q_; ++i) triplets.emplace_back(i, i, 0.0);
  for (const auto& pr : pairs_) {
    const int r0 = offset_[static_cast<size_t>(pr.t1)] + pr.l1 * k_[static_cast<size_t>(pr.t1)];
    const int c0 = offset_[static_cast<size_t>(pr.t2)] + pr.l2 * k_[static_cast<size_t>(pr.t2)];
    for (int j = 0; j < k_[static_cast<size_t>(pr.t2)]; ++j)
      for (int i = 0; i < k_[static_cast<size_t>(pr.t1)]; ++i)
        if (r0 + i >= c0 + j) triplets.emplace_back(r0 + i, c0 + j, 0.0);
  }
  A_.resize(q_, q_);
  A_.setFromTriplets(triplets.begin(), triplets.end());
  A_.makeCompressed();
  const double* base = A_.valuePtr();
  for (auto& pr : pairs_) {
    pr.idx = value_index_.size();
    const int r0 = offset_[static_cast<size_t>(pr.t1)] + pr.l1 * k_[static_cast<size_t>(pr.t1)];
    const int c0 = offset_[static_cast<size_t>(pr.t2)] + pr.l2 * k_[static_cast<size_t>(pr.t2)];
    for (int j = 0; j < k_[static_cast<size_t>(pr.t2)]; ++j)
      for (int i = 0; i < k_[static_cast<size_t>(pr.t1)]; ++i)
        value_index_.push_back(r0 + i >= c0 + j ? static_cast<int>(&A_.coeffRef(r0 + i, c0 + j) - base) : -1);
  }
  for (int i = 0; i < q_; ++i) diagonal_index_.push_back(static_cast<int>(&A_.coeffRef(i, i) - base));
  llt_.analyzePattern(A_);
}

Eigen::MatrixXd LmmDeviance::term_factor(size_t t, const std::vector<double>& theta) const {
  const int k = k_[t];
  Eigen::MatrixXd T = Eigen::MatrixXd::Zero(k, k);
  size_t m = static_cast<size_t>(theta_offset_[t]);
  for (int j = 0; j < k; ++j)
    for (int i = j; i < k; ++i) T(i, j) = theta[m++];
  return T;
}

void LmmDeviance::set_theta(const std::vector<double>& theta) {
  T_.resize(terms_.size());
  for (size_t t = 0; t < terms_.size(); ++t) T_[t] = term_factor(t, theta);
}

bool LmmDeviance::update(const std::vector<double>& theta, bool fixed) {
  const size_t nt = terms_.size();
  set_theta(theta);
  double* values = A_.valuePtr();
  std::fill(values, values + A_.nonZeros(), 0.0);
  for (const auto& pr : pairs_) {
    const int k1 = k_[static_cast<size_t>(pr.t1)], k2 = k_[static_cast<size_t>(pr.t2)];
    Eigen::Map<const Eigen::MatrixXd> B(zz_.data() + pr.b, k1, k2);
    const Eigen::MatrixXd M = T_[static_cast<size_t>(pr.t1)].transpose() * B * T_[static_cast<size_t>(pr.t2)];
    const int* idx = value_index_.data() + pr.idx;
    for (int j = 0; j < k2; ++j)
      for (int i = 0; i < k1; ++i, ++idx)
        if (*idx >= 0) values[*idx] += M(i, j);
  }
  for (int i : diagonal_index_) values[i] += 1.0;
  llt_.factorize(A_);
  if (llt_.info() != Eigen::Success) return false;
  const auto& Lm = llt_.matrixL().nestedExpression();
  ldL2_ = 0;
  for (int j = 0; j < q_; ++j) ldL2_ += std::log(Lm.valuePtr()[Lm.outerIndexPtr()[j]]);  // diagonal first in column j
  ldL2_ *= 2;
  // Lambda' Z'X and Lambda' Z'y, then R_ZX = L^-1 P Lambda'Z'X, cu = L^-1 P Lambda'Z'y
  Eigen::MatrixXd LZX(q_, X_.cols());
  Eigen::VectorXd LZy(q_);
  for (size_t t = 0; t < nt; ++t)
    for (int l = 0; l < nl_[t]; ++l) {
      const int r0 = offset_[t] + l * k_[t];
      LZX.middleRows(r0, k_[t]).noalias() = T_[t].transpose() * ZtX_.middleRows(r0, k_[t]);
      LZy.segment(r0, k_[t]).noalias() = T_[t].transpose() * Zty_.segment(r0, k_[t]);
    }
  cu_ = llt_.permutationP() * LZy;
  llt_.matrixL().solveInPlace(cu_);
  if (!fixed) return true;
  RZX_ = llt_.permutationP() * LZX;
  llt_.matrixL().solveInPlace(RZX_);
  Eigen::MatrixXd down = XtX_;
  down.noalias() -= RZX_.transpose() * RZX_;
  rx_.compute(down);
  if (rx_.info() != Eigen::Success) return false;
  ldRX2_ = 2.0 * rx_.matrixLLT().diagonal().array().abs().log().sum();
  Eigen::VectorXd cb = rx_.matrixL().solve(Xty_ - RZX_.transpose() * cu_);
  beta_ = rx_.matrixU().solve(cb);
  pwrss_ = yty_ - cu_.squaredNorm() - cb.squaredNorm();
  // Cancellation guard: when r^2 is a small part of y'y, form it from the residuals.
  if (!(pwrss_ > 1e-6 * yty_)) pwrss_ = residual_pwrss();
  return true;
}

Eigen::VectorXd LmmDeviance::u_only() const {
  Eigen::VectorXd v = cu_;
  llt_.matrixU().solveInPlace(v);
  return llt_.permutationPinv() * v;
}

Eigen::VectorXd LmmDeviance::random_part(const Eigen::VectorXd& u) const {
  Eigen::VectorXd out = Eigen::VectorXd::Zero(X_.rows());
  for (size_t t = 0; t < terms_.size(); ++t) {
    const auto& g = groupings_[static_cast<size_t>(terms_[t].grouping)];
    std::vector<Eigen::VectorXd> b(static_cast<size_t>(nl_[t]));
    for (int l = 0; l < nl_[t]; ++l) b[static_cast<size_t>(l)] = T_[t] * u.segment(offset_[t] + l * k_[t], k_[t]);
    for (Eigen::Index i = 0; i < X_.rows(); ++i) {
      const Eigen::VectorXd& bl = b[static_cast<size_t>(g.index[static_cast<size_t>(i)])];
      for (int j = 0; j < k_[t]; ++j) out(i) += Zsrc_(i, terms_[t].columns[static_cast<size_t>(j)]) * bl(j);
    }
  }
  return out;
}

Eigen::VectorXd LmmDeviance::u() const {
  Eigen::VectorXd v = cu_ - RZX_ * beta_;
  llt_.matrixU().solveInPlace(v);
  return llt_.permutationPinv() * v;
}

double LmmDeviance::residual_pwrss() const {
  const Eigen::VectorXd uu = u();
  Eigen::VectorXd r = y_ - X_ * beta_ - random_part(uu);
  if (sqrt_w_.size() > 0) r = r.cwiseProduct(sqrt_w_);
  return r.squaredNorm() + uu.squaredNorm();
}

double LmmDeviance::operator()(const std::vector<double>& theta) {
  if (!update(theta)) return std::numeric_limits<double>::infinity();
  const double n = static_cast<double>(X_.rows());
  const double two_pi = 2.0 * std::numbers::pi;
  if (!reml_) return ldL2_ + n * (1.0 + std::log(two_pi * pwrss_ / n));
  const double nmp = n - static_cast<double>(X_.cols());
  return ldL2_ + ldRX2_ + nmp * (1.0 + std::log(two_pi * pwrss_ / nmp));
}

double LmmDeviance::deviance_vp(const std::vector<double>& varpar) {
  const std::vector<double> theta(varpar.begin(), varpar.end() - 1);
  const double sigma2 = varpar.back() * varpar.back();
  if (!update(theta)) return std::numeric_limits<double>::infinity();
  const double two_pi = 2.0 * std::numbers::pi;
  double dev = ldL2_ + pwrss_ / sigma2 + static_cast<double>(X_.rows()) * std::log(two_pi * sigma2);
  if (reml_) dev += ldRX2_ - static_cast<double>(X_.cols()) * std::log(two_pi * sigma2);
  return dev;
}

Eigen::MatrixXd LmmDeviance::covbeta(const std::vector<double>& varpar) {
  const std::vector<double> theta(varpar.begin(), varpar.end() - 1);
  if (!update(theta))
    return Eigen::MatrixXd::Constant(X_.cols(), X_.cols(), std::numeric_limits<double>::quiet_NaN());
  return varpar.back() * varpar.back() * unscaled_vcov();
}

Eigen::MatrixXd LmmDeviance::unscaled_vcov() const {
  const Eigen::MatrixXd I = Eigen::MatrixXd::Identity(X_.cols(), X_.cols());
  const Eigen::MatrixXd Ri = rx_.matrixU().solve(I);  // R_X^-1
  return Ri * Ri.transpose();
}

double LmmDeviance::sigma() const {
  const double n = static_cast<double>(X_.rows());
  return std::sqrt(pwrss_ / (reml_ ? n - static_cast<double>(X_.cols()) : n));
}

}  // namespace dtlab::stats::detail

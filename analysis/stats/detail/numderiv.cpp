// numDeriv's Richardson derivatives and lme4's deriv12; see numderiv.h.
#include "analysis/stats/detail/numderiv.h"

#include <cmath>
#include <limits>

namespace dtlab::stats::detail {
namespace {

constexpr double kStepFloor = 1e-4;
constexpr int kR = 4;  // Richardson steps (v = 2: each halves h)
const double kZeroTol = std::sqrt(std::numeric_limits<double>::epsilon() / 7e-7);

std::vector<double> initial_steps(const std::vector<double>& x, double d) {
  std::vector<double> h(x.size());
  for (size_t i = 0; i < x.size(); ++i) h[i] = std::fabs(d * x[i]) + kStepFloor * (std::fabs(x[i]) < kZeroTol ? 1.0 : 0.0);
  return h;
}

// numDeriv's in-place Richardson improvement of a[0..r-1] (a[k+1] is the finer step).
template <class T>
T extrapolate(std::vector<T> a) {
  for (int m = 1; m < kR; ++m) {
    const double f = std::pow(4.0, m);
    for (int k = 0; k < kR - m; ++k) a[static_cast<size_t>(k)] = (a[static_cast<size_t>(k) + 1] * f - a[static_cast<size_t>(k)]) / (f - 1.0);
  }
  return a[0];
}

}  // namespace

Eigen::MatrixXd numderiv_hessian(const ScalarFunction& f, const std::vector<double>& x) {
  const size_t n = x.size();
  const double f0 = f(x);
  const std::vector<double> h0 = initial_steps(x, 0.1);
  Eigen::VectorXd hdiag(static_cast<Eigen::Index>(n));
  for (size_t i = 0; i < n; ++i) {
    std::vector<double> h = h0, ha(kR);
    for (int k = 0; k < kR; ++k) {
      std::vector<double> xp = x, xm = x;
      xp[i] = x[i] + h[i];
      xm[i] = x[i] - h[i];
      ha[static_cast<size_t>(k)] = (f(xp) - 2 * f0 + f(xm)) / (h[i] * h[i]);
      for (auto& v : h) v /= 2;
    }
    hdiag(static_cast<Eigen::Index>(i)) = extrapolate(ha);
  }
  Eigen::MatrixXd H(n, n);
  for (size_t i = 0; i < n; ++i)
    for (size_t j = 0; j <= i; ++j) {
      if (i == j) {
        H(i, i) = hdiag(static_cast<Eigen::Index>(i));
        continue;
      }
      std::vector<double> h = h0, da(kR);
      for (int k = 0; k < kR; ++k) {
        std::vector<double> xp = x, xm = x;
        xp[i] = x[i] + h[i];
        xp[j] = x[j] + h[j];
        xm[i] = x[i] - h[i];
        xm[j] = x[j] - h[j];
        da[static_cast<size_t>(k)] = (f(xp) - 2 * f0 + f(xm) - hdiag(static_cast<Eigen::Index>(i)) * h[i] * h[i] -
                                      hdiag(static_cast<Eigen::Index>(j)) * h[j] * h[j]) /
                                     (2 * h[i] * h[j]);
        for (auto& v : h) v /= 2;
      }
      H(i, j) = H(j, i) = extrapolate(da);
    }
  return H;
}

Eigen::MatrixXd numderiv_jacobian(const VectorFunction& f, const std::vector<double>& x) {
  const size_t n = x.size();
  std::vector<double> h = initial_steps(x, 1e-4);
  std::vector<std::vector<Eigen::VectorXd>> a(n, std::vector<Eigen::VectorXd>(kR));
  for (int k = 0; k < kR; ++k) {
    for (size_t i = 0; i < n; ++i) {
      std::vector<double> xp = x, xm = x;
      xp[i] = x[i] + h[i];
      xm[i] = x[i] - h[i];
      a[i][static_cast<size_t>(k)] = (f(xp) - f(xm)) / (2 * h[i]);
    }
    for (auto& v : h) v /= 2;
  }
  Eigen::MatrixXd J;
  for (size_t i = 0; i < n; ++i) {
    const Eigen::VectorXd col = extrapolate(a[i]);
    if (J.size() == 0) J.resize(col.size(), static_cast<Eigen::Index>(n));
    J.col(static_cast<Eigen::Index>(i)) = col;
  }
  return J;
}

Derivatives lme4_deriv12(const ScalarFunction& f, const std::vector<double>& x) {
  const double delta = 1e-4;
  const size_t n = x.size();
  const double fx = f(x);
  Derivatives d{Eigen::VectorXd(static_cast<Eigen::Index>(n)), Eigen::MatrixXd(n, n)};
  auto at = [&](size_t i, double di, size_t j, double dj) {
    std::vector<double> y = x;
    y[i] = x[i] + di;
    y[j] = x[j] + dj;
    return f(y);
  };
  for (size_t j = 0; j < n; ++j) {
    std::vector<double> xa = x, xs = x;
    xa[j] = x[j] + delta;
    xs[j] = x[j] - delta;
    const double fadd = f(xa), fsub = f(xs);
    d.hessian(j, j) = fadd / (delta * delta) - 2 * fx / (delta * delta) + fsub / (delta * delta);
    d.gradient(static_cast<Eigen::Index>(j)) = (fadd - fsub) / (delta + delta);
    for (size_t i = 0; i < j; ++i) {
      const double s = (delta + delta) * (delta + delta);
      d.hessian(i, j) = d.hessian(j, i) = at(i, delta, j, delta) / s - at(i, delta, j, -delta) / s -
                                          at(i, -delta, j, delta) / s + at(i, -delta, j, -delta) / s;
    }
  }
  return d;
}

}  // namespace dtlab::stats::detail

// Numerical derivatives exactly as R's numDeriv 2016.8 computes them, so
// quantities built on them (lmerTest's Satterthwaite df: the Hessian of the
// deviance in the variance parameters and the Jacobian of vcov(beta)) equal
// lmerTest's to the rounding of the function values: Richardson
// extrapolation of central differences (r = 4 halvings, v = 2), steps
// h = |d x| + eps (|x| < zero.tol) with eps = 1e-4, zero.tol =
// sqrt(.Machine$double.eps / 7e-7); hessian() uses genD with d = 0.1,
// jacobian() d = 1e-4. Also lme4's deriv12 (plain central differences,
// delta = 1e-4) for its convergence checks. Never evaluates outside x +- h.
#pragma once
#include <Eigen/Dense>

#include <functional>
#include <vector>

namespace dtlab::stats::detail {

using ScalarFunction = std::function<double(const std::vector<double>&)>;
using VectorFunction = std::function<Eigen::VectorXd(const std::vector<double>&)>;

// numDeriv::hessian(func, x) (method "Richardson", through genD).
Eigen::MatrixXd numderiv_hessian(const ScalarFunction& f, const std::vector<double>& x);

// numDeriv::jacobian(func, x) (method "Richardson"): rows = outputs, columns = x.
Eigen::MatrixXd numderiv_jacobian(const VectorFunction& f, const std::vector<double>& x);

struct Derivatives {
  Eigen::VectorXd gradient;
  Eigen::MatrixXd hessian;
};

// lme4's deriv12(fun, x, delta = 1e-4) without bounds (as optwrap calls it).
Derivatives lme4_deriv12(const ScalarFunction& f, const std::vector<double>& x);

}  // namespace dtlab::stats::detail

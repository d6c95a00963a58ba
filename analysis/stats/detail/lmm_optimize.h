// lme4 1.1's optimisation of a mixed model's criterion, step for step:
// optwrap(nloptwrap) is NLopt's BOBYQA with nloptr's options as lme4 passes
// them (xtol_abs = ftol_abs = 1e-8, xtol_rel = 1e-4, maxeval = 1e5, lower
// bounds 0 on the diagonals of T, no upper bounds, NLopt's default initial
// step), followed by deriv12 at the optimum; optimizeLmer adds restart_edge
// (restart when the deviance falls off a boundary) and check.boundary
// (parameters within 1e-5 of their bound are set onto it when that lowers
// the deviance); checkConv gives lme4's singular-fit message and its
// gradient / Hessian warnings with lme4's wording.
// Same library (NLopt 2.7.1, Debian libnlopt0, which R's nloptr links), same
// settings and start: the same path as lme4 up to rounding of the criterion.
// Never throws; an NLopt failure becomes lme4's "convergence code" warning.
#pragma once
#include <string>
#include <vector>

#include "analysis/stats/detail/numderiv.h"

namespace dtlab::stats::detail {

struct Optimum {
  std::vector<double> par;
  double fval = 0;
  int status = 0;          // NLopt's result code
  int evaluations = 0;     // criterion evaluations by the optimiser
  Derivatives derivs;      // deriv12 at par (before check.boundary)
  std::vector<std::string> warnings;  // "convergence code N from nloptwrap: ..."
};

// optwrap("nloptwrap", f, start, lower) with calc.derivs = TRUE.
Optimum nloptwrap(const ScalarFunction& f, const std::vector<double>& start, const std::vector<double>& lower);

// optimizeLmer(): nloptwrap, restart_edge, check.boundary(boundary.tol = 1e-5).
Optimum optimize_lmer(const ScalarFunction& f, const std::vector<double>& start, const std::vector<double>& lower);

struct ConvergenceCheck {
  bool singular = false;               // some diagonal theta < 1e-4 (isSingular)
  std::vector<std::string> messages;   // "boundary (singular) fit: see help('isSingular')"
  std::vector<std::string> warnings;   // gradient and Hessian warnings
};

// lme4's checkConv(derivs, par, lmerControl()$checkConv, lower).
ConvergenceCheck check_convergence(const Derivatives& derivs, const std::vector<double>& par,
                                   const std::vector<double>& lower);

}  // namespace dtlab::stats::detail

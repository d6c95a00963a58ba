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

// NLopt BOBYQA settings; the defaults are nloptwrap's as lme4 passes them.
struct BobyqaSettings {
  double xtol_abs = 1e-8, ftol_abs = 1e-8, xtol_rel = 1e-4, ftol_rel = 0;
  int maxeval = 100000;
  std::vector<double> initial_step;  // empty: NLopt's default
};

// BOBYQA with `settings`, then deriv12 at the optimum (optwrap with calc.derivs = TRUE).
Optimum bobyqa(const ScalarFunction& f, const std::vector<double>& start, const std::vector<double>& lower,
               const BobyqaSettings& settings);

// optwrap("nloptwrap", f, start, lower) with calc.derivs = TRUE.
Optimum nloptwrap(const ScalarFunction& f, const std::vector<double>& start, const std::vector<double>& lower);

// check.boundary(rho, opt, devfun, boundary.tol = 1e-5): parameters within 1e-5
// above a finite lower bound are set onto it when that does not raise f.
void check_boundary(const ScalarFunction& f, const std::vector<double>& lower, Optimum& o);

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

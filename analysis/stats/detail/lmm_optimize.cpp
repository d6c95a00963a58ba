// lme4's optimisation steps around NLopt's BOBYQA; see lmm_optimize.h.
#include "analysis/stats/detail/lmm_optimize.h"

#include <nlopt.hpp>

#include <cmath>
#include <cstdio>
#include <limits>

namespace dtlab::stats::detail {
namespace {

// nloptr's message for a result code (as lme4 appends it to its warning).
std::string nloptr_message(int status) {
  switch (status) {
    case 5: return "NLOPT_MAXEVAL_REACHED: Optimization stopped because maxeval (above) was reached.";
    case 6: return "NLOPT_MAXTIME_REACHED: Optimization stopped because maxtime (above) was reached.";
    case -1: return "NLOPT_FAILURE: Generic failure code.";
    case -2: return "NLOPT_INVALID_ARGS: Invalid arguments (e.g. lower bounds are bigger than upper bounds, an unknown algorithm was specified, etcetera).";
    case -3: return "NLOPT_OUT_OF_MEMORY: Ran out of memory.";
    case -4:
      return "NLOPT_ROUNDOFF_LIMITED: Roundoff errors led to a breakdown of the optimization algorithm. In this case, "
             "the returned minimum may still be useful. (e.g. this error occurs in NEWUOA if one tries to achieve a "
             "tolerance too close to machine precision.)";
    default: return "NLOPT_FAILURE: Generic failure code.";
  }
}

struct Counted {
  const ScalarFunction* f;
  int evaluations = 0;
};

double objective(unsigned n, const double* x, double* /*grad*/, void* data) {
  auto* c = static_cast<Counted*>(data);
  ++c->evaluations;
  const double v = (*c->f)(std::vector<double>(x, x + n));
  return std::isnan(v) ? std::numeric_limits<double>::infinity() : v;
}

std::string format_g(double v) {
  char b[64];
  std::snprintf(b, sizeof b, "%g", v);
  return b;
}

}  // namespace

Optimum nloptwrap(const ScalarFunction& f, const std::vector<double>& start, const std::vector<double>& lower) {
  return bobyqa(f, start, lower, BobyqaSettings{});
}

Optimum bobyqa(const ScalarFunction& f, const std::vector<double>& start, const std::vector<double>& lower,
               const BobyqaSettings& settings) {
  const unsigned n = static_cast<unsigned>(start.size());
  Optimum o;
  o.par = start;
  Counted counted{&f};
  nlopt::opt opt(nlopt::LN_BOBYQA, n);
  opt.set_lower_bounds(lower);
  opt.set_upper_bounds(std::vector<double>(n, std::numeric_limits<double>::infinity()));
  opt.set_xtol_abs(settings.xtol_abs);
  opt.set_ftol_abs(settings.ftol_abs);
  opt.set_xtol_rel(settings.xtol_rel);
  if (settings.ftol_rel > 0) opt.set_ftol_rel(settings.ftol_rel);
  opt.set_maxeval(settings.maxeval);
  if (!settings.initial_step.empty()) opt.set_initial_step(settings.initial_step);
  opt.set_min_objective(objective, &counted);
  try {
    o.status = static_cast<int>(opt.optimize(o.par, o.fval));
  } catch (const nlopt::roundoff_limited&) {
    o.status = -4;
  } catch (const nlopt::forced_stop&) {
    o.status = -5;
  } catch (const std::invalid_argument&) {
    o.status = -2;
  } catch (const std::bad_alloc&) {
    o.status = -3;
  } catch (const std::runtime_error&) {
    o.status = -1;
  }
  if (o.status < 0) o.fval = f(o.par);
  o.evaluations = counted.evaluations;
  if (o.status < 0 || o.status == 5)
    o.warnings.push_back("convergence code " + std::to_string(o.status) + " from nloptwrap: " + nloptr_message(o.status));
  o.derivs = lme4_deriv12(f, o.par);
  return o;
}

Optimum optimize_lmer(const ScalarFunction& f, const std::vector<double>& start, const std::vector<double>& lower) {
  Optimum o = nloptwrap(f, start, lower);
  // restart_edge: a parameter exactly on its bound whose one-sided slope is negative
  std::vector<size_t> on_bound;
  for (size_t i = 0; i < o.par.size(); ++i)
    if (o.par[i] == lower[i]) on_bound.push_back(i);
  if (!on_bound.empty()) {
    const double d0 = f(o.par);
    bool restart = false;
    for (size_t i : on_bound) {
      std::vector<double> t = o.par;
      t[i] = lower[i] + 1e-5;
      restart = restart || (f(t) - d0) / 1e-5 < 0;
    }
    if (restart) {
      std::vector<std::string> earlier = o.warnings;
      o = nloptwrap(f, o.par, lower);
      earlier.insert(earlier.end(), o.warnings.begin(), o.warnings.end());
      o.warnings = earlier;
    }
  }
  check_boundary(f, lower, o);
  return o;
}

void check_boundary(const ScalarFunction& f, const std::vector<double>& lower, Optimum& o) {
  bool edge = false;
  std::vector<double> pp = o.par;
  for (size_t i = 0; i < o.par.size(); ++i) {
    const double bdiff = o.par[i] - lower[i];
    if (0 < bdiff && bdiff < 1e-5) {
      edge = true;
      std::vector<double> t = pp;
      t[i] = lower[i];
      if (f(t) < o.fval) pp[i] = t[i];
    }
  }
  if (edge) {
    o.par = pp;
    o.fval = f(o.par);
  }
}

ConvergenceCheck check_convergence(const Derivatives& derivs, const std::vector<double>& par,
                                   const std::vector<double>& lower) {
  ConvergenceCheck c;
  for (size_t i = 0; i < par.size(); ++i)
    if (lower[i] == 0 && par[i] < 1e-4) c.singular = true;
  if (c.singular) {
    c.messages.push_back("boundary (singular) fit: see help('isSingular')");
    return c;
  }
  const Eigen::VectorXd& g = derivs.gradient;
  if (!g.allFinite()) {
    c.warnings.push_back("Gradient contains NAs");
    return c;
  }
  const Eigen::MatrixXd& H = derivs.hessian;
  Eigen::LLT<Eigen::MatrixXd> chol(H);
  if (chol.info() != Eigen::Success) {
    c.warnings.push_back("unable to evaluate scaled gradient");
  } else {
    const Eigen::VectorXd scaled = chol.matrixU().solve(g);  // solve(chol(H), g)
    double worst = 0;
    for (Eigen::Index i = 0; i < g.size(); ++i) worst = std::max(worst, std::min(std::fabs(scaled(i)), std::fabs(g(i))));
    if (worst > 0.002)
      c.warnings.push_back("Model failed to converge with max|grad| = " + format_g(worst) +
                           " (tol = 0.002, component 1)");
  }
  // checkHess(H, tol = 1e-6)
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(H, Eigen::EigenvaluesOnly);
  if (eig.info() != Eigen::Success || !H.allFinite()) {
    c.warnings.push_back("Problem with Hessian check (infinite or missing values?)");
    return c;
  }
  const Eigen::VectorXd ev = eig.eigenvalues();
  const double tol = 1e-6;
  int negative = 0, zero = 0;
  for (Eigen::Index i = 0; i < ev.size(); ++i) {
    negative += ev(i) < -tol;
    zero += std::fabs(ev(i)) < tol;
  }
  if (negative > 0) {
    c.warnings.push_back("Model failed to converge: degenerate  Hessian with " + std::to_string(negative) +
                         " negative eigenvalues");
  } else if (zero > 0 || chol.info() != Eigen::Success) {
    c.warnings.push_back(" Hessian is numerically singular: parameters are not uniquely determined");
  } else {
    if (ev.maxCoeff() * tol > 1) c.warnings.push_back("Model is nearly unidentifiable: very large eigenvalue\n - Rescale variables?");
    if (ev.minCoeff() / ev.maxCoeff() < tol)
      c.warnings.push_back("Model is nearly unidentifiable: large eigenvalue ratio\n - Rescale variables?");
  }
  return c;
}

}  // namespace dtlab::stats::detail

// The binomial GLMM by the Laplace approximation; see glmm.h.
#include "analysis/stats/detail/glmm.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

#include "analysis/stats/detail/lmm_fit.h"
#include "analysis/stats/distributions.h"

namespace dtlab::stats::detail {
namespace {

constexpr double kEps = std::numeric_limits<double>::epsilon();
constexpr int kMaxIterations = 100, kMaxHalvings = 20;

double linkinv(double eta) { return std::clamp(1.0 / (1.0 + std::exp(-eta)), kEps, 1.0 - kEps); }
double mu_eta(double eta) {
  const double e = std::exp(-std::fabs(eta));
  return std::max(kEps, e / ((1 + e) * (1 + e)));
}

}  // namespace

BinomialLaplace::BinomialLaplace(const Eigen::MatrixXd& X, const Eigen::MatrixXd& Zsrc, const Eigen::VectorXd& y,
                                 const std::vector<Grouping>& groupings, const std::vector<RandomTerm>& terms)
    : X_(X), y_(y), sys_(X, Zsrc, y, groupings, terms, false) {
  // glm's binomial initialize: mustart = (y + 0.5) / 2, eta = logit(mustart)
  eta_start_ = y_.unaryExpr([](double v) { return std::log((v + 0.5) / (1.5 - v)); });
}

double BinomialLaplace::aic(const Eigen::VectorXd& mu) const {
  double s = 0;
  for (Eigen::Index i = 0; i < mu.size(); ++i) s += std::log(y_(i) > 0.5 ? mu(i) : 1.0 - mu(i));
  return -2.0 * s;
}

double BinomialLaplace::penalised_deviance(const Eigen::VectorXd& eta, const Eigen::VectorXd& u) const {
  return aic(eta.unaryExpr([](double e) { return linkinv(e); })) + u.squaredNorm();
}

void BinomialLaplace::set_working(const Eigen::VectorXd& eta, const Eigen::VectorXd& offset, bool fixed) {
  const Eigen::Index n = y_.size();
  Eigen::VectorXd sqrt_w(n), z(n);
  for (Eigen::Index i = 0; i < n; ++i) {
    const double mu = linkinv(eta(i)), me = mu_eta(eta(i));
    sqrt_w(i) = me / std::sqrt(mu * (1 - mu));
    z(i) = eta(i) - offset(i) + (y_(i) - mu) / me;
  }
  sys_.set_response(z, sqrt_w, fixed);
}

// One Gauss-Newton step from `it` (the weights at it.eta already set), halved while the
// penalised deviance rises beyond its rounding noise (a rise of a few ulps near the mode
// must not freeze u short of it). False with failure_ set when it cannot be taken.
bool BinomialLaplace::step(bool with_beta, const Eigen::VectorXd& offset, const Iterate* from, Iterate& to) {
  to.u = with_beta ? sys_.u() : sys_.u_only();
  to.beta = with_beta ? sys_.beta() : (from ? from->beta : Eigen::VectorXd::Zero(X_.cols()));
  auto finish = [&] {
    to.eta = offset + sys_.random_part(to.u);
    if (with_beta) to.eta += X_ * to.beta;
    to.pdev = penalised_deviance(to.eta, to.u);
  };
  finish();
  for (int k = 0; k < kMaxHalvings && from && (std::isnan(to.pdev) || to.pdev > from->pdev + 1e-11 * std::fabs(from->pdev)); ++k) {
    to.u = (from->u + to.u) / 2;
    if (with_beta) to.beta = (from->beta + to.beta) / 2;
    finish();
  }
  if (std::isnan(to.pdev)) failure_ = "PIRLS loop resulted in NaN value";
  else if (from && to.pdev - from->pdev > 1e-7)
    failure_ = "(maxstephalfit) PIRLS step-halvings failed to reduce deviance in pwrssUpdate";
  else return true;
  return false;
}

// lme4's pwrssUpdate: Gauss-Newton steps for u (and beta) with step halving,
// run until the step is at rounding level (lme4 stops at a relative change of
// the penalised deviance of tolPwrss = 1e-7, which leaves u off the mode by
// ~1e-3 and noise of about 1e-5 in its criterion).
double BinomialLaplace::pirls(const std::vector<double>& theta, bool with_beta, const Eigen::VectorXd& offset) {
  constexpr double kInf = std::numeric_limits<double>::infinity();
  sys_.set_theta(theta);
  std::optional<Iterate> it;  // the current iterate (none before the first step)
  Eigen::VectorXd eta0 = with_beta ? eta_start_ : offset;
  // stage 2 starts from the last mode (it converges to rounding level from anywhere)
  if (!with_beta && static_cast<size_t>(u_.size()) == sys_.q()) {
    it = Iterate{u_, Eigen::VectorXd::Zero(X_.cols()), offset + sys_.random_part(u_), 0};
    it->pdev = penalised_deviance(it->eta, it->u);
  }
  bool converged = false;
  int flat = 0, done = 0;
  double change = kInf;
  for (; done < kMaxIterations && !converged; ++done) {
    set_working(it ? it->eta : eta0, offset, with_beta);
    if (!sys_.update(theta, with_beta)) {
      // X'WX has lost rank to rounding: weights near 0 where mu is clamped (separation). Keep
      // the last iterate as the mode; lme4 stops with "Downdated VtV is not positive definite".
      if (it) break;
      failure_ = "PIRLS: the penalised weighted least-squares system is not positive definite";
      return kInf;
    }
    Iterate next;
    if (!step(with_beta, offset, it ? &*it : nullptr, next)) return kInf;
    double size = 1, moved = 0;
    if (it) {
      change = std::fabs((it->pdev - next.pdev) / next.pdev);
      moved = (next.u - it->u).cwiseAbs().maxCoeff();
      size += it->u.cwiseAbs().maxCoeff();
      if (with_beta) {
        moved = std::max(moved, (next.beta - it->beta).cwiseAbs().maxCoeff());
        size += it->beta.cwiseAbs().maxCoeff();
      }
      // a large step that lowers nothing: the criterion is flat along it (mu clamped at 0 or 1,
      // separation); keep the previous iterate, as glm.fit stops once the deviance stops changing
      if (next.pdev >= it->pdev && moved > 1e-4 * size) break;
      flat = change < 1e-15 ? flat + 1 : 0;
      converged = moved <= 1e-12 * size || flat >= 3;
    }
    it = std::move(next);
  }
  if (!converged && done >= kMaxIterations && !(change < 1e-7)) {  // lme4's tolPwrss
    failure_ = "pwrssUpdate did not converge in (maxit) iterations";
    return kInf;
  }
  set_working(it->eta, offset, false);  // log|L|^2 with the weights at the mode
  if (!sys_.update(theta, false)) return kInf;
  u_ = it->u;
  if (with_beta) beta_ = it->beta;
  return sys_.ldL2() + it->u.squaredNorm() + aic(it->eta.unaryExpr([](double e) { return linkinv(e); }));
}

double BinomialLaplace::stage1(const std::vector<double>& theta) {
  return pirls(theta, true, Eigen::VectorXd::Zero(y_.size()));
}

double BinomialLaplace::laplace(const std::vector<double>& par) {
  const size_t nt = n_theta();
  const std::vector<double> theta(par.begin(), par.begin() + static_cast<std::ptrdiff_t>(nt));
  Eigen::VectorXd beta(X_.cols());
  for (Eigen::Index j = 0; j < beta.size(); ++j) beta(j) = par[nt + static_cast<size_t>(j)];
  beta_ = beta;
  return pirls(theta, false, X_ * beta);
}

std::vector<double> BinomialFit::theta() const {
  return std::vector<double>(opt.par.begin(), opt.par.begin() + static_cast<std::ptrdiff_t>(model->n_theta()));
}

BinomialFit fit_binomial(const PreparedModel& m, const Eigen::MatrixXd& X, const std::vector<FormulaTerm>& terms) {
  BinomialFit f;
  f.formula_terms = terms;
  f.model = std::make_unique<BinomialLaplace>(X, m.design.X, m.y, m.groupings, expand_terms(terms, m.groupings));
  BinomialLaplace& g = *f.model;
  const std::vector<double> lower = g.theta_lower();
  // stage 1 (nAGQ = 0), from theta = 1 on the diagonals; minqa's rhobeg 0.2, rhoend 2e-7
  std::vector<double> theta0;
  for (double lo : lower) theta0.push_back(std::isfinite(lo) ? 1.0 : 0.0);
  BobyqaSettings s1;
  s1.xtol_abs = 0;
  s1.ftol_abs = 0;
  s1.xtol_rel = 1e-6;
  s1.initial_step.assign(theta0.size(), 0.2);
  const ScalarFunction stage1 = [&g](const std::vector<double>& t) { return g.stage1(t); };
  const Optimum o1 = bobyqa(stage1, theta0, lower, s1);
  g.stage1(o1.par);
  // stage 2 (nAGQ = 1): (theta, beta) from stage 1, steps as glmer's Nelder-Mead (0.2 x (0.1, min(SD(beta), 10)))
  std::vector<double> start = o1.par, lower2 = lower, step(lower.size(), 0.02);
  const Eigen::VectorXd beta1 = g.beta();
  Eigen::MatrixXd unsc = g.system().unscaled_vcov();
  for (Eigen::Index j = 0; j < beta1.size(); ++j) {
    start.push_back(beta1(j));
    lower2.push_back(-std::numeric_limits<double>::infinity());
    const double sd = std::sqrt(unsc(j, j));
    step.push_back(0.2 * (std::isfinite(sd) && sd > 0 ? std::min(sd, 10.0) : 1.0));
  }
  BobyqaSettings s2;
  s2.xtol_abs = 0;
  s2.ftol_abs = 0;
  s2.xtol_rel = 1e-12;
  s2.ftol_rel = 1e-14;  // stops on a flat criterion too (separation: estimates drift while nothing changes)
  s2.initial_step = step;
  const ScalarFunction laplace = [&g](const std::vector<double>& par) { return g.laplace(par); };
  f.opt = bobyqa(laplace, start, lower2, s2);
  if (f.opt.status == -4) f.opt.warnings.clear();  // stopped by rounding: at the optimum to the last bits
  check_boundary(laplace, lower2, f.opt);
  f.opt.fval = g.laplace(f.opt.par);
  f.conv = check_convergence(f.opt.derivs, f.opt.par, lower2);
  if (g.failed()) f.warnings.push_back(g.failure());
  for (size_t j = lower.size(); j < f.opt.par.size(); ++j)
    if (std::fabs(f.opt.par[j]) > 10) {
      f.warnings.push_back("an estimate exceeds 10 on the logit scale: fitted probabilities of 0 or 1 (complete "
                           "separation?); its SE, test and the likelihood-ratio test are not meaningful (dtlab)");
      break;
    }
  return f;
}

std::vector<std::vector<double>> column_variances(const BinomialFit& f) {
  std::vector<std::vector<double>> out;
  const LmmDeviance& sys = f.model->system();
  for (size_t t = 0; t < sys.terms().size(); ++t) {
    const Eigen::MatrixXd T = sys.term_factor(t, f.theta());
    const Eigen::MatrixXd S = T * T.transpose();
    out.emplace_back(S.diagonal().data(), S.diagonal().data() + S.rows());
  }
  return out;
}

namespace {

// vcov.merMod for a GLMM: 2 (H^-1)[beta, beta] from deriv12's Hessian, or
// from R_X with lme4's warning when that is not positive definite.
Eigen::MatrixXd glmm_vcov(BinomialFit& f, std::vector<std::string>& warnings) {
  const size_t nt = f.model->n_theta();
  const Eigen::Index p = static_cast<Eigen::Index>(f.model->p());
  const Eigen::MatrixXd& H = f.opt.derivs.hessian;
  Eigen::MatrixXd V = Eigen::MatrixXd::Constant(p, p, std::numeric_limits<double>::quiet_NaN());
  Eigen::FullPivLU<Eigen::MatrixXd> lu(H);
  bool bad = !H.allFinite() || !lu.isInvertible();
  if (!bad) {
    const Eigen::MatrixXd Hi = lu.inverse();
    const Eigen::MatrixXd B = Hi.block(static_cast<Eigen::Index>(nt), static_cast<Eigen::Index>(nt), p, p);
    V = B + B.transpose();
    Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(V, Eigen::EigenvaluesOnly);
    bad = !V.allFinite() || eig.eigenvalues().minCoeff() <= 0;
  }
  if (!bad) return V;
  warnings.push_back(
      "variance-covariance matrix computed from finite-difference Hessian is\nnot positive definite or contains NA "
      "values: falling back to var-cov estimated from RX");
  LmmDeviance& sys = f.model->system();
  sys.update(f.theta(), true);
  return sys.unscaled_vcov();
}

}  // namespace

LmmFit report_binomial(const PreparedModel& m, BinomialFit& f, const LmmOptions& o) {
  LmmFit r;
  describe_model(r, m, f.formula_terms, o);
  const std::vector<double> theta = f.theta();
  const size_t nt = theta.size();
  const Eigen::Index p = static_cast<Eigen::Index>(f.model->p());
  r.theta = theta;
  r.sigma = 1;
  r.beta.resize(p);
  for (Eigen::Index j = 0; j < p; ++j) r.beta(j) = f.opt.par[nt + static_cast<size_t>(j)];
  r.singular = f.conv.singular;
  r.messages = f.conv.messages;
  r.warnings = f.opt.warnings;
  r.warnings.insert(r.warnings.end(), f.conv.warnings.begin(), f.conv.warnings.end());
  r.warnings.insert(r.warnings.end(), f.warnings.begin(), f.warnings.end());
  f.model->laplace(f.opt.par);  // the state at the optimum
  r.vcov = glmm_vcov(f, r.warnings);
  r.vcov_unadjusted = r.vcov;
  for (Eigen::Index j = 0; j < p; ++j) {
    const double est = r.beta(j), se = std::sqrt(r.vcov(j, j));
    const Tail tail = normal_two_sided(est / se);
    r.coefficients.push_back({m.design.column_names[static_cast<size_t>(j)], est, se,
                              std::numeric_limits<double>::infinity(), est / se, tail.p, tail.log10_p});
  }
  add_variances(r, m, f.formula_terms, f.model->system(), theta, 1.0);
  const double crit = f.opt.fval;
  r.df = static_cast<int>(static_cast<size_t>(p) + nt);
  r.reml_criterion = std::numeric_limits<double>::quiet_NaN();
  r.deviance = crit;
  r.loglik = -crit / 2;
  r.aic = crit + 2.0 * r.df;
  r.bic = crit + std::log(static_cast<double>(r.n)) * r.df;
  for (const auto& term : m.design.terms) {
    BinomialFit reduced = fit_binomial(m, drop_term(m.design, term), f.formula_terms);
    LmmLrtRow row;
    row.term = term.name;
    row.df = static_cast<double>(term.columns.size());
    row.deviance_full = crit;
    row.deviance_reduced = reduced.opt.fval;
    row.chisq = std::max(0.0, row.deviance_reduced - crit);
    const Tail tail = chi_squared_upper(row.chisq, row.df);
    row.p = tail.p;
    row.log10_p = tail.log10_p;
    row.warnings = reduced.conv.messages;
    row.warnings.insert(row.warnings.end(), reduced.conv.warnings.begin(), reduced.conv.warnings.end());
    r.lrt.push_back(row);
  }
  return r;
}

}  // namespace dtlab::stats::detail

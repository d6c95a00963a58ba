// One lmer() fit and its report; see lmm_fit.h.
#include "analysis/stats/detail/lmm_fit.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "analysis/stats/detail/kenward_roger.h"
#include "analysis/stats/detail/satterthwaite.h"
#include "analysis/stats/distributions.h"

namespace dtlab::stats::detail {
namespace {

// R's mean(): long double sum, then the mean of the residuals added.
long double r_mean(const std::vector<double>& x) {
  long double s = 0;
  for (double v : x) s += v;
  s /= static_cast<long double>(x.size());
  long double t = 0;
  for (double v : x) t += v - s;
  return s + t / static_cast<long double>(x.size());
}

// R's var() of one vector: two passes in long double, n - 1 in the denominator.
double r_var(const std::vector<double>& x) {
  const long double m = r_mean(x);
  long double s = 0;
  for (double v : x) s += (v - m) * (v - m);
  return static_cast<double>(s / static_cast<long double>(x.size() - 1));
}

// mkLmerDevfun's start: for scalar intercept terms of distinct grouping
// factors, theta = sqrt(var(ave(y, f)) / (var(y) - sum of those)) when that
// is positive; otherwise 1 on the diagonals and 0 elsewhere.
std::vector<double> start_theta(const LmmDeviance& dev, const Eigen::VectorXd& y) {
  std::vector<double> start;
  for (double lo : dev.lower()) start.push_back(std::isfinite(lo) ? 1.0 : 0.0);
  const auto& terms = dev.terms();
  bool scalar = true;
  for (size_t i = 0; i < terms.size(); ++i) {
    scalar = scalar && terms[i].columns == std::vector<int>{0};
    for (size_t j = 0; j < i; ++j) scalar = scalar && terms[i].grouping != terms[j].grouping;
  }
  if (!scalar) return start;
  const std::vector<double> yv(y.data(), y.data() + y.size());
  std::vector<double> v;
  double sum = 0;
  for (const auto& t : terms) {
    const Grouping& g = dev.groupings()[static_cast<size_t>(t.grouping)];
    std::vector<std::vector<double>> groups(g.levels.size());
    for (size_t r = 0; r < yv.size(); ++r) groups[static_cast<size_t>(g.index[r])].push_back(yv[r]);
    std::vector<double> means;
    for (const auto& grp : groups) means.push_back(static_cast<double>(r_mean(grp)));
    std::vector<double> ave(yv.size());
    for (size_t r = 0; r < yv.size(); ++r) ave[r] = means[static_cast<size_t>(g.index[r])];
    v.push_back(r_var(ave));
    sum += v.back();
  }
  const double ve = r_var(yv) - sum;
  if (!(ve > 0)) return start;
  for (size_t i = 0; i < v.size(); ++i) start[i] = std::sqrt(v[i] / ve);
  return start;
}

std::string random_name(const PreparedModel& m, int column, bool correlated) {
  return column == 0 || correlated ? m.design.column_names[static_cast<size_t>(column)] : re_column_name(m, column);
}

}  // namespace

GaussianFit fit_gaussian(const PreparedModel& m, const Eigen::MatrixXd& X, const std::vector<FormulaTerm>& terms,
                         bool reml) {
  GaussianFit f;
  f.formula_terms = terms;
  f.center = m.y.mean();
  const Eigen::VectorXd y = m.y.array() - f.center;
  f.dev = std::make_unique<LmmDeviance>(X, m.design.X, y, m.groupings, expand_terms(terms, m.groupings), reml);
  LmmDeviance& dev = *f.dev;
  const ScalarFunction criterion = [&dev](const std::vector<double>& theta) { return dev(theta); };
  f.opt = optimize_lmer(criterion, start_theta(dev, y), dev.lower());
  f.conv = check_convergence(f.opt.derivs, f.opt.par, dev.lower());
  f.opt.fval = dev(f.opt.par);
  return f;
}

std::vector<std::vector<double>> column_variances(const GaussianFit& f) {
  std::vector<std::vector<double>> out;
  const double s2 = f.dev->sigma() * f.dev->sigma();
  for (size_t t = 0; t < f.dev->terms().size(); ++t) {
    const Eigen::MatrixXd T = f.dev->term_factor(t, f.opt.par);
    const Eigen::MatrixXd S = s2 * T * T.transpose();
    out.emplace_back(S.diagonal().data(), S.diagonal().data() + S.rows());
  }
  return out;
}

void add_variances(LmmFit& r, const PreparedModel& m, const std::vector<FormulaTerm>& terms, const LmmDeviance& sys,
                   const std::vector<double>& theta, double scale2) {
  for (size_t t = 0; t < sys.terms().size(); ++t) {
    const RandomTerm& term = sys.terms()[t];
    const std::string& group = m.groupings[static_cast<size_t>(term.grouping)].name;
    bool correlated = true;
    for (const auto& ft : terms)
      if (ft.grouping == term.grouping) correlated = ft.correlated;
    const Eigen::MatrixXd T = sys.term_factor(t, theta);
    const Eigen::MatrixXd S = scale2 * T * T.transpose();
    for (size_t j = 0; j < term.columns.size(); ++j) {
      const double v = S(static_cast<Eigen::Index>(j), static_cast<Eigen::Index>(j));
      r.variances.push_back({group, random_name(m, term.columns[j], correlated), v, std::sqrt(v)});
    }
    for (size_t j = 0; j < term.columns.size(); ++j)
      for (size_t i = j + 1; i < term.columns.size(); ++i) {
        const auto I = static_cast<Eigen::Index>(i), J = static_cast<Eigen::Index>(j);
        r.correlations.push_back({group, random_name(m, term.columns[j], true), random_name(m, term.columns[i], true),
                                  S(I, J) / std::sqrt(S(I, I) * S(J, J))});
      }
  }
}

void describe_model(LmmFit& r, const PreparedModel& m, const std::vector<FormulaTerm>& terms, const LmmOptions& o) {
  r.family = o.family;
  r.transform = o.transform;
  r.reml = o.reml && o.family == Family::gaussian;
  r.formula = lme4_formula(m, terms);
  r.r_code = detail::r_code(m, terms, o);
  r.n = static_cast<size_t>(m.y.size());
  for (const auto& g : m.groupings) r.groups.emplace_back(g.name, g.levels.size());
  for (const auto& t : terms) {
    LmmRandomTerm rt{m.groupings[static_cast<size_t>(t.grouping)].name, {}, t.correlated || t.columns.size() == 1};
    for (int c : t.columns) rt.columns.push_back(m.design.column_names[static_cast<size_t>(c)]);
    r.random.push_back(rt);
  }
  for (const auto& fac : m.design.factors) {
    r.factor_names.push_back(fac.name);
    r.factor_levels.push_back(fac.levels);
  }
  r.column_names = m.design.column_names;
}

Eigen::MatrixXd drop_term(const FixedDesign& design, const FixedTerm& term) {
  std::vector<Eigen::Index> keep;
  for (Eigen::Index c = 0; c < design.X.cols(); ++c)
    if (std::find(term.columns.begin(), term.columns.end(), static_cast<int>(c)) == term.columns.end()) keep.push_back(c);
  Eigen::MatrixXd X(design.X.rows(), static_cast<Eigen::Index>(keep.size()));
  for (size_t j = 0; j < keep.size(); ++j) X.col(static_cast<Eigen::Index>(j)) = design.X.col(keep[j]);
  return X;
}

namespace {

// lmerTest's summary(m, ddf = "Kenward-Roger") and anova(m, ddf = "Kenward-Roger").
void add_kenward_roger(LmmFit& r, const PreparedModel& m, const VarparModel& vp, const KrModel& kr) {
  r.vcov = kr.vcov_adjusted;
  r.kenward_roger = true;
  const Eigen::Index p = vp.vcov.rows();
  for (Eigen::Index j = 0; j < p; ++j) {
    Eigen::MatrixXd L = Eigen::MatrixXd::Zero(1, p);
    L(0, j) = 1;
    const KrTest t = kenward_roger_test(kr, vp.beta, L);
    const double est = vp.beta(j), se = std::sqrt(kr.vcov_adjusted(j, j));
    const Tail tail = t_two_sided(est / se, t.ddf);
    r.coefficients.push_back({m.design.column_names[static_cast<size_t>(j)], est, se, t.ddf, est / se, tail.p, tail.log10_p});
  }
  for (const auto& term : m.design.terms) {
    const KrTest t = kenward_roger_test(kr, vp.beta, type3_hypothesis(m.design, term));
    LmmAnovaRow row{term.name, 0, 0, t.ndf, t.ddf, t.F, t.p, t.log10_p};
    row.mean_sq = t.F_unscaled * vp.sigma * vp.sigma;
    row.sum_sq = row.mean_sq * t.ndf;
    r.anova.push_back(row);
  }
}

}  // namespace

LmmFit report_gaussian(const PreparedModel& m, GaussianFit& f, const LmmOptions& o) {
  LmmFit r;
  LmmDeviance& dev = *f.dev;
  const std::vector<double>& theta = f.opt.par;
  describe_model(r, m, f.formula_terms, o);
  r.theta = theta;
  VarparModel vp = varpar_model(dev, theta);
  vp.beta(0) += f.center + m.y_offset;
  r.sigma = vp.sigma;
  r.singular = f.conv.singular;
  r.messages = f.conv.messages;
  r.warnings = f.opt.warnings;
  r.warnings.insert(r.warnings.end(), f.conv.warnings.begin(), f.conv.warnings.end());
  r.warnings.insert(r.warnings.end(), vp.warnings.begin(), vp.warnings.end());
  const double crit = f.opt.fval;
  r.df = static_cast<int>(dev.p() + theta.size() + 1);
  r.reml_criterion = o.reml ? crit : std::numeric_limits<double>::quiet_NaN();
  r.deviance = o.reml ? std::numeric_limits<double>::quiet_NaN() : crit;
  r.loglik = -crit / 2;
  r.aic = crit + 2.0 * r.df;
  r.bic = crit + std::log(static_cast<double>(r.n)) * r.df;
  add_variances(r, m, f.formula_terms, dev, theta, r.sigma * r.sigma);
  r.variances.push_back({"Residual", "", r.sigma * r.sigma, r.sigma});
  r.beta = vp.beta;
  r.vcov = vp.vcov;
  r.vcov_unadjusted = vp.vcov;
  r.jacobian = vp.jacobian;
  r.vcov_varpar = vp.vcov_varpar;
  if (o.ddf == DenominatorDf::kenward_roger) {
    const KrModel kr = kenward_roger_model(dev, theta, vp);
    if (kr.ok) {
      add_kenward_roger(r, m, vp, kr);
      return r;
    }
    r.warnings.push_back("Unable to compute Kenward-Roger tests (" + kr.error + "): using Satterthwaite instead");
  }
  for (Eigen::Index j = 0; j < vp.beta.size(); ++j) {
    Eigen::RowVectorXd L = Eigen::RowVectorXd::Zero(vp.beta.size());
    L(j) = 1;
    const TTest t = satterthwaite_t(vp, L);
    r.coefficients.push_back({m.design.column_names[static_cast<size_t>(j)], t.estimate, t.se, t.df, t.t, t.p,
                              t.log10_p});
  }
  for (const auto& term : m.design.terms) {
    const FTest t = satterthwaite_f(vp, type3_hypothesis(m.design, term));
    r.anova.push_back({term.name, t.sum_sq, t.mean_sq, t.num_df, t.den_df, t.F, t.p, t.log10_p});
  }
  return r;
}

}  // namespace dtlab::stats::detail

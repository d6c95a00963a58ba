// Simulated power of a mixed-model test; see lmm_power.h.
#include "analysis/stats/lmm_power.h"

#include <cmath>
#include <map>

#include "analysis/stats/detail/lmm_design.h"
#include "analysis/stats/detail/lmm_model.h"
#include "study/common/random.h"

namespace dtlab::stats {
namespace {

// The fitted random-effects terms in lme4's order, each with its factor T (scaled by sigma for an LMM).
struct Structure {
  std::vector<detail::RandomTerm> terms;
  std::vector<Eigen::MatrixXd> factor;
};

Result<Structure> structure_of(const detail::PreparedModel& m, const LmmFit& fit) {
  std::vector<detail::FormulaTerm> formula;
  for (const auto& r : fit.random) {
    detail::FormulaTerm t;
    t.correlated = r.correlated;
    for (size_t g = 0; g < m.groupings.size(); ++g)
      if (m.groupings[g].name == r.grouping) t.grouping = static_cast<int>(g);
    for (const auto& c : r.columns)
      for (size_t j = 0; j < m.design.column_names.size(); ++j)
        if (m.design.column_names[j] == c) t.columns.push_back(static_cast<int>(j));
    formula.push_back(t);
  }
  Structure s;
  s.terms = detail::expand_terms(formula, m.groupings);
  size_t at = 0;
  const double scale = fit.family == Family::gaussian ? fit.sigma : 1.0;
  for (const auto& t : s.terms) {
    const Eigen::Index k = static_cast<Eigen::Index>(t.columns.size());
    Eigen::MatrixXd T = Eigen::MatrixXd::Zero(k, k);
    for (Eigen::Index j = 0; j < k; ++j)
      for (Eigen::Index i = j; i < k; ++i) {
        if (at >= fit.theta.size()) return Error{"", 0, 0, "", "the fit's theta does not match its random terms"};
        T(i, j) = scale * fit.theta[at++];
      }
    s.factor.push_back(T);
  }
  return s;
}

// One simulated study of n subjects (designs of pilot subjects drawn with replacement).
LmmData simulate(const detail::PreparedModel& m, const LmmData& pilot, const LmmFit& fit, const Structure& st,
                 const std::vector<std::vector<size_t>>& rows_of, size_t n, Random<SplitMix64>& rng) {
  LmmData sim;
  sim.subject_name = pilot.subject_name;
  sim.item_name = pilot.item_name;
  sim.data.source = "simulated";
  sim.data.dv_name = pilot.data.dv_name;
  std::vector<Factor*> factor_of;
  for (const auto& f : m.design.factors) {
    auto& list = f.within ? sim.data.within : sim.data.between;
    list.push_back({f.name, {}});
  }
  for (auto& f : sim.data.within) factor_of.push_back(&f);
  for (auto& f : sim.data.between) factor_of.push_back(&f);
  // the items' random effects, once for this study
  std::map<std::pair<size_t, int>, Eigen::VectorXd> item_b;
  auto draw = [&](size_t t) {
    Eigen::VectorXd z(st.factor[t].rows());
    for (Eigen::Index i = 0; i < z.size(); ++i) z(i) = rng.normal();
    return Eigen::VectorXd(st.factor[t] * z);
  };
  std::vector<double> values;
  for (size_t j = 0; j < n; ++j) {
    const size_t s = static_cast<size_t>(rng.below(rows_of.size()));
    std::vector<Eigen::VectorXd> subject_b(st.terms.size());
    for (size_t t = 0; t < st.terms.size(); ++t)
      if (st.terms[t].grouping == 0) subject_b[t] = draw(t);
    for (size_t r : rows_of[s]) {
      const auto R = static_cast<Eigen::Index>(r);
      double eta = m.design.X.row(R).dot(fit.beta);
      for (size_t t = 0; t < st.terms.size(); ++t) {
        const Eigen::VectorXd* b = &subject_b[t];
        if (st.terms[t].grouping != 0) {
          const auto key = std::make_pair(t, m.groupings[static_cast<size_t>(st.terms[t].grouping)].index[r]);
          auto it = item_b.find(key);
          if (it == item_b.end()) it = item_b.emplace(key, draw(t)).first;
          b = &it->second;
        }
        for (size_t a = 0; a < st.terms[t].columns.size(); ++a) eta += m.design.X(R, st.terms[t].columns[a]) * (*b)(static_cast<Eigen::Index>(a));
      }
      double v;
      if (fit.family == Family::binomial) v = rng.uniform() < 1 / (1 + std::exp(-eta)) ? 1 : 0;
      else v = eta + fit.sigma * rng.normal();
      if (fit.transform == Transform::log) v = std::exp(v);
      values.push_back(v);
      sim.data.subject.push_back("sim" + std::to_string(j));
      for (size_t f = 0; f < m.design.factors.size(); ++f)
        factor_of[f]->level.push_back(m.design.factors[f].levels[static_cast<size_t>(m.design.factors[f].index[r])]);
      if (!pilot.item_name.empty()) sim.item.push_back(m.groupings[1].levels[static_cast<size_t>(m.groupings[1].index[r])]);
    }
  }
  sim.data.dv = Measurements::from_doubles(values);
  return sim;
}

// The term's p in a fit: Satterthwaite F (LMM) or the likelihood-ratio test (GLMM); NaN if absent.
double p_of(const LmmFit& f, const std::string& term) {
  for (const auto& a : f.anova)
    if (a.term == term) return a.p;
  for (const auto& l : f.lrt)
    if (l.term == term) return l.p;
  return std::nan("");
}

}  // namespace

Result<std::vector<LmmPowerRow>> lmm_power(const LmmData& pilot, const LmmOptions& options, const LmmFit& fit,
                                           const LmmPowerOptions& power) {
  if (options.random == RandomEffects::maximal)
    return Error{"", 0, 0, "random", "simulated power needs --random intercepts or slopes (max reruns its fallback)"};
  if (!(power.alpha > 0 && power.alpha < 1)) return Error{"", 0, 0, "alpha", "alpha must lie between 0 and 1"};
  if (std::isnan(p_of(fit, power.term)))
    return Error{"", 0, 0, "term", "no test of the term " + name_for_message(power.term) + " in the model"};
  auto prepared = detail::prepare_model(pilot, options);
  if (!prepared) return prepared.error();
  const detail::PreparedModel& m = *prepared;
  auto st = structure_of(m, fit);
  if (!st) return st.error();
  std::vector<std::vector<size_t>> rows_of(m.groupings[0].levels.size());
  for (size_t r = 0; r < static_cast<size_t>(m.y.size()); ++r) rows_of[static_cast<size_t>(m.groupings[0].index[r])].push_back(r);
  LmmOptions refit = options;
  refit.lrt = false;
  std::vector<LmmPowerRow> out;
  for (size_t n : power.subjects) {
    if (n < 2) return Error{"", 0, 0, "subjects", "each planned size needs 2 subjects or more"};
    LmmPowerRow row{n, {}};
    row.power.replications = power.replications;
    for (size_t b = 0; b < power.replications; ++b) {
      Random<SplitMix64> rng(mix64(mix64(power.seed, n), b));
      auto f = fit_lmm(simulate(m, pilot, fit, *st, rows_of, n, rng), refit);
      const double p = f ? p_of(*f, power.term) : std::nan("");
      if (std::isnan(p)) ++row.power.undefined;
      else if (p < power.alpha) ++row.power.rejections;
    }
    share_with_wilson_interval(row.power);
    out.push_back(row);
  }
  return out;
}

}  // namespace dtlab::stats

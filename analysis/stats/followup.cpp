// Simple effects and within-subject CIs; see followup.h.
#include "analysis/stats/followup.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <stdexcept>

#include "analysis/stats/detail/design.h"
#include "analysis/stats/detail/multivariate.h"
#include "analysis/stats/detail/numbers.h"
#include "analysis/stats/detail/sum.h"
#include "analysis/stats/distributions.h"
#include "analysis/stats/rm_anova.h"

namespace dtlab::stats {
namespace {

double mean(const std::vector<double>& x) {
  detail::Sum s;
  for (double v : x) s.add(v);
  return s.value() / static_cast<double>(x.size());
}

// marginal[s][la][lb]: subject s's mean over the other within factors at A = la, B = lb (deltas).
using Marginals = std::vector<std::vector<std::vector<double>>>;

Marginals marginals(const detail::CellDesign& d, std::size_t fa, std::size_t fb) {
  const std::size_t La = d.within_levels[fa].size(), Lb = d.within_levels[fb].size();
  Marginals m(d.subjects.size(), std::vector<std::vector<double>>(La, std::vector<double>(Lb, 0.0)));
  std::vector<std::vector<std::vector<std::size_t>>> cells(La, std::vector<std::vector<std::size_t>>(Lb));
  for (std::size_t c = 0; c < d.cells; ++c) {
    const auto lv = d.cell_levels(c);
    cells[lv[fa]][lv[fb]].push_back(c);
  }
  for (std::size_t s = 0; s < d.subjects.size(); ++s)
    for (std::size_t i = 0; i < La; ++i)
      for (std::size_t j = 0; j < Lb; ++j) m[s][i][j] = detail::subject_mean(d, s, cells[i][j]).delta;
  return m;
}

// Holm's p over the rows from `first` on (one family).
void holm_family(std::vector<SimpleEffect>& out, std::size_t first) {
  std::vector<double> ps;
  for (std::size_t i = first; i < out.size(); ++i) ps.push_back(out[i].p);
  const auto adj = holm(ps);
  for (std::size_t i = first; i < out.size(); ++i) {
    out[i].p_holm = adj[i - first];
    const bool contrast = out[i].test == "paired t" || out[i].test == "emmeans t";
    out[i].contrast.p_holm = contrast ? out[i].p_holm : kNaN;
  }
}

// A joint test as an ANOVA row: name, df, F, p (sums of squares and effect sizes NaN).
Effect joint_effect(const std::string& name, const detail::JointTest& j) {
  Effect e;
  e.name = name;
  e.within = false;
  e.df1 = j.df1;
  e.df2 = j.df2;
  e.F = j.F;
  const Tail t = f_upper(j.F, j.df1, j.df2);
  e.p = t.p;
  e.log10_p = t.log10_p;
  e.ss = e.ss_error = e.mse = e.eta_p2 = e.eta_g2 = e.eta_p2_ci_low = e.eta_p2_ci_high = kNaN;
  e.mauchly_W = e.mauchly_p = e.gg_epsilon = e.hf_epsilon = kNaN;
  e.df1_gg = e.df2_gg = e.df1_hf = e.df2_hf = e.p_gg = e.log10_p_gg = e.p_hf = e.log10_p_hf = kNaN;
  return e;
}

// One family: the effect of factor `f` (index fa, levels along `first`) at each level of the other.
Status family(const detail::CellDesign& d, const Marginals& m, bool a_varies, std::size_t fa, std::size_t fb,
              std::vector<SimpleEffect>& out) {
  const std::size_t tested = a_varies ? fa : fb, held = a_varies ? fb : fa;
  const auto& levels = d.within_levels[tested];
  const std::size_t first = out.size();
  for (std::size_t h = 0; h < d.within_levels[held].size(); ++h) {
    SimpleEffect se;
    se.factor = d.within_names[tested];
    se.at_factor = d.within_names[held];
    se.at_level = d.within_levels[held][h];
    se.n = d.subjects.size();
    auto value = [&](std::size_t s, std::size_t l) { return a_varies ? m[s][l][h] : m[s][h][l]; };
    if (levels.size() == 2) {
      std::vector<double> x, y;
      for (std::size_t s = 0; s < d.subjects.size(); ++s) {
        x.push_back(value(s, 0));
        y.push_back(value(s, 1));
      }
      se.test = "paired t";
      se.contrast = paired_comparison(levels[0], levels[1], x, y);
      se.p = se.contrast.p;
    } else {
      LongData sub;
      sub.dv_name = "y";
      sub.within.push_back({se.factor, {}});
      std::vector<double> y;
      for (std::size_t s = 0; s < d.subjects.size(); ++s)
        for (std::size_t l = 0; l < levels.size(); ++l) {
          sub.subject.push_back(d.subjects[s]);
          sub.within[0].level.push_back(levels[l]);
          y.push_back(value(s, l));
        }
      sub.dv = Measurements::from_doubles(std::move(y));
      auto r = rm_anova(sub);
      if (!r) return r.error();
      se.test = "rm-anova";
      se.anova = r->effects.front();
      se.p = se.anova.p;
    }
    out.push_back(se);
  }
  holm_family(out, first);
  return {};
}

// Mixed designs: the effect of factor `tested` at each level of `held` (any
// two factors, between first in the model's order), as emmeans' joint_tests /
// pairs(emmeans(fit, ~ tested | held)) on the afex fit: a t contrast for two
// levels, the joint F otherwise; Holm within the family.
void multivariate_family(const detail::MultivariateModel& m, std::size_t tested, std::size_t held,
                         std::vector<SimpleEffect>& out) {
  const std::size_t first = out.size();
  for (std::size_t h = 0; h < m.levels(held); ++h) {
    SimpleEffect se;
    se.factor = m.name(tested);
    se.at_factor = m.name(held);
    se.at_level = m.label(held, h);
    se.n = m.subjects();
    detail::FactorWeights w = m.averaging();
    w[held].assign(m.levels(held), 0.0);
    w[held][h] = 1.0;
    if (m.levels(tested) == 2) {
      se.test = "emmeans t";
      se.contrast = m.pair(tested, 0, 1, w);
      se.p = se.contrast.p;
    } else {
      const detail::JointTest j = m.levels_differ(tested, w);
      se.test = "emmeans F";
      se.anova = joint_effect(se.factor, j);
      se.p = se.anova.p;
    }
    out.push_back(se);
  }
  holm_family(out, first);
}

Result<SimpleEffects> multivariate_simple_effects(const LongData& data, const detail::CellDesign& d, std::size_t fa,
                                                  std::size_t fb) {
  auto m = detail::MultivariateModel::fit(d, data.source);
  if (!m) return m.error();
  SimpleEffects r;
  r.dropped_subjects = d.dropped;
  r.warnings = d.warnings;
  multivariate_family(*m, fa, fb, r.rows);
  multivariate_family(*m, fb, fa, r.rows);
  return r;
}

}  // namespace

Result<SimpleEffects> simple_effects(const LongData& data, const std::string& a, const std::string& b) {
  auto built = detail::build_cell_design(data);
  if (!built) return built.error();
  const detail::CellDesign& d = *built;
  if (!d.between_names.empty()) {  // factors in the model's order: between first, then within
    std::vector<std::string> names = d.between_names;
    names.insert(names.end(), d.within_names.begin(), d.within_names.end());
    auto at = [&](const std::string& name) -> Result<std::size_t> {
      const auto it = std::find(names.begin(), names.end(), name);
      if (it == names.end()) return Error{data.source, 0, 0, name, "not a factor of the design"};
      return static_cast<std::size_t>(it - names.begin());
    };
    auto fa = at(a), fb = at(b);
    if (!fa) return fa.error();
    if (!fb) return fb.error();
    if (*fa == *fb) return Error{data.source, 0, 0, a, "simple effects need two different factors"};
    return multivariate_simple_effects(data, d, *fa, *fb);
  }
  auto index = [&](const std::string& name) -> Result<std::size_t> {
    const auto it = std::find(d.within_names.begin(), d.within_names.end(), name);
    if (it == d.within_names.end()) return Error{data.source, 0, 0, name, "not a within-subject factor of the design"};
    return static_cast<std::size_t>(it - d.within_names.begin());
  };
  auto fa = index(a), fb = index(b);
  if (!fa) return fa.error();
  if (!fb) return fb.error();
  if (*fa == *fb) return Error{data.source, 0, 0, a, "simple effects need two different factors"};
  if (d.within_levels[*fa].size() < 2 || d.within_levels[*fb].size() < 2)
    return Error{data.source, 0, 0, "", "simple effects need two levels or more in each factor"};
  if (d.subjects.size() < 2) return Error{data.source, 0, 0, "", "simple effects need two complete subjects or more"};
  SimpleEffects r;
  r.dropped_subjects = d.dropped;
  r.warnings = d.warnings;
  const Marginals m = marginals(d, *fa, *fb);
  if (auto s = family(d, m, true, *fa, *fb, r.rows); !s) return s.error();
  if (auto s = family(d, m, false, *fa, *fb, r.rows); !s) return s.error();
  return r;
}

Result<std::vector<CellInterval>> within_subject_intervals(const LongData& data, double level) {
  if (!(level > 0 && level < 1)) throw std::invalid_argument("within_subject_intervals: level must be in (0, 1)");
  auto built = detail::build_cell_design(data);
  if (!built) return built.error();
  const detail::CellDesign& d = *built;
  if (d.subjects.empty()) return Error{data.source, 0, 0, "", "no subject has every cell: nothing left after listwise deletion"};
  const std::size_t C = d.cells;
  std::map<std::vector<std::size_t>, std::vector<std::size_t>> groups;
  for (std::size_t s = 0; s < d.subjects.size(); ++s) groups[d.group[s]].push_back(s);
  std::vector<CellInterval> out;
  for (const auto& [g, members] : groups) {
    const double N = static_cast<double>(members.size());
    std::vector<double> subject_mean;
    for (std::size_t s : members) subject_mean.push_back(mean(d.delta[s]));
    const double grand = mean(subject_mean);
    const double morey = C > 1 ? std::sqrt(static_cast<double>(C) / static_cast<double>(C - 1)) : kNaN;
    const double q = members.size() > 1 ? t_quantile(1.0 - (1.0 - level) / 2.0, N - 1.0) : kNaN;
    for (std::size_t c = 0; c < C; ++c) {
      CellInterval ci;
      for (std::size_t f = 0; f < d.between_names.size(); ++f)
        ci.levels.emplace_back(d.between_names[f], d.between_levels[f][g[f]]);
      const auto lv = d.cell_levels(c);
      for (std::size_t f = 0; f < d.within_names.size(); ++f)
        ci.levels.emplace_back(d.within_names[f], d.within_levels[f][lv[f]]);
      std::vector<double> raw, normalised;
      for (std::size_t i = 0; i < members.size(); ++i) {
        raw.push_back(d.delta[members[i]][c]);
        normalised.push_back(d.delta[members[i]][c] - subject_mean[i] + grand);
      }
      ci.n = members.size();
      const double m = mean(raw), mn = mean(normalised);
      detail::Sum ss;
      for (double v : normalised) ss.add((v - mn) * (v - mn));
      const double sd = members.size() > 1 ? std::sqrt(ss.value() / (N - 1.0)) : kNaN;
      ci.mean = d.offset + m;
      ci.se = sd / std::sqrt(N) * morey;
      ci.ci_low = ci.mean - q * ci.se;
      ci.ci_high = ci.mean + q * ci.se;
      out.push_back(ci);
    }
  }
  return out;
}

}  // namespace dtlab::stats

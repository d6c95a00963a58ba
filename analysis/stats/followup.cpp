// Simple effects and within-subject CIs; see followup.h.
#include "analysis/stats/followup.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <stdexcept>

#include "analysis/stats/detail/design.h"
#include "analysis/stats/detail/sum.h"
#include "analysis/stats/distributions.h"
#include "analysis/stats/rm_anova.h"

namespace dtlab::stats {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

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
  std::vector<std::vector<double>> count(La, std::vector<double>(Lb, 0.0));
  for (std::size_t c = 0; c < d.cells; ++c) {
    const auto lv = d.cell_levels(c);
    count[lv[fa]][lv[fb]] += 1.0;
    for (std::size_t s = 0; s < d.subjects.size(); ++s) m[s][lv[fa]][lv[fb]] += d.delta[s][c];
  }
  for (auto& per : m)
    for (std::size_t i = 0; i < La; ++i)
      for (std::size_t j = 0; j < Lb; ++j) per[i][j] /= count[i][j];
  return m;
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
  std::vector<double> ps;
  for (std::size_t i = first; i < out.size(); ++i) ps.push_back(out[i].p);
  const auto adj = holm(ps);
  for (std::size_t i = first; i < out.size(); ++i) {
    out[i].p_holm = adj[i - first];
    out[i].contrast.p_holm = out[i].test == "paired t" ? out[i].p_holm : kNaN;
  }
  return {};
}

}  // namespace

Result<SimpleEffects> simple_effects(const LongData& data, const std::string& a, const std::string& b) {
  if (!data.between.empty())
    return Error{data.source, 0, 0, data.between.front().name,
                 "simple effects are computed for all-within designs; this one has a between-subject factor"};
  auto built = detail::build_cell_design(data);
  if (!built) return built.error();
  const detail::CellDesign& d = *built;
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

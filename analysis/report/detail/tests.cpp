// Tests on participant x cell tables; see tests.h. The statistics themselves
// are analysis/stats' (validated there against R and NIST); this file only
// chooses the data each test sees and collects what the tables show.
#include "analysis/report/detail/tests.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "analysis/report/detail/format.h"

namespace dtlab::report::detail {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// What every test report holds: names, the participants kept, cell and marginal descriptives.
// False, with not_tested set, when nothing can be tested.
bool begin_report(TestReport& r, const CellMatrix& m, std::string test, std::string measure, std::string unit,
                  std::string scope) {
  r.test = std::move(test);
  r.measure = std::move(measure);
  r.unit = std::move(unit);
  r.scope = std::move(scope);
  r.m = &m;
  r.kept = m.complete();
  r.excluded = m.missing_notes();
  for (size_t c = 0; c < m.cells(); ++c) {
    std::vector<double> v;
    for (size_t s : r.kept) v.push_back(m.value[s][c]);
    r.cells.push_back(stats::describe(v));
  }
  for (size_t k = 0; k < m.factors.size(); ++k) {
    std::vector<stats::Descriptives> per_level;
    int levels = 0;
    for (size_t c = 0; c < m.cells(); ++c) levels = std::max(levels, m.level(c, k) + 1);
    for (int l = 0; l < levels; ++l) {
      const auto all = marginal(m, k, l);
      std::vector<double> v;
      for (size_t s : r.kept) v.push_back(all[s]);
      per_level.push_back(stats::describe(v));
    }
    r.marginals.push_back(std::move(per_level));
  }
  if (m.factors.empty()) {
    r.not_tested = "no factor varies";
    return false;
  }
  if (r.kept.empty()) {
    r.not_tested = "no participant has a value in every cell";
    return false;
  }
  return true;
}

// The paired difference of a two-level primary factor (marginal means).
void paired_effect(TestReport& r, const CellMatrix& m, const Design& d) {
  for (size_t k = 0; k < m.factors.size(); ++k) {
    if (m.factors[k] != d.primary || d.factor(d.primary).levels.size() != 2 || r.kept.size() < 2) continue;
    const auto a = marginal(m, k, 0), b = marginal(m, k, 1);
    std::vector<double> x, y;
    for (size_t s : r.kept) {
      x.push_back(b[s]);
      y.push_back(a[s]);
    }
    PairedEffect e;
    e.factor = d.primary;
    e.t = stats::paired_t(x, y);
    e.dz = e.t.sd > 0 ? e.t.mean_difference / e.t.sd : kNaN;
    r.paired = e;
  }
}

}  // namespace

const stats::Effect* TestReport::effect(const std::string& name) const {
  if (!anova) return nullptr;
  for (const auto& e : anova->effects)
    if (e.name == name) return &e;
  return nullptr;
}

const std::vector<stats::Descriptives>* TestReport::marginal_of(int f) const {
  for (size_t k = 0; k < m->factors.size(); ++k)
    if (m->factors[k] == f) return &marginals[k];
  return nullptr;
}

Result<stats::RmAnovaResult> rm_anova_of(const CellMatrix& m, const Design& d, const std::vector<size_t>& kept) {
  return stats::rm_anova(long_data(m, d, kept, "y"));
}

TestReport run_rm_anova(const CellMatrix& m, const Design& d, std::string measure, std::string unit,
                        std::string scope) {
  TestReport r;
  if (!begin_report(r, m, "rm-anova", std::move(measure), std::move(unit), std::move(scope))) return r;
  const auto data = long_data(m, d, r.kept, "y");
  auto res = stats::rm_anova(data);  // = rm_anova_of(m, d, r.kept); the data serve the post-hoc tests too
  if (!res) {
    r.not_tested = res.error().message;
    return r;
  }
  r.warnings = res->warnings;
  r.anova = std::move(*res);
  if (r.kept.size() < 2) r.not_tested = "one participant: no error variance, F is undefined";
  for (size_t k = 0; k < m.factors.size(); ++k) {
    const auto& f = d.factor(m.factors[k]);
    if (f.levels.size() < 3 || r.kept.size() < 2) continue;
    auto ph = stats::pairwise_within(data, f.name, stats::PairwiseTest::paired_t);
    if (ph) r.posthoc[f.name] = std::move(*ph);
  }
  paired_effect(r, m, d);
  return r;
}

TestReport run_friedman(const CellMatrix& m, const Design& d, std::string measure, std::string unit,
                        std::string scope, std::uint64_t seed) {
  TestReport r;
  if (!begin_report(r, m, "friedman", std::move(measure), std::move(unit), std::move(scope))) return r;
  const auto data = long_data(m, d, r.kept, "y");
  stats::ExactOptions exact;
  exact.seed = seed;
  auto res = stats::friedman(data, exact);
  if (!res) {
    r.not_tested = res.error().message;
    return r;
  }
  r.warnings = res->warnings;
  r.friedman = std::move(*res);
  for (size_t k = 0; k < m.factors.size(); ++k) {
    const auto& f = d.factor(m.factors[k]);
    if (f.levels.size() < 3 || r.kept.size() < 2) continue;
    stats::WilcoxonOptions wo;
    wo.exact.seed = seed;
    auto ph = stats::pairwise_within(data, f.name, stats::PairwiseTest::wilcoxon, wo);
    if (ph) r.posthoc[f.name] = std::move(*ph);
  }
  paired_effect(r, m, d);
  return r;
}

nlohmann::json to_json(const stats::Descriptives& d) {
  return {{"n", d.n},           {"mean", num(d.mean)},     {"sd", num(d.sd)},         {"se", num(d.se)},
          {"ci_low", num(d.ci_low)}, {"ci_high", num(d.ci_high)}, {"median", num(d.median)},
          {"q1", num(d.q1)},    {"q3", num(d.q3)},         {"min", num(d.min)},       {"max", num(d.max)}};
}

nlohmann::json to_json(const stats::Effect& e) {
  return {{"effect", e.name},       {"df1", num(e.df1)},          {"df2", num(e.df2)},
          {"ss", num(e.ss)},        {"ss_error", num(e.ss_error)}, {"F", num(e.F)},
          {"p", num(e.p)},          {"log10_p", num(e.log10_p)},  {"eta_p2", num(e.eta_p2)},
          {"eta_g2", num(e.eta_g2)}, {"mauchly_W", num(e.mauchly_W)}, {"mauchly_p", num(e.mauchly_p)},
          {"gg_epsilon", num(e.gg_epsilon)}, {"hf_epsilon", num(e.hf_epsilon)}, {"p_gg", num(e.p_gg)},
          {"log10_p_gg", num(e.log10_p_gg)}, {"p_hf", num(e.p_hf)},     {"log10_p_hf", num(e.log10_p_hf)}};
}

nlohmann::json to_json(const TestReport& r, const Design& d) {
  using nlohmann::json;
  const CellMatrix& m = *r.m;
  json j{{"measure", r.measure}, {"unit", r.unit}, {"scope", r.scope}, {"test", r.test}};
  json factors = json::array();
  for (int f : m.factors) factors.push_back(d.factor(f).name);
  j["factors"] = factors;
  j["n"] = r.kept.size();
  j["excluded"] = r.excluded;
  json cells = json::array();
  for (size_t c = 0; c < m.cells(); ++c) {
    json levels = json::object();
    for (size_t k = 0; k < m.factors.size(); ++k)
      levels[d.factor(m.factors[k]).name] = d.factor(m.factors[k]).levels[static_cast<size_t>(m.level(c, k))];
    json cj = to_json(r.cells[c]);
    cj["cell"] = m.cell_names[c];
    cj["levels"] = levels;
    cells.push_back(cj);
  }
  j["cells"] = cells;
  json marg = json::object();
  for (size_t k = 0; k < m.factors.size(); ++k) {
    json per = json::array();
    for (size_t l = 0; l < r.marginals[k].size(); ++l) {
      json lj = to_json(r.marginals[k][l]);
      lj["level"] = d.factor(m.factors[k]).levels[l];
      per.push_back(lj);
    }
    marg[d.factor(m.factors[k]).name] = per;
  }
  j["marginals"] = marg;
  if (r.anova) {
    json eff = json::array();
    for (const auto& e : r.anova->effects) eff.push_back(to_json(e));
    j["effects"] = eff;
  }
  if (r.friedman) {
    const auto& f = *r.friedman;
    j["friedman"] = {{"Q", num(f.Q)},
                     {"df", num(f.df)},
                     {"p", num(f.p)},
                     {"log10_p", num(f.log10_p)},
                     {"p_exact", num(f.p_exact)},
                     {"exact_method", f.exact_method},
                     {"kendall_W", num(f.kendall_W)},
                     {"iman_davenport_F", num(f.iman_davenport_F)},
                     {"p_iman_davenport", num(f.p_iman_davenport)},
                     {"n", f.n},
                     {"k", f.k},
                     {"treatments", f.treatments},
                     {"mean_ranks", f.mean_ranks}};
  }
  if (!r.posthoc.empty()) {
    json ph = json::object();
    for (const auto& [factor, list] : r.posthoc) {
      json arr = json::array();
      for (const auto& c : list)
        arr.push_back({{"a", c.a}, {"b", c.b}, {"test", c.test}, {"estimate", num(c.estimate)},
                       {"statistic", num(c.statistic)}, {"df", num(c.df)}, {"p", num(c.p)},
                       {"p_holm", num(c.p_holm)}});
      ph[factor] = arr;
    }
    j["posthoc"] = ph;
  }
  if (r.paired) {
    const auto& p = *r.paired;
    const auto& lv = d.factor(p.factor).levels;
    j["paired"] = {{"factor", d.factor(p.factor).name},
                   {"difference", lv[static_cast<size_t>(p.b)] + " - " + lv[static_cast<size_t>(p.a)]},
                   {"n", p.t.n},
                   {"mean_difference", num(p.t.mean_difference)},
                   {"ci_low", num(p.t.ci_low)},
                   {"ci_high", num(p.t.ci_high)},
                   {"t", num(p.t.t)},
                   {"df", num(p.t.df)},
                   {"p", num(p.t.p)},
                   {"dz", num(p.dz)}};
  }
  j["not_tested"] = r.not_tested.empty() ? json(nullptr) : json(r.not_tested);
  j["warnings"] = r.warnings;
  return j;
}

std::string effect_sentence(const stats::Effect& e) {
  std::string s = "F(" + df_text(e.df1) + ", " + df_text(e.df2) + ") = " + f_text(e.F) + ", p = " +
                  p_text(e.p, e.log10_p);
  if (e.df1 > 1 && std::isfinite(e.gg_epsilon))
    s += " (Greenhouse-Geisser ε = " + fixed(e.gg_epsilon, 3) + ", p = " + p_text(e.p_gg, e.log10_p_gg) + ")";
  s += ", η²p = " + fixed(e.eta_p2, 3);
  return s;
}

std::string friedman_sentence(const stats::FriedmanResult& f) {
  std::string s = "χ²(" + df_text(f.df) + ") = " + fixed(f.Q, 2) + ", p = " + p_text(f.p, f.log10_p);
  if (std::isfinite(f.p_exact)) s += " (exact p = " + p_text(f.p_exact, std::log10(f.p_exact)) + ")";
  s += ", Kendall's W = " + fixed(f.kendall_W, 3) + ", n = " + std::to_string(f.n);
  return s;
}

}  // namespace dtlab::report::detail

// Planning from the report's tests; see planning.h. The statistics are
// analysis/stats/power.h's (validated there against R and G*Power); this file
// chooses the tests and the data each resample sees.
#include "analysis/report/detail/planning.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "analysis/report/detail/format.h"
#include "analysis/stats/apa.h"
#include "study/common/random.h"
#include "study/protocol/protocol.h"

namespace dtlab::report::detail {
namespace {


bool planned_section(const std::string& section) { return section == "time" || section == "accuracy"; }

double analytic_power(const PlannedEffect& pe, const stats::Effect& e, double n, double alpha) {
  if (!std::isfinite(e.F) || pe.pilot_n < 2) return kNaN;
  if (e.df1 == 1) return stats::power_paired_t(n, pe.dz, 1.0, alpha, stats::Alternative::two_sided, /*strict=*/true);
  return stats::power_of_effect(e, static_cast<double>(pe.pilot_n), n, alpha);
}

// Participant x cell matrix of the resampled participants: row k is kept[draw[k]] of m, named uniquely.
CellMatrix resampled(const CellMatrix& m, const std::vector<size_t>& kept, const std::vector<std::size_t>& draw) {
  CellMatrix r;
  r.factors = m.factors;
  r.cell_levels = m.cell_levels;
  r.cell_names = m.cell_names;
  r.subjects.reserve(draw.size());
  r.value.reserve(draw.size());
  for (std::size_t k = 0; k < draw.size(); ++k) {
    r.subjects.push_back("r" + std::to_string(k + 1));
    r.value.push_back(m.value[kept[draw[k]]]);
  }
  return r;
}

// One stream per test and planned size, so adding a size or a test leaves the others' draws alone:
// mix64 of the seed plus (test x 1000003 + n) golden gammas (the values the report always drew).
std::uint64_t stream_seed(std::uint64_t seed, std::size_t test, int n) {
  return mix64(seed + kGoldenGamma * (static_cast<std::uint64_t>(test) * 1000003ULL + static_cast<std::uint64_t>(n)));
}

// The smallest planned size whose resampled power reaches `target` (0: none).
int resampled_smallest(const PlannedEffect& pe, double target) {
  for (const auto& a : pe.at)
    if (a.resampled.power >= target) return a.n;
  return 0;
}

// n rounded up to a multiple of the order rows (NaN stays NaN).
double balanced(double n, long long rows) {
  if (!std::isfinite(n) || rows <= 1) return n;
  return std::ceil(n / static_cast<double>(rows)) * static_cast<double>(rows);
}

// The effects of one tested ANOVA, with analytic power (resampling is added by the caller).
std::vector<PlannedEffect> effects_of(const TestReport& r, const std::string& section, const PlanningOptions& o,
                                      long long order_rows) {
  std::vector<PlannedEffect> out;
  for (const auto& e : r.anova->effects) {
    PlannedEffect pe;
    pe.section = section;
    pe.measure = r.measure;
    pe.scope = r.scope;
    pe.effect = e.name;
    pe.pilot_n = r.kept.size();
    pe.df1 = e.df1;
    pe.df2 = e.df2;
    pe.F = e.F;
    pe.p = reported_p(e);
    const bool gg = stats::applied_correction(e, stats::Correction::greenhouse_geisser) != stats::Correction::none;
    pe.p_df1 = gg ? e.df1_gg : e.df1;
    pe.p_df2 = gg ? e.df2_gg : e.df2;
    pe.eta_p2 = e.eta_p2;
    pe.epsilon = e.df1 > 1 && std::isfinite(e.gg_epsilon) ? e.gg_epsilon : 1.0;
    pe.dz = e.df1 == 1 && e.F >= 0 ? std::sqrt(e.F / static_cast<double>(pe.pilot_n)) : kNaN;
    for (int n : o.sizes) {
      PowerAt a;
      a.n = n;
      a.resampled.power = a.resampled.ci_low = a.resampled.ci_high = kNaN;
      a.analytic = analytic_power(pe, e, n, o.alpha);
      pe.at.push_back(a);
    }
    const auto at_n = [&](double n) { return analytic_power(pe, e, n, o.alpha); };
    const bool finite = std::isfinite(at_n(2.0));
    pe.n80 = finite ? stats::smallest_n(at_n, 0.8) : kNaN;
    pe.n90 = finite ? stats::smallest_n(at_n, 0.9) : kNaN;
    pe.n80_balanced = balanced(pe.n80, order_rows);
    pe.n90_balanced = balanced(pe.n90, order_rows);
    out.push_back(std::move(pe));
  }
  return out;
}

}  // namespace

std::string planned_label(const PlannedEffect& e) {
  return (e.scope == "overall" ? std::string("all tasks") : e.scope) + ", " + e.measure + ": " + e.effect;
}

nlohmann::json to_json(const PlannedEffect& e) {
  nlohmann::json at = nlohmann::json::array();
  for (const auto& a : e.at)
    at.push_back({{"n", a.n},
                  {"analytic", num(a.analytic)},
                  {"resampled", num(a.resampled.power)},
                  {"resampled_ci95_low", num(a.resampled.ci_low)},
                  {"resampled_ci95_high", num(a.resampled.ci_high)},
                  {"replications", a.resampled.replications},
                  {"undefined", a.resampled.undefined}});
  const auto n_or_null = [](int n) { return n ? nlohmann::json(n) : nlohmann::json(nullptr); };
  return {{"section", e.section}, {"measure", e.measure}, {"scope", e.scope}, {"effect", e.effect},
          {"pilot_n", e.pilot_n}, {"df1", num(e.df1)},    {"df2", num(e.df2)},    {"F", num(e.F)},
          {"p", num(e.p)},        {"p_df1", num(e.p_df1)}, {"p_df2", num(e.p_df2)},
          {"eta_p2", num(e.eta_p2)}, {"epsilon", num(e.epsilon)}, {"dz", num(e.dz)},
          {"power", at},          {"n_for_80", num(e.n80)}, {"n_for_90", num(e.n90)},
          {"n_for_80_balanced", num(e.n80_balanced)}, {"n_for_90_balanced", num(e.n90_balanced)},
          {"resampled_n_for_80", n_or_null(e.resampled_n80)}, {"resampled_n_for_90", n_or_null(e.resampled_n90)}};
}

PlanningInput planning_input(const Design& design, const protocol::Protocol& protocol, const TimeResult& time,
                             const AccuracyResult& accuracy) {
  PlanningInput in{design, std::max<long long>(1, protocol::declared_order_rows(protocol)), {}};
  for (const TestReport* r : time.tests) in.tests.emplace_back("time", r);
  for (const TestReport* r : accuracy.tests) in.tests.emplace_back("accuracy", r);
  return in;
}

namespace {

// The tests of `in` that can be planned (section, test); the others go to `not_planned` with their reason.
std::vector<std::pair<std::string, const TestReport*>> plannable(const PlanningInput& in,
                                                                 std::vector<std::string>& not_planned) {
  std::vector<std::pair<std::string, const TestReport*>> out;
  for (const auto& [section, test] : in.tests) {
    const TestReport& r = *test;
    if (!planned_section(section) || r.test != "rm-anova") continue;
    const std::string label = (r.scope == "overall" ? std::string("all tasks") : r.scope) + ", " + r.measure;
    if (!r.anova || r.anova->effects.empty()) {
      not_planned.push_back(label + ": not tested (" + (r.not_tested.empty() ? "no effect" : r.not_tested) + ")");
      continue;
    }
    if (r.kept.size() < 2) {
      not_planned.push_back(label + ": fewer than 2 participants with every cell");
      continue;
    }
    out.emplace_back(section, test);
  }
  return out;
}

}  // namespace

std::vector<PlannedEffect> plan_effects(const PlanningInput& in, const PlanningOptions& o,
                                        std::vector<std::string>& not_planned) {
  // The tests to plan, then their effects; progress counts (test, size) steps.
  const auto tests = plannable(in, not_planned);
  std::vector<PlannedEffect> out;
  const std::size_t steps = tests.size() * o.sizes.size();
  std::size_t done = 0;
  for (std::size_t t = 0; t < tests.size(); ++t) {
    const TestReport& r = *tests[t].second;
    std::vector<PlannedEffect> effects = effects_of(r, tests[t].first, o, in.order_rows);
    if (o.replications > 0) {
      const auto test = [&](const std::vector<std::size_t>& draw) {
        const CellMatrix m = resampled(*r.m, r.kept, draw);
        std::vector<size_t> all(m.subjects.size());
        for (size_t s = 0; s < all.size(); ++s) all[s] = s;
        const auto res = rm_anova_of(m, in.design, all);
        std::vector<double> p(effects.size(), kNaN);
        if (!res) return p;
        for (std::size_t h = 0; h < effects.size(); ++h)
          for (const auto& e : res->effects)
            if (e.name == effects[h].effect) p[h] = reported_p(e);
        return p;
      };
      for (std::size_t k = 0; k < o.sizes.size(); ++k) {
        const int n = o.sizes[k];
        const auto power = stats::power_by_resampling(r.kept.size(), static_cast<std::size_t>(n), effects.size(), test,
                                                      o.replications, stream_seed(o.seed, t, n), o.alpha, o.threads);
        for (std::size_t h = 0; h < effects.size(); ++h) effects[h].at[k].resampled = power[h];
        if (o.progress) o.progress(++done, steps);
      }
      for (auto& pe : effects) {
        pe.resampled_n80 = resampled_smallest(pe, 0.8);
        pe.resampled_n90 = resampled_smallest(pe, 0.9);
      }
    }
    for (auto& pe : effects) out.push_back(std::move(pe));
  }
  return out;
}

}  // namespace dtlab::report::detail

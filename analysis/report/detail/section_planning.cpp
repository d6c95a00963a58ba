// Planning the next study: for every effect of the completion-time and
// accuracy ANOVAs, the analytic power at 8 to 32 participants from the effect
// this study observed, and the smallest n for 80% and 90% power
// (analysis/report/planning.h, the same code as `dtlab power`, without the
// resampling, which the section names as the next step). Costs a few
// noncentral t / F evaluations per effect: nothing next to the rest.
// section_planning computes the PlanningResult; lay_out_planning lays it out.
#include <cmath>

#include "analysis/report/detail/format.h"
#include "analysis/report/detail/planning.h"
#include "analysis/report/detail/sections.h"

namespace dtlab::report::detail {
namespace {

std::string n_text(double n) { return std::isfinite(n) ? integer(static_cast<long long>(n)) : std::string("> 10⁷"); }

}  // namespace

PlanningResult section_planning(Context& ctx, const TimeResult& time, const AccuracyResult& accuracy) {
  PlanningOptions o;
  o.replications = 0;  // analytic only: `dtlab power` resamples
  o.alpha = 0.05;
  PlanningResult result{o.sizes, o.alpha, {}, {}, {}};
  result.effects = plan_effects(planning_input(ctx.design, ctx.data.protocol, time, accuracy), o, result.not_planned);
  return result;
}

void lay_out_planning(Layout& out, const Context& ctx, const PlanningResult& result) {
  const std::vector<PlannedEffect>& effects = result.effects;
  const std::vector<int>& planned_sizes = result.sizes;
  Section s{"planning", "Planning the next study", 2, {}};
  std::string sizes;
  for (std::size_t k = 0; k < planned_sizes.size(); ++k)
    sizes += (k ? (k + 1 == planned_sizes.size() ? " and " : ", ") : "") + std::to_string(planned_sizes[k]);
  s.text("How many participants would a study of this design need to detect the effects seen here? For every effect "
         "of the repeated-measures ANOVAs above (completion time and accuracy, per task and over all tasks), the "
         "table gives the power of the same test at " + sizes + " participants (α = .05), computed from the effect "
         "observed in these data. An effect with one degree of freedom is a paired comparison: its power is that of "
         "the paired t test with the observed standardized difference d_z = √(F / N) (noncentral t). An effect with "
         "more degrees of freedom uses the noncentral F distribution with noncentrality λ = F · df1 · n / N, the "
         "observed Greenhouse-Geisser ε applied to λ and both df (as G*Power does). The last columns give the "
         "smallest number of participants that reaches 80% and 90% power.");
  s.text("These numbers take the observed effect as the true one. An effect estimated from few participants is "
         "uncertain, and effects noticed because they were significant tend to be overestimated, so treat the "
         "powers as optimistic for small effects. `dtlab power " + ctx.data.path +
         " --participants 8,12,16,24,32` adds the power found by resampling these participants with replacement "
         "and rerunning the same tests, with a Monte Carlo 95% interval.");
  Table t;
  t.id = "table-planning";
  t.caption = "Power of each ANOVA effect at the planned numbers of participants, from the observed effect "
              "(analytic), and the smallest n for 80% and 90% power.";
  t.header = {"Test", "Effect", "N", "η²p", "ε"};
  for (int n : planned_sizes) t.header.push_back("n = " + std::to_string(n));
  t.header.insert(t.header.end(), {"n for 80%", "n for 90%"});
  t.text_columns = 2;
  for (const auto& e : effects) {
    std::vector<std::string> row = {(e.scope == "overall" ? std::string("All tasks") : e.scope) + ", " + e.measure,
                                    e.effect, std::to_string(e.pilot_n), fixed(e.eta_p2, 3),
                                    e.df1 > 1 ? fixed(e.epsilon, 3) : kDash};
    for (const auto& a : e.at) row.push_back(fixed(a.analytic, 3));
    const bool finite = std::isfinite(e.F);
    row.push_back(finite ? n_text(e.n80) : kDash);
    row.push_back(finite ? n_text(e.n90) : kDash);
    t.rows.push_back(std::move(row));
  }
  t.notes.push_back("N: participants in the test. Power: probability that the test (two-sided, α = .05; "
                    "Greenhouse-Geisser corrected for effects with more than one df) rejects the null hypothesis when "
                    "the true effect equals the observed one. —: no finite F (e.g. no error variance).");
  if (effects.empty()) s.text("No ANOVA effect could be planned.");
  else s.add(t);
  for (const auto& why : result.not_planned) s.text("Not planned: " + why + ".");
  out.doc.sections.push_back(std::move(s));
}

}  // namespace dtlab::report::detail

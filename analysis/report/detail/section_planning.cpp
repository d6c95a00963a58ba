// Planning the next study: for every effect of the completion-time and
// accuracy ANOVAs, the analytic power at 8 to 32 participants from the effect
// this study observed, and the smallest n for 80% and 90% power
// (analysis/report/planning.h, the same code as `dtlab power`, without the
// resampling, which the section names as the next step). Costs a few
// noncentral t / F evaluations per effect: nothing next to the rest.
// Computes the PlanningResult only; layout_models.cpp lays it out.
#include <cmath>

#include "analysis/report/detail/format.h"
#include "analysis/report/detail/planning.h"
#include "analysis/report/detail/sections.h"

namespace dtlab::report::detail {
PlanningResult section_planning(Context& ctx, const TimeResult& time, const AccuracyResult& accuracy) {
  PlanningOptions o;
  o.replications = 0;  // analytic only: `dtlab power` resamples
  o.alpha = 0.05;
  PlanningResult result{o.sizes, o.alpha, {}, {}, {}};
  result.effects = plan_effects(planning_input(ctx.design, ctx.data.protocol, time, accuracy), o, result.not_planned);
  return result;
}

}  // namespace dtlab::report::detail

// The power planning of analysis/report/planning.h on a Context whose
// sections have run: which of the stored tests are planned (the completion
// time and accuracy repeated-measures ANOVAs), their analytic power, and the
// resampling that reruns rm_anova_of (tests.h) on participants drawn from the
// test's own participant x cell matrix. Shared by `dtlab power` and the
// report's "Planning the next study" section, so both say the same numbers.
// Never reads the database, never writes.
#pragma once
#include <nlohmann/json.hpp>

#include <string>
#include <vector>

#include "analysis/report/detail/sections.h"
#include "analysis/report/planning.h"

namespace dtlab::report::detail {

// Every effect of the planned tests of ctx, in the report's order; a test
// that cannot be planned (not tested, fewer than 2 participants) goes to
// `not_planned` with its reason.
std::vector<PlannedEffect> plan_effects(const Context& ctx, const PlanningOptions& options,
                                        std::vector<std::string>& not_planned);

// "T1, completion time: transparency" for tables and messages.
std::string planned_label(const PlannedEffect& e);

// One effect as JSON (NaN as null): what report.json's "planning" and `dtlab power --json` print.
nlohmann::json to_json(const PlannedEffect& e);

}  // namespace dtlab::report::detail

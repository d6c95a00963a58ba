// The power planning of analysis/report/planning.h on its own input (the
// design, the order rows and the completion-time and accuracy sections'
// declared results, never the report's Context): which tests are planned
// (their repeated-measures ANOVAs), their analytic power, and the
// resampling that reruns rm_anova_of (inference.h) on participants drawn from the
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

// What planning reads: the design, the protocol's number of order rows, and the tests it may plan, each
// with the section that stored it ("time", "accuracy"), in the report's order.
struct PlanningInput {
  const Design& design;
  long long order_rows = 1;
  std::vector<std::pair<std::string, const TestReport*>> tests;
};
// The input from the completion-time and accuracy sections' results (time's tests, then accuracy's).
PlanningInput planning_input(const Design& design, const protocol::Protocol& protocol, const TimeResult& time,
                             const AccuracyResult& accuracy);

// Every effect of the planned tests (the rm-anova ones) of `in`, in its order; a test
// that cannot be planned (not tested, fewer than 2 participants) goes to
// `not_planned` with its reason.
std::vector<PlannedEffect> plan_effects(const PlanningInput& in, const PlanningOptions& options,
                                        std::vector<std::string>& not_planned);

// "T1, completion time: transparency" for tables and messages.
std::string planned_label(const PlannedEffect& e);

// One effect as JSON (NaN as null): what report.json's "planning" and `dtlab power --json` print.
nlohmann::json to_json(const PlannedEffect& e);

}  // namespace dtlab::report::detail

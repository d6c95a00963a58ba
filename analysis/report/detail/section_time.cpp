// Completion time: per task and over all tasks, the participant x condition
// means and their repeated-measures ANOVA (sphericity, Holm post-hoc tests
// for factors with more than two levels, follow-ups of interactions, all in
// run_rm_anova), then the rank tests and, with --log-time, the log-time
// ANOVAs (section_time_checks.cpp). Overall, a participant's condition mean
// is the mean of its per-task means (every task weighs the same, as in a
// balanced design). Computes the TimeResult only; layout_time.cpp lays it
// out.
#include <cmath>
#include <set>

#include "analysis/report/detail/format.h"
#include "analysis/report/detail/sections.h"

namespace dtlab::report::detail {
namespace {

std::optional<double> time_of(const TrialRow& t) { return t.completion_s; }

}  // namespace

Reducer overall_time(const Design& d, const std::function<std::optional<double>(const TrialRow&)>& field) {
  return [&d, field](const std::vector<const TrialRow*>& ts) {
    const double v = mean_of_task_means(field)(ts);
    std::set<std::string> tasks;
    for (const TrialRow* t : ts) tasks.insert(t->planned.task);
    if (ts.empty() || static_cast<int>(tasks.size()) < d.tasks_in(d.scenario_of(*ts.front())))
      return std::nan("");
    return v;
  };
}

namespace {

using Rows = TestRows;

// The completion-time ANOVAs (one per task, then one over all tasks, result.rows), computed before any
// layout; returns the one over all tasks.
const TestReport* run_time_tests(Context& ctx, TimeResult& result) {
  const Design& d = ctx.design;
  for (const auto& task : d.tasks) {
    const auto& m = ctx.cells(task.factors, [&](const TrialRow& t) { return t.planned.task == task.id; }, mean_of(time_of));
    const auto& r = ctx.add_test("time", run_rm_anova(m, d, "completion time", "s", task.id), result.tally);
    result.by_scope[task.id] = &r;
    result.tests.push_back(&r);
    result.rows.push_back({task.id, &r});
    result.means.push_back({&m, "completion_time_s", task.id});
  }
  const auto& mo = ctx.cells(d.all_factors, [](const TrialRow&) { return true; }, overall_time(d, time_of));
  const auto& overall = ctx.add_test("time", run_rm_anova(mo, d, "completion time", "s", "overall"), result.tally);
  result.by_scope["overall"] = &overall;
  result.tests.push_back(&overall);
  result.rows.push_back({"All tasks", &overall});
  result.means.push_back({&mo, "completion_time_s", "overall"});
  return &overall;
}

}  // namespace

TimeResult time_tests(Context& ctx) {
  TimeResult result;
  run_time_tests(ctx, result);
  return result;
}

TimeResult section_time(Context& ctx) {
  TimeResult result;
  run_time_tests(ctx, result);
  // Robustness and assumptions (section_time_checks.cpp).
  run_rank_tests(ctx, result);
  if (ctx.options.log_time) result.log_rows = run_log_time(ctx, result);
  return result;
}

}  // namespace dtlab::report::detail

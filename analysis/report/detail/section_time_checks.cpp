// The tests beside the completion-time ANOVAs: rank tests as a robustness
// check (each design factor on its own marginal means: Wilcoxon signed-rank
// for two levels, Friedman for more, so "all tasks" never mixes the factors
// into one) and, with --log-time, the ANOVAs of log completion times
// (reported beside the seconds, never instead of them). Statistics come from
// analysis/stats; these functions choose the data and store the tests in
// the section's TimeResult. The residuals' normality is in each ANOVA's
// TestReport; layout_time.cpp lays all of it out.
#include <algorithm>
#include <cmath>

#include "analysis/report/detail/format.h"
#include "analysis/report/detail/sections.h"

namespace dtlab::report::detail {
void run_rank_tests(Context& ctx, TimeResult& result) {
  for (const auto& [label, r] : result.rows)
    for (size_t k = 0; k < r->m->factors.size(); ++k) {
      const auto& mk = ctx.keep(marginal_matrix(*r->m, k));
      const auto& x = ctx.add_test("time", run_rank_test(mk, ctx.design, "completion time (ranks)", "s", r->scope,
                                                         ctx.options.seed), result.tally);
      result.tests.push_back(&x);
      result.rank_tests.push_back(&x);
    }
}

TestRows run_log_time(Context& ctx, TimeResult& result) {
  const Design& d = ctx.design;
  auto log_time = [](const TrialRow& t) -> std::optional<double> {
    if (!(t.completion_s > 0)) return std::nullopt;  // NaN (no time) or not positive
    return std::log(t.completion_s);
  };
  TestRows rows;
  for (const auto& task : d.tasks) {
    const auto& m =
        ctx.cells(task.factors, [&](const TrialRow& t) { return t.planned.task == task.id; }, mean_of(log_time));
    rows.push_back({task.id, &ctx.add_test("time", run_rm_anova(m, d, "log completion time", "log s", task.id),
                                           result.tally)});
    result.tests.push_back(rows.back().second);
  }
  const auto& mo = ctx.cells(d.all_factors, [](const TrialRow&) { return true; }, overall_time(d, log_time));
  const auto& overall =
      ctx.add_test("time", run_rm_anova(mo, d, "log completion time", "log s", "overall"), result.tally);
  result.tests.push_back(&overall);
  rows.push_back({"All tasks", &overall});
  return rows;
}

}  // namespace dtlab::report::detail

// The Context's bookkeeping shared by the sections' computations (sections.h):
// which trials are analysed, the analysed participants, the participant x
// cell matrices, storing a test for tests.csv and counting it in the
// section's Tally, and the declared results' lookups. Lays out nothing
// (layout_common.cpp has the layout's helpers).
#include <algorithm>
#include <cmath>
#include <map>

#include "analysis/report/detail/format.h"
#include "analysis/report/detail/sections.h"
#include "analysis/stats/apa.h"

namespace dtlab::report::detail {

bool Context::analysed(const TrialRow& t) const {
  if (t.planned.practice) return false;
  for (int l : t.level_index)
    if (l < 0) return false;
  return true;
}

const CellMatrix& Context::cells(const std::vector<int>& factors, const TrialFilter& include, const Reducer& reduce) {
  return keep(aggregate(
      data, design, subjects, factors, [&](const TrialRow& t) { return analysed(t) && include(t); }, reduce));
}

void collect_subjects(Context& ctx) {
  for (const auto& p : ctx.data.participants) {
    long long n = 0;
    for (const auto& t : ctx.data.trials) n += t.participant == p.id && ctx.analysed(t) ? 1 : 0;
    if (n) ctx.subjects.push_back(p.id);
    ctx.analysed_trials += n;
  }
}

const TestReport* TimeResult::of(const std::string& scope) const {
  const auto it = by_scope.find(scope);
  return it == by_scope.end() ? nullptr : it->second;
}

const TestReport* AccuracyResult::of(const std::string& id) const {
  const auto it = by_task.find(id);
  return it == by_task.end() ? nullptr : it->second;
}

const TestReport& Context::add_test(const std::string& section, TestReport r, Tally& tally) {
  if (r.anova)
    tally.tests += static_cast<int>(r.anova->effects.size());
  else if (r.friedman || r.wilcoxon)
    ++tally.tests;
  reports.push_back(std::move(r));
  report_section.push_back(section);
  return reports.back();
}

}  // namespace dtlab::report::detail

// The report's data section as a computation: sessions by status, trials
// planned, recorded and practice, and the data's warnings (incomplete
// sessions, unknown levels, excluded data, too few participants), which
// report.json and the top of the report show. layout_overview.cpp lays it
// out with the method and the closing notes.
#include <algorithm>
#include <cmath>
#include <set>

#include "analysis/report/detail/format.h"
#include "analysis/report/detail/sections.h"

namespace dtlab::report::detail {
namespace {

// Incomplete sessions, unknown levels, exclusions, too few participants: shown at the top, and report.json's warnings.
std::vector<std::string> data_warnings(const Context& ctx, long long unknown) {
  const StudyData& data = ctx.data;
  std::vector<std::string> warnings;
  for (const auto& pr : data.participants) {
    if (pr.session_status == store::SessionStatus::running || pr.session_status == store::SessionStatus::abandoned)
      warnings.push_back(pr.id + ": session " + store::to_string(*pr.session_status) + " with " + std::to_string(pr.recorded) + " of " +
                         dtlab::count(pr.planned, "trial") + " recorded; their recorded trials are analysed, and tests "
                         "needing a missing condition leave them out (named under each table).");
    if (!pr.session_status) warnings.push_back(pr.id + ": enrolled, no session started; not analysed.");
    else if (pr.recorded == 0) warnings.push_back(pr.id + ": no trial recorded; not analysed.");
  }
  if (unknown)
    warnings.push_back(dtlab::count(unknown, "trial") + " carry a factor level the protocol does not declare; left out.");
  if (!data.excluded_participants.empty() || data.excluded_trials > 0)
    warnings.push_back(data.with_excluded
                           ? "Excluded data are KEPT in this analysis (--with-excluded): " +
                                 std::to_string(data.excluded_trials) + " excluded trials are analysed; the "
                                 "exclusions are listed below."
                           : std::to_string(data.excluded_trials) + " recorded trial" +
                                 (data.excluded_trials == 1 ? " is" : "s are") + " excluded (" +
                                 std::to_string(data.excluded_participants.size()) + " excluded participant" +
                                 (data.excluded_participants.size() == 1 ? "" : "s") +
                                 ") and left out of every table and test; each exclusion and its reason is listed "
                                 "below.");
  if (ctx.subjects.size() < 2)
    warnings.push_back("Only " + std::to_string(ctx.subjects.size()) + " participant: no test across participants "
                       "is possible (F and p are undefined); the tables show descriptives only.");
  return warnings;
}

}  // namespace

OverviewResult section_overview(Context& ctx) {
  const StudyData& data = ctx.data;
  OverviewResult r;
  for (const auto& pr : data.participants) {
    r.finished += pr.session_status == store::SessionStatus::finished;
    r.running += pr.session_status == store::SessionStatus::running;
    r.abandoned += pr.session_status == store::SessionStatus::abandoned;
    r.never_started += !pr.session_status;
    r.planned += pr.planned;
    r.recorded += pr.recorded;
  }
  long long unknown = 0;
  for (const auto& t : data.trials) {
    r.practice += t.planned.practice ? 1 : 0;
    if (!t.planned.practice && !ctx.analysed(t)) ++unknown;
  }
  r.tally.warnings = data_warnings(ctx, unknown);
  return r;
}

}  // namespace dtlab::report::detail

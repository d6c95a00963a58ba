// Walked paths: one figure per participant and WALKTHROUGH task, each trial's
// recorded eye positions on its building's floor plan with the target and
// the marked answer (drawn by the app's path-figure function, ReportOptions,
// which report.cpp calls). The result holds the figures drawn, the trials
// left out of them and the warning about those; layout_overview.cpp links
// the figures from a table and report.json lists them (render_data.h).
#include "analysis/report/detail/sections.h"

namespace dtlab::report::detail {

PathsResult section_paths(std::vector<PathFigure> figures, std::vector<std::string> left_out) {
  PathsResult r;
  r.shown = !figures.empty() || !left_out.empty();
  // A scene generated differently by this build would put the path on the wrong building.
  if (!left_out.empty())
    r.tally.warnings.push_back("walked paths: " + std::to_string(left_out.size()) + " trial" +
                               (left_out.size() == 1 ? "" : "s") + " not drawn (" + left_out.front() +
                               (left_out.size() > 1 ? "; ..." : "") + ")");
  r.figures = std::move(figures);
  r.left_out = std::move(left_out);
  return r;
}

}  // namespace dtlab::report::detail

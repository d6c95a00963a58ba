// Walked paths: one figure per participant and WALKTHROUGH task, each trial's
// recorded eye positions on its building's floor plan with the target and
// the marked answer (drawn by the app's path-figure function, ReportOptions),
// linked from a table. A reader sees how each person searched: straight to
// the target, room by room, or lost. Listed only where poses were recorded;
// report.json lists the same figures (render_data.h). section_paths takes
// what report.cpp drew; lay_out_paths lays it out.
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

void lay_out_paths(Layout& out, const PathsResult& r) {
  if (!r.shown) return;
  const std::vector<std::string>& left_out = r.left_out;
  Section s{"paths", "Walked paths", 2, {}};
  s.text("Where each participant walked in the WALKTHROUGH tasks: one figure per participant and task, a floor "
         "plan per trial (each trial has its own building) with the recorded eye positions as a line, the start "
         "cell, the target (circle, T3-like tasks), the position the participant marked (cross) and the distance "
         "walked. The figures are SVG files beside this page.");
  Table t;
  t.id = "table-paths";
  t.caption = "Walked-path figures per participant and task.";
  t.header = {"Participant", "Task", "Trials", "Figure"};
  t.text_columns = 2;
  t.last_is_text = true;
  for (const PathFigure& f : r.figures) {
    t.rows.push_back({f.participant, f.task, std::to_string(f.trials), f.file});
    t.links.push_back(f.file);
  }
  if (!left_out.empty())
    t.notes.push_back("Not drawn: " + std::to_string(left_out.size()) + " trial" + (left_out.size() == 1 ? "" : "s") +
                      ", e.g. " + left_out.front() + ".");
  if (!t.rows.empty()) s.add(std::move(t));
  else s.text(t.notes.front());
  out.doc.sections.push_back(std::move(s));
}

}  // namespace dtlab::report::detail

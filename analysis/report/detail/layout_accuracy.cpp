// The layout of the accuracy and the speed-accuracy sections (layout.h):
// the accuracy table (per task and measure, the test of the primary factor
// with its effect size and difference, published values beside), its notes
// and full ANOVAs; the speed-accuracy table of mean time and error per
// level with its reading, the repeated-measures correlations and the
// scatter of the participant x condition means. Lays out AccuracyResult and
// SpeedAccuracyResult; computes no statistic.
#include <cmath>

#include "analysis/report/detail/format.h"
#include "analysis/report/detail/layout.h"

namespace dtlab::report::detail {
namespace {

using protocol::TaskType;
using Row = AccuracyRow;

// "F(1, 15) = 1.82" (df Greenhouse-Geisser corrected where ε < 1, as the p beside it) or "χ²(1) = 0.11".
std::string statistic_text(const TestReport& r, const std::string& factor) {
  if (const stats::Effect* e = r.effect(factor)) return "F(" + df_cell(*e) + ") = " + f_text(e->F);
  if (r.friedman) return "χ²(" + df_text(r.friedman->df) + ") = " + fixed(r.friedman->Q, 2);
  return kDash;
}

std::string p_of(const TestReport& r, const std::string& factor) {
  if (const stats::Effect* e = r.effect(factor)) return p_text(reported_p(*e));
  if (r.friedman) {
    std::string s = p_text(r.friedman->p);
    if (std::isfinite(r.friedman->p_exact)) s += " (exact " + p_text(r.friedman->p_exact) + ")";
    return s;
  }
  return kDash;
}

std::string effect_size_text(const TestReport& r, const std::string& factor) {
  if (const stats::Effect* e = r.effect(factor)) return "ηp² = " + bounded(e->eta_p2);
  if (r.friedman) return "W = " + bounded(r.friedman->kendall_W);
  return kDash;
}

// The table's cells of one row: measure, mean (SD) per level, test, p, effect size, difference, published.
std::vector<std::string> accuracy_cells(const Design& d, const Row& row) {
  const auto& primary = d.factor(d.primary);
  const TestReport& r = *row.r;
  std::vector<std::string> cells = {row.label, row.measure};
  for (const auto& c : primary_cells(r, d, row.decimals)) cells.push_back(c);
  cells.push_back(std::to_string(r.kept.size()));
  cells.push_back(statistic_text(r, primary.name));
  cells.push_back(p_of(r, primary.name));
  cells.push_back(effect_size_text(r, primary.name));
  if (primary.levels.size() == 2) cells.push_back(difference_text(r, row.decimals));
  const auto* a = row.published.empty() ? nullptr : d.published("accuracy", row.published);
  for (const auto& c : d.published_cells("accuracy", row.published, row.decimals)) cells.push_back(a ? c : "");
  return cells;
}

Table accuracy_table(const Design& d, const AccuracyResult& result) {
  const auto& primary = d.factor(d.primary);
  const bool two = primary.levels.size() == 2;
  Table t;
  t.id = "table-accuracy";
  t.caption = "Accuracy per task: mean (SD) over participants of the participant x condition values, and the test "
              "of " + primary.name + ".";
  t.header = {"Task", "Measure"};
  t.text_columns = 2;
  for (size_t l = 0; l < primary.levels.size(); ++l) t.header.push_back(d.level_label(d.primary, static_cast<int>(l)));
  t.header.insert(t.header.end(), {"n", "Test", "p", "Effect size"});
  if (two) t.header.push_back("Δ " + primary.levels[1] + " − " + primary.levels[0] + " [95% CI]");
  const size_t ours = t.header.size();
  for (const auto& h : d.published_header()) t.header.push_back(h);
  for (const auto& row : result.rows) t.rows.push_back(accuracy_cells(d, row));
  if (d.reference)
    t.groups = {{"this study", static_cast<int>(ours)},
                {d.published_group("accuracy"), static_cast<int>(t.header.size() - ours)}};
  t.notes.push_back(d.tasks_note() + " Relative error is a proportion (0 = exact count); proportion correct is 0..1; "
                    "distance is in world units. Test: repeated-measures ANOVA (F) or Friedman's test (χ², with the "
                    "exact permutation p in parentheses when computed). p in APA style (exact values in report.json). "
                    "Effect size: partial η² (ηp²) or Kendall's W.");
  if (!two)
    t.notes.push_back("df and p of F tests are Greenhouse-Geisser corrected where ε < 1 (" +
                      std::to_string(primary.levels.size()) + " levels).");
  else
    t.notes.push_back("Δ: mean paired difference " + primary.levels[1] + " − " + primary.levels[0] +
                      " with its 95% CI (paired t); negative = smaller error / fewer correct with " + primary.levels[1] +
                      ".");
  if (d.reference) t.notes.push_back(d.published_note("accuracy"));
  for (const auto& n : result.notes) t.notes.push_back(n);
  return t;
}

// Participant x cell error, lower = better (the accuracy matrix, flipped for letters).
double error_value(const CellMatrix& m, TaskType type, size_t s, size_t c) {
  const double v = m.value[s][c];
  return type == TaskType::identify_letter ? 1 - v : v;
}

// The scatter's data of one task: a dataset per primary level, points = participant x cell means; `finite`
// becomes true when a point is finite.
std::string scatter_data(const Design& d, const TaskInfo& task, const TestReport& tr, const TestReport& ar,
                         bool& finite) {
  const auto& primary = d.factor(d.primary);
  std::string scatter;
  const CellMatrix& mt = *tr.m;
  const CellMatrix& ma = *ar.m;
  size_t k = mt.factors.size();
  for (size_t i = 0; i < mt.factors.size(); ++i)
    if (mt.factors[i] == d.primary) k = i;
  for (size_t l = 0; l < primary.levels.size(); ++l) {
    scatter += "# " + task.id + " " + primary.levels[l] + ": time_s error participant\n";
    for (size_t si = 0; si < mt.subjects.size(); ++si)
      for (size_t ci = 0; ci < mt.cells(); ++ci)
        if (k < mt.factors.size() && mt.level(ci, k) == static_cast<int>(l)) {
          finite = finite || (std::isfinite(mt.value[si][ci]) && std::isfinite(error_value(ma, task.type, si, ci)));
          scatter += gp_value(mt.value[si][ci]) + " " + gp_value(error_value(ma, task.type, si, ci)) + " \"" +
                     mt.subjects[si] + "\"\n";
        }
    scatter += "\n\n";
  }
  return scatter;
}

// The scatter figure: one panel per task with a finite point (`panels`: "title|ylabel", "" = nothing to draw).
PlotSpec scatter_plot(const Design& d, const std::string& scatter, const std::vector<std::string>& panels) {
  const auto& primary = d.factor(d.primary);
  const int panel_index = static_cast<int>(panels.size());
  PlotSpec p;
  p.id = "fig-speed-accuracy";
  p.data["fig-speed-accuracy.dat"] = scatter;
  const int shown = static_cast<int>(std::count_if(panels.begin(), panels.end(), [](const std::string& x) { return !x.empty(); }));
  const int cols = std::min(shown, 2), rows = (shown + cols - 1) / std::max(cols, 1);
  p.width = 420 * std::max(cols, 1) + 40;
  p.height = 330 * std::max(rows, 1) + 40;
  std::string cmd = "set multiplot layout " + std::to_string(rows) + "," + std::to_string(std::max(cols, 1)) +
                    "\nset xlabel 'Completion time (s)'\nset key above center horizontal\n";
  const size_t levels = primary.levels.size();
  int drawn = 0;
  for (int i = 0; i < panel_index; ++i) {
    const std::string& spec = panels[static_cast<size_t>(i)];
    if (spec.empty()) continue;  // no finite point: gnuplot cannot scale an empty panel
    ++drawn;
    const size_t bar = spec.find('|');
    cmd += "set title " + gp_quote(spec.substr(0, bar)) + "\nset ylabel " + gp_quote(spec.substr(bar + 1)) + "\nplot ";
    for (size_t l = 0; l < levels; ++l)
      cmd += std::string(l ? ", " : "") + "'fig-speed-accuracy.dat' index " + std::to_string(static_cast<size_t>(i) * levels + l) +
             " using 1:2 with points pt 7 ps 0.7 lc rgb '" + series_color(l) + "' title " +
             gp_quote(d.level_label(d.primary, static_cast<int>(l)));
    cmd += "\n";
  }
  p.commands = cmd;
  p.empty = drawn == 0;
  return p;
}

// The empty time-and-error table: task, error measure, time and error per primary level, reading.
Table speed_accuracy_table(const Design& d) {
  const auto& primary = d.factor(d.primary);
  Table t;
  t.id = "table-speed-accuracy";
  t.caption = "Time and error per task and level of " + primary.name + " (means over participants), and what the "
              "differences say.";
  t.header = {"Task", "Error measure"};
  for (size_t l = 0; l < primary.levels.size(); ++l) {
    t.header.push_back("time (s), " + primary.levels[l]);
    t.header.push_back("error, " + primary.levels[l]);
  }
  t.header.push_back("Reading");
  t.text_columns = 2;
  t.last_is_text = true;
  return t;
}

// The empty table of the repeated-measures correlations.
Table rmcorr_table() {
  Table c;
  c.id = "table-speed-accuracy-rmcorr";
  c.caption = "Within-participant relation of a trial's completion time and its error (repeated-measures "
              "correlation over trials, groups = participant x condition).";
  c.header = {"Task", "Error measure", "Trials", "Groups", "r_rm", "95% CI", "df", "p", "Error change per 10 s"};
  c.text_columns = 2;
  return c;
}

// The table row of a task: per level, mean time and error, then the reading.
std::vector<std::string> table_row(const SpeedAccuracyRow& row, TaskType type) {
  std::vector<std::string> cells = {row.task, row.error_measure};
  for (const auto& l : row.levels) {
    cells.push_back(fixed(l.time_s, 2));
    cells.push_back(fixed(l.error, type == TaskType::find_unique ? 2 : 3));
  }
  cells.push_back(row.reading);
  return cells;
}

// The correlation table's row of a task.
std::vector<std::string> rmcorr_row(const SpeedAccuracyRow& row, TaskType type) {
  const RmCorr& rc = row.rmcorr;
  return {row.task, row.error_measure, std::to_string(rc.n), std::to_string(rc.groups), bounded(rc.r),
          std::isfinite(rc.ci_low) ? stats::apa_interval(rc.ci_low, rc.ci_high, true) : kDash, df_text(rc.df),
          p_text(rc.p), fixed(10 * rc.slope, type == TaskType::find_unique ? 2 : 4)};
}

}  // namespace

void lay_out_accuracy(Layout& out, const Context& ctx, const AccuracyResult& result) {
  const Design& d = ctx.design;
  Section s{"accuracy", "Accuracy", 2, {}};
  s.text("Accuracy is measured per task type. Counting tasks: the relative error |answer − truth| / truth of each "
         "trial, averaged per participant and condition; and the aggregated form, |sum of the true "
         "counts − sum of the answers| / sum of the true counts over a participant's trials in a condition (an "
         "over-count and an under-count cancel in it). Letter tasks: the proportion of correct answers per "
         "participant and condition, tested with Friedman's test. Find-unique tasks: the "
         "Euclidean distance between the marked and the true position, in world units. Continuous measures are "
         "tested with repeated-measures ANOVA over the participant x condition means.");
  if (result.rows.empty()) {
    s.text("The protocol has no task with an answer key the report scores.");
    out.doc.sections.push_back(std::move(s));
    return;
  }
  s.add(accuracy_table(d, result));
  const auto& rows = result.rows;
  for (const auto& row : rows) {
    const TestReport& r = *row.r;
    for (const auto& note : test_notes(r))
      if (note.rfind("n = ", 0) != 0 || !r.excluded.empty()) s.text(row.label + ", " + row.measure + ": " + note);
  }
  for (const auto& row : rows)
    if (row.r->m->factors.size() > 1 && row.r->anova)
      add_anova(out, s, d, *row.r, "table-accuracy-anova-" + row.r->scope + "-" + std::to_string(&row - &rows[0]),
                        "Repeated-measures ANOVA of " + row.measure + ", " + row.label + ".");
  out.doc.sections.push_back(std::move(s));
}

void lay_out_speed_accuracy(Layout& out, const Context& ctx, const SpeedAccuracyResult& r, const TimeResult& time,
                            const AccuracyResult& accuracy) {
  const Design& d = ctx.design;
  const auto& primary = d.factor(d.primary);
  Section s{"speed-accuracy", "Speed and accuracy", 2, {}};
  s.text("Did participants buy speed with accuracy, or accuracy with time? For every task with an answer key, the "
         "table sets the mean completion time beside the mean error of each level of " + primary.name +
         " (error: relative error for counting, error rate = 1 − proportion correct for letters, distance for "
         "positions; lower is better throughout). A level that is faster without being less accurate shows no "
         "speed-accuracy trade-off. The within-participant correlation then asks whether, inside one participant "
         "and condition, slower trials were more accurate (repeated-measures correlation, Bakdash & Marusich 2017).");

  Table t = speed_accuracy_table(d);
  Table c = rmcorr_table();
  std::string scatter;
  std::vector<std::string> panels;
  for (const SpeedAccuracyRow& row : r.rows) {
    const TaskInfo& task = *d.task(row.task);
    t.rows.push_back(table_row(row, task.type));
    c.rows.push_back(rmcorr_row(row, task.type));
    // Scatter data: one dataset per primary level, points = participant x cell means.
    bool finite = false;
    scatter += scatter_data(d, task, *time.of(task.id), *accuracy.of(task.id), finite);
    panels.push_back(finite ? d.task_label(task) + "|" + row.error_measure : "");
  }
  if (t.rows.empty()) {
    s.text("No task has both a completion time and an error measure.");
    out.doc.sections.push_back(std::move(s));
    return;
  }
  t.notes.push_back(d.tasks_note() + " Reading: from the paired difference of the participants' mean times (paired "
                    "t) and the test of the error measure in the Accuracy section; \"reliable\" means p < .05. "
                    "Percentages are relative to the first level's mean time.");
  s.add(t);
  c.notes.push_back("r_rm < 0: within a participant and condition, slower trials had smaller errors (time bought "
                    "accuracy); r_rm > 0: slower trials were also less accurate (difficulty drives both). df = trials − "
                    "groups − 1. Error change per 10 s: the common within-group slope times 10 s.");
  s.add(c);

  const PlotSpec p = scatter_plot(d, scatter, panels);
  out.add_figure(s, p, "Speed-accuracy scatter: each point is one participant's mean completion time and mean error "
                       "in one condition of the task, coloured by " + primary.name + ".");
  out.doc.sections.push_back(std::move(s));
}

}  // namespace dtlab::report::detail

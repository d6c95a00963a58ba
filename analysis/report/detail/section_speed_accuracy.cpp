// Speed and accuracy together: per task and level of the primary factor, the
// mean time and the mean error (lower = better for every measure: relative
// error, error rate = 1 - proportion correct, distance), the differences
// between levels and what they say (a trade-off or not); within
// participants, the repeated-measures correlation of a trial's time with its
// error (does taking longer buy accuracy?); a scatter of the participant x
// condition means. section_speed_accuracy computes the rows;
// lay_out_speed_accuracy lays them out (the scatter's points are the
// participant x cell means the time and accuracy tests hold).
#include <algorithm>
#include <cmath>

#include "analysis/report/detail/format.h"
#include "analysis/report/detail/rmcorr.h"
#include "analysis/report/detail/sections.h"

namespace dtlab::report::detail {
namespace {

using protocol::TaskType;

// The per-trial error of a task, lower = better; nullopt when not answered.
std::optional<double> trial_error(const TrialRow& t, TaskType type) {
  const auto& correct = t.scores.correct;
  if (type == TaskType::identify_letter) return correct ? std::optional<double>(*correct ? 0.0 : 1.0) : std::nullopt;
  if (type == TaskType::find_unique) return t.scores.distance;
  return t.scores.rel_error;
}

std::string error_name(TaskType type) {
  if (type == TaskType::identify_letter) return "error rate";
  if (type == TaskType::find_unique) return "distance";
  return "relative error";
}

// Participant x cell error, lower = better (the accuracy matrix, flipped for letters).
double error_value(const CellMatrix& m, TaskType type, size_t s, size_t c) {
  const double v = m.value[s][c];
  return type == TaskType::identify_letter ? 1 - v : v;
}

// The reading of a two-level primary factor, from the paired time difference and the error test ("—" otherwise);
// the differences and their p go to `row`.
std::string reading_of(const Design& d, const TaskInfo& task, const TestReport& tr, const TestReport& ar,
                       SpeedAccuracyRow& row) {
  const auto& primary = d.factor(d.primary);
  const auto* tm = tr.marginal_of(d.primary);
  std::string reading = kDash;
  if (primary.levels.size() == 2 && tr.paired && ar.paired) {
    const double dt = tr.paired->t.mean_difference, pt = tr.paired->t.p;
    double de = ar.paired->t.mean_difference;
    if (task.type == TaskType::identify_letter) de = -de;
    double pe = ar.paired->t.p;
    if (const stats::Effect* e = ar.effect(primary.name)) pe = e->p;
    if (ar.friedman) pe = ar.friedman->p;
    const bool faster = pt < 0.05 && dt < 0, slower = pt < 0.05 && dt > 0;
    const bool better = pe < 0.05 && de < 0, worse = pe < 0.05 && de > 0;
    const std::string b = primary.levels[1];
    const double base = tm ? (*tm)[0].mean : NAN;
    const std::string pct = std::isfinite(base) && base > 0 ? " (" + fixed(100 * dt / base, 0) + "%)" : "";
    if (faster && worse)
      reading = "trade-off: " + b + " " + fixed(-dt, 1) + " s faster" + pct + " but less accurate";
    else if (faster)
      reading = b + " " + fixed(-dt, 1) + " s faster" + pct +
                (better ? " and more accurate" : " at no measurable cost in accuracy");
    else if (slower && better)
      reading = "trade-off: " + b + " more accurate but " + fixed(dt, 1) + " s slower" + pct;
    else if (slower)
      reading = b + " " + fixed(dt, 1) + " s slower" + pct + (worse ? " and less accurate" : " with no accuracy gain");
    else if (better)
      reading = b + " more accurate at no measurable cost in time";
    else if (worse)
      reading = b + " less accurate, time not reliably different";
    else
      reading = "no reliable difference in time or accuracy";
    row.differences = SpeedAccuracyRow::Differences{dt, pt, de, pe};
  }
  return reading;
}

// The repeated-measures correlation of the task's trials' time and error (groups: participant x condition).
RmCorr trial_rmcorr(const Context& ctx, const TaskInfo& task) {
  std::vector<std::string> group;
  std::vector<double> x, y;
  for (const auto& tri : ctx.data.trials) {
    if (tri.planned.task != task.id || !ctx.analysed(tri)) continue;
    const auto e = trial_error(tri, task.type);
    std::string cell;
    for (int f : task.factors) cell += "/" + tri.levels[static_cast<size_t>(f)];
    group.push_back(tri.participant + cell);
    x.push_back(tri.completion_s);
    y.push_back(e ? *e : NAN);
  }
  return rm_corr(group, x, y);
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

// The row of one task from its time and error tests, and its points in the scatter's data.
SpeedAccuracyRow task_row(const Context& ctx, const TaskInfo& task, const TestReport& tr, const TestReport& ar) {
  const Design& d = ctx.design;
  const auto& primary = d.factor(d.primary);
  const auto* tm = tr.marginal_of(d.primary);
  const auto* am = ar.marginal_of(d.primary);
  SpeedAccuracyRow row;
  row.task = task.id;
  row.error_measure = error_name(task.type);
  for (size_t l = 0; l < primary.levels.size(); ++l) {
    const double mean_time = tm ? (*tm)[l].mean : NAN;
    double err = am ? (*am)[l].mean : NAN;
    if (task.type == TaskType::identify_letter) err = 1 - err;
    row.levels.push_back({primary.levels[l], mean_time, err});
  }
  row.reading = reading_of(d, task, tr, ar, row);
  row.rmcorr = trial_rmcorr(ctx, task);  // within-participant correlation over trials
  return row;
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

SpeedAccuracyResult section_speed_accuracy(Context& ctx, const TimeResult& time, const AccuracyResult& accuracy) {
  SpeedAccuracyResult r;
  for (const auto& task : ctx.design.tasks) {
    const TestReport* ti = time.of(task.id);
    const TestReport* ai = accuracy.of(task.id);
    if (!ti || !ai) continue;
    r.rows.push_back(task_row(ctx, task, *ti, *ai));
    ++r.tally.tests;  // its repeated-measures correlation
  }
  return r;
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
    panels.push_back(finite ? d.task_label(task) + "|" + error_name(task.type) : "");
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

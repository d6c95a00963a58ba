// Completion time: per task and over all tasks, the participant x condition
// means, the repeated-measures ANOVA (one row per task, the primary factor's
// levels as columns, F and p, published values beside when the protocol
// declares them), the full ANOVA
// tables with sphericity, Holm post-hoc tests for factors with more than two
// levels, a bar chart with SD error bars and the
// per-participant lines. Overall, a participant's condition mean is the mean
// of its per-task means (every task weighs the same, as in a balanced design).
// section_time runs every test into a TimeResult; lay_out_time lays it out
// and computes nothing but the figures' geometry.
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

std::string difference_text(const TestReport& r, int decimals) {
  if (!r.paired) return kDash;
  const auto& t = r.paired->t;
  return fixed(t.mean_difference, decimals) + " [" + fixed(t.ci_low, decimals) + ", " + fixed(t.ci_high, decimals) +
         "]";
}

}  // namespace

// Fig. 9: mean time per task (and overall) per primary level, SD error bars.
PlotSpec bar_plot(const Context& ctx, const std::vector<std::pair<std::string, const TestReport*>>& rows,
                  const std::string& id, const std::string& ylabel) {
  const Design& d = ctx.design;
  const size_t levels = d.factor(d.primary).levels.size();
  std::string dat = "# group";
  for (size_t l = 0; l < levels; ++l) dat += " mean_" + d.factor(d.primary).levels[l] + " sd";
  dat += "\n";
  bool any = false;
  for (const auto& [label, r] : rows) {
    dat += "\"" + label + "\"";
    const auto* m = r->marginal_of(d.primary);
    for (size_t l = 0; l < levels; ++l) {
      const double mean = m ? (*m)[l].mean : NAN, sd = m ? (*m)[l].sd : NAN;
      any = any || std::isfinite(mean);
      // An undefined SD (one participant) draws the bar without an error bar.
      dat += " " + gp_value(mean) + " " + gp_value(std::isfinite(sd) ? sd : 0.0);
    }
    dat += "\n";
  }
  PlotSpec p;
  p.empty = !any;
  p.id = id;
  p.data[id + ".dat"] = dat;
  std::string c = "set style data histogram\nset style histogram errorbars gap 1.5 lw 1.2\n"
                  "set style fill solid 0.85 border rgb '#333333'\nset boxwidth 0.9\n"
                  "set yrange [0:*]\nset ylabel " + gp_quote(ylabel) + "\nset xtics scale 0\n"
                  "set key above center horizontal\nplot ";
  for (size_t l = 0; l < levels; ++l) {
    c += (l ? ", '' " : gp_quote(id + ".dat") + " ") + "using " + std::to_string(2 + 2 * l) + ":" +
         std::to_string(3 + 2 * l) + (l == 0 ? ":xtic(1)" : "") + " title " +
         gp_quote(d.level_label(d.primary, static_cast<int>(l))) + " lc rgb '" + series_color(l) + "'";
  }
  p.commands = c + "\n";
  return p;
}

// Per-participant lines: one panel per scope, x = primary levels, a grey line per participant, the mean in black.
PlotSpec participant_lines(const Context& ctx, const std::vector<std::pair<std::string, const TestReport*>>& rows,
                           const std::string& id, const std::string& ylabel) {
  const Design& d = ctx.design;
  const size_t levels = d.factor(d.primary).levels.size();
  std::string dat;
  int panels = 0;
  for (const auto& [label, r] : rows) {
    const CellMatrix& m = *r->m;
    size_t k = m.factors.size();
    for (size_t i = 0; i < m.factors.size(); ++i)
      if (m.factors[i] == d.primary) k = i;
    const auto* mg = r->marginal_of(d.primary);
    bool finite = false;
    for (size_t l = 0; mg && l < levels; ++l) finite = finite || std::isfinite((*mg)[l].mean);
    if (k == m.factors.size() || !finite) continue;
    dat += "# " + label + ": participants (x = level index, y = marginal mean)\n";
    std::vector<std::vector<double>> per_level;
    for (size_t l = 0; l < levels; ++l) per_level.push_back(marginal(m, k, static_cast<int>(l)));
    for (size_t s = 0; s < m.subjects.size(); ++s) {
      for (size_t l = 0; l < levels; ++l) dat += std::to_string(l) + " " + gp_value(per_level[l][s]) + "\n";
      dat += "\n";
    }
    dat += "\n# " + label + ": mean over the participants of the test\n";
    for (size_t l = 0; l < levels; ++l) dat += std::to_string(l) + " " + gp_value((*mg)[l].mean) + "\n";
    dat += "\n\n";
    ++panels;
  }
  PlotSpec p;
  p.id = id;
  p.empty = panels == 0;
  p.data[id + ".dat"] = dat;
  const int cols = std::min(panels, 3), rows_n = (panels + cols - 1) / std::max(cols, 1);
  p.width = 300 * std::max(cols, 1) + 60;
  p.height = 280 * std::max(rows_n, 1) + 40;
  std::string xt = "set xtics (";
  for (size_t l = 0; l < levels; ++l)
    xt += (l ? ", " : "") + gp_quote(d.factor(d.primary).levels[l]) + " " + std::to_string(l);
  xt += ")\n";
  std::string c = "set multiplot layout " + std::to_string(rows_n) + "," + std::to_string(std::max(cols, 1)) + "\n" +
                  xt + "set xrange [-0.3:" + std::to_string(levels - 1) + ".3]\nset yrange [0:*]\nset ylabel " +
                  gp_quote(ylabel) + "\nunset key\n";
  int panel = 0;
  for (const auto& [label, r] : rows) {
    const auto* mg = r->marginal_of(d.primary);
    bool finite = false;
    for (size_t l = 0; mg && l < levels; ++l) finite = finite || std::isfinite((*mg)[l].mean);
    if (!finite) continue;
    c += "set title " + gp_quote(label) + "\nplot " + gp_quote(id + ".dat") + " index " + std::to_string(2 * panel) +
         " using 1:2 with linespoints lc rgb '#9a9a9a' pt 7 ps 0.5 lw 1, '' index " + std::to_string(2 * panel + 1) +
         " using 1:2 with linespoints lc rgb '#000000' pt 7 ps 1 lw 3\n";
    ++panel;
  }
  p.commands = c;
  return p;
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

// One row per task and one over all tasks, published values beside (when the protocol declares them).
Table time_table(const Design& d, const Rows& rows) {
  const auto& primary = d.factor(d.primary);
  const bool two = primary.levels.size() == 2;
  Table t3;
  t3.id = "table-time";
  t3.caption = "Average completion time (s) per task: mean (SD) over participants, and the repeated-measures ANOVA "
               "of " + primary.name + ".";
  t3.header = {"Task"};
  for (size_t l = 0; l < primary.levels.size(); ++l) t3.header.push_back(d.level_label(d.primary, static_cast<int>(l)));
  t3.header.insert(t3.header.end(), {"n", "F", "df", "p", "ηp²"});
  if (two)
    t3.header.push_back("Δ " + primary.levels[1] + " − " + primary.levels[0] + " [95% CI]");
  const size_t ours = t3.header.size();
  for (const auto& h : d.published_header()) t3.header.push_back(h);
  for (const auto& [label, r] : rows) {
    const TaskInfo* task = d.task(r->scope);
    std::vector<std::string> row = {task ? task->id : label};
    for (const auto& c : primary_cells(*r, d, 2)) row.push_back(c);
    row.push_back(std::to_string(r->kept.size()));
    const stats::Effect* e = r->effect(primary.name);
    for (auto& c : effect_cells(e)) row.push_back(std::move(c));
    if (two) row.push_back(difference_text(*r, 2));
    for (const auto& c : d.published_cells("time", r->scope, 2)) row.push_back(c);
    t3.rows.push_back(std::move(row));
  }
  if (d.reference)
    t3.groups = {{"this study", static_cast<int>(ours)},
                 {d.published_group("time"), static_cast<int>(t3.header.size() - ours)}};
  t3.notes.push_back(d.tasks_note() + " n: participants with a value in every condition of the row (others are "
                     "excluded, listwise). F, df, p: the repeated-measures ANOVA's test of " + primary.name +
                     " (p: the upper tail of F, in APA style; exact values in report.json and tests.csv); ηp²: "
                     "partial eta squared.");
  if (two)
    t3.notes.push_back("Δ: mean paired difference of the participants' means, " + primary.levels[1] + " minus " +
                       primary.levels[0] + ", with its 95% confidence interval (paired t). With two levels, "
                       "sphericity holds trivially and the F test equals the paired t test (F = t²).");
  else
    t3.notes.push_back("df and p are Greenhouse-Geisser corrected where ε < 1 (sphericity is not assumed with " +
                       std::to_string(primary.levels.size()) + " levels).");
  if (d.reference) t3.notes.push_back(d.published_note("time"));
  return t3;
}

// One sentence per row, as a results section would state them.
void time_sentences(const Design& d, Section& s, const Rows& rows) {
  const auto& primary = d.factor(d.primary);
  for (const auto& [label, r] : rows) {
    const stats::Effect* e = r->effect(primary.name);
    if (!e) {
      s.text(label + ": not tested (" + (r->not_tested.empty() ? "no test" : r->not_tested) + ").");
      continue;
    }
    std::string line = (d.task(r->scope) ? d.task_label(*d.task(r->scope)) : label) + ": " + primary.name + " " +
                       effect_sentence(*e);
    if (r->paired && std::isfinite(r->paired->t.mean_difference))
      line += "; " + primary.levels[1] + " − " + primary.levels[0] + ": M = " +
              stats::apa_number(r->paired->t.mean_difference) + " s, 95% CI " +
              stats::apa_interval(r->paired->t.ci_low, r->paired->t.ci_high, false) + ", d_z = " +
              stats::apa_number(r->paired->dz);
    s.text(line + ".");
  }
}

// Full ANOVA tables (over all tasks always; per task when more than one factor varies in it), then post-hoc tests.
void time_anovas(Layout& out, Section& s, const Design& d, const Rows& rows, const TestReport& overall) {
  add_anova(out, s, d, overall, "table-time-anova-overall",
                    "Repeated-measures ANOVA of completion time over all tasks (participant x condition means of the "
                    "per-task means, s).");
  for (const auto& [label, r] : rows) {
    if (r == &overall || r->m->factors.size() < 2) continue;
    add_anova(out, s, d, *r, "table-time-anova-" + r->scope,
              "Repeated-measures ANOVA of completion time, " + label + ".");
  }
  for (const auto& [label, r] : rows)
    for (const auto& [factor, list] : r->posthoc)
      s.add(comparison_table(list, "table-time-posthoc-" + r->scope + "-" + factor,
                             "Post-hoc comparisons of completion time between the levels of " + factor + ", " + label +
                                 ": paired t tests on the participants' marginal means, Holm-corrected.",
                             "s"));
}

// Descriptives of every cell.
Table time_cells_table(const Rows& rows) {
  Table dt;
  dt.id = "table-time-cells";
  dt.caption = "Completion time per task and condition (s): descriptives over the participants' means.";
  dt.header = {"Task", "Condition", "n", "Mean", "SD", "SE", "95% CI", "Median", "Min", "Max"};
  dt.text_columns = 2;
  for (const auto& [label, r] : rows)
    for (size_t c = 0; c < r->m->cells(); ++c) {
      const auto& x = r->cells[c];
      dt.rows.push_back({label, r->m->cell_names[c], std::to_string(x.n), fixed(x.mean, 2), fixed(x.sd, 2),
                         fixed(x.se, 2), "[" + fixed(x.ci_low, 2) + ", " + fixed(x.ci_high, 2) + "]",
                         fixed(x.median, 2), fixed(x.min, 2), fixed(x.max, 2)});
    }
  dt.notes.push_back("Over the participants kept by the test of the row's task (complete cases). 95% CI: mean ± "
                     "t(0.975, n − 1) SE.");
  return dt;
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

void lay_out_time(Layout& out, const Context& ctx, const TimeResult& result) {
  const Design& d = ctx.design;
  const auto& primary = d.factor(d.primary);
  Section s{"time", "Completion time", 2, {}};
  s.text("Completion time is the time from a trial's start to the participant's answer, in seconds. For each "
         "task, every participant contributes one value per condition: the mean of their trials in that "
         "condition. These participant x condition means enter a repeated-measures ANOVA over participants "
         "(with n participants and two levels, F has 1 and n − 1 degrees of freedom). Over all tasks, a participant's "
         "condition value is the mean of their per-task means.");
  const Rows& rows = result.rows;
  const TestReport& overall = *rows.back().second;  // "All tasks", the last row
  s.add(time_table(d, rows));
  time_sentences(d, s, rows);
  out.add_figure(s, bar_plot(ctx, rows, "fig-time", "Completion time (s)"),
                 "Average completion time per task and over all tasks, by " + primary.name +
                     " (error bars: standard deviation over participants" + d.published_cf() + ").");
  out.add_figure(s, participant_lines(ctx, rows, "fig-time-participants", "Completion time (s)"),
                 "Each participant's mean completion time per level of " + primary.name +
                     " (grey lines, one per participant) and the mean over participants (black).");
  time_anovas(out, s, d, rows, overall);

  // Robustness and assumptions (section_time_checks.cpp).
  lay_out_rank_tests(s, ctx, result);
  lay_out_normality(out, s, rows, "time", false);
  if (result.log_rows) lay_out_log_time(out, s, ctx, *result.log_rows);
  s.add(time_cells_table(rows));
  out.doc.sections.push_back(std::move(s));
}

}  // namespace dtlab::report::detail

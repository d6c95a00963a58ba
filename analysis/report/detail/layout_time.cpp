// The layout of the completion-time section (layout.h) from its TimeResult:
// the table per task and over all tasks (the primary factor's levels as
// columns, F and p, published values beside when the protocol declares
// them), one sentence per row, the bar chart with SD error bars (the
// article's Fig. 9) and the per-participant lines, the full ANOVA tables
// with sphericity and post-hoc tests, the rank tests' table, the residuals'
// normality with Q-Q plots, the log-time analysis (--log-time) and the cells'
// descriptives. Computes no statistic: the figures' points come from the
// matrices and tests the result points to.
#include <algorithm>
#include <cmath>

#include "analysis/report/detail/format.h"
#include "analysis/report/detail/layout.h"

namespace dtlab::report::detail {
namespace {

using Rows = TestRows;

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

// R's ppoints(n)[i] (i from 1): (i - a) / (n + 1 - 2a), a = 3/8 for n <= 10, else 1/2.
double ppoint(size_t i, size_t n) {
  const double a = n <= 10 ? 0.375 : 0.5;
  return (static_cast<double>(i) - a) / (static_cast<double>(n) + 1 - 2 * a);
}

// R's quantile(x, p, type = 7) of sorted x.
double quantile7(const std::vector<double>& sorted, double p) {
  const double h = (static_cast<double>(sorted.size()) - 1) * p;
  const size_t lo = static_cast<size_t>(std::floor(h));
  const size_t hi = std::min(lo + 1, sorted.size() - 1);
  return sorted[lo] + (h - static_cast<double>(lo)) * (sorted[hi] - sorted[lo]);
}

// One panel per row: sorted residuals against normal quantiles (qqnorm) and the line through the quartiles (qqline).
PlotSpec qq_plot(const std::vector<std::pair<std::string, const TestReport*>>& rows, const std::string& id,
                 const std::string& ylabel) {
  std::string dat, cmd;
  int panels = 0;
  for (const auto& [label, r] : rows) {
    std::vector<double> y;
    for (double v : r->residuals)
      if (std::isfinite(v)) y.push_back(v);
    if (y.size() < 3) continue;
    std::sort(y.begin(), y.end());
    dat += "# " + label + ": normal quantile, residual\n";
    for (size_t i = 0; i < y.size(); ++i)
      dat += gp_value(stats::normal_quantile(ppoint(i + 1, y.size()))) + " " + gp_value(y[i]) + "\n";
    const double x1 = stats::normal_quantile(0.25), x2 = stats::normal_quantile(0.75);
    const double y1 = quantile7(y, 0.25), y2 = quantile7(y, 0.75), slope = (y2 - y1) / (x2 - x1);
    const double xa = stats::normal_quantile(ppoint(1, y.size())), xb = -xa;
    dat += "\n\n# " + label + ": the line through the quartiles\n" + gp_value(xa) + " " +
           gp_value(y1 + slope * (xa - x1)) + "\n" + gp_value(xb) + " " + gp_value(y1 + slope * (xb - x1)) + "\n\n\n";
    cmd += "set title " + gp_quote(label) + "\nplot " + gp_quote(id + ".dat") + " index " +
           std::to_string(2 * panels) + " using 1:2 with points pt 7 ps 0.6 lc rgb '" + series_color(0) +
           "', '' index " + std::to_string(2 * panels + 1) + " using 1:2 with lines lw 1.5 lc rgb '#555555'\n";
    ++panels;
  }
  PlotSpec p;
  p.id = id;
  p.empty = panels == 0;
  p.data[id + ".dat"] = dat;
  const int cols = std::min(std::max(panels, 1), 3), rows_n = (panels + cols - 1) / cols;
  p.width = 280 * cols + 60;
  p.height = 260 * std::max(rows_n, 1) + 40;
  p.commands = "set multiplot layout " + std::to_string(std::max(rows_n, 1)) + "," + std::to_string(cols) +
               "\nunset key\nset xlabel 'normal quantile'\nset ylabel " + gp_quote(ylabel) + "\n" + cmd + "unset multiplot\n";
  return p;
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

void lay_out_rank_tests(Section& s, const Context& ctx, const TimeResult& result) {
  const Design& d = ctx.design;
  Table t;
  t.id = "table-time-ranks";
  t.caption = "Robustness check: rank tests of the same participant means of completion time, each factor on its "
              "own (no normality or sphericity assumed).";
  t.header = {"Task", "Factor", "Test", "n", "Statistic", "p", "exact p", "Effect size"};
  t.text_columns = 3;
  size_t next = 0;  // the rank tests, in the order run_rank_tests ran them
  for (const auto& [label, r] : result.rows)
    for (size_t k = 0; k < r->m->factors.size(); ++k) {
      const TestReport& x = *result.rank_tests.at(next++);
      std::vector<std::string> row = {label, d.factor(r->m->factors[k]).name};
      if (x.wilcoxon) {
        const auto& w = *x.wilcoxon;
        row.insert(row.end(), {"Wilcoxon signed-rank", std::to_string(w.n),
                               "V = " + stats::apa_number(w.V, w.V == std::floor(w.V) ? 0 : 1), p_text(w.p),
                               p_text(w.p_exact), "r_rb = " + bounded(rank_biserial(w))});
      } else if (x.friedman) {
        const auto& f = *x.friedman;
        row.insert(row.end(), {"Friedman", std::to_string(f.n), "χ²(" + df_text(f.df) + ") = " + fixed(f.Q, 2),
                               p_text(f.p), p_text(f.p_exact), "W = " + bounded(f.kendall_W)});
      } else {
        row.insert(row.end(), {"not tested: " + x.not_tested, std::to_string(x.kept.size()), kDash, kDash, kDash,
                               kDash});
      }
      t.rows.push_back(std::move(row));
    }
  t.notes.push_back("Each factor is tested on the participants' marginal means of its levels (averaged over the "
                    "other factors), so over all tasks the design factors stay apart. Two levels: Wilcoxon "
                    "signed-rank test of the first level against the second (R's wilcox.test(paired = TRUE): exact p "
                    "without ties or zeros and n < 50, else the normal approximation with continuity correction; "
                    "exact p: the exact conditional permutation p where it can be enumerated), r_rb: matched-pairs "
                    "rank-biserial correlation. More levels: Friedman's test, Kendall's W. Interactions have no rank "
                    "test here.");
  s.add(t);
}

void lay_out_normality(Layout& out, Section& s, const TestRows& rows, const std::string& measure, bool log_scale) {
  Table t;
  t.id = "table-" + measure + "-normality";
  t.caption = std::string("Normality of the ANOVA residuals") + (log_scale ? " (log completion time)" : "") +
              ": Shapiro-Wilk test per task and over all tasks.";
  t.header = {"Task", "n", "Residuals", "W", "p"};
  for (const auto& [label, r] : rows) {
    if (!r->normality) continue;
    const auto& sw = *r->normality;
    t.rows.push_back({label, std::to_string(r->kept.size()), std::to_string(sw.n), bounded(sw.W, 3), p_text(sw.p)});
  }
  if (t.rows.empty()) return;
  t.notes.push_back("Residuals of each row's repeated-measures ANOVA, one per participant and cell: value − "
                    "participant mean − cell mean + grand mean. Shapiro-Wilk W with Royston's (1995) p, as R's "
                    "shapiro.test. With two cells a participant's two residuals are opposite. p < .05 says the "
                    "residuals are not normal: read the rank tests beside the ANOVA (and the log-scale analysis, "
                    "`dtlab analyze --log-time`).");
  s.add(t);
  out.add_figure(s, qq_plot(rows, "fig-" + measure + "-qq", log_scale ? "residual (log s)" : "residual (s)"),
                 std::string("Normal Q-Q plots of the ANOVA residuals") + (log_scale ? " of log completion time" : "") +
                     " per task: sorted residuals against normal quantiles (R's "
                 "qqnorm), with the line through the quartiles (qqline).");
}

void lay_out_log_time(Layout& out, Section& s, const Context& ctx, const TestRows& rows) {
  const Design& d = ctx.design;
  const auto& primary = d.factor(d.primary);
  const bool two = primary.levels.size() == 2;
  const TestReport& overall = *rows.back().second;
  s.text("Log completion times (--log-time). Completion times are skewed to the right; on the log scale a "
         "difference between conditions is a ratio of times. The same ANOVAs on the participants' mean log times:");
  Table t;
  t.id = "table-time-log";
  t.caption = "Completion time on the log scale (--log-time): geometric means (s) per level of " + primary.name +
              " and the repeated-measures ANOVA of the participants' mean log times, beside the analysis in seconds.";
  t.header = {"Task"};
  for (size_t l = 0; l < primary.levels.size(); ++l)
    t.header.push_back("GM " + d.level_label(d.primary, static_cast<int>(l)));
  t.header.insert(t.header.end(), {"n", "F", "df", "p", "ηp²"});
  if (two) t.header.push_back("ratio " + primary.levels[1] + " / " + primary.levels[0] + " [95% CI]");
  for (const auto& [label, r] : rows) {
    std::vector<std::string> row = {label};
    const auto* mg = r->marginal_of(d.primary);
    for (size_t l = 0; l < primary.levels.size(); ++l) row.push_back(mg ? fixed(std::exp((*mg)[l].mean), 2) : kDash);
    row.push_back(std::to_string(r->kept.size()));
    const stats::Effect* e = r->effect(primary.name);
    for (auto& c : effect_cells(e)) row.push_back(std::move(c));
    if (two)
      row.push_back(r->paired ? fixed(std::exp(r->paired->t.mean_difference), 2) + " " +
                                    stats::apa_interval(std::exp(r->paired->t.ci_low), std::exp(r->paired->t.ci_high), false)
                              : kDash);
    t.rows.push_back(std::move(row));
  }
  t.notes.push_back("Each participant's value per condition is the mean of the natural logs of their trial times (a "
                    "trial without a positive time is left out); over all tasks, the mean of the per-task means. GM: "
                    "geometric mean, exp of the mean over participants. Ratio: exp of the mean paired difference of "
                    "the logs, with its 95% CI (paired t), e.g. 0.80 = 20% faster. Log times make skewed times more "
                    "symmetric; the analysis in seconds above stays the primary one.");
  s.add(t);
  for (const auto& [label, r] : rows)
    if (const stats::Effect* e = r->effect(primary.name))
      s.text(label + ", log scale: " + primary.name + " " + effect_sentence(*e) + ".");
  add_anova(out, s, d, overall, "table-time-log-anova-overall",
            "Repeated-measures ANOVA of log completion time over all tasks (participant x condition means of the "
            "per-task mean log times).");
  lay_out_normality(out, s, rows, "time-log", true);
}

}  // namespace dtlab::report::detail

// The checks beside the completion-time ANOVAs: rank tests as a robustness
// check (each design factor on its own marginal means: Wilcoxon signed-rank
// for two levels, Friedman for more, so "all tasks" never mixes the factors
// into one), Shapiro-Wilk of each ANOVA's residuals with a Q-Q plot per row,
// and, with --log-time, the ANOVAs of log completion times (reported beside
// the seconds, never instead of them). Statistics come from analysis/stats;
// the run_* functions choose the data and store the tests in the section's
// TimeResult (from which render_data.h writes report.json); the lay_out_*
// functions lay out tables and figures from it and compute no statistic.
#include <algorithm>
#include <cmath>

#include "analysis/report/detail/format.h"
#include "analysis/report/detail/sections.h"

namespace dtlab::report::detail {
namespace {

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

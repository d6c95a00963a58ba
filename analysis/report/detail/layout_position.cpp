// The layout of the position section (layout.h) from its PositionResult:
// the balance of conditions over block positions, per split (block position,
// repetition) a sentence on what its test says, a table of relative and raw
// times and its full ANOVA, the order row's mixed ANOVA (or why it is not
// tested) and a figure of relative time by position. Computes nothing.
#include <algorithm>
#include <cmath>

#include "analysis/report/detail/format.h"
#include "analysis/report/detail/layout.h"

namespace dtlab::report::detail {
namespace {

// The balance's table: a row per protocol condition, a column per block position.
Table balance_table(const Context& ctx, const PositionResult& result, int blocks) {
  Table bt;
  bt.id = "table-balance";
  bt.caption = "Counterbalancing as run: number of participants who had each condition at each block position.";
  bt.header = {"Condition"};
  for (int b = 1; b <= blocks; ++b) bt.header.push_back("block " + std::to_string(b));
  for (const auto& cond : ctx.design.protocol->conditions) {
    std::vector<std::string> row = {cond.name};
    for (int n : result.balance.at(cond.name)) row.push_back(std::to_string(n));
    bt.rows.push_back(row);
  }
  bt.notes.push_back(result.balanced
                         ? "Every condition was at every block position equally often: the order is balanced "
                           "over the participants analysed."
                         : "Not every condition was at every position equally often (participants missing from "
                           "a complete square, or an order scheme that does not balance positions): position "
                           "effects can bias condition means.");
  return bt;
}

// The figure's data of one split: position, mean relative time and its SE per level, then two blank lines.
struct PositionPlot {
  std::string data;
  std::vector<std::pair<std::string, int>> titles;  // (title or "" when nothing to draw, positions)
};

// The table of one split (position, n, relative time, its CI, seconds) and its data in the figure.
Table position_table(const PositionResult::Split& split, PositionPlot& plot) {
  const bool by_block = split.key == "block";
  Table t;
  t.id = by_block ? "table-position-block" : "table-position-repetition";
  t.caption = by_block ? "Completion time by block position in the session (each block is one condition)."
                       : "Completion time by repetition inside a task set (trial 1, 2, ... of a task in a block).";
  t.header = {by_block ? "Block position" : "Repetition", "n", "Relative time, mean (SD)", "95% CI",
              "Time (s), mean (SD)"};
  bool finite = false;
  for (const PositionResult::Level& level : split.levels) {
    const auto& x = level.relative;
    const auto& rd = level.time_s;
    t.rows.push_back({std::to_string(level.position), std::to_string(x.n), mean_sd(x.mean, x.sd, 3),
                      "[" + fixed(x.ci_low, 3) + ", " + fixed(x.ci_high, 3) + "]", mean_sd(rd.mean, rd.sd, 2)});
    plot.data += std::to_string(level.position) + " " + gp_value(x.mean) + " " +
                 gp_value(std::isfinite(x.se) ? x.se : 0.0) + "\n";
    finite = finite || std::isfinite(x.mean);
  }
  plot.data += "\n\n";
  plot.titles.push_back({finite ? (by_block ? "Block position" : "Repetition in the task set") : "",
                         static_cast<int>(split.levels.size())});
  t.notes = test_notes(*split.test);
  return t;
}

// What the test of one split says, as a sentence ("" when there is no effect to speak of).
std::string position_verdict(const std::string& name, const TestReport& r, bool by_block, bool balanced) {
  const stats::Effect* e = r.effect(name);
  std::string verdict = e ? name + ": " + effect_sentence(*e) + ". " : "";
  const double first = r.cells.front().mean, last = r.cells.back().mean;
  if (e && std::isfinite(e->p))
    verdict += e->p_gg < 0.05
                   ? std::string(last < first ? "Participants became faster at later " : "Participants became slower at later ") +
                         (by_block ? "blocks of the session" : "repetitions inside a task set") + " (relative time " +
                         fixed(first, 2) + " at the first, " + fixed(last, 2) + " at the last; " +
                         (last < first ? "practice" : by_block ? "fatigue" : "fatigue, or trials that differ by repetition") +
                         (balanced || !by_block ? "). With a balanced order this adds noise, not bias, to the "
                                                  "condition means."
                                                : "). With an unbalanced order it can bias the condition means.")
                   : "No reliable position effect (relative time " + fixed(first, 2) + " at the first, " +
                         fixed(last, 2) + " at the last).";
  return verdict;
}

// A split's verdict, table and full ANOVA (more than two positions).
void lay_out_split(Layout& out, Section& s, const Design& d, const PositionResult::Split& split, bool balanced,
                   PositionPlot& plot) {
  const bool by_block = split.key == "block";
  const std::string name = by_block ? "block position" : "repetition";
  const TestReport& r = *split.test;
  const Table t = position_table(split, plot);
  const std::string verdict = position_verdict(name, r, by_block, balanced);
  if (!verdict.empty()) s.text(verdict);
  s.add(t);
  if (r.effect(name) && split.levels.size() > 2)
    add_anova(out, s, d, r, by_block ? "table-position-block-anova" : "table-position-repetition-anova",
              std::string("Repeated-measures ANOVA of relative time by ") +
                  (by_block ? "block position." : "repetition inside a task set."));
}

void lay_out_order_row(Layout& out, Section& s, const Design& d, const PositionResult& result) {
  if (const TestReport* kr = result.order_row) {
    s.text("Order rows: the participants' row of the ordering scheme enters a mixed ANOVA of the overall condition "
           "means as a between-subject factor. An order_row main effect says the groups differ in speed overall "
           "(harmless, it is between participants); an interaction of order_row with a within factor says the "
           "effect of that factor depends on the order (asymmetric transfer), which counterbalancing cannot "
           "remove.");
    add_anova(out, s, d, *kr, "table-position-order", "Mixed ANOVA of completion time over all tasks with the order "
                                                      "row as between-subject factor (s).");
    return;
  }
  s.text("Order rows: not tested (" + std::to_string(result.order_rows_seen) + " order row(s) among " +
         std::to_string(result.order_complete) + " complete participants; a between-subject test needs at least two "
         "rows and more participants than rows).");
}

PlotSpec position_figure(const PositionPlot& plot) {
  PlotSpec p;
  p.id = "fig-position";
  p.data["fig-position.dat"] = plot.data;
  p.width = 380 * static_cast<int>(plot.titles.size()) + 40;
  p.height = 320;
  const auto shown = std::count_if(plot.titles.begin(), plot.titles.end(), [](const auto& x) { return !x.first.empty(); });
  std::string cmd = "set multiplot layout 1," + std::to_string(std::max<long>(shown, 1)) +
                    "\nset ylabel 'Relative time (1 = task x condition mean)'\nunset key\nset xtics 1\n";
  int drawn = 0;
  for (size_t i = 0; i < plot.titles.size(); ++i)
    if (!plot.titles[i].first.empty() && ++drawn)
      cmd += "set title " + gp_quote(plot.titles[i].first) + "\nset xlabel " + gp_quote(plot.titles[i].first) +
             "\nset xrange [0.5:" + std::to_string(plot.titles[i].second) + ".5]\nplot 'fig-position.dat' index " +
             std::to_string(i) + " using 1:2:3 with yerrorlines lc rgb '" + series_color(0) + "' pt 7 lw 2\n";
  p.commands = cmd;
  p.empty = drawn == 0;
  return p;
}

}  // namespace

void lay_out_position(Layout& out, const Context& ctx, const PositionResult& result) {
  Section s{"position", "Position effects and counterbalancing", 2, {}};
  s.text("A within-subject design is only as good as its counterbalancing: practice and fatigue must not "
         "favour a condition. Relative time below is a trial's completion time divided by the mean time of its task "
         "and condition over all participants (1 = typical for that task and condition), so that positions holding "
         "different tasks and conditions compare. Per participant, the relative times are averaged per block "
         "position (a block is one condition) and per repetition inside a task set, and tested with "
         "repeated-measures ANOVA.");
  s.add(balance_table(ctx, result, result.blocks));
  PositionPlot plot;
  for (const auto& split : result.splits) lay_out_split(out, s, ctx.design, split, result.balanced, plot);
  lay_out_order_row(out, s, ctx.design, result);
  if (!plot.titles.empty())
    out.add_figure(s, position_figure(plot), "Mean relative completion time by block position and by repetition "
                                             "inside a task set (error bars: standard error over participants).");
  out.doc.sections.push_back(std::move(s));
}

}  // namespace dtlab::report::detail

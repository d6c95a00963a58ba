// Position effects left by the counterbalancing: how the conditions fell on
// the session's block positions (the Latin square's balance, from the data),
// completion time by block position and by repetition inside a task set
// (learning, fatigue), each by RM ANOVA on relative time, and the order row
// as a between-subject factor (a mixed ANOVA: does the effect of the primary
// factor depend on the order the participant had?). Relative time = a
// trial's time / the mean time of its task and condition over all
// participants, so tasks and conditions of different length compare.
// section_position computes the counts and tests into a PositionResult;
// lay_out_position lays them out and computes nothing.
#include <cmath>
#include <map>
#include <set>

#include "analysis/report/detail/format.h"
#include "analysis/report/detail/sections.h"

namespace dtlab::report::detail {

PositionDesign::PositionDesign(const std::string& name, int levels) {
  protocol::Factor f;
  f.name = name;
  for (int l = 1; l <= levels; ++l) f.levels.push_back(std::to_string(l));
  protocol.factors.push_back(f);
  design.protocol = &protocol;
  design.all_factors = {0};
  design.primary = 0;
}

namespace {

std::string condition_of(const Design& d, const TrialRow& t) {
  std::string c;
  for (size_t f = 0; f < t.levels.size(); ++f) c += (f ? "/" : "") + t.levels[f];
  (void)d;
  return c;
}

// Relative time: a trial's time / the mean time of its task and condition over all participants.
struct RelativeTimes {
  std::map<std::string, std::pair<double, int>> cell_mean;  // "task|condition" -> (sum of times, trials)
  int blocks = 0, reps = 0;                                  // the largest block and repetition seen
  const Design* design = nullptr;
  std::optional<double> of(const TrialRow& t) const {
    const auto& cm = cell_mean.at(t.planned.task + "|" + condition_of(*design, t));
    const double mean = cm.first / cm.second;
    return mean > 0 ? std::optional<double>(t.completion_s / mean) : std::nullopt;
  }
};

RelativeTimes relative_times(const Context& ctx) {
  RelativeTimes rt;
  rt.design = &ctx.design;
  for (const auto& t : ctx.data.trials) {
    if (!ctx.analysed(t)) continue;
    auto& cm = rt.cell_mean[t.planned.task + "|" + condition_of(ctx.design, t)];
    cm.first += t.completion_s;
    ++cm.second;
    rt.blocks = std::max(rt.blocks, t.planned.block);
    rt.reps = std::max(rt.reps, t.planned.trial);
  }
  return rt;
}

// Balance: how often each condition was at each block position (counts per condition, and whether they
// are equal, to `result`).
void count_balance(const Context& ctx, int blocks, PositionResult& result) {
  const Design& d = ctx.design;
  std::map<std::string, std::vector<int>> balance;
  std::set<std::pair<std::string, int>> seen;
  for (const auto& t : ctx.data.trials) {
    if (!ctx.analysed(t)) continue;
    const std::string c = condition_of(d, t);
    if (!seen.insert({t.participant + "|" + c, t.planned.block}).second) continue;
    auto& row = balance[c];
    row.resize(static_cast<size_t>(blocks), 0);
    ++row[static_cast<size_t>(t.planned.block - 1)];
  }
  result.balanced = true;
  for (const auto& cond : d.protocol->conditions) {
    const auto it = balance.find(cond.name);
    std::vector<int> counts = it == balance.end() ? std::vector<int>(static_cast<size_t>(blocks), 0) : it->second;
    counts.resize(static_cast<size_t>(blocks), 0);
    for (int n : counts) result.balanced = result.balanced && n == counts[0];
    result.balance[cond.name] = counts;
  }
}

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

// Per participant x position: mean relative time (m) and mean seconds (raw).
struct PositionMatrices {
  CellMatrix m, raw;
};

PositionMatrices position_matrices(const Context& ctx, const RelativeTimes& rt, bool by_block, int levels) {
  PositionMatrices out;
  CellMatrix &m = out.m, &raw = out.raw;
  for (CellMatrix* x : {&m, &raw}) {
    x->factors = {0};
    for (int l = 0; l < levels; ++l) {
      x->cell_levels.push_back({l});
      x->cell_names.push_back(std::to_string(l + 1));
    }
    x->subjects = ctx.subjects;
    x->value.assign(ctx.subjects.size(), std::vector<double>(static_cast<size_t>(levels), NAN));
    x->trials.assign(ctx.subjects.size(), std::vector<int>(static_cast<size_t>(levels), 0));
  }
  std::vector<std::vector<double>> sum(ctx.subjects.size(), std::vector<double>(static_cast<size_t>(levels), 0)),
      rsum = sum;
  for (const auto& t : ctx.data.trials) {
    if (!ctx.analysed(t)) continue;
    const size_t si = static_cast<size_t>(std::find(ctx.subjects.begin(), ctx.subjects.end(), t.participant) -
                                          ctx.subjects.begin());
    const int pos = (by_block ? t.planned.block : t.planned.trial) - 1;
    const auto rel = rt.of(t);
    if (si >= ctx.subjects.size() || pos < 0 || pos >= levels || !rel) continue;
    sum[si][static_cast<size_t>(pos)] += *rel;
    rsum[si][static_cast<size_t>(pos)] += t.completion_s;
    ++m.trials[si][static_cast<size_t>(pos)];
    ++raw.trials[si][static_cast<size_t>(pos)];
  }
  for (size_t si = 0; si < ctx.subjects.size(); ++si)
    for (int l = 0; l < levels; ++l)
      if (const int n = m.trials[si][static_cast<size_t>(l)]) {
        m.value[si][static_cast<size_t>(l)] = sum[si][static_cast<size_t>(l)] / n;
        raw.value[si][static_cast<size_t>(l)] = rsum[si][static_cast<size_t>(l)] / n;
      }
  return out;
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

// One split (block position or repetition): its ANOVA of relative time and its levels.
PositionResult::Split position_split(Context& ctx, const std::string& name, int levels, const RelativeTimes& rt,
                                     Tally& tally) {
  const bool by_block = name == "block position";
  PositionResult::Split split{by_block ? "block" : "repetition", std::make_shared<PositionDesign>(name, levels),
                              nullptr, {}};
  PositionMatrices pm = position_matrices(ctx, rt, by_block, levels);
  const auto& km = ctx.keep(std::move(pm.m));
  const auto& r = ctx.add_test("position", run_rm_anova(km, split.design->design, "relative time", "", name), tally);
  split.test = &r;
  for (int l = 0; l < levels; ++l) {
    std::vector<double> v;
    for (size_t si : r.kept) v.push_back(pm.raw.value[si][static_cast<size_t>(l)]);
    split.levels.push_back({l + 1, r.cells[static_cast<size_t>(l)], stats::describe(v)});
  }
  return split;
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

// The overall test `ov` rerun with the order row as a between-subject factor.
TestReport order_row_report(const TestReport& ov, const Design& d, const std::map<std::string, int>& row_of) {
  auto data = long_data(*ov.m, d, ov.kept, "time");
  stats::Factor between{"order_row", {}};
  for (const auto& subject : data.subject) between.level.push_back("row " + std::to_string(row_of.at(subject)));
  data.between.push_back(between);
  auto res = stats::rm_anova(data);
  TestReport r;
  r.measure = "completion time";
  r.unit = "s";
  r.scope = "overall, by order row";
  r.test = "rm-anova";
  r.m = ov.m;
  r.kept = ov.kept;
  r.excluded = ov.excluded;
  r.cells = ov.cells;  // the same participants and cells as the overall test
  r.marginals = ov.marginals;
  if (res) {
    r.warnings = res->warnings;
    r.anova = std::move(*res);
  } else {
    r.not_tested = res.error().message;
  }
  return r;
}

// Order row as a between-subject factor (mixed ANOVA) on the overall condition means of `ov`: the test to
// result.order_row, or nullptr when there are too few rows or participants (their numbers to `result`).
void order_row_test(Context& ctx, const TestReport& ov, PositionResult& result) {
  std::set<int> rows_seen;
  std::map<std::string, int> row_of;
  for (const auto& p : ctx.data.participants) row_of[p.id] = p.order_row;
  for (size_t si : ov.kept) rows_seen.insert(row_of[ov.m->subjects[si]]);
  result.order_rows_seen = rows_seen.size();
  result.order_complete = ov.kept.size();
  if (rows_seen.size() >= 2 && ov.kept.size() > rows_seen.size())
    result.order_row = &ctx.add_test("position", order_row_report(ov, ctx.design, row_of), result.tally);
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

PositionResult section_position(Context& ctx, const TimeResult& time) {
  const RelativeTimes rt = relative_times(ctx);
  PositionResult result;
  result.blocks = rt.blocks;
  count_balance(ctx, rt.blocks, result);
  for (const auto& [name, levels] : std::vector<std::pair<std::string, int>>{{"block position", rt.blocks},
                                                                             {"repetition", rt.reps}})
    if (levels >= 2) result.splits.push_back(position_split(ctx, name, levels, rt, result.tally));
  if (const TestReport* overall = time.of("overall")) order_row_test(ctx, *overall, result);
  return result;
}

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

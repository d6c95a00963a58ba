// Position effects left by the counterbalancing: how the conditions fell on
// the session's block positions (the Latin square's balance, from the data),
// completion time by block position and by repetition inside a task set
// (learning, fatigue), each by RM ANOVA on relative time, and the order row
// as a between-subject factor (a mixed ANOVA: does the effect of the primary
// factor depend on the order the participant had?). Relative time = a
// trial's time / the mean time of its task and condition over all
// participants, so tasks and conditions of different length compare.
// Computes the PositionResult only; layout_position.cpp lays it out.
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

}  // namespace dtlab::report::detail

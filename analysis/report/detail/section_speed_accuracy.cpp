// Speed and accuracy together: per task and level of the primary factor, the
// mean time and the mean error (lower = better for every measure: relative
// error, error rate = 1 - proportion correct, distance), the differences
// between levels and what they say (a trade-off or not); within
// participants, the repeated-measures correlation of a trial's time with its
// error (does taking longer buy accuracy?). Computes the rows only;
// layout_accuracy.cpp lays them out with a scatter of the participant x
// condition means the time and accuracy tests hold.
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

}  // namespace dtlab::report::detail

// Accuracy, by task type (STUDY.md "Measures"): counting tasks get the
// relative error |answer - truth| / truth per trial (averaged per participant
// x condition) and the aggregated form |sum truths - sum answers| /
// sum truths per participant x condition, each by RM ANOVA, per task and for
// all counting tasks together; letter tasks the proportion correct by
// Friedman; find-unique tasks the Euclidean distance by RM ANOVA. Trials
// without an answer are left out of the error measures and counted in a note.
// Computes the AccuracyResult only; layout_accuracy.cpp lays it out.
#include <cmath>

#include "analysis/report/detail/format.h"
#include "analysis/report/detail/sections.h"

namespace dtlab::report::detail {
namespace {

using protocol::TaskType;

bool is_count(TaskType t) { return t == TaskType::count_targets || t == TaskType::count_kind; }

using Row = AccuracyRow;

// The accuracy tests of every task (and of all counting tasks together), computed before any layout into
// the section's AccuracyResult; what computing them needs beside.
struct AccuracyTests {
  std::vector<const TaskInfo*> count_tasks;
  std::vector<int> count_factors;                 // the factors varying in any counting task
  // Stores a row and its matrix (`measure`: the matrix's name in accuracy_means.csv).
  void add(AccuracyResult& result, Row row, const CellMatrix& m, const std::string& measure) {
    result.tests.push_back(row.r);
    result.means.push_back({&m, measure, row.r->scope});
    result.rows.push_back(std::move(row));
  }
};

// Notes on the task's trials without an answer or with a true count of 0.
void answer_notes(const Context& ctx, const TaskInfo& task, std::vector<std::string>& notes) {
  int unanswered = 0, zero_truth = 0, n = 0;
  for (const auto& t : ctx.data.trials)
    if (t.planned.task == task.id && ctx.analysed(t)) {
      ++n;
      unanswered += t.answer ? 0 : 1;
      const auto truth = count_of(t.truth);
      zero_truth += (truth && *truth == 0) ? 1 : 0;
    }
  if (unanswered)
    notes.push_back(task.id + ": " + std::to_string(unanswered) + " of " + dtlab::count(n, "trial") +
                    " without an answer, left out of its error measures.");
  if (zero_truth)
    notes.push_back(task.id + ": " + dtlab::count(zero_truth, "trial") + " with a true count of 0 have no per-trial "
                    "relative error (division by 0); the aggregated form keeps them.");
}

// The tests of one task by its type: relative errors (counting), proportion correct (letter), distance (find-unique).
void task_tests(Context& ctx, const TaskInfo& task, AccuracyTests& out, AccuracyResult& result) {
  const Design& d = ctx.design;
  auto in_task = [id = task.id](const TrialRow& t) { return t.planned.task == id; };
  if (is_count(task.type)) {
    out.count_tasks.push_back(&task);
    for (int f : task.factors)
      if (std::find(out.count_factors.begin(), out.count_factors.end(), f) == out.count_factors.end())
        out.count_factors.push_back(f);
    const auto& m1 = ctx.cells(task.factors, in_task, mean_of([](const TrialRow& t) { return t.scores.rel_error; }));
    const auto& r1 =
        ctx.add_test("accuracy", run_rm_anova(m1, d, "relative error (per trial)", "", task.id), result.tally);
    result.by_task[task.id] = &r1;
    out.add(result, {task.id, "rel. error, mean of trials", "", &r1, "", 3}, m1, "rel_error_mean");
    const auto& m2 = ctx.cells(task.factors, in_task, aggregated_relative_error());
    const auto& r2 =
        ctx.add_test("accuracy", run_rm_anova(m2, d, "relative error (aggregated)", "", task.id), result.tally);
    out.add(result, {task.id, "rel. error, aggregated", "", &r2, task.id, 3}, m2, "rel_error_aggregated");
    const auto& m3 = ctx.cells(task.factors, in_task, mean_of([](const TrialRow& t) {
                                 const auto& e = t.scores.signed_error;
                                 return e ? std::optional<double>(static_cast<double>(*e)) : std::nullopt;
                               }));
    result.means.push_back({&m3, "signed_error_mean", task.id});
  } else if (task.type == TaskType::identify_letter) {
    const auto& m = ctx.cells(task.factors, in_task, proportion_correct());
    const auto& r = ctx.add_test(
        "accuracy", run_friedman(m, d, "proportion correct", "", task.id, ctx.options.seed), result.tally);
    result.by_task[task.id] = &r;
    out.add(result, {task.id, "proportion correct", "", &r, task.id, 3}, m, "proportion_correct");
  } else if (task.type == TaskType::find_unique) {
    const auto& m = ctx.cells(task.factors, in_task, mean_of([](const TrialRow& t) { return t.scores.distance; }));
    const auto& r = ctx.add_test("accuracy", run_rm_anova(m, d, "distance", "world units", task.id), result.tally);
    result.by_task[task.id] = &r;
    out.add(result, {task.id, "distance (world units)", "world units", &r, task.id, 2}, m, "distance_mean");
  }
}

// The relative errors of all counting tasks together (when there are several).
void pooled_count_tests(Context& ctx, AccuracyTests& out, AccuracyResult& result) {
  const Design& d = ctx.design;
  std::string ids;
  for (const auto* t : out.count_tasks) ids += (ids.empty() ? "" : "+") + t->id;
  auto in_count = [&out](const TrialRow& t) {
    for (const auto* c : out.count_tasks)
      if (c->id == t.planned.task) return true;
    return false;
  };
  std::sort(out.count_factors.begin(), out.count_factors.end());
  const auto& m1 =
      ctx.cells(out.count_factors, in_count, mean_of([](const TrialRow& t) { return t.scores.rel_error; }));
  out.add(result, {ids, "rel. error, mean of trials", "",
          &ctx.add_test("accuracy", run_rm_anova(m1, d, "relative error (per trial)", "", ids), result.tally), "", 3},
          m1, "rel_error_mean");
  const auto& m2 = ctx.cells(out.count_factors, in_count, aggregated_relative_error());
  out.add(result, {ids, "rel. error, aggregated", "",
          &ctx.add_test("accuracy", run_rm_anova(m2, d, "relative error (aggregated)", "", ids), result.tally),
          "counting", 3}, m2, "rel_error_aggregated");
}

void run_accuracy_tests(Context& ctx, AccuracyResult& result) {
  AccuracyTests out;
  for (const auto& task : ctx.design.tasks) {
    answer_notes(ctx, task, result.notes);
    task_tests(ctx, task, out, result);
  }
  if (out.count_tasks.size() > 1) pooled_count_tests(ctx, out, result);
}

}  // namespace

AccuracyResult accuracy_tests(Context& ctx) {
  AccuracyResult result;
  run_accuracy_tests(ctx, result);
  return result;
}

AccuracyResult section_errors(Context& ctx) { return accuracy_tests(ctx); }

}  // namespace dtlab::report::detail

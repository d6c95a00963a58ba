// Accuracy, by task type (STUDY.md "Measures"): counting tasks get the
// relative error |answer - truth| / truth per trial (averaged per participant
// x condition) and the aggregated form |sum truths - sum answers| /
// sum truths per participant x condition, each by RM ANOVA, per task and for
// all counting tasks together; letter tasks the proportion correct by
// Friedman; find-unique tasks the Euclidean distance by RM ANOVA. Trials
// without an answer are left out of the error measures and counted in a note.
// section_errors runs the tests into an AccuracyResult; lay_out_accuracy lays
// it out and computes nothing.
#include <cmath>

#include "analysis/report/detail/format.h"
#include "analysis/report/detail/sections.h"

namespace dtlab::report::detail {
namespace {

using protocol::TaskType;

bool is_count(TaskType t) { return t == TaskType::count_targets || t == TaskType::count_kind; }

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
  if (primary.levels.size() == 2) {
    cells.push_back(r.paired ? fixed(r.paired->t.mean_difference, row.decimals) + " [" +
                                   fixed(r.paired->t.ci_low, row.decimals) + ", " +
                                   fixed(r.paired->t.ci_high, row.decimals) + "]"
                             : kDash);
  }
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

}  // namespace

AccuracyResult accuracy_tests(Context& ctx) {
  AccuracyResult result;
  run_accuracy_tests(ctx, result);
  return result;
}

AccuracyResult section_errors(Context& ctx) { return accuracy_tests(ctx); }

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

}  // namespace dtlab::report::detail

// The aggregation every test in the report starts from: per participant x
// cell (a combination of levels of some factors), one number computed from
// that participant's trials in the cell (by default the mean). This is how
// the article's F(1,15) arise: per participant x condition means of the
// trials, then a repeated-measures test over participants.
// Guarantees: cells are in protocol level order (first factor slowest);
// subjects in enrollment order; a cell with no usable trial is NaN (missing),
// and complete() / missing_notes() say which participants a repeated-measures
// test must leave out (listwise deletion) and why. No I/O, no statistics.
#pragma once
#include <functional>
#include <string>
#include <vector>

#include "analysis/report/detail/report_design.h"
#include "analysis/report/detail/study_data.h"
#include "analysis/stats/long_data.h"

namespace dtlab::report::detail {

using TrialFilter = std::function<bool(const TrialRow&)>;
// One value from a participant's trials in a cell; NaN = not computable (missing).
using Reducer = std::function<double(const std::vector<const TrialRow*>&)>;

struct CellMatrix {
  std::vector<int> factors;                   // design factor indices, protocol order
  std::vector<std::vector<int>> cell_levels;  // per cell: level index per entry of `factors`
  std::vector<std::string> cell_names;        // "off/abstract" (levels joined by '/'); "all" with no factor
  std::vector<std::string> subjects;          // participant ids, enrollment order
  std::vector<std::vector<double>> value;     // value[s][c]; NaN = missing
  std::vector<std::vector<int>> trials;       // trials[s][c]: trials in the cell (before the reducer)

  size_t cells() const { return cell_names.size(); }
  // Subjects with every cell present (the ones a repeated-measures test keeps).
  std::vector<size_t> complete() const;
  // One note per incomplete subject: "P07 (off/walkthrough: no trial)", or "... : no value" when
  // trials exist but the reducer found nothing to compute (e.g. no answer given).
  std::vector<std::string> missing_notes() const;
  // Level index of factor entry `k` (position in `factors`) of cell c.
  int level(size_t c, size_t k) const { return cell_levels[c][k]; }
};

// Per participant (all of `subjects`) x cell of `factors`: reduce() of the
// trials that pass `include`. Trials with an unknown level are skipped.
CellMatrix aggregate(const StudyData& data, const Design& design, const std::vector<std::string>& subjects,
                     const std::vector<int>& factors, const TrialFilter& include, const Reducer& reduce);

// Per subject, the mean over the cells holding level `level` of factor entry
// k (a marginal mean); NaN when any of those cells is missing.
std::vector<double> marginal(const CellMatrix& m, size_t k, int level);

// The matrix of factor entry k alone: per subject, its marginal means (one cell per level of
// that factor; NaN where a cell averaged over is missing; trials summed).
CellMatrix marginal_matrix(const CellMatrix& m, size_t k);

// The rows of `kept` subjects as long data for analysis/stats (one row per
// subject x cell, levels named by the protocol), dv named `dv`.
stats::LongData long_data(const CellMatrix& m, const Design& design, const std::vector<size_t>& kept,
                          const std::string& dv);

// --- reducers -----------------------------------------------------------------------
// Mean of a per-trial value over the trials where it is present.
Reducer mean_of(std::function<std::optional<double>(const TrialRow&)> field);
// Mean over tasks of the per-task means of `field` (every task weighs the same).
Reducer mean_of_task_means(std::function<std::optional<double>(const TrialRow&)> field);
// The article's aggregated relative error |sum of truths - sum of answers| / sum of truths
// over the answered count trials; NaN when no answered trial or the truths sum to 0.
Reducer aggregated_relative_error();
// Share of answered letter trials that were correct.
Reducer proportion_correct();

}  // namespace dtlab::report::detail

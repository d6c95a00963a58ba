// A short summary of a study database for `dtlab simulate` and `dtlab demo`:
// per task and level of the rendering factor, the number of trials, the mean
// and SD of the completion time and the task's accuracy measure, read through
// the store's typed reader (one snapshot). Practice trials and excluded trials
// are left out. Descriptive only: the statistics live in `dtlab analyze`
// (analysis/report). Never writes to the database.
#pragma once
#include <string>
#include <vector>

#include "study/common/error.h"
#include "study/store/read.h"

namespace dtlab::sim {

struct SummaryCell {
  std::string task;        // task id
  std::string rendering;   // level of the rendering factor ("" if the protocol has none)
  int trials = 0;          // recorded, non-practice trials
  double time_mean = 0, time_sd = 0;  // completion_time_s (sd: n - 1; 0 when n < 2)
  std::string measure;     // "rel_error", "correct" or "distance"
  double measure_mean = 0; // mean over the trials that have it
  int measured = 0;        // trials that have it
};

struct Summary {
  int participants = 0;    // with at least one recorded trial
  long long trials = 0;    // recorded, non-practice, not excluded
  long long excluded = 0;  // recorded, non-practice trials left out because they are excluded
  std::vector<SummaryCell> cells;  // task order of first appearance, then rendering level
};

// `rendering_factor`: the factor holding the rendering level (e.g. "transparency"); may be "".
Result<Summary> summarize(store::StudyReader& reader, const std::string& rendering_factor);

// The summary as an aligned text table.
std::string format_summary(const Summary& s);

}  // namespace dtlab::sim

// The long-format table every test in this library takes: one row per
// observation with a subject id, within-subject factor levels, between-subject
// factor levels and the dependent variable. Built from a CSV (long, or wide
// with one column per condition) or directly from vectors by a caller such as
// the study report. Guarantees: every dv cell is a finite number or missing
// (empty or "NA"); text, "NaN" or "Inf" in the dv column is an Error naming
// file, line and column; ids and levels are non-empty. Never reorders rows.
#pragma once
#include <string>
#include <vector>

#include "analysis/stats/csv.h"
#include "analysis/stats/measurements.h"
#include "study/common/error.h"

namespace dtlab::stats {

// A categorical column: level[i] is the label on row i.
struct Factor {
  std::string name;
  std::vector<std::string> level;
};

// What several rows for one subject and cell mean: by default an error (the
// table is meant to hold one value per subject and cell, e.g. per-participant
// means); `mean` or `median` reduce them to one value (afex's fun_aggregate).
enum class Aggregate { none, mean, median };

struct LongData {
  std::string source;                // file name used in messages; empty for in-memory data
  std::vector<int> line;             // line[i]: 1-based source line of row i, 0 if unknown (may be empty)
  std::vector<std::string> subject;  // subject id per row; empty when the design has no subjects (one-way ANOVA)
  std::vector<Factor> within;        // within-subject factors
  std::vector<Factor> between;       // between-subject factors
  std::string dv_name = "y";         // name of the dependent variable
  Measurements dv;                   // one per row; NaN = missing
  Aggregate aggregate = Aggregate::none;  // repeated subject x cell rows: error, mean or median

  size_t rows() const { return dv.size(); }
  // "file:line" of row i for messages ("row i+1" when there is no source).
  std::string where(size_t row) const;
};

// Which CSV column plays which part in a long-format table.
struct ColumnRoles {
  std::string dv;                    // required
  std::string subject;               // required for repeated measures; empty for one-way ANOVA
  std::vector<std::string> within;   // within-subject factor columns
  std::vector<std::string> between;  // between-subject factor columns
};

// Long format: one row per observation. Errors name file, line, column.
Result<LongData> long_data_from_csv(const CsvTable& table, const ColumnRoles& roles);

// Wide format: one row per subject (or, for a between design, per row of
// groups), one column per condition.
struct WideRoles {
  std::string subject;                // optional id column; default id is "line N"
  std::vector<std::string> between;   // optional between-subject factor columns
  std::vector<std::string> conditions;  // condition columns; empty = every column not named above
  std::string factor = "condition";   // name given to the factor the condition columns form
  bool conditions_are_groups = false; // true: each cell is its own observation (one-way ANOVA)
  std::string dv = "y";               // name given to the dependent variable
};
Result<LongData> long_data_from_wide_csv(const CsvTable& table, const WideRoles& roles);

// True for the cells read as missing: "" and "NA" (R's read.csv default).
bool is_missing_token(const std::string& cell);

}  // namespace dtlab::stats

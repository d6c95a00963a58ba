// Which rows of a CSV table a test sees: `COL=VALUE` / `COL!=VALUE`
// conditions (all must hold), practice trials, and rows marked excluded.
// Defaults that protect a dtlab export (`dtlab export` writes the columns
// `practice` (1 for practice trials) and `excluded` (empty, or the reason a
// participant or trial was excluded)):
//   - rows whose `excluded` cell is non-empty (and not NA) are left out
//     whenever that column exists, unless with_excluded;
//   - practice rows are left out when the table is a dtlab export (it has
//     the columns practice, trial_seed and protocol_sha256) or when asked
//     (Practice::exclude), and kept when Practice::include.
//   Practice cells read 1/0, true/false, TRUE/FALSE, yes/no; empty or NA = not
//   practice; anything else is an Error naming file, line and column.
// Every row left out is counted by reason, so the caller can say what it did.
// Comparisons are on the cell text exactly as written (no trimming inside
// quotes, no number conversion). Never reorders the rows that stay.
#pragma once
#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

#include "analysis/stats/csv.h"
#include "study/common/error.h"

namespace dtlab::stats {

struct RowCondition {
  std::string column, value;
  bool equal = true;  // COL=VALUE (true) or COL!=VALUE (false)
};

// Parses "COL=VALUE" or "COL!=VALUE" (split at the first '='; VALUE may be empty).
Result<RowCondition> parse_row_condition(std::string_view text);

enum class Practice { automatic, exclude, include };

struct RowSelection {
  std::vector<RowCondition> where;
  Practice practice = Practice::automatic;
  bool with_excluded = false;  // keep rows with a non-empty `excluded` cell
};

struct SelectionReport {
  std::size_t read = 0, kept = 0;
  std::size_t where_left_out = 0, practice_left_out = 0, excluded_left_out = 0;
  bool dtlab_export = false;       // the table has dtlab export's columns
  bool practice_column = false, excluded_column = false;
  bool practice_excluded = false;  // practice rows were left out (by default or on request)
  std::vector<std::string> notes;  // one sentence per rule that applied, naming the option that undoes it
};

// The header's column names for a message ("a, b, c"; the first 40, then "and N more").
std::string column_list(const CsvTable& table);

// Removes from `table` the rows the selection leaves out; an unknown column or
// an unreadable practice cell is an Error (file, line, column).
Result<SelectionReport> select_rows(CsvTable& table, const RowSelection& selection);

}  // namespace dtlab::stats

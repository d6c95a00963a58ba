// `dtlab export`: the trial_table view of a study database as a tidy CSV
// file, one row per recorded trial (docs/store.md, "Export"). Opens the
// database read-only and never modifies it; the CSV is what R's read.csv and
// pandas.read_csv read without options: a header row, RFC 4180 quoting, '.'
// decimals, NA for missing values, ISO-8601 UTC timestamps, LF line ends.
#pragma once
#include <ostream>
#include <string>
#include <vector>

#include "study/common/error.h"

namespace dtlab::store {

struct ExportSummary {
  std::vector<std::string> columns;  // the header, in order
  long long rows = 0;                // data rows written
};

// Writes every recorded trial of the database at `db_path` to `out`, ordered
// by enrollment index, then position. Errors name the file; on error `out`
// may hold a partial table (callers write to a temporary file and rename).
Result<ExportSummary> export_trials_csv(const std::string& db_path, std::ostream& out);

// One CSV field as written by the export: quoted only when it holds a comma,
// a double quote, CR or LF (quotes doubled); "NA" for a missing value.
std::string csv_field(const std::string& text);

}  // namespace dtlab::store

// `dtlab export`: the recorded trials of a study database as a tidy CSV
// file, one row per recorded trial of every participant who did not withdraw
// their consent (README, "Study database and export"), with the demographics
// each participant was enrolled with, read through the store's StudyReader
// (one snapshot) and never modifying the database. The CSV is what R's read.csv and pandas.read_csv read without
// options: a header row, RFC 4180 quoting, '.' decimals, NA for missing
// values, ISO-8601 UTC timestamps, LF line ends. Its columns equal the
// trial_table view's, which SQLite clients read (a test holds them equal).
#pragma once
#include <ostream>
#include <string>
#include <vector>

#include "study/common/error.h"
#include "study/store/read.h"

namespace dtlab::store {

struct ExportSummary {
  std::vector<std::string> columns;  // the header, in order
  long long rows = 0;                // data rows written
  long long excluded = 0;            // rows whose `excluded` column holds a reason
  long long withdrawn = 0;           // participants who withdrew (declined or later): none of their rows written
  long long withdrawn_rows = 0;      // recorded trials of theirs left out
};

// The export's column of a demographic field: "demo_" + field (e.g. demo_age). No fixed column
// starts with "demo_" and Store::open refuses a factor that does, so it never clashes.
std::string demographic_column(const std::string& field);

// The export's columns: the fixed ones, with one column per factor named in any protocol
// revision (order of first appearance) after "block", then design_revision and excluded, then
// one demographic column per field any participant of `ledger` was enrolled with (in order of
// first appearance: by enrollment index, then in the order stored).
std::vector<std::string> export_columns(const std::vector<Revision>& revisions, const std::vector<LedgerEntry>& ledger);

// The columns that hold what was measured while the study ran (wall-clock stamps and frame
// times) and so differ between two runs of the same design with the same answers, and the
// session's row id. Everything else in a row is fixed by the protocol, seed and answers.
const std::vector<std::string>& measured_columns();

// Writes every recorded trial to `out`, ordered by enrollment index, then position, leaving out
// the participants who withdrew their consent (counted in the summary). Errors
// name the file; on error `out` may hold a partial table (callers write to a temporary file
// and rename, e.g. write_file_atomically in study/common).
Result<ExportSummary> export_trials_csv(StudyReader& reader, std::ostream& out);
// The same with the trials already read from `reader` (reader.trials()), so a caller that needs them too reads once.
Result<ExportSummary> export_trials_csv(StudyReader& reader, const std::vector<TrialRow>& trials, std::ostream& out);
// The same for the database at `db_path`, opened read-only with `options`.
Result<ExportSummary> export_trials_csv(const std::string& db_path, std::ostream& out, ReadOptions options = {});

// One CSV field as written by the export: quoted only when it holds a comma,
// a double quote, CR or LF (quotes doubled); "NA" for a missing value.
std::string csv_field(const std::string& text);

}  // namespace dtlab::store

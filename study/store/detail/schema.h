// The migrations that build the study database's schema on either engine,
// plus the `trial_table` view whose columns are the export columns.
// docs/store.md is the reference for every table, constraint and trigger
// defined here. Only the store's open and copy call these, inside their
// write transaction; nothing here commits.
#pragma once
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "study/common/error.h"
#include "study/store/detail/db.h"
#include "study/store/store.h"

namespace dtlab::store::detail {

// Stored values read back: a seed column (decimal text, 1-20 digits by the schema's CHECK) and a
// session status ("running", "finished", "abandoned", as to_string(SessionStatus) writes them).
std::uint64_t parse_seed(const std::string& s);
SessionStatus parse_status(const std::string& s);

// The fixed columns of trial_table, in order; the factor columns go after
// "block", the demographic columns (kDemographicPrefix + field) after the last. A factor may
// not be named like one of these, nor start with kDemographicPrefix (case-insensitive).
const std::vector<std::string>& fixed_trial_columns_before_factors();
const std::vector<std::string>& fixed_trial_columns_after_factors();
inline constexpr const char* kDemographicPrefix = "demo_";

// The demographic fields the ledger records, each once, in order of first appearance: by
// enrollment index, then in each participant's stored order. The export's demographic columns
// (export.h) follow the same rule from the reader's ledger.
Result<std::vector<std::string>> demographic_fields(Db& db);

// The order session_displays rows are read in, the same on both engines (neither has a rowid the
// other keeps): by session, the time recorded (distinct within a session: Store::record_display
// stamps a display recorded in the same millisecond as the last one a millisecond later), then
// every other column.
inline constexpr const char* kDisplayOrder =
    "session_id, recorded_at, kind, width, height, refresh_hz IS NULL, refresh_hz, renderer, monitor";

// Highest migration applied (0 for a database without the migrations table).
Result<int> applied_schema_version(Db& db);

// Every table the migrations up to `version` create (read from their SQL text, so the list cannot
// drift from the schema), and schema_migrations: a table missing from a database of that version is
// damage. Refused when the database is opened (kind invalid_input), before any command reads or
// writes, instead of by the first query that needs the table.
Status check_tables(Db& db, int version);

// A schema_migrations row as another database recorded it (dtlab copy keeps the history).
struct AppliedMigration {
  std::string description, applied_at, software_version;
};

// Applies every migration above `from` up to kSchemaVersion, each recorded
// in schema_migrations (with the row of `history` for its version, if any,
// else now and `software_version`). Must run inside a write transaction.
Status migrate(Db& db, int from, const std::string& software_version,
               const std::map<int, AppliedMigration>& history = {});

// (Re)creates the trial_table view with one column per factor named in any
// study of the database, in order of first appearance, and one per demographic field the ledger
// records (demographic_fields); withdrawn participants' trials are left out, as in the export.
// Inside a transaction; needs schema v4.
Status create_trial_table_view(Db& db);

}  // namespace dtlab::store::detail

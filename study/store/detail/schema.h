// Schema v1 of the study database and the migrations that build it, plus the
// `trial_table` view whose columns are the export columns. docs/store.md is
// the reference for every table, constraint and trigger defined here. Only
// store.cpp calls these, inside its open transaction; nothing here commits.
#pragma once
#include <string>
#include <vector>

#include "study/common/error.h"
#include "study/store/detail/sqlite.h"

namespace dtlab::store::detail {

// The fixed columns of trial_table, in order; the factor columns go after
// "block". A factor may not be named like one of these (case-insensitive).
const std::vector<std::string>& fixed_trial_columns_before_factors();
const std::vector<std::string>& fixed_trial_columns_after_factors();

// Highest migration applied (0 for a database without the migrations table).
Result<int> applied_schema_version(Db& db);

// Applies every migration above `from` up to kSchemaVersion, each recorded
// in schema_migrations. Must run inside a write transaction.
Status migrate(Db& db, int from, const std::string& software_version);

// (Re)creates the trial_table view with one column per factor named in any
// study of the database, in order of first appearance. Inside a transaction.
Status create_trial_table_view(Db& db);

}  // namespace dtlab::store::detail

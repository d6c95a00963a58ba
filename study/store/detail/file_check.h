// The one check every opener of a study database makes (Store::open before
// and inside its first write transaction, StudyReader::open): is this a dtlab
// database of a schema version this build reads, or a new empty file? The
// header and the schema version are read in ONE read transaction, so a file
// being created by another process at that moment reads as empty or as
// whole, never half made. Never writes.
#pragma once
#include <cstdint>
#include <string>

#include "study/common/error.h"
#include "study/store/detail/sqlite.h"

namespace dtlab::store::detail {

struct FileState {
  bool empty = true;                // no schema object at all: a new file
  std::int64_t application_id = 0;  // PRAGMA application_id
  int user_version = 0;             // PRAGMA user_version
  int migrations = 0;               // max(schema_migrations.version); 0 without that table
};

// Reads the state; `in_transaction`: the caller holds a transaction already (no BEGIN here).
Result<FileState> inspect(Db& db, bool in_transaction = false);

// Refuses a non-dtlab file and a schema newer than kSchemaVersion (by user_version or by
// schema_migrations, whichever says more); an empty file passes only when `allow_empty`.
Status check_dtlab(const std::string& path, const FileState& s, bool allow_empty);

}  // namespace dtlab::store::detail

// The one check every opener of a study database makes (Store::open before
// and inside its first write transaction, StudyReader::open, dtlab copy): is
// this a dtlab database of a schema version this build reads, or a new empty
// one? The state is read by Connection::inspect in ONE snapshot, so a
// database being created by another process at that moment reads as empty or
// as whole, never half made. Never writes.
#pragma once
#include <string>

#include "study/common/error.h"
#include "study/store/detail/db.h"

namespace dtlab::store::detail {

// Reads the state; `in_transaction`: the caller holds a transaction already.
inline Result<FileState> inspect(Db& db, bool in_transaction = false) { return db.conn().inspect(in_transaction); }

// Refuses a non-dtlab database and a schema newer than kSchemaVersion (by user_version or by
// schema_migrations, whichever says more); an empty one (or a PostgreSQL schema that does not
// exist yet) passes only when `allow_empty`.
Status check_dtlab(const Db& db, const FileState& s, bool allow_empty);

}  // namespace dtlab::store::detail

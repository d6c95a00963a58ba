// Read-only access for the commands that only look (export, plan --db): opens
// an existing file without SQLITE_OPEN_CREATE and checks that it is a dtlab
// database of a schema version this build reads. Never creates, migrates or
// writes content (PRAGMA query_only); as the last connection to close it
// checkpoints the write-ahead log and removes -wal and -shm, as writers do.
#pragma once
#include <string>

#include "study/common/error.h"
#include "study/store/detail/sqlite.h"

namespace dtlab::store::detail {

// The open connection, or an Error naming `path` and what it expected.
Result<Db> open_readonly_dtlab(const std::string& path);

}  // namespace dtlab::store::detail

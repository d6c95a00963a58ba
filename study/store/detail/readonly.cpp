// Read-only opening of a dtlab database; see readonly.h.
#include "study/store/detail/readonly.h"

#include "study/store/store.h"

namespace dtlab::store::detail {

Result<Db> open_readonly_dtlab(const std::string& path) {
  // Read-write without CREATE, made read-only by query_only: a connection opened with
  // SQLITE_OPEN_READONLY cannot checkpoint, so when it is the last one to close a WAL database it
  // leaves the -wal and -shm files behind (even ones it created itself just to read); this one
  // checkpoints committed pages and removes both like any writer. A write-protected file still
  // opens (SQLite then falls back to read-only by itself).
  auto opened = Db::open(path, SQLITE_OPEN_READWRITE);
  if (!opened) return opened.error();
  Db& db = *opened;
  sqlite3_busy_timeout(db.get(), 10000);
  if (auto s = db.exec("PRAGMA query_only = ON", "making the connection read-only"); !s) return s.error();
  auto app_id = db.query_int("PRAGMA application_id", "reading the file header");
  if (!app_id) {
    if (sqlite3_extended_errcode(db.get()) == SQLITE_NOTADB)
      return Error{path, 0, 0, "", "not an SQLite database; expected a dtlab study database"};
    return app_id.error();
  }
  if (app_id->value_or(0) != kApplicationId)
    return Error{path, 0, 0, "", "not a dtlab study database (no dtlab application_id)"};
  auto version = db.query_int("PRAGMA user_version", "reading the schema version");
  if (!version) return version.error();
  if (version->value_or(0) > kSchemaVersion)
    return Error{path, 0, 0, "schema_migrations.version",
                 "schema version " + std::to_string(version->value_or(0)) +
                     " was written by a newer dtlab; this build reads schema versions up to " +
                     std::to_string(kSchemaVersion)};
  return std::move(*opened);
}

}  // namespace dtlab::store::detail

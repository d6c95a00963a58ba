// Inspecting a database file before using it; see file_check.h.
#include "study/store/detail/file_check.h"

#include <cstdio>

#include "study/store/store.h"

namespace dtlab::store::detail {
namespace {

std::string hex32(std::int64_t v) {
  char buf[16];
  std::snprintf(buf, sizeof buf, "0x%08x", static_cast<unsigned>(static_cast<std::uint32_t>(v)));
  return buf;
}

Result<FileState> read_state(Db& db) {
  FileState s;
  auto app_id = db.query_int("PRAGMA application_id", "reading the file header");
  if (!app_id) {
    if (sqlite3_extended_errcode(db.get()) == SQLITE_NOTADB)
      return Error{db.path(), 0, 0, "", "not an SQLite database; expected a dtlab study database"};
    return app_id.error();
  }
  s.application_id = app_id->value_or(0);
  auto objects = db.query_int("SELECT count(*) FROM sqlite_schema", "reading the schema");
  if (!objects) return objects.error();
  s.empty = objects->value_or(0) == 0;
  auto version = db.query_int("PRAGMA user_version", "reading the schema version");
  if (!version) return version.error();
  s.user_version = static_cast<int>(version->value_or(0));
  auto has = db.query_int("SELECT count(*) FROM sqlite_schema WHERE type = 'table' AND name = 'schema_migrations'",
                          "reading the schema");
  if (!has) return has.error();
  if (has->value_or(0) > 0) {
    auto m = db.query_int("SELECT max(version) FROM schema_migrations", "reading the schema version");
    if (!m) return m.error();
    s.migrations = static_cast<int>(m->value_or(0));
  }
  return s;
}

}  // namespace

Result<FileState> inspect(Db& db, bool in_transaction) {
  if (in_transaction) return read_state(db);
  // BEGIN (deferred) + the first read fix one snapshot for all four reads.
  if (auto b = db.exec("BEGIN", "starting a read transaction"); !b) return b.error();
  auto s = read_state(db);
  db.exec("COMMIT", "ending the read transaction");  // a read-only transaction: nothing to lose if it fails
  return s;
}

Status check_dtlab(const std::string& path, const FileState& s, bool allow_empty) {
  if (s.application_id == 0 && s.empty) {
    if (allow_empty) return {};
    return Error{path, 0, 0, "", "an empty SQLite file, not a dtlab study database (no session was ever started in it)"};
  }
  if (s.application_id != kApplicationId)
    return Error{path, 0, 0, "",
                 "not a dtlab study database (application_id " + hex32(s.application_id) + ", expected " +
                     hex32(kApplicationId) + "); refusing to use it"};
  const int version = std::max(s.user_version, s.migrations);
  if (version > kSchemaVersion)
    return Error{path, 0, 0, "schema_migrations.version",
                 "schema version " + std::to_string(version) + " was written by a newer dtlab; this build reads schema "
                 "versions up to " + std::to_string(kSchemaVersion),
                 ErrorKind::conflict};
  return {};
}

}  // namespace dtlab::store::detail

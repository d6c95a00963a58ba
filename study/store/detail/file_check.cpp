// Judging what Connection::inspect found; see file_check.h.
#include "study/store/detail/file_check.h"

#include <algorithm>
#include <cstdio>

#include "study/store/store.h"

namespace dtlab::store::detail {
namespace {

std::string hex32(std::int64_t v) {
  char buf[16];
  std::snprintf(buf, sizeof buf, "0x%08x", static_cast<unsigned>(static_cast<std::uint32_t>(v)));
  return buf;
}

}  // namespace

Status check_dtlab(const Db& db, const FileState& s, bool allow_empty) {
  const std::string& path = db.path();
  const bool server = db.backend() == Backend::postgresql;
  if (s.application_id == 0 && s.empty) {
    if (allow_empty) return {};
    if (server && !s.exists)
      return Error{path, 0, 0, "schema", "no study here: the schema does not exist (dtlab simulate or run creates it)",
                   ErrorKind::not_found};
    return Error{path, 0, 0, "",
                 server ? "an empty schema, not a dtlab study database (no session was ever started in it)"
                        : "an empty SQLite file, not a dtlab study database (no session was ever started in it)"};
  }
  if (s.application_id != kApplicationId)
    return Error{path, 0, 0, "",
                 server ? "not a dtlab study database: the schema holds other tables (no dtlab_header); "
                          "refusing to use it; name another schema (?schema=NAME) or database"
                        : "not a dtlab study database (application_id " + hex32(s.application_id) + ", expected " +
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

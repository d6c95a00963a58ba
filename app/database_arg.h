// How subcommands take a study database on the command line: a file (SQLite)
// or a postgresql:// URI (a lab's server); a participant ID, checked as the
// store would check it (never cut to fit); and who decides, by default. The check accepts an existing file
// or any URI (the store checks the server when it connects); it never opens
// the database itself, and never lets a password reach what is printed.
#pragma once
#include <CLI/CLI.hpp>

#include <cstdlib>
#include <string>

#include "study/store/store.h"

namespace dtlab::app {

// The help text of a database argument.
inline constexpr const char* kDatabaseHelp =
    "Study database: a file (SQLite) or postgresql://[user@]host[:port]/database[?schema=NAME] (a lab's server; "
    "README, \"Several stations\")";

// CLI11 check: an existing path, or a PostgreSQL URI. A directory passes here and is refused by
// the store as invalid input (exit 1), as in every command that takes a database.
inline CLI::Validator existing_database() {
  return CLI::Validator(
      [](std::string& where) -> std::string {
        if (store::is_server_uri(where)) return {};
        return CLI::ExistingPath(where);
      },
      "FILE|URI", "EXISTING_DATABASE");
}

// CLI11 check of a --participant value: what Store::enroll accepts (store::check_participant_id),
// so that an ID too long to have been stored is refused at the command line, not "not found".
inline CLI::Validator participant_id() {
  return CLI::Validator(
      [](std::string& id) -> std::string {
        const Status st = store::check_participant_id(id);
        return st ? std::string() : st.error().message;
      },
      "ID", "PARTICIPANT_ID");
}

// Who records a decision (exclude, include, withdraw) when --by is not given: $DTLAB_EXPERIMENTER,
// else $USER, else $LOGNAME, else "".
inline std::string default_experimenter() {
  for (const char* var : {"DTLAB_EXPERIMENTER", "USER", "LOGNAME"})
    if (const char* v = std::getenv(var); v && *v) return v;
  return "";
}

}  // namespace dtlab::app

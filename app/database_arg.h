// How subcommands take a study database on the command line: a file (SQLite)
// or a postgresql:// URI (a lab's server). The check accepts an existing file
// or any URI (the store checks the server when it connects); it never opens
// the database itself, and never lets a password reach what is printed.
#pragma once
#include <CLI/CLI.hpp>

#include <string>

#include "study/store/store.h"

namespace dtlab::app {

// The help text of a database argument.
inline constexpr const char* kDatabaseHelp =
    "Study database: a file (SQLite) or postgresql://[user@]host[:port]/database[?schema=NAME] (a lab's server; "
    "README, \"Several stations\")";

// CLI11 check: an existing file, or a PostgreSQL URI.
inline CLI::Validator existing_database() {
  return CLI::Validator(
      [](std::string& where) -> std::string {
        if (store::is_server_uri(where)) return {};
        return CLI::ExistingFile(where);
      },
      "FILE|URI", "EXISTING_DATABASE");
}

}  // namespace dtlab::app

// The parts of the schema migrations that are not table description
// (schema_tables.h generates the tables, columns, constraints and indexes of
// both engines): each engine's triggers per migration (SQLite:
// schema_sqlite.cpp; PostgreSQL: schema_pg.cpp) and the session_table view,
// the same text on both. Internal to study/store: the migrations list in
// schema.cpp is the only caller. Each function returns DDL only; nothing
// here runs a statement.
#pragma once
#include <string>

namespace dtlab::store::detail {

// SQLite's triggers of migration `version` (1-4); "" for any other.
std::string sqlite_triggers(int version);
// PostgreSQL's triggers of migration `version` (1-4), and for 0 what SQLite keeps in its file
// header (the dtlab_header table) with the trigger function that refuses changes; "" for any other.
std::string pg_triggers(int version);
// The session_table view of schema v1, on both engines.
std::string session_table_view();

}  // namespace dtlab::store::detail

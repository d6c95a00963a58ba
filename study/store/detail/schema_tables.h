// The one description of the study database's tables (docs/store.md,
// "Schema"): every table, column, constraint and index of schema v1 to v4,
// each written once with the migration that adds it, and the engine's
// spelling of each type and pattern check chosen in one place
// (schema_ddl.cpp). The CREATE TABLE, ALTER TABLE ADD COLUMN and CREATE INDEX
// text of both engines is generated from it; triggers and views stay per
// engine (schema_sqlite.cpp, schema_pg.cpp). Pure data and text: nothing
// here runs a statement, and a table is never described twice.
#pragma once
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "study/store/detail/backend.h"

namespace dtlab::store::detail {

// SQL whose text differs by engine (a pattern check, a JSON check); most of it is the same on both.
struct Sql {
  std::string sqlite, postgresql;
  Sql(const char* both = "") : sqlite(both), postgresql(both) {}  // NOLINT: the same text on both engines
  Sql(std::string both) : sqlite(both), postgresql(std::move(both)) {}  // NOLINT
  Sql(std::string s, std::string p) : sqlite(std::move(s)), postgresql(std::move(p)) {}
  const std::string& in(Backend b) const { return b == Backend::postgresql ? postgresql : sqlite; }
};

// The schema's three value types (SQLite STRICT INTEGER/REAL/TEXT; PostgreSQL BIGINT/DOUBLE
// PRECISION/TEXT COLLATE "C", which compares bytes as SQLite's BINARY collation does).
enum class ColumnType { integer, real, text };

struct Column {
  std::string name;
  ColumnType type = ColumnType::text;
  std::string attrs;  // PRIMARY KEY, NOT NULL, UNIQUE, REFERENCES, DEFAULT, in that order; "" if none
  Sql check;          // "CHECK (...)", or ""
  int since = 0;      // the migration that adds the column; 0: it came with its table
  Column(std::string n, ColumnType t, std::string a = "", Sql c = "", int v = 0)
      : name(std::move(n)), type(t), attrs(std::move(a)), check(std::move(c)), since(v) {}
};

struct Table {
  std::string name;
  int since = 1;                     // the migration that creates it (0: the migrations table itself)
  std::vector<Column> columns;       // in stored order (a later migration's columns at the end)
  std::vector<Sql> constraints;      // table constraints, after the columns, in order
  bool without_rowid = false;        // SQLite's WITHOUT ROWID (no meaning on PostgreSQL)
  std::vector<std::string> indexes;  // whole CREATE INDEX statements without the semicolon
  Table(std::string n, int v, std::vector<Column> c, std::vector<Sql> k = {}, bool wr = false,
        std::vector<std::string> i = {})
      : name(std::move(n)), since(v), columns(std::move(c)), constraints(std::move(k)), without_rowid(wr),
        indexes(std::move(i)) {}
};

// Every table, in creation order (schema_tables.cpp).
const std::vector<Table>& schema_tables();

// Pattern checks as each engine spells them (SQLite GLOB, PostgreSQL regular expressions).
Sql iso_check(std::string_view column);           // CHECK (column is an ISO-8601 UTC ms timestamp)
Sql iso_check_nullable(std::string_view column);  // the same, NULL allowed
Sql hex_check(std::string_view column, int length);  // lowercase hex of exactly `length` digits
Sql digits_check(std::string_view column, int max_length);  // 1 to max_length decimal digits

// The DDL of migration `version` on `backend`: ALTER TABLE ADD COLUMN for the columns it adds to
// older tables, then CREATE TABLE and CREATE INDEX for the tables it creates, in description order.
std::string table_ddl(Backend backend, int version);

// The names of the tables the migrations up to `version` create (schema_migrations included).
std::vector<std::string> table_names(int version);

}  // namespace dtlab::store::detail

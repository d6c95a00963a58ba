// The table DDL of both engines, generated from the one description
// (schema_tables.h): each engine's spelling of the three column types and of
// the pattern checks lives here and nowhere else. The SQLite text is the
// text earlier builds wrote out by hand, byte for byte (sqlite_schema keeps
// it), so a database created now and one created then read the same.
// Nothing here runs a statement.
#include <string>

#include "study/store/detail/schema_tables.h"
#include "study/store/detail/time.h"

namespace dtlab::store::detail {
namespace {

constexpr const char* kIsoRegex = "'^[0-9]{4}-[0-1][0-9]-[0-3][0-9]T[0-2][0-9]:[0-5][0-9]:[0-6][0-9][.][0-9]{3}Z$'";

const char* type_name(ColumnType t, Backend b) {
  const bool pg = b == Backend::postgresql;
  switch (t) {
    case ColumnType::integer: return pg ? "BIGINT" : "INTEGER";
    case ColumnType::real: return pg ? "DOUBLE PRECISION" : "REAL";
    case ColumnType::text: return pg ? "TEXT COLLATE \"C\"" : "TEXT";
  }
  return "TEXT";
}

std::string column_ddl(const Column& c, Backend b) {
  std::string s = c.name + " " + type_name(c.type, b);
  if (!c.attrs.empty()) s += " " + c.attrs;
  if (const std::string& check = c.check.in(b); !check.empty()) s += " " + check;
  return s;
}

std::string create_table(const Table& t, Backend b) {
  std::string s = "CREATE TABLE " + t.name + " (";
  const char* sep = "\n  ";
  for (const Column& c : t.columns) {
    if (c.since > t.since) continue;  // added by a later migration's ALTER TABLE
    s += sep + column_ddl(c, b);
    sep = ",\n  ";
  }
  for (const Sql& k : t.constraints) s += sep + k.in(b);
  s += "\n)";
  if (b == Backend::sqlite) s += t.without_rowid ? " STRICT, WITHOUT ROWID" : " STRICT";
  s += ";\n";
  for (const std::string& index : t.indexes) s += index + ";\n";
  return s;
}

}  // namespace

Sql iso_check(std::string_view column) {
  const std::string c(column);
  return {"CHECK (" + c + " GLOB " + kIsoGlob + ")", "CHECK (" + c + " ~ " + kIsoRegex + ")"};
}

Sql iso_check_nullable(std::string_view column) {
  const std::string c(column);
  return {"CHECK (" + c + " IS NULL OR " + c + " GLOB " + kIsoGlob + ")",
          "CHECK (" + c + " IS NULL OR " + c + " ~ " + kIsoRegex + ")"};
}

Sql hex_check(std::string_view column, int length) {
  const std::string c(column);
  const std::string head = "CHECK (length(" + c + ") = " + std::to_string(length) + " AND " + c;
  return {head + " NOT GLOB '*[^0-9a-f]*')", head + " !~ '[^0-9a-f]')"};
}

Sql digits_check(std::string_view column, int max_length) {
  const std::string c(column);
  const std::string head = "CHECK (length(" + c + ") BETWEEN 1 AND " + std::to_string(max_length) + " AND " + c;
  return {head + " NOT GLOB '*[^0-9]*')", head + " !~ '[^0-9]')"};
}

std::string table_ddl(Backend backend, int version) {
  std::string s;
  for (const Table& t : schema_tables())
    for (const Column& c : t.columns)
      if (c.since == version && t.since < version)
        s += "ALTER TABLE " + t.name + " ADD COLUMN " + column_ddl(c, backend) + ";\n";
  for (const Table& t : schema_tables())
    if (t.since == version) s += "\n" + create_table(t, backend);
  return s;
}

std::vector<std::string> table_names(int version) {
  std::vector<std::string> names;
  for (const Table& t : schema_tables())
    if (t.since <= version) names.push_back(t.name);
  return names;
}

}  // namespace dtlab::store::detail

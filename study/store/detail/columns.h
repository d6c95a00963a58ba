// Rows bound and read by column name, against the one column list of each
// table (schema_tables.h): a RowInsert names its cells, and its INSERT lists
// the described table's columns with `:column` parameters; NamedColumns
// reads a result row by the names its SELECT gave. No parameter or column
// number is written by hand. A name the description lacks is an Error (kind
// internal) when the row is written, never a cell bound to the wrong column;
// a name the query lacks reads as NULL (never a crash).
#pragma once
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "study/common/error.h"
#include "study/store/detail/db.h"
#include "study/store/detail/schema_tables.h"

namespace dtlab::store::detail {

// The described table `name`; nullptr if there is none.
const Table* find_table(std::string_view name);

// "p.a AS a, p.b AS b, ..." for the columns of `table` the schema `version` has, NULL AS the newer ones.
std::string select_list(const Table& table, const std::string& prefix, int version);

// One row of a described table, set column by column; unset columns are NULL (never their DEFAULT).
class RowInsert {
 public:
  explicit RowInsert(std::string_view table);

  RowInsert& set(std::string_view column, Value v);  // the cell of `column`
  RowInsert& set(std::string_view column, int v) { return set(column, Value{static_cast<std::int64_t>(v)}); }
  RowInsert& set(std::string_view column, std::int64_t v) { return set(column, Value{v}); }
  RowInsert& set(std::string_view column, double v) { return set(column, Value{v}); }
  RowInsert& set(std::string_view column, const std::string& v) { return set(column, Value{v}); }
  RowInsert& set(std::string_view column, const char* v) { return set(column, Value{std::string(v)}); }
  template <class T>
  RowInsert& set(std::string_view column, const std::optional<T>& v) {
    return v ? set(column, *v) : set(column, Value{});
  }

  // INSERT INTO the table (every described column) VALUES (the cells); Error (internal) if a set
  // name is not a column of the table.
  Status run(Db& db, std::string_view what) const;

  // Error (internal) if a set name is not a column of the table; else ok.
  Status check(const Db& db, std::string_view what) const;
  const Table* table() const { return table_; }
  const std::vector<Value>& cells() const { return cells_; }

 private:
  const Table* table_ = nullptr;
  std::string name_;
  std::vector<Value> cells_;  // one per described column, in order
  std::string unknown_;       // the first name set that the table lacks
};

// Inserts `rows` (all of one described table) in one bulk insert (Connection::insert_rows: one
// prepared INSERT on SQLite, one COPY on PostgreSQL), every described column listed by name.
// Error (internal) if a row names a column the table lacks, or rows of two tables are mixed.
Status insert_all(Db& db, const std::vector<RowInsert>& rows, std::string_view what);

// The columns of a result row by name (Stmt's own names, kept for the callers of by_name).
class NamedColumns {
 public:
  explicit NamedColumns(const Stmt& st) : st_(&st) {}
  bool has(std::string_view name) const { return st_->has(name); }
  bool is_null(const Stmt& st, std::string_view name) const;  // true too for a name the query lacks
  std::int64_t int64(const Stmt& st, std::string_view name) const;
  double real(const Stmt& st, std::string_view name) const;
  std::string text(const Stmt& st, std::string_view name) const;
  std::optional<std::int64_t> opt_int(const Stmt& st, std::string_view name) const;
  std::optional<double> opt_real(const Stmt& st, std::string_view name) const;
  std::optional<std::string> opt_text(const Stmt& st, std::string_view name) const;
  std::optional<int> opt_int32(const Stmt& st, std::string_view name) const;  // a position, a count

 private:
  const Stmt* st_;
};

// A row callback for each_row (reader_impl.h) that reads by name: calls f(columns, statement), the
// names taken once, from the first row.
template <class F>
auto by_name(F f) {
  return [f = std::move(f), col = std::optional<NamedColumns>()](const Stmt& q) mutable {
    if (!col) col.emplace(q);
    f(*col, q);
  };
}

}  // namespace dtlab::store::detail

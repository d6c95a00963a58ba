// Rows as values, for copying a study between databases (copy.cpp, merge.cpp):
// the tables a copy carries in copy order (their columns from the one schema
// description), reading rows of either engine as typed Values named by
// column, writing them in chunks through the engine's bulk insert by column
// name, and a canonical text of a row for comparing what two databases hold.
// No cell is found by its column's number. Never writes outside the
// caller's transaction.
#pragma once
#include <cstdint>
#include <functional>
#include <initializer_list>
#include <memory>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "study/common/error.h"
#include "study/store/copy.h"
#include "study/store/detail/db.h"
#include "study/store/detail/schema_tables.h"

namespace dtlab::store::detail {

// One result row, its cells read and set by column name (the names its SELECT gave, shared by
// every row of one query). A name the row lacks is a programmer error: it asserts, and in a
// release build reads NULL and writes nowhere.
class Row {
 public:
  Row() = default;
  Row(std::shared_ptr<const std::vector<std::string>> names, std::vector<Value> cells)
      : names_(std::move(names)), cells_(std::move(cells)) {}

  bool has(std::string_view column) const { return index(column) >= 0; }
  const Value& operator[](std::string_view column) const;
  Value& operator[](std::string_view column);
  Row without(std::string_view column) const;  // the row less one column

  const std::vector<std::string>& names() const;
  const std::vector<Value>& cells() const { return cells_; }
  bool operator==(const Row& o) const { return cells_ == o.cells_; }  // rows of one query: same names

 private:
  int index(std::string_view column) const;
  std::shared_ptr<const std::vector<std::string>> names_;
  std::vector<Value> cells_;
  Value scratch_;  // what a name the row lacks reads and writes (after the assert)
};

// Two rows hold the same content: every cell equal but those of the columns `ignored` (ids that
// differ between databases).
bool same_except(const Row& a, const Row& b, std::initializer_list<std::string_view> ignored);

// A table a copy carries: its name, the order that keeps every trigger satisfied, and its
// description (schema_tables.h), whose columns are the ones copied.
struct TableSpec {
  const char* name;
  const char* order_by;
  const Table& table() const;
  const std::vector<std::string>& columns() const;  // the described columns, in stored order

  // The select list reading the described columns from a database of schema `version`, each
  // prefixed with `alias` ("" for none) and named AS itself; a column that version lacks reads as
  // NULL under its name.
  std::string select_list(int version, const std::string& alias = "") const;
};

// Every table of the study except schema_migrations (carried as the migration history) and
// session_claims (operational, never copied), parents before children, results in plan order.
const std::vector<TableSpec>& copied_tables();
// The copied table `name` (a programmer error if it is not one).
const TableSpec& copied_table(std::string_view name);

// The `:name` parameters of a query and their values.
using Binds = std::vector<std::pair<std::string, Value>>;

// Runs `sql` with `binds` and calls `row` with each result row.
Status each_row(Db& db, const std::string& sql, const Binds& binds, const std::function<Status(Row&)>& row);

// Inserts `rows` into `table` in one bulk insert, each cell into the column its name says.
Status insert_named(Db& db, const std::string& table, const std::vector<Row>& rows, std::string_view what);

// Collects rows for one table and inserts them in chunks (one bulk insert per chunk), each cell
// into the column its name says.
class RowSink {
 public:
  RowSink(Db& db, std::string table) : db_(db), table_(std::move(table)) {}
  Status add(Row row);
  Status finish();
  std::int64_t count() const { return count_; }

 private:
  Db& db_;
  std::string table_;
  std::vector<Row> rows_;
  std::int64_t count_ = 0;
};

// A value as canonical text: NULL, integers and reals (shortest exact form) and texts (quoted),
// so two rows compare equal exactly when their values are equal.
std::string canonical(const Value& v);
std::string canonical(const Row& row);

// The merge of `src` into `dst`, which holds a study already (merge.cpp); runs inside DST's write
// transaction, after DST's schema is current. Adds to `summary`.
Status merge_study(Db& src, int src_version, Db& dst, const CopyOptions& options, CopySummary& summary);

}  // namespace dtlab::store::detail

// Rows as values, for copying a study between databases (copy.cpp, merge.cpp):
// the list of tables a copy carries with their columns and copy order, reading
// rows of either engine as typed Values, writing them in chunks through the
// engine's bulk insert, and a canonical text of a row for comparing what two
// databases hold. Never writes outside the caller's transaction.
#pragma once
#include <cstdint>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "study/common/error.h"
#include "study/store/copy.h"
#include "study/store/detail/db.h"

namespace dtlab::store::detail {

using Row = std::vector<Value>;

// A table a copy carries: its columns (as inserted into DST, whose schema is current), the order
// that keeps every trigger satisfied, the schema version that added it, and the columns a later
// version added to it (with that version).
struct TableSpec {
  const char* name;
  std::vector<std::string> columns;
  const char* order_by;
  int since_version;
  std::vector<std::pair<std::string, int>> added_later = {};

  // The select list reading `columns` from a database of schema `version`, each prefixed with
  // `alias` ("" for none); a column that version lacks reads as NULL.
  std::string select_list(int version, const std::string& alias = "") const;
};

// Every table of the study except schema_migrations (carried as the migration history) and
// session_claims (operational, never copied), parents before children, results in plan order.
const std::vector<TableSpec>& copied_tables();

// Runs `sql` with `binds` and calls `row` with each result row's values.
Status each_row(Db& db, const std::string& sql, const Row& binds, const std::function<Status(Row&)>& row);

// Collects rows for one table and inserts them in chunks (one bulk insert per chunk).
class RowSink {
 public:
  RowSink(Db& db, std::string table, std::vector<std::string> columns)
      : db_(db), table_(std::move(table)), columns_(std::move(columns)) {}
  Status add(Row row);
  Status finish();
  std::int64_t count() const { return count_; }

 private:
  Db& db_;
  std::string table_;
  std::vector<std::string> columns_;
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

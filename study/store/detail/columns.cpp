// RowInsert and NamedColumns (columns.h): the INSERT's column list and its
// `:column` parameters come from the table's description, and a result row
// is read through Stmt's names, so no placeholder or column number is
// written by hand.
// Never binds a cell to a column it was not set for.
#include "study/store/detail/columns.h"

#include <algorithm>

namespace dtlab::store::detail {

const Table* find_table(std::string_view name) {
  for (const Table& t : schema_tables())
    if (t.name == name) return &t;
  return nullptr;
}

std::string select_list(const Table& table, const std::string& prefix, int version) {
  std::string s;
  for (const Column& c : table.columns) {
    s += s.empty() ? "" : ", ";
    s += (std::max(c.since, table.since) <= version ? prefix + c.name : std::string("NULL")) + " AS " + c.name;
  }
  return s;
}

RowInsert::RowInsert(std::string_view table) : table_(find_table(table)), name_(table) {
  if (table_) cells_.resize(table_->columns.size());
}

RowInsert& RowInsert::set(std::string_view column, Value v) {
  if (table_)
    for (std::size_t c = 0; c < table_->columns.size(); ++c)
      if (table_->columns[c].name == column) {
        cells_[c] = std::move(v);
        return *this;
      }
  if (unknown_.empty()) unknown_ = std::string(column);
  return *this;
}

Status RowInsert::check(const Db& db, std::string_view what) const {
  if (table_ && unknown_.empty()) return {};
  return Error{db.path(), 0, 0, name_ + (table_ ? "." + unknown_ : ""),
               std::string(what) + ": the schema has no " + (table_ ? "column " + unknown_ + " in " : "table ") + name_,
               ErrorKind::internal};
}

Status RowInsert::run(Db& db, std::string_view what) const {
  if (auto s = check(db, what); !s) return s;
  std::string columns, values;
  for (std::size_t c = 0; c < table_->columns.size(); ++c) {
    columns += (c ? ", " : "") + table_->columns[c].name;
    values += (c ? ", :" : ":") + table_->columns[c].name;
  }
  auto st = Stmt::prepare(db, "INSERT INTO " + name_ + " (" + columns + ") VALUES (" + values + ")", what);
  if (!st) return st.error();
  for (std::size_t c = 0; c < cells_.size(); ++c) st->bind(table_->columns[c].name, cells_[c]);
  return st->run(what);
}

Status insert_all(Db& db, const std::vector<RowInsert>& rows, std::string_view what) {
  if (rows.empty()) return {};
  std::vector<std::vector<Value>> cells;
  cells.reserve(rows.size());
  for (const RowInsert& r : rows) {
    if (auto s = r.check(db, what); !s) return s;
    if (r.table() != rows.front().table())
      return Error{db.path(), 0, 0, r.table()->name, std::string(what) + ": rows of two tables in one insert",
                   ErrorKind::internal};
    cells.push_back(r.cells());
  }
  std::vector<std::string> names;
  for (const Column& c : rows.front().table()->columns) names.push_back(c.name);
  return db.conn().insert_rows(rows.front().table()->name, names, cells, what);
}

bool NamedColumns::is_null(const Stmt& st, std::string_view name) const { return st.is_null(name); }
std::int64_t NamedColumns::int64(const Stmt& st, std::string_view name) const { return st.int64(name); }
double NamedColumns::real(const Stmt& st, std::string_view name) const { return st.real(name); }
std::string NamedColumns::text(const Stmt& st, std::string_view name) const { return st.text(name); }

std::optional<std::int64_t> NamedColumns::opt_int(const Stmt& st, std::string_view name) const {
  if (is_null(st, name)) return std::nullopt;
  return int64(st, name);
}

std::optional<double> NamedColumns::opt_real(const Stmt& st, std::string_view name) const {
  if (is_null(st, name)) return std::nullopt;
  return real(st, name);
}

std::optional<std::string> NamedColumns::opt_text(const Stmt& st, std::string_view name) const {
  if (is_null(st, name)) return std::nullopt;
  return text(st, name);
}

std::optional<int> NamedColumns::opt_int32(const Stmt& st, std::string_view name) const {
  if (is_null(st, name)) return std::nullopt;
  return static_cast<int>(int64(st, name));
}

}  // namespace dtlab::store::detail

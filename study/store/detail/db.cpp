// The engine-independent handles (db.h) and the choice of engine by the
// name of the database (backend.h): a postgresql:// or postgres:// URI is a
// server, anything else a file. Nothing here speaks an engine's API.
#include "study/store/detail/db.h"

#include "study/store/detail/pg_uri.h"
#include "study/store/detail/time.h"
#include "study/store/store.h"

namespace dtlab::store::detail {

bool is_server_uri(std::string_view where) {
  return where.rfind("postgresql://", 0) == 0 || where.rfind("postgres://", 0) == 0;
}

}  // namespace dtlab::store::detail

namespace dtlab::store {

bool is_server_uri(const std::string& where) { return detail::is_server_uri(where); }

std::string display_name(const std::string& where) {
  if (!detail::is_server_uri(where)) return where;
  auto a = detail::parse_pg_uri(where);
  return a ? a->display : a.error().file;
}

}  // namespace dtlab::store

namespace dtlab::store::detail {

Result<std::unique_ptr<Connection>> open_connection(const std::string& where, Access access, int busy_timeout_ms) {
  if (is_server_uri(where)) return open_postgres(where, access, busy_timeout_ms);
  return open_sqlite(where, access, busy_timeout_ms);
}

namespace {

// The column `n` of the first row, read by `get`; nullopt if there is no row or it is NULL; an
// internal Error if the query names no column `n`.
template <class T, class Get>
Result<std::optional<T>> query_one(const Db& db, const std::string& sql, std::string_view what, const Db::Binds& binds,
                                   Get get) {
  auto st = Stmt::prepare(db, sql, what);
  if (!st) return st.error();
  for (const auto& [name, value] : binds) st->bind(name, value);
  auto row = st->step(what);
  if (!row) return row.error();
  if (*row && !st->has("n"))
    return Error{db.path(), 0, 0, "", std::string(what) + ": the query names no column n: " + sql, ErrorKind::internal};
  if (!*row || st->is_null("n")) return std::optional<T>{};
  return std::optional<T>{get(*st)};
}

}  // namespace

Result<std::optional<std::int64_t>> Db::query_int(const std::string& sql, std::string_view what, const Binds& binds) {
  return query_one<std::int64_t>(*this, sql, what, binds, [](const Stmt& st) { return st.int64("n"); });
}

Result<std::optional<std::string>> Db::query_text(const std::string& sql, std::string_view what, const Binds& binds) {
  return query_one<std::string>(*this, sql, what, binds, [](const Stmt& st) { return st.text("n"); });
}

Result<std::string> Db::now_iso() {
  auto t = c_->now();
  if (!t) return t.error();
  return iso8601_utc(*t);
}

Result<std::int64_t> next_id(Db& db, const char* table) {
  auto id = db.query_int(std::string("SELECT coalesce(max(id), 0) + 1 AS n FROM ") + table, "assigning an id");
  if (!id) return id.error();
  return id->value_or(1);
}

Result<Stmt> Stmt::prepare(const Db& db, std::string_view sql, std::string_view what) {
  auto st = db.conn().prepare(sql, what);
  if (!st) return st.error();
  return Stmt(std::move(*st), db.path());
}

int Stmt::parameter(std::string_view name) {
  const int i = st_->parameter_index(name);
  if (i == 0 && unbound_.empty()) unbound_ = std::string(name);
  return i;
}

Stmt& Stmt::bind(std::string_view name, std::int64_t v) {
  if (const int i = parameter(name)) st_->bind_int(i, v);
  return *this;
}

Stmt& Stmt::bind(std::string_view name, double v) {
  if (const int i = parameter(name)) st_->bind_real(i, v);
  return *this;
}

Stmt& Stmt::bind(std::string_view name, std::string_view v) {
  if (const int i = parameter(name)) st_->bind_text(i, v);
  return *this;
}

Stmt& Stmt::bind_null(std::string_view name) {
  if (const int i = parameter(name)) st_->bind_null(i);
  return *this;
}

Stmt& Stmt::bind(std::string_view name, const Value& v) {
  if (const auto* n = std::get_if<std::int64_t>(&v)) return bind(name, *n);
  if (const auto* d = std::get_if<double>(&v)) return bind(name, *d);
  if (const auto* s = std::get_if<std::string>(&v)) return bind(name, *s);
  return bind_null(name);
}

Result<bool> Stmt::step(std::string_view what) {
  if (!unbound_.empty())
    return Error{db_, 0, 0, unbound_, std::string(what) + ": the statement has no parameter :" + unbound_,
                 ErrorKind::internal};
  return st_->step(what);
}

Status Stmt::run(std::string_view what) {
  for (;;) {
    auto r = step(what);
    if (!r) {
      reset();
      return r.error();
    }
    if (!*r) break;
  }
  reset();
  return {};
}

void Stmt::reset() {
  st_->reset();
  unbound_.clear();
}

int Stmt::at(std::string_view column) const {
  if (columns_.empty())
    for (int c = 0; c < st_->columns(); ++c) columns_.emplace(st_->column_name(c), c);
  const auto it = columns_.find(column);
  return it == columns_.end() ? -1 : it->second;
}

bool Stmt::is_null(std::string_view column) const {
  const int c = at(column);
  return c < 0 || st_->is_null(c);
}

std::int64_t Stmt::int64(std::string_view column) const {
  const int c = at(column);
  return c < 0 ? 0 : st_->int64(c);
}

double Stmt::real(std::string_view column) const {
  const int c = at(column);
  return c < 0 ? 0.0 : st_->real(c);
}

std::string Stmt::text(std::string_view column) const {
  const int c = at(column);
  return c < 0 ? std::string() : st_->text(c);
}

Value Stmt::value(std::string_view column) const {
  const int c = at(column);
  return c < 0 ? Value{} : st_->value(c);
}

std::vector<std::string> Stmt::column_names() const {
  std::vector<std::string> out;
  for (int c = 0; c < st_->columns(); ++c) out.push_back(st_->column_name(c));
  return out;
}

std::vector<Value> Stmt::cells() const {
  std::vector<Value> out;
  out.reserve(static_cast<std::size_t>(st_->columns()));
  for (int c = 0; c < st_->columns(); ++c) out.push_back(st_->value(c));
  return out;
}

Status Transaction::begin(std::string_view what) {
  if (auto s = db_.conn().begin_write(what); !s) return s;
  open_ = true;
  return {};
}

Status Transaction::commit(std::string_view what) {
  if (auto s = db_.conn().commit(what); !s) return s;  // still open: the destructor rolls back
  open_ = false;
  return {};
}

bool Transaction::rollback() {
  if (!open_) return true;
  open_ = false;
  return db_.conn().rollback();
}

}  // namespace dtlab::store::detail

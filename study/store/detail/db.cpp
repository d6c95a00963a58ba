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

// The first column of the first row, read by `get`; nullopt if there is no row or it is NULL.
template <class T, class Get>
Result<std::optional<T>> query_one(const Db& db, const std::string& sql, std::string_view what, Get get) {
  auto st = Stmt::prepare(db, sql, what);
  if (!st) return st.error();
  auto row = st->step(what);
  if (!row) return row.error();
  if (!*row || st->is_null(0)) return std::optional<T>{};
  return std::optional<T>{get(*st)};
}

}  // namespace

Result<std::optional<std::int64_t>> Db::query_int(const std::string& sql, std::string_view what) {
  return query_one<std::int64_t>(*this, sql, what, [](const Stmt& st) { return st.int64(0); });
}

Result<std::optional<std::string>> Db::query_text(const std::string& sql, std::string_view what) {
  return query_one<std::string>(*this, sql, what, [](const Stmt& st) { return st.text(0); });
}

Result<std::string> Db::now_iso() {
  auto t = c_->now();
  if (!t) return t.error();
  return iso8601_utc(*t);
}

Result<std::int64_t> next_id(Db& db, const char* table) {
  auto id = db.query_int(std::string("SELECT coalesce(max(id), 0) + 1 FROM ") + table, "assigning an id");
  if (!id) return id.error();
  return id->value_or(1);
}

Result<Stmt> Stmt::prepare(const Db& db, std::string_view sql, std::string_view what) {
  auto st = db.conn().prepare(sql, what);
  if (!st) return st.error();
  return Stmt(std::move(*st));
}

Stmt& Stmt::bind(int i, const Value& v) {
  if (const auto* n = std::get_if<std::int64_t>(&v)) return bind(i, *n);
  if (const auto* d = std::get_if<double>(&v)) return bind(i, *d);
  if (const auto* s = std::get_if<std::string>(&v)) return bind(i, *s);
  return bind_null(i);
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

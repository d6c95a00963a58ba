// RAII layer over the SQLite C API; see sqlite.h. Every failure becomes an
// Error naming the file and the operation; nothing here aborts.
#include "study/store/detail/sqlite.h"

#include <utility>

namespace dtlab::store::detail {

ErrorKind kind_of(int code) {
  switch (code & 0xff) {
    case SQLITE_BUSY:
    case SQLITE_LOCKED: return ErrorKind::busy;
    case SQLITE_CONSTRAINT: return ErrorKind::conflict;  // a trigger or constraint refused the write
    case SQLITE_NOTADB: return ErrorKind::invalid_input;
    default: return ErrorKind::environment;
  }
}

Error sqlite_error(sqlite3* db, const std::string& path, std::string_view what) {
  std::string msg(what);
  msg += ": ";
  int code = SQLITE_NOMEM;
  if (db) {
    code = sqlite3_extended_errcode(db);
    msg += sqlite3_errmsg(db);
    msg += " (SQLite code " + std::to_string(code) + ")";
    if ((code & 0xff) == SQLITE_BUSY || (code & 0xff) == SQLITE_LOCKED)
      msg += "; another process held the database past the busy timeout: try again";
  } else {
    msg += "out of memory";
  }
  return Error{path, 0, 0, "sqlite", std::move(msg), kind_of(code)};
}

Db& Db::operator=(Db&& o) noexcept {
  if (this != &o) {
    sqlite3_close_v2(db_);
    db_ = o.db_;
    path_ = std::move(o.path_);
    o.db_ = nullptr;
  }
  return *this;
}

Db::~Db() { sqlite3_close_v2(db_); }

Result<Db> Db::open(const std::string& path, int flags) {
  sqlite3* handle = nullptr;
  const int rc = sqlite3_open_v2(path.c_str(), &handle, flags | SQLITE_OPEN_NOMUTEX, nullptr);
  if (rc != SQLITE_OK) {
    Error e = sqlite_error(handle, path, "cannot open the database");
    sqlite3_close_v2(handle);
    return e;
  }
  sqlite3_extended_result_codes(handle, 1);
  return Db(handle, path);
}

Status Db::exec(const std::string& sql, std::string_view what) {
  if (sqlite3_exec(db_, sql.c_str(), nullptr, nullptr, nullptr) != SQLITE_OK) return error(what);
  return {};
}

Result<std::optional<std::int64_t>> Db::query_int(const std::string& sql, std::string_view what) {
  auto st = Stmt::prepare(*this, sql, what);
  if (!st) return st.error();
  auto row = st->step(what);
  if (!row) return row.error();
  if (!*row || st->is_null(0)) return std::optional<std::int64_t>{};
  return std::optional<std::int64_t>{st->int64(0)};
}

Result<std::optional<std::string>> Db::query_text(const std::string& sql, std::string_view what) {
  auto st = Stmt::prepare(*this, sql, what);
  if (!st) return st.error();
  auto row = st->step(what);
  if (!row) return row.error();
  if (!*row || st->is_null(0)) return std::optional<std::string>{};
  return std::optional<std::string>{st->text(0)};
}

Result<Stmt> Stmt::prepare(const Db& db, std::string_view sql, std::string_view what) {
  Stmt s;
  s.db_ = &db;
  if (sqlite3_prepare_v2(db.get(), sql.data(), static_cast<int>(sql.size()), &s.st_, nullptr) != SQLITE_OK)
    return db.error(what);
  return s;
}

Result<bool> Stmt::step(std::string_view what) {
  const int rc = sqlite3_step(st_);
  if (rc == SQLITE_ROW) return true;
  if (rc == SQLITE_DONE) return false;
  Error e = db_->error(what);
  sqlite3_reset(st_);
  return e;
}

Status Stmt::run(std::string_view what) {
  for (;;) {
    auto r = step(what);
    if (!r) return r.error();
    if (!*r) break;
  }
  reset();
  return {};
}

std::string Stmt::text(int c) const {
  const auto* p = reinterpret_cast<const char*>(sqlite3_column_text(st_, c));
  return p ? std::string(p, static_cast<std::size_t>(sqlite3_column_bytes(st_, c))) : std::string();
}

Status Transaction::begin(std::string_view what) {
  if (auto s = db_.exec("BEGIN IMMEDIATE", what); !s) return s;
  open_ = true;
  return {};
}

Status Transaction::commit(std::string_view what) {
  if (auto s = db_.exec("COMMIT", what); !s) return s;  // still open: the destructor rolls back
  open_ = false;
  return {};
}

bool Transaction::rollback() {
  if (!open_) return true;
  open_ = false;
  if (sqlite3_get_autocommit(db_.get())) return true;  // SQLite already rolled back (e.g. after SQLITE_FULL)
  return sqlite3_exec(db_.get(), "ROLLBACK", nullptr, nullptr, nullptr) == SQLITE_OK;
}

}  // namespace dtlab::store::detail

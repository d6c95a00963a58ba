// Thin RAII layer over the SQLite C API for study/store only: a connection, a
// prepared statement and a transaction guard, every failure turned into a
// dtlab::Error that names the database file, the operation and SQLite's own
// message. It never aborts and never leaves a transaction open: a Transaction
// that is not committed rolls back when it goes out of scope.
#pragma once
#include <sqlite3.h>

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

#include "study/common/error.h"

namespace dtlab::store::detail {

// The ErrorKind of an SQLite result code: busy (BUSY, LOCKED), conflict (a
// constraint or trigger refused the write), invalid_input (NOTADB), else environment.
ErrorKind kind_of(int sqlite_code);

// The Error for a failed SQLite call: file = path, field = "sqlite", message =
// "<what>: <sqlite message>", kind from kind_of(the connection's last code).
Error sqlite_error(sqlite3* db, const std::string& path, std::string_view what);

// An open connection. Move-only; closes on destruction.
class Db {
 public:
  Db() = default;
  Db(sqlite3* handle, std::string path) : db_(handle), path_(std::move(path)) {}
  Db(Db&& o) noexcept : db_(o.db_), path_(std::move(o.path_)) { o.db_ = nullptr; }
  Db& operator=(Db&& o) noexcept;
  Db(const Db&) = delete;
  Db& operator=(const Db&) = delete;
  ~Db();

  // Opens `path` with SQLite `flags`; never creates a file unless flags say so.
  static Result<Db> open(const std::string& path, int flags);

  sqlite3* get() const { return db_; }
  const std::string& path() const { return path_; }
  void set_path(std::string path) { path_ = std::move(path); }  // the name errors use (e.g. the file behind a URI)
  Error error(std::string_view what) const { return sqlite_error(db_, path_, what); }

  // Runs one or more statements that return no rows (DDL, PRAGMA setters).
  Status exec(const std::string& sql, std::string_view what);
  // Runs a query expected to return one row with one column; nullopt if no row.
  Result<std::optional<std::int64_t>> query_int(const std::string& sql, std::string_view what);
  Result<std::optional<std::string>> query_text(const std::string& sql, std::string_view what);

 private:
  sqlite3* db_ = nullptr;
  std::string path_;
};

// A prepared statement with 1-based binds and 0-based column reads.
class Stmt {
 public:
  Stmt() = default;
  Stmt(Stmt&& o) noexcept : st_(o.st_), db_(o.db_) { o.st_ = nullptr; }
  Stmt& operator=(Stmt&&) = delete;
  Stmt(const Stmt&) = delete;
  Stmt& operator=(const Stmt&) = delete;
  ~Stmt() { sqlite3_finalize(st_); }

  static Result<Stmt> prepare(const Db& db, std::string_view sql, std::string_view what);

  Stmt& bind(int i, std::int64_t v) { sqlite3_bind_int64(st_, i, v); return *this; }
  Stmt& bind(int i, int v) { sqlite3_bind_int64(st_, i, v); return *this; }
  Stmt& bind(int i, double v) { sqlite3_bind_double(st_, i, v); return *this; }
  Stmt& bind(int i, std::string_view v) {
    sqlite3_bind_text(st_, i, v.data(), static_cast<int>(v.size()), SQLITE_TRANSIENT);
    return *this;
  }
  Stmt& bind(int i, const char* v) { return bind(i, std::string_view(v)); }
  Stmt& bind(int i, const std::string& v) { return bind(i, std::string_view(v)); }
  Stmt& bind_null(int i) { sqlite3_bind_null(st_, i); return *this; }
  template <class T>
  Stmt& bind(int i, const std::optional<T>& v) { return v ? bind(i, *v) : bind_null(i); }

  // Advances one row: true = a row is ready, false = done; Error on failure.
  Result<bool> step(std::string_view what);
  // Steps to completion (for INSERT/UPDATE), then resets for the next bind.
  Status run(std::string_view what);
  void reset() { sqlite3_reset(st_); sqlite3_clear_bindings(st_); }

  bool is_null(int c) const { return sqlite3_column_type(st_, c) == SQLITE_NULL; }
  std::int64_t int64(int c) const { return sqlite3_column_int64(st_, c); }
  double real(int c) const { return sqlite3_column_double(st_, c); }
  std::string text(int c) const;
  int columns() const { return sqlite3_column_count(st_); }
  std::string column_name(int c) const { return sqlite3_column_name(st_, c); }
  int column_type(int c) const { return sqlite3_column_type(st_, c); }
  sqlite3_stmt* get() const { return st_; }

 private:
  sqlite3_stmt* st_ = nullptr;
  const Db* db_ = nullptr;
};

// BEGIN IMMEDIATE ... COMMIT. The write lock is taken at begin() (waiting up
// to the busy timeout), so no other process can write in between. Destroyed
// without commit() -> ROLLBACK. `failed_rollback()` reports a ROLLBACK that
// itself failed: the connection is then in an unknown state (store ERROR).
class Transaction {
 public:
  explicit Transaction(Db& db) : db_(db) {}
  Transaction(const Transaction&) = delete;
  Transaction& operator=(const Transaction&) = delete;
  ~Transaction() { rollback(); }

  Status begin(std::string_view what);
  Status commit(std::string_view what);
  // Rolls back if a transaction is open; returns false if ROLLBACK failed.
  bool rollback();

 private:
  Db& db_;
  bool open_ = false;
};

}  // namespace dtlab::store::detail

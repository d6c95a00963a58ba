// The handles the store's code holds, whatever the engine behind them (see
// backend.h): Db owns a Connection, Stmt a prepared Statement with chained
// binds, Transaction a write transaction that rolls back unless committed.
// Every failure is a dtlab::Error naming the database and the operation;
// nothing here aborts, and a Transaction never outlives its scope open.
#pragma once
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <string_view>

#include "study/common/error.h"
#include "study/store/detail/backend.h"

namespace dtlab::store::detail {

// An open connection. Move-only; closes on destruction.
class Db {
 public:
  Db() = default;
  explicit Db(std::unique_ptr<Connection> c) : c_(std::move(c)) {}

  Connection& conn() const { return *c_; }
  Backend backend() const { return c_->backend(); }
  const std::string& path() const { return c_->name(); }  // the file, or the URI without its password

  // Runs statements that return no rows (DDL, settings).
  Status exec(const std::string& sql, std::string_view what) { return c_->exec(sql, what); }
  // Runs a query expected to return one row with one column; nullopt if no row or NULL.
  Result<std::optional<std::int64_t>> query_int(const std::string& sql, std::string_view what);
  Result<std::optional<std::string>> query_text(const std::string& sql, std::string_view what);
  // The current time as stored (ISO-8601 UTC, milliseconds), by the engine's clock (backend.h).
  Result<std::string> now_iso();

 private:
  std::unique_ptr<Connection> c_;
};

// The id the next row of `table` (one with an `id` column) gets: one above the largest. Ids are
// assigned inside the write transaction, so the same history gives the same ids on both
// engines and none is skipped.
Result<std::int64_t> next_id(Db& db, const char* table);

// A prepared statement with 1-based binds and 0-based column reads.
class Stmt {
 public:
  static Result<Stmt> prepare(const Db& db, std::string_view sql, std::string_view what);

  Stmt& bind(int i, std::int64_t v) { st_->bind_int(i, v); return *this; }
  Stmt& bind(int i, int v) { st_->bind_int(i, v); return *this; }
  Stmt& bind(int i, double v) { st_->bind_real(i, v); return *this; }
  Stmt& bind(int i, std::string_view v) { st_->bind_text(i, v); return *this; }
  Stmt& bind(int i, const char* v) { return bind(i, std::string_view(v)); }
  Stmt& bind(int i, const std::string& v) { return bind(i, std::string_view(v)); }
  Stmt& bind(int i, const Value& v);
  Stmt& bind_null(int i) { st_->bind_null(i); return *this; }
  template <class T>
  Stmt& bind(int i, const std::optional<T>& v) { return v ? bind(i, *v) : bind_null(i); }

  // Advances one row: true = a row is ready, false = done; Error on failure.
  Result<bool> step(std::string_view what) { return st_->step(what); }
  // Steps to completion (for INSERT/UPDATE), then resets for the next bind.
  Status run(std::string_view what);
  void reset() { st_->reset(); }

  bool is_null(int c) const { return st_->is_null(c); }
  std::int64_t int64(int c) const { return st_->int64(c); }
  double real(int c) const { return st_->real(c); }
  std::string text(int c) const { return st_->text(c); }
  Value value(int c) const { return st_->value(c); }
  int columns() const { return st_->columns(); }
  std::string column_name(int c) const { return st_->column_name(c); }

 private:
  explicit Stmt(std::unique_ptr<Statement> st) : st_(std::move(st)) {}
  std::unique_ptr<Statement> st_;
};

// The study's write transaction (Connection::begin_write). Destroyed without commit() ->
// ROLLBACK. `rollback()` returns false when the ROLLBACK itself failed: the connection is
// then in an unknown state (store ERROR).
class Transaction {
 public:
  explicit Transaction(Db& db) : db_(db) {}
  Transaction(const Transaction&) = delete;
  Transaction& operator=(const Transaction&) = delete;
  ~Transaction() { rollback(); }

  Status begin(std::string_view what);
  Status commit(std::string_view what);
  bool rollback();

 private:
  Db& db_;
  bool open_ = false;
};

}  // namespace dtlab::store::detail

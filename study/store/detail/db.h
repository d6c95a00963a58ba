// The handles the store's code holds, whatever the engine behind them (see
// backend.h): Db owns a Connection, Stmt a prepared Statement bound and read
// by name, Transaction a write transaction that rolls back unless committed.
// Every failure is a dtlab::Error naming the database and the operation;
// nothing here aborts, and a Transaction never outlives its scope open.
#pragma once
#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

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
  // Runs a query expected to return one row with a column named `n` (SELECT count(*) AS n ...),
  // its `:name` parameters bound from `binds`; nullopt if no row or NULL.
  using Binds = std::vector<std::pair<std::string, Value>>;
  Result<std::optional<std::int64_t>> query_int(const std::string& sql, std::string_view what, const Binds& binds = {});
  Result<std::optional<std::string>> query_text(const std::string& sql, std::string_view what, const Binds& binds = {});
  // The current time as stored (ISO-8601 UTC, milliseconds), by the engine's clock (backend.h).
  Result<std::string> now_iso();

 private:
  std::unique_ptr<Connection> c_;
};

// The id the next row of `table` (one with an `id` column) gets: one above the largest. Ids are
// assigned inside the write transaction, so the same history gives the same ids on both
// engines and none is skipped.
Result<std::int64_t> next_id(Db& db, const char* table);

// A prepared statement whose parameters are bound and whose columns are read by name: a `:name`
// parameter of the SQL is bound as bind("name", v), a result column (named with AS where it is
// not a plain column) is read as int64("name"). No number is written by hand. Binding a name the
// SQL lacks makes the next step() an Error (kind internal) that runs nothing; reading a name the
// result lacks reads as NULL (as NamedColumns, columns.h).
class Stmt {
 public:
  static Result<Stmt> prepare(const Db& db, std::string_view sql, std::string_view what);

  Stmt& bind(std::string_view name, std::int64_t v);
  Stmt& bind(std::string_view name, int v) { return bind(name, static_cast<std::int64_t>(v)); }
  Stmt& bind(std::string_view name, double v);
  Stmt& bind(std::string_view name, std::string_view v);
  Stmt& bind(std::string_view name, const char* v) { return bind(name, std::string_view(v)); }
  Stmt& bind(std::string_view name, const std::string& v) { return bind(name, std::string_view(v)); }
  Stmt& bind(std::string_view name, const Value& v);
  Stmt& bind_null(std::string_view name);
  template <class T>
  Stmt& bind(std::string_view name, const std::optional<T>& v) { return v ? bind(name, *v) : bind_null(name); }
  template <class T>
  Stmt& bind(int, const T&) = delete;  // parameters are bound by name

  // Advances one row: true = a row is ready, false = done; Error on failure.
  Result<bool> step(std::string_view what);
  // Steps to completion (for INSERT/UPDATE), then resets for the next bind.
  Status run(std::string_view what);
  void reset();  // ready to run again; binds cleared

  bool has(std::string_view column) const { return at(column) >= 0; }
  bool is_null(std::string_view column) const;  // true too for a column the result lacks
  std::int64_t int64(std::string_view column) const;
  double real(std::string_view column) const;
  std::string text(std::string_view column) const;
  Value value(std::string_view column) const;
  std::int64_t int64(int) const = delete;  // columns are read by name
  double real(int) const = delete;
  std::string text(int) const = delete;
  Value value(int) const = delete;
  bool is_null(int) const = delete;

  // The result's column names and the current row's cells, in the order the SELECT lists them.
  std::vector<std::string> column_names() const;
  std::vector<Value> cells() const;

 private:
  Stmt(std::unique_ptr<Statement> st, std::string db) : st_(std::move(st)), db_(std::move(db)) {}
  int parameter(std::string_view name);  // 0 (and the next step() fails) if the SQL lacks it
  int at(std::string_view column) const;  // -1 if the result lacks it
  std::unique_ptr<Statement> st_;
  std::string db_;                     // the database, for errors
  std::string unbound_;                // the first name bound that the SQL lacks
  mutable std::map<std::string, int, std::less<>> columns_;  // filled at the first read by name
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

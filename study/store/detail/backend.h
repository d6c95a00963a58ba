// The seam between the store and its two database engines: SQLite (a file,
// the embedded default) and PostgreSQL (a lab's server, several stations).
// A Connection runs SQL, transactions and the few things the engines do
// differently (looking at a database before touching it, marking it as a
// dtlab study, bulk inserts, the clock claims are judged by); a Statement
// binds parameters and reads rows. The store's SQL is written once, with
// named `:name` parameters, in the dialect both engines accept; the store's
// code binds and reads only by name (db.h's Stmt), the numbered calls below
// being the engines' own API that Stmt maps names onto. Every failure is
// a dtlab::Error naming the database (a file, or a URI without its password)
// and its kind; nothing here aborts or leaves a transaction open.
#pragma once
#include <chrono>
#include <cstdint>
#include <memory>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "study/common/error.h"

namespace dtlab::store::detail {

enum class Backend { sqlite, postgresql };

// True for a PostgreSQL connection URI (postgresql://... or postgres://...); anything else is a file.
bool is_server_uri(std::string_view where);

// One cell: NULL, an integer, a real or a text (the four types of the schema).
using Value = std::variant<std::monostate, std::int64_t, double, std::string>;

// What a look at a database before using it finds (read in ONE snapshot).
struct FileState {
  bool exists = true;               // PostgreSQL: the schema exists (a missing file never gets this far)
  bool empty = true;                // no schema object at all: a new database
  std::int64_t application_id = 0;  // SQLite: PRAGMA application_id; PostgreSQL: the dtlab_header row
  int user_version = 0;             // SQLite: PRAGMA user_version; PostgreSQL: the dtlab_header row
  int migrations = 0;               // max(schema_migrations.version); 0 without that table
};

// How a connection is used: written (created if missing, or existing only) or read only.
enum class Access { create, write, read };

class Statement {
 public:
  virtual ~Statement() = default;
  // The engines' numbered API (parameters 1-based, columns 0-based), reached by name through
  // parameter_index() and column_index(). Binds stay until reset().
  // The number of the parameter written `:name` in the SQL (`name` without the colon); 0 if none.
  virtual int parameter_index(std::string_view name) const = 0;
  // The number of the result column named `name` (the first of that name); -1 if none.
  int column_index(std::string_view name) const {
    for (int c = 0; c < columns(); ++c)
      if (column_name(c) == name) return c;
    return -1;
  }
  virtual void bind_int(int i, std::int64_t v) = 0;
  virtual void bind_real(int i, double v) = 0;
  virtual void bind_text(int i, std::string_view v) = 0;
  virtual void bind_null(int i) = 0;
  // Advances one row: true = a row is ready, false = done; Error on failure.
  virtual Result<bool> step(std::string_view what) = 0;
  virtual void reset() = 0;  // ready to run again; binds cleared
  virtual bool is_null(int c) const = 0;
  virtual std::int64_t int64(int c) const = 0;  // a boolean column reads as 0/1
  virtual double real(int c) const = 0;
  virtual std::string text(int c) const = 0;
  virtual Value value(int c) const = 0;  // the cell with the type the engine reports
  virtual int columns() const = 0;
  virtual std::string column_name(int c) const = 0;
};

class Connection {
 public:
  virtual ~Connection() = default;
  virtual Backend backend() const = 0;
  const std::string& name() const { return name_; }  // what errors name: the file, or the URI without password
  void set_name(std::string n) { name_ = std::move(n); }

  virtual Result<std::unique_ptr<Statement>> prepare(std::string_view sql, std::string_view what) = 0;
  // Runs statements without parameters that return no rows (DDL, settings); may hold several.
  virtual Status exec(const std::string& sql, std::string_view what) = 0;

  // A write transaction that holds the study's one write lock from its first statement (SQLite:
  // BEGIN IMMEDIATE; PostgreSQL: BEGIN + an advisory lock on the study), waiting up to the busy
  // timeout (then a busy Error): writers never interleave, readers never wait.
  virtual Status begin_write(std::string_view what) = 0;
  // A read transaction whose snapshot is taken now and holds until commit.
  virtual Status begin_read(std::string_view what) = 0;
  virtual Status commit(std::string_view what) = 0;
  virtual bool rollback() = 0;  // rolls back an open transaction; false if the ROLLBACK itself failed
  virtual bool in_transaction() const = 0;
  virtual void set_busy_timeout(int ms) = 0;
  // After the look (inspect) and before the first write: the settings a writer needs (SQLite:
  // WAL, synchronous FULL, foreign keys; PostgreSQL sets everything when it connects).
  virtual Status configure_for_writing(int busy_timeout_ms) = 0;

  // Reads FileState in one snapshot (`in_transaction`: the caller holds one already).
  virtual Result<FileState> inspect(bool in_transaction) = 0;
  // Creates what holds the study if missing (PostgreSQL: its schema; SQLite: nothing, the file
  // exists once opened), then records the application id and schema version; both run inside
  // the schema's write transaction.
  virtual Status create_namespace() = 0;
  virtual Status mark_as_dtlab(int schema_version) = 0;
  virtual Result<bool> has_table(const std::string& name) = 0;
  // The engine's own consistency check: "ok", or what it reports.
  virtual Result<std::string> integrity_check() = 0;
  // The clock timestamps are written with: the machine's for SQLite, the server's for PostgreSQL
  // (stations' clocks differ; a session claim must be judged by one clock).
  virtual Result<std::chrono::system_clock::time_point> now() = 0;
  // Inserts rows into `table` (SQLite: one prepared INSERT, its parameters named after the
  // columns; PostgreSQL: one COPY, whose text format is by column order, the list given with it).
  // Each row has one Value per column, in `columns` order. Constraints and triggers apply as to any INSERT.
  virtual Status insert_rows(const std::string& table, const std::vector<std::string>& columns,
                             const std::vector<std::vector<Value>>& rows, std::string_view what) = 0;

 protected:
  std::string name_;
};

// Opens `where` -- a file path (SQLite) or a postgresql:// URI -- as `access` asks, configured
// for the store (docs/store.md, "Connection settings"), WITHOUT looking at its content: the caller
// inspects it next. Errors: not_found (no such file), environment (cannot open or connect).
Result<std::unique_ptr<Connection>> open_connection(const std::string& where, Access access, int busy_timeout_ms);

// The two engines (sqlite.cpp, postgres.cpp); open_connection chooses.
Result<std::unique_ptr<Connection>> open_sqlite(const std::string& path, Access access, int busy_timeout_ms);
Result<std::unique_ptr<Connection>> open_postgres(const std::string& uri, Access access, int busy_timeout_ms);

}  // namespace dtlab::store::detail

// The SQLite engine behind the store (backend.h): one file per study, WAL
// mode, BEGIN IMMEDIATE for every write. Opening for reading chooses how so
// that nothing is left beside the file and read-only media work. Every
// failure is an Error naming the file, the operation and SQLite's message;
// nothing here aborts or leaves a transaction open.
#include <sqlite3.h>
#include <unistd.h>

#include <charconv>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <thread>
#include <utility>

#include "study/store/detail/backend.h"
#include "study/store/store.h"

namespace dtlab::store::detail {
namespace {

// The ErrorKind of an SQLite result code: busy (BUSY, LOCKED), conflict (a
// constraint or trigger refused the write), invalid_input (NOTADB, CORRUPT: the
// file is not a sound database, whatever the command), else environment.
ErrorKind kind_of(int code) {
  switch (code & 0xff) {
    case SQLITE_BUSY:
    case SQLITE_LOCKED: return ErrorKind::busy;
    case SQLITE_CONSTRAINT: return ErrorKind::conflict;
    case SQLITE_NOTADB:
    case SQLITE_CORRUPT: return ErrorKind::invalid_input;
    default: return ErrorKind::environment;
  }
}

// file = path, field = "sqlite", message = "<what>: <sqlite message> (SQLite code N)".
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
    if ((code & 0xff) == SQLITE_CORRUPT)
      msg += "; the file is damaged (truncated or overwritten): restore the study database from a copy";
  } else {
    msg += "out of memory";
  }
  return Error{path, 0, 0, "sqlite", std::move(msg), kind_of(code)};
}

class SqliteStatement final : public Statement {
 public:
  SqliteStatement(sqlite3_stmt* st, sqlite3* db, const std::string& path) : st_(st), db_(db), path_(path) {}
  ~SqliteStatement() override { sqlite3_finalize(st_); }

  int parameter_index(std::string_view name) const override {
    return sqlite3_bind_parameter_index(st_, (":" + std::string(name)).c_str());
  }
  void bind_int(int i, std::int64_t v) override { sqlite3_bind_int64(st_, i, v); }
  void bind_real(int i, double v) override { sqlite3_bind_double(st_, i, v); }
  void bind_text(int i, std::string_view v) override {
    sqlite3_bind_text(st_, i, v.data(), static_cast<int>(v.size()), SQLITE_TRANSIENT);
  }
  void bind_null(int i) override { sqlite3_bind_null(st_, i); }

  Result<bool> step(std::string_view what) override {
    const int rc = sqlite3_step(st_);
    if (rc == SQLITE_ROW) return true;
    if (rc == SQLITE_DONE) return false;
    Error e = sqlite_error(db_, path_, what);
    sqlite3_reset(st_);
    return e;
  }
  void reset() override {
    sqlite3_reset(st_);
    sqlite3_clear_bindings(st_);
  }

  bool is_null(int c) const override { return sqlite3_column_type(st_, c) == SQLITE_NULL; }
  std::int64_t int64(int c) const override { return sqlite3_column_int64(st_, c); }
  double real(int c) const override { return sqlite3_column_double(st_, c); }
  std::string text(int c) const override {
    const auto* p = reinterpret_cast<const char*>(sqlite3_column_text(st_, c));
    return p ? std::string(p, static_cast<std::size_t>(sqlite3_column_bytes(st_, c))) : std::string();
  }
  Value value(int c) const override {
    switch (sqlite3_column_type(st_, c)) {
      case SQLITE_NULL: return std::monostate{};
      case SQLITE_INTEGER: return int64(c);
      case SQLITE_FLOAT: return real(c);
      default: return text(c);
    }
  }
  int columns() const override { return sqlite3_column_count(st_); }
  std::string column_name(int c) const override { return sqlite3_column_name(st_, c); }

 private:
  sqlite3_stmt* st_ = nullptr;
  sqlite3* db_ = nullptr;
  const std::string& path_;
};

class SqliteConnection final : public Connection {
 public:
  SqliteConnection(sqlite3* db, std::string path) : db_(db) { name_ = std::move(path); }
  ~SqliteConnection() override { sqlite3_close_v2(db_); }

  Backend backend() const override { return Backend::sqlite; }

  Result<std::unique_ptr<Statement>> prepare(std::string_view sql, std::string_view what) override {
    sqlite3_stmt* st = nullptr;
    if (sqlite3_prepare_v2(db_, sql.data(), static_cast<int>(sql.size()), &st, nullptr) != SQLITE_OK)
      return sqlite_error(db_, name_, what);
    return std::unique_ptr<Statement>(std::make_unique<SqliteStatement>(st, db_, name_));
  }
  Status exec(const std::string& sql, std::string_view what) override {
    if (sqlite3_exec(db_, sql.c_str(), nullptr, nullptr, nullptr) != SQLITE_OK) return sqlite_error(db_, name_, what);
    return {};
  }

  Status begin_write(std::string_view what) override { return exec("BEGIN IMMEDIATE", what); }
  Status begin_read(std::string_view what) override {
    if (auto s = exec("BEGIN", what); !s) return s;
    // The snapshot starts at the first read: take it now, so every read sees the same one.
    if (auto s = exec("SELECT count(*) FROM sqlite_schema", what); !s) {
      rollback();
      return s;
    }
    return {};
  }
  Status commit(std::string_view what) override { return exec("COMMIT", what); }
  bool rollback() override {
    if (sqlite3_get_autocommit(db_)) return true;  // none open, or SQLite already rolled back (e.g. SQLITE_FULL)
    return sqlite3_exec(db_, "ROLLBACK", nullptr, nullptr, nullptr) == SQLITE_OK;
  }
  bool in_transaction() const override { return !sqlite3_get_autocommit(db_); }
  void set_busy_timeout(int ms) override { sqlite3_busy_timeout(db_, ms); }

  Status configure_for_writing(int busy_timeout_ms) override {
    // WAL: readers never block the writer. FULL: a committed trial survives power loss too.
    auto mode = set_wal(busy_timeout_ms);
    if (!mode) return mode.error();
    if (*mode != "wal")
      return Error{name_, 0, 0, "sqlite", "cannot use WAL mode (journal_mode is \"" + *mode + "\")",
                   ErrorKind::environment};
    return exec("PRAGMA foreign_keys = ON; PRAGMA synchronous = FULL", "configuring the connection");
  }

  Result<FileState> inspect(bool in_transaction) override {
    if (in_transaction) return read_state();
    // BEGIN (deferred) + the first read fix one snapshot for all four reads.
    if (auto b = exec("BEGIN", "starting a read transaction"); !b) return b.error();
    auto s = read_state();
    exec("COMMIT", "ending the read transaction");  // a read-only transaction: nothing to lose if it fails
    return s;
  }
  Status create_namespace() override { return {}; }
  Status mark_as_dtlab(int schema_version) override {
    return exec("PRAGMA application_id = " + std::to_string(kApplicationId) +
                    "; PRAGMA user_version = " + std::to_string(schema_version),
                "marking the file as a dtlab database");
  }
  Result<bool> has_table(const std::string& name) override {
    auto st = prepare("SELECT count(*) AS n FROM sqlite_schema WHERE type = 'table' AND name = :name",
                      "reading the schema");
    if (!st) return st.error();
    (*st)->bind_text((*st)->parameter_index("name"), name);
    auto row = (*st)->step("reading the schema");
    if (!row) return row.error();
    return *row && (*st)->int64((*st)->column_index("n")) > 0;
  }
  Result<std::string> integrity_check() override {
    std::string report, fk;
    if (auto s = each("PRAGMA integrity_check", "checking integrity",
                      [&](Statement& q) {
                        report += (report.empty() ? "" : "; ") + q.text(q.column_index("integrity_check"));
                      });
        !s)
      return s.error();
    if (auto s = each("PRAGMA foreign_key_check", "checking foreign keys",
                      [&](Statement& q) {
                        fk += (fk.empty() ? "" : "; ") + q.text(q.column_index("table")) + " row " +
                              q.text(q.column_index("rowid")) + " points to a missing " +
                              q.text(q.column_index("parent"));
                      });
        !s)
      return s.error();
    if (report == "ok" && fk.empty()) return std::string("ok");
    return report == "ok" ? fk : report + (fk.empty() ? "" : "; " + fk);
  }
  Result<std::chrono::system_clock::time_point> now() override { return std::chrono::system_clock::now(); }

  Status insert_rows(const std::string& table, const std::vector<std::string>& columns,
                     const std::vector<std::vector<Value>>& rows, std::string_view what) override {
    if (rows.empty()) return {};
    std::string sql = "INSERT INTO " + table + " (";
    for (std::size_t c = 0; c < columns.size(); ++c) sql += (c ? ", " : "") + columns[c];
    sql += ") VALUES (";
    for (std::size_t c = 0; c < columns.size(); ++c) sql += (c ? ", :" : ":") + columns[c];
    sql += ")";
    auto st = prepare(sql, what);
    if (!st) return st.error();
    Statement& s = **st;
    std::vector<int> index;  // each column's parameter, found once by its name
    for (const std::string& c : columns) index.push_back(s.parameter_index(c));
    for (const auto& row : rows) {
      for (std::size_t c = 0; c < row.size(); ++c) {
        const int i = index[c];
        if (const auto* n = std::get_if<std::int64_t>(&row[c])) s.bind_int(i, *n);
        else if (const auto* d = std::get_if<double>(&row[c])) s.bind_real(i, *d);
        else if (const auto* t = std::get_if<std::string>(&row[c])) s.bind_text(i, *t);
        else s.bind_null(i);
      }
      auto r = s.step(what);
      if (!r) return r.error();
      s.reset();
    }
    return {};
  }

  sqlite3* handle() const { return db_; }

 private:
  template <class Row>
  Status each(const std::string& sql, std::string_view what, Row&& row) {
    auto st = prepare(sql, what);
    if (!st) return st.error();
    for (;;) {
      auto r = (*st)->step(what);
      if (!r) return r.error();
      if (!*r) return {};
      row(**st);
    }
  }

  // The column `column` of the first row of `sql` (0 without a row).
  Result<std::int64_t> query_int(const char* sql, std::string_view column, std::string_view what) {
    auto st = prepare(sql, what);
    if (!st) return st.error();
    auto row = (*st)->step(what);
    if (!row) return row.error();
    return *row ? (*st)->int64((*st)->column_index(column)) : 0;
  }

  Result<FileState> read_state() {
    FileState s;
    auto app_id = query_int("PRAGMA application_id", "application_id", "reading the file header");
    if (!app_id) {
      if (sqlite3_extended_errcode(db_) == SQLITE_NOTADB)
        return Error{name_, 0, 0, "", "not an SQLite database; expected a dtlab study database"};
      return app_id.error();
    }
    s.application_id = *app_id;
    auto objects = query_int("SELECT count(*) AS n FROM sqlite_schema", "n", "reading the schema");
    if (!objects) return objects.error();
    s.empty = *objects == 0;
    auto version = query_int("PRAGMA user_version", "user_version", "reading the schema version");
    if (!version) return version.error();
    s.user_version = static_cast<int>(*version);
    auto has = has_table("schema_migrations");
    if (!has) return has.error();
    if (*has) {
      auto m =
          query_int("SELECT coalesce(max(version), 0) AS n FROM schema_migrations", "n", "reading the schema version");
      if (!m) return m.error();
      s.migrations = static_cast<int>(*m);
    }
    return s;
  }

  // PRAGMA journal_mode = WAL. Switching needs an exclusive lock, and SQLite
  // answers SQLITE_BUSY at once instead of calling the busy handler, so when
  // several processes create the same file together the losers retry here
  // (until the busy timeout) and then find the file already in WAL mode.
  Result<std::string> set_wal(int timeout_ms) {
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::milliseconds(timeout_ms);
    for (;;) {
      auto st = prepare("PRAGMA journal_mode = WAL", "switching to WAL mode");
      if (st) {
        auto row = (*st)->step("switching to WAL mode");
        if (row) return *row ? (*st)->text((*st)->column_index("journal_mode")) : std::string();
        st = row.error();
      }
      const int code = sqlite3_errcode(db_);
      if ((code != SQLITE_BUSY && code != SQLITE_LOCKED) || std::chrono::steady_clock::now() >= deadline)
        return st.error();
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
  }

  sqlite3* db_ = nullptr;
};

Result<std::unique_ptr<Connection>> open_file(const std::string& path, int flags) {
  sqlite3* handle = nullptr;
  const int rc = sqlite3_open_v2(path.c_str(), &handle, flags | SQLITE_OPEN_NOMUTEX, nullptr);
  if (rc != SQLITE_OK) {
    Error e = sqlite_error(handle, path, "cannot open the database");
    sqlite3_close_v2(handle);
    return e;
  }
  sqlite3_extended_result_codes(handle, 1);
  return std::unique_ptr<Connection>(std::make_unique<SqliteConnection>(handle, path));
}

std::string uri_escape(const std::string& path) {
  std::string out = "file:";
  for (unsigned char ch : path) {
    if (ch == '?' || ch == '#' || ch == '%' || ch < 0x20) {
      char buf[4];
      std::snprintf(buf, sizeof buf, "%%%02X", ch);
      out += buf;
    } else {
      out += static_cast<char>(ch);
    }
  }
  return out;
}

// Opens `path` for reading only, choosing how so that nothing is left behind:
// writable file in a writable directory -> read-write without CREATE, made
// read-only by query_only (as the last connection it checkpoints and removes
// -wal/-shm like any writer; a SQLITE_OPEN_READONLY connection could not);
// otherwise (read-only media, a write-protected file) -> immutable when no
// write-ahead log is waiting, plain read-only when one is.
Result<std::unique_ptr<Connection>> open_for_reading(const std::string& path) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::path p(path);
  const fs::path dir = p.has_parent_path() ? p.parent_path() : fs::path(".");
  const bool writable = ::access(path.c_str(), W_OK) == 0 && ::access(dir.c_str(), W_OK) == 0;
  if (writable) {
    auto db = open_file(path, SQLITE_OPEN_READWRITE);
    if (!db) return db.error();
    if (auto s = (*db)->exec("PRAGMA query_only = ON", "making the connection read-only"); !s) return s.error();
    return db;
  }
  const bool wal_waiting = fs::exists(path + "-wal", ec) && fs::file_size(path + "-wal", ec) > 0;
  const std::string uri = uri_escape(path) + (wal_waiting ? "?mode=ro" : "?mode=ro&immutable=1");
  auto db = open_file(uri, SQLITE_OPEN_READONLY | SQLITE_OPEN_URI);
  if (!db) {
    Error e = db.error();
    e.file = path;
    if (wal_waiting)
      e.message += "; the file has an unfinished write-ahead log (" + path +
                   "-wal) in a directory this process cannot write: copy the database and its -wal file to a "
                   "writable place and read it there";
    return e;
  }
  (*db)->set_name(path);
  return db;
}

}  // namespace

Result<std::unique_ptr<Connection>> open_sqlite(const std::string& path, Access access, int busy_timeout_ms) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec))
    return Error{path, 0, 0, "", "is a directory; expected a dtlab study database file", ErrorKind::invalid_input};
  const bool exists = std::filesystem::exists(path, ec);
  if (access != Access::create && !exists)
    return Error{path, 0, 0, "", "no such file; expected an existing dtlab study database", ErrorKind::not_found};
  // A write SQLite would refuse only at its first statement, after creating -wal and -shm beside
  // the file: refused here, before anything is touched.
  if (access != Access::read && exists && ::access(path.c_str(), W_OK) != 0)
    return Error{path, 0, 0, "",
                 "the database file is read-only for this user; nothing was written (this command records to the "
                 "study: give it a writable copy, or change the file's permissions)",
                 ErrorKind::environment};
  auto db = access == Access::read
                ? open_for_reading(path)
                : open_file(path, SQLITE_OPEN_READWRITE | (access == Access::create ? SQLITE_OPEN_CREATE : 0));
  if (!db) return db.error();
  (*db)->set_busy_timeout(busy_timeout_ms);
  return db;
}

}  // namespace dtlab::store::detail

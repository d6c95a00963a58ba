// The PostgreSQL engine behind the store (backend.h), through libpq: a lab's
// server shared by several stations. A study lives in one schema of one
// database (the URI's `schema` parameter, default `public`); every write
// transaction first takes the study's advisory lock, so writers queue like
// SQLite's single writer and enrollment's read-decide-write never interleaves
// across stations; readers take a REPEATABLE READ snapshot and never wait.
// Errors name the URI without its password. Never: leaves a transaction open,
// aborts, or sends a password anywhere but to libpq.
#include <libpq-fe.h>

#include <algorithm>
#include <charconv>
#include <optional>
#include <string>
#include <vector>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <utility>

#include "study/store/detail/backend.h"
#include "study/store/detail/pg_uri.h"
#include "study/store/store.h"

namespace dtlab::store::detail {
namespace {

// Type OIDs of the built-in types the store uses (PostgreSQL's catalog/pg_type.h).
constexpr Oid kBool = 16, kInt8 = 20, kInt2 = 21, kInt4 = 23, kText = 25, kFloat4 = 700, kFloat8 = 701, kNumeric = 1700;

// libpq's messages end in a newline and may hold more lines ("\n\tIs the server running ..."):
// one line for an Error.
std::string one_line(std::string m) {
  std::string out;
  for (char c : m) {
    if (c == '\n' || c == '\t') {
      if (!out.empty() && out.back() != ' ') out += ' ';
    } else {
      out += c;
    }
  }
  while (!out.empty() && out.back() == ' ') out.pop_back();
  return out;
}

// The ErrorKind of an SQLSTATE: integrity violations (class 23, our triggers raise 23000) are
// conflicts; a lock held past lock_timeout, a serialization failure or a deadlock is busy
// (retrying helps); a syntax error is ours (internal); bad data is the input's; the rest, the
// environment's (connection, permissions, disk).
ErrorKind kind_of(const std::string& state) {
  if (state.rfind("23", 0) == 0) return ErrorKind::conflict;
  if (state == "55P03" || state == "40001" || state == "40P01" || state == "57014") return ErrorKind::busy;
  if (state == "42601") return ErrorKind::internal;
  if (state.rfind("22", 0) == 0) return ErrorKind::invalid_input;
  return ErrorKind::environment;
}

Error pg_error(PGconn* conn, const PGresult* res, const std::string& name, std::string_view what) {
  std::string state, message;
  if (res && PQresultErrorField(res, PG_DIAG_SQLSTATE)) {
    state = PQresultErrorField(res, PG_DIAG_SQLSTATE);
    const char* primary = PQresultErrorField(res, PG_DIAG_MESSAGE_PRIMARY);
    const char* detail = PQresultErrorField(res, PG_DIAG_MESSAGE_DETAIL);
    message = primary ? primary : "";
    if (detail) message += std::string(" (") + detail + ")";
  } else {
    message = conn ? one_line(PQerrorMessage(conn)) : "out of memory";
    if (conn && PQstatus(conn) != CONNECTION_OK) message += "; the connection to the server is lost";
  }
  std::string msg = std::string(what) + ": " + message;
  if (!state.empty()) msg += " (SQLSTATE " + state + ")";
  const ErrorKind kind = state.empty() ? ErrorKind::environment : kind_of(state);
  if (kind == ErrorKind::busy) msg += "; another station held the study past the busy timeout: try again";
  return Error{name, 0, 0, "postgresql", std::move(msg), kind};
}

// `:name` -> `$k`, the k-th distinct name in order of first use (`names` receives them), outside
// quoted literals and identifiers; a cast's `::` is left alone. PostgreSQL numbers its parameters
// only; the store's SQL names them (backend.h).
std::string numbered_placeholders(std::string_view sql, std::vector<std::string>& names) {
  auto ident = [](char c, bool first) {
    return c == '_' || (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (!first && c >= '0' && c <= '9');
  };
  std::string out;
  names.clear();
  out.reserve(sql.size() + 16);
  char quote = 0;
  for (std::size_t i = 0; i < sql.size(); ++i) {
    const char c = sql[i];
    if (quote) {
      out += c;
      if (c == quote) quote = 0;
      continue;
    }
    if (c == '\'' || c == '"') {
      quote = c;
      out += c;
      continue;
    }
    if (c == ':' && i + 1 < sql.size() && sql[i + 1] == ':') {  // a cast
      out += "::";
      ++i;
      continue;
    }
    if (c != ':' || i + 1 >= sql.size() || !ident(sql[i + 1], true)) {
      out += c;
      continue;
    }
    std::size_t j = i + 1;
    while (j < sql.size() && ident(sql[j], false)) ++j;
    const std::string name(sql.substr(i + 1, j - i - 1));
    auto it = std::find(names.begin(), names.end(), name);
    if (it == names.end()) it = names.insert(names.end(), name);
    out += '$' + std::to_string(it - names.begin() + 1);
    i = j - 1;
  }
  return out;
}

// The shortest text that reads back as exactly `v`. A zero is written as 0, never -0: SQLite
// cannot keep the sign of a zero (it stores integral reals as integers), and both engines must
// hold the same values.
std::string shortest(double v) {
  if (v == 0) v = 0;
  char buf[64];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, r.ptr);
}

// A value in COPY's text format: \N for NULL, backslash escapes in text.
void copy_field(std::string& out, const Value& v) {
  if (const auto* n = std::get_if<std::int64_t>(&v)) {
    out += std::to_string(*n);
  } else if (const auto* d = std::get_if<double>(&v)) {
    out += shortest(*d);
  } else if (const auto* t = std::get_if<std::string>(&v)) {
    for (char c : *t) {
      switch (c) {
        case '\\': out += "\\\\"; break;
        case '\t': out += "\\t"; break;
        case '\n': out += "\\n"; break;
        case '\r': out += "\\r"; break;
        default: out += c;
      }
    }
  } else {
    out += "\\N";
  }
}

class PgConnection;

class PgStatement final : public Statement {
 public:
  PgStatement(PgConnection& c, std::string_view sql) : c_(c) { sql_ = numbered_placeholders(sql, names_); }
  ~PgStatement() override { PQclear(res_); }

  int parameter_index(std::string_view name) const override {
    const auto it = std::find(names_.begin(), names_.end(), name);
    return it == names_.end() ? 0 : static_cast<int>(it - names_.begin() + 1);
  }
  void bind_int(int i, std::int64_t v) override { set(i, std::to_string(v), kInt8); }
  void bind_real(int i, double v) override { set(i, shortest(v), kFloat8); }
  void bind_text(int i, std::string_view v) override { set(i, std::string(v), kText); }
  void bind_null(int i) override { set(i, std::nullopt, 0); }

  Result<bool> step(std::string_view what) override;
  void reset() override {
    PQclear(res_);
    res_ = nullptr;
    values_.clear();
    types_.clear();
  }

  bool is_null(int c) const override { return PQgetisnull(res_, row_, c) != 0; }
  std::int64_t int64(int c) const override {
    const char* s = PQgetvalue(res_, row_, c);
    if (s[0] == 't' && s[1] == 0) return 1;  // a boolean column
    if (s[0] == 'f' && s[1] == 0) return 0;
    std::int64_t v = 0;
    const auto* end = s + std::char_traits<char>::length(s);
    if (std::from_chars(s, end, v).ec == std::errc() ) return v;
    return static_cast<std::int64_t>(real(c));
  }
  double real(int c) const override {
    const char* s = PQgetvalue(res_, row_, c);
    double v = 0;
    std::from_chars(s, s + std::char_traits<char>::length(s), v);
    return v;
  }
  std::string text(int c) const override {
    return std::string(PQgetvalue(res_, row_, c), static_cast<std::size_t>(PQgetlength(res_, row_, c)));
  }
  Value value(int c) const override {
    if (is_null(c)) return std::monostate{};
    switch (PQftype(res_, c)) {
      case kBool:
      case kInt2:
      case kInt4:
      case kInt8: return int64(c);
      case kFloat4:
      case kFloat8:
      case kNumeric: return real(c);
      default: return text(c);
    }
  }
  int columns() const override { return res_ ? PQnfields(res_) : 0; }
  std::string column_name(int c) const override { return res_ ? PQfname(res_, c) : ""; }

 private:
  void set(int i, std::optional<std::string> v, Oid type) {
    const auto at = static_cast<std::size_t>(i - 1);
    if (values_.size() <= at) {
      values_.resize(at + 1);
      types_.resize(at + 1, 0);
    }
    values_[at] = std::move(v);
    types_[at] = type;
  }

  PgConnection& c_;
  std::string sql_;
  // The parameters' names, $1's first; an unbound one is sent as NULL, as SQLite reads it.
  std::vector<std::string> names_;
  std::vector<std::optional<std::string>> values_;
  std::vector<Oid> types_;
  PGresult* res_ = nullptr;
  int row_ = -1, rows_ = 0;
};

class PgConnection final : public Connection {
 public:
  PgConnection(PGconn* conn, PgAddress address) : conn_(conn), address_(std::move(address)) {
    name_ = address_.display;
  }
  ~PgConnection() override { PQfinish(conn_); }

  Backend backend() const override { return Backend::postgresql; }
  PGconn* handle() const { return conn_; }
  const std::string& schema() const { return address_.schema; }

  Result<std::unique_ptr<Statement>> prepare(std::string_view sql, std::string_view) override {
    return std::unique_ptr<Statement>(std::make_unique<PgStatement>(*this, sql));
  }

  Status exec(const std::string& sql, std::string_view what) override {
    PGresult* res = PQexec(conn_, sql.c_str());
    const auto status = PQresultStatus(res);
    Status out;
    if (status != PGRES_COMMAND_OK && status != PGRES_TUPLES_OK) out = pg_error(conn_, res, name_, what);
    PQclear(res);
    return out;
  }

  Status begin_write(std::string_view what) override {
    // One round trip: the transaction, the study's write lock (released by COMMIT or ROLLBACK, and
    // by the server when the client dies), and the server's clock once the lock is held.
    const std::string sql = "BEGIN ISOLATION LEVEL READ COMMITTED; SELECT pg_advisory_xact_lock(" +
                            std::to_string(kApplicationId) + ", " + std::to_string(address_.lock_key) +
                            ") AS locked, extract(epoch FROM clock_timestamp())::float8 AS now";
    PGresult* res = PQexec(conn_, sql.c_str());
    Status out;
    if (PQresultStatus(res) != PGRES_TUPLES_OK) {
      out = pg_error(conn_, res, name_, what);
    } else {
      clock_offset_ = from_epoch(std::strtod(PQgetvalue(res, 0, PQfnumber(res, "now")), nullptr)) -
                      std::chrono::system_clock::now();
      in_write_ = true;
    }
    PQclear(res);
    if (!out) rollback();
    return out;
  }
  Status begin_read(std::string_view what) override {
    if (auto s = exec("BEGIN ISOLATION LEVEL REPEATABLE READ READ ONLY", what); !s) return s;
    if (auto s = exec("SELECT 1", what); !s) {  // the snapshot is taken by the first statement: now
      rollback();
      return s;
    }
    return {};
  }
  Status commit(std::string_view what) override {
    in_write_ = false;
    if (PQtransactionStatus(conn_) == PQTRANS_INERROR)
      return Error{name_, 0, 0, "postgresql", std::string(what) + ": the transaction failed earlier; nothing of it is saved",
                   ErrorKind::internal};
    PGresult* res = PQexec(conn_, "COMMIT");
    Status out;
    if (PQresultStatus(res) != PGRES_COMMAND_OK) out = pg_error(conn_, res, name_, what);
    else if (std::string(PQcmdStatus(res)) != "COMMIT")
      out = Error{name_, 0, 0, "postgresql", std::string(what) + ": the server rolled the transaction back",
                  ErrorKind::environment};
    PQclear(res);
    return out;
  }
  bool rollback() override {
    in_write_ = false;
    const auto t = PQtransactionStatus(conn_);
    if (t == PQTRANS_IDLE) return true;
    if (t == PQTRANS_UNKNOWN) return false;  // the connection is gone: the server rolled back
    return static_cast<bool>(exec("ROLLBACK", "rolling back"));
  }
  bool in_transaction() const override {
    const auto t = PQtransactionStatus(conn_);
    return t != PQTRANS_IDLE && t != PQTRANS_UNKNOWN;
  }
  void set_busy_timeout(int ms) override {
    exec("SET lock_timeout = '" + std::to_string(std::max(ms, 1)) + "ms'", "setting the lock timeout");
  }
  Status configure_for_writing(int) override { return {}; }  // everything is set at connect

  Result<FileState> inspect(bool in_transaction) override {
    if (in_transaction) return read_state();
    if (auto b = begin_read("starting a read transaction"); !b) return b.error();
    auto s = read_state();
    rollback();  // read only: nothing to keep
    return s;
  }

  Status create_namespace() override {
    return exec("CREATE SCHEMA IF NOT EXISTS " + quote_pg_identifier(address_.schema), "creating the study's schema");
  }
  Status mark_as_dtlab(int schema_version) override {
    return exec("INSERT INTO dtlab_header (one, application_id, user_version) VALUES (TRUE, " +
                    std::to_string(kApplicationId) + ", " + std::to_string(schema_version) +
                    ") ON CONFLICT (one) DO UPDATE SET application_id = excluded.application_id, "
                    "user_version = excluded.user_version",
                "marking the schema as a dtlab database");
  }

  Result<bool> has_table(const std::string& table) override {
    auto n = count("SELECT count(*) AS n FROM pg_class c JOIN pg_namespace n ON n.oid = c.relnamespace "
                   "WHERE n.nspname = :schema AND c.relname = :table AND c.relkind IN ('r', 'p')",
                   {{"schema", address_.schema}, {"table", table}}, "reading the schema");
    if (!n) return n.error();
    return *n > 0;
  }

  Result<std::string> integrity_check() override {
    // The server keeps its pages consistent; what a client could break is switched-off guards.
    std::string report;
    auto add = [&](const std::string& sql, const std::string& what) -> Status {
      auto st = prepare(sql, what);
      (*st)->bind_text((*st)->parameter_index("schema"), address_.schema);
      for (;;) {
        auto r = (*st)->step(what);
        if (!r) return r.error();
        if (!*r) return {};
        report += (report.empty() ? "" : "; ") + (*st)->text((*st)->column_index("problem"));
      }
    };
    if (auto s = add("SELECT 'constraint ' || c.conname || ' is not validated' AS problem FROM pg_constraint c "
                     "JOIN pg_namespace n ON n.oid = c.connamespace WHERE n.nspname = :schema AND NOT c.convalidated",
                     "checking constraints");
        !s)
      return s.error();
    if (auto s = add("SELECT 'trigger ' || t.tgname || ' on ' || r.relname || ' is disabled' AS problem "
                     "FROM pg_trigger t "
                     "JOIN pg_class r ON r.oid = t.tgrelid JOIN pg_namespace n ON n.oid = r.relnamespace "
                     "WHERE n.nspname = :schema AND NOT t.tgisinternal AND t.tgenabled = 'D'",
                     "checking triggers");
        !s)
      return s.error();
    return report.empty() ? std::string("ok") : report;
  }

  // The server's clock: read in the write transaction's first round trip and advanced by this
  // machine's clock while the transaction runs (milliseconds); outside one, read from the server.
  Result<std::chrono::system_clock::time_point> now() override {
    if (in_write_) return std::chrono::system_clock::now() + clock_offset_;
    auto st = prepare("SELECT extract(epoch FROM clock_timestamp())::float8 AS now", "reading the server's clock");
    auto row = (*st)->step("reading the server's clock");
    if (!row) return row.error();
    return from_epoch((*st)->real((*st)->column_index("now")));
  }

  Status insert_rows(const std::string& table, const std::vector<std::string>& columns,
                     const std::vector<std::vector<Value>>& rows, std::string_view what) override {
    if (rows.empty()) return {};
    std::string sql = "COPY " + table + " (";
    for (std::size_t c = 0; c < columns.size(); ++c) sql += (c ? ", " : "") + columns[c];
    sql += ") FROM STDIN";
    PGresult* res = PQexec(conn_, sql.c_str());
    if (PQresultStatus(res) != PGRES_COPY_IN) {
      Error e = pg_error(conn_, res, name_, what);
      PQclear(res);
      return e;
    }
    PQclear(res);
    std::string buf;
    bool sent = true;
    for (const auto& row : rows) {
      for (std::size_t c = 0; c < row.size(); ++c) {
        if (c) buf += '\t';
        copy_field(buf, row[c]);
      }
      buf += '\n';
      if (buf.size() >= (1u << 16)) {
        sent = sent && PQputCopyData(conn_, buf.data(), static_cast<int>(buf.size())) == 1;
        buf.clear();
      }
    }
    if (!buf.empty()) sent = sent && PQputCopyData(conn_, buf.data(), static_cast<int>(buf.size())) == 1;
    PQputCopyEnd(conn_, sent ? nullptr : "dtlab: sending the rows failed");
    Status out;
    while ((res = PQgetResult(conn_)) != nullptr) {
      if (out && PQresultStatus(res) != PGRES_COMMAND_OK) out = pg_error(conn_, res, name_, what);
      PQclear(res);
    }
    return out;
  }

  // Runs a query that returns one count, named `n`, with its `:name` parameters bound to texts.
  Result<std::int64_t> count(const char* sql, const std::vector<std::pair<std::string, std::string>>& params,
                             std::string_view what) {
    PgStatement st(*this, sql);
    for (const auto& [name, value] : params) st.bind_text(st.parameter_index(name), value);
    auto row = st.step(what);
    if (!row) return row.error();
    if (!*row || st.is_null(st.column_index("n"))) return std::int64_t{0};
    return st.int64(st.column_index("n"));
  }

 private:
  Result<FileState> read_state() {
    FileState s;
    const char* what = "reading the schema";
    auto exists =
        count("SELECT count(*) AS n FROM pg_namespace WHERE nspname = :schema", {{"schema", address_.schema}}, what);
    if (!exists) return exists.error();
    s.exists = *exists > 0;
    auto objects = count("SELECT (SELECT count(*) FROM pg_class c JOIN pg_namespace n ON n.oid = c.relnamespace "
                         "WHERE n.nspname = :schema) + (SELECT count(*) FROM pg_proc p JOIN pg_namespace n ON "
                         "n.oid = p.pronamespace WHERE n.nspname = :schema) AS n",
                         {{"schema", address_.schema}}, what);
    if (!objects) return objects.error();
    s.empty = *objects == 0;
    auto header = has_table("dtlab_header");
    if (!header) return header.error();
    if (*header) {
      auto app = count("SELECT application_id AS n FROM dtlab_header", {}, "reading the dtlab header");
      if (!app) return app.error();
      auto version = count("SELECT user_version AS n FROM dtlab_header", {}, "reading the dtlab header");
      if (!version) return version.error();
      s.application_id = *app;
      s.user_version = static_cast<int>(*version);
    }
    auto migrations = has_table("schema_migrations");
    if (!migrations) return migrations.error();
    if (*migrations) {
      auto m = count("SELECT coalesce(max(version), 0) AS n FROM schema_migrations", {}, "reading the schema version");
      if (!m) return m.error();
      s.migrations = static_cast<int>(*m);
    }
    return s;
  }

  static std::chrono::system_clock::time_point from_epoch(double seconds) {
    return std::chrono::system_clock::time_point(
        std::chrono::duration_cast<std::chrono::system_clock::duration>(std::chrono::duration<double>(seconds)));
  }

  PGconn* conn_ = nullptr;
  PgAddress address_;
  bool in_write_ = false;  // a write transaction is open: now() needs no round trip
  std::chrono::system_clock::duration clock_offset_{};  // server clock - this machine's, at its start
};

Result<bool> PgStatement::step(std::string_view what) {
  if (!res_) {
    if (values_.size() < names_.size()) {
      values_.resize(names_.size());
      types_.resize(names_.size(), 0);
    }
    std::vector<const char*> values;
    values.reserve(values_.size());
    for (const auto& v : values_) values.push_back(v ? v->c_str() : nullptr);
    res_ = PQexecParams(c_.handle(), sql_.c_str(), static_cast<int>(values.size()), types_.data(), values.data(),
                        nullptr, nullptr, 0);
    const auto status = PQresultStatus(res_);
    if (status != PGRES_TUPLES_OK && status != PGRES_COMMAND_OK) {
      Error e = pg_error(c_.handle(), res_, c_.name(), what);
      PQclear(res_);
      res_ = nullptr;
      return e;
    }
    rows_ = PQntuples(res_);
    row_ = -1;
  }
  if (row_ + 1 >= rows_) {
    row_ = rows_;
    return false;
  }
  ++row_;
  return true;
}

}  // namespace

Result<std::unique_ptr<Connection>> open_postgres(const std::string& uri, Access access, int busy_timeout_ms) {
  auto address = parse_pg_uri(uri);
  if (!address) return address.error();
  // Defaults first, the URI after them (it may override them), the encoding last (always UTF-8).
  const char* keys[] = {"connect_timeout", "application_name", "dbname", "client_encoding", nullptr};
  const char* values[] = {"10", "dtlab", address->conninfo.c_str(), "UTF8", nullptr};
  PGconn* conn = PQconnectdbParams(keys, values, 1);
  if (!conn)
    return Error{address->display, 0, 0, "postgresql", "cannot connect: out of memory", ErrorKind::environment};
  if (PQstatus(conn) != CONNECTION_OK) {
    const std::string msg = one_line(PQerrorMessage(conn));
    PQfinish(conn);
    return Error{address->display, 0, 0, "postgresql", "cannot connect to the PostgreSQL server: " + msg,
                 ErrorKind::environment};
  }
  if (PQserverVersion(conn) < 110000) {
    const int v = PQserverVersion(conn);
    PQfinish(conn);
    return Error{address->display, 0, 0, "postgresql",
                 "the server runs PostgreSQL " + std::to_string(v / 10000) + "; dtlab needs 11 or newer",
                 ErrorKind::environment};
  }
  auto c = std::make_unique<PgConnection>(conn, std::move(*address));
  // docs/store.md, "Connection settings": the study's schema only; commits durable; floats in their
  // shortest exact text; no NOTICE chatter on stderr; the lock wait is the busy timeout.
  std::string settings = "SET search_path TO " + quote_pg_identifier(c->schema()) +
                         "; SET synchronous_commit = on; SET extra_float_digits = 1; "
                         "SET standard_conforming_strings = on; SET TIME ZONE 'UTC'; SET client_min_messages = warning; "
                         "SET lock_timeout = '" +
                         std::to_string(std::max(busy_timeout_ms, 1)) + "ms'";
  if (access == Access::read) settings += "; SET default_transaction_read_only = on";
  if (auto s = c->exec(settings, "configuring the connection"); !s) return s.error();
  return std::unique_ptr<Connection>(std::move(c));
}

}  // namespace dtlab::store::detail

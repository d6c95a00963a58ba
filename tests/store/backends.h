// The two engines the store tests run against: SQLite (a file in a fresh
// temporary directory) and PostgreSQL (a fresh schema on a throwaway server
// that pg_server.sh starts: once per ctest run as a fixture, or once per test
// program run by hand). RawDb reads and writes either with the engine's own C
// API (sqlite3, libpq), never through the code under test. Where the server
// binaries are missing, every PostgreSQL test skips with a message saying so.
#pragma once
#include <gtest/gtest.h>
#include <libpq-fe.h>
#include <sqlite3.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

namespace dtlab::store::testing {

enum class Backend { sqlite, postgresql };

// "SQLite" / "Pg": the suffix of a parameterized test's name (Store.RoundTripOfASession/Pg).
inline std::string backend_param_name(const ::testing::TestParamInfo<Backend>& info) {
  return info.param == Backend::sqlite ? "SQLite" : "Pg";
}

// The test server: its base URI (database dtlab_test), or why there is none.
struct TestServer {
  std::string uri, unavailable;
};

// Reads STATE/status written by pg_server.sh.
inline TestServer read_server_state(const std::string& state) {
  std::ifstream in(state + "/status");
  std::string word, rest;
  in >> word;
  std::getline(in, rest);
  if (!rest.empty() && rest[0] == ' ') rest.erase(0, 1);
  if (word == "uri") return {rest, ""};
  if (word == "unavailable") return {"", rest};
  return {"", "the test server did not start (no " + state + "/status); see the PgServer.Start test's output"};
}

// The server of this test run: ctest's fixture (DTLAB_TEST_PG_STATE), else one this process
// starts and stops at exit.
inline const TestServer& test_server() {
  static const TestServer server = [] {
    if (const char* state = std::getenv("DTLAB_TEST_PG_STATE"); state && *state) return read_server_state(state);
    static const std::string own = std::filesystem::temp_directory_path().string() + "/dtlab-pg-state-" +
                                   std::to_string(::getpid());
    const std::string script = std::string(DTLAB_SOURCE_DIR) + "/tests/store/pg_server.sh";
    if (std::system(("'" + script + "' start '" + own + "'").c_str()) != 0)
      return TestServer{"", "pg_server.sh could not start a server (its output is above)"};
    std::atexit([] { std::system(("'" + std::string(DTLAB_SOURCE_DIR) + "/tests/store/pg_server.sh' stop '" + own +
                                  "' && rm -rf '" + own + "'").c_str()); });
    return read_server_state(own);
  }();
  return server;
}

// Skips the current test, visibly, when it needs the server and there is none.
#define DTLAB_SKIP_WITHOUT_SERVER(backend)                                                          \
  do {                                                                                               \
    if ((backend) == ::dtlab::store::testing::Backend::postgresql &&                                 \
        !::dtlab::store::testing::test_server().unavailable.empty())                                 \
      GTEST_SKIP() << "PostgreSQL half skipped: " << ::dtlab::store::testing::test_server().unavailable; \
  } while (0)

// A new, unused study location: a file path under `dir`, or the test server's URI with a schema
// no other test uses.
inline std::string new_study(Backend backend, const std::string& dir, const std::string& name) {
  if (backend == Backend::sqlite) return dir + "/" + name + ".sqlite";
  static int counter = 0;
  return test_server().uri + "&schema=t" + std::to_string(::getpid()) + "_" + std::to_string(counter++);
}

inline bool is_uri(const std::string& where) { return where.rfind("postgresql://", 0) == 0; }

// The libpq URI and the schema of a study URI made by new_study (the test's own parsing).
inline std::pair<std::string, std::string> split_schema(const std::string& uri) {
  const auto at = uri.find("&schema=");
  if (at == std::string::npos) return {uri, "public"};
  return {uri.substr(0, at), uri.substr(at + 8)};
}

// Independent raw reader and writer for assertions: every value as text, "NULL" for NULL.
// SQLite reals are printed with 17 significant digits (exact round trip); PostgreSQL's text
// output of a double is its shortest exact form.
class RawDb {
 public:
  explicit RawDb(const std::string& where, int sqlite_flags = SQLITE_OPEN_READWRITE) {
    if (!is_uri(where)) {
      if (sqlite3_open_v2(where.c_str(), &db_, sqlite_flags, nullptr) != SQLITE_OK) ADD_FAILURE() << "cannot open " << where;
      sqlite3_busy_timeout(db_, 10000);
      return;
    }
    const auto [conninfo, schema] = split_schema(where);
    schema_ = schema;
    pg_ = PQconnectdb(conninfo.c_str());
    if (PQstatus(pg_) != CONNECTION_OK) ADD_FAILURE() << "cannot connect: " << PQerrorMessage(pg_);
    exec("SET search_path TO " + schema_ + "; SET extra_float_digits = 1");
  }
  ~RawDb() {
    if (db_) sqlite3_close_v2(db_);
    if (pg_) PQfinish(pg_);
  }
  RawDb(const RawDb&) = delete;
  RawDb& operator=(const RawDb&) = delete;

  bool postgres() const { return pg_ != nullptr; }

  std::vector<std::vector<std::string>> rows(const std::string& sql) {
    std::vector<std::vector<std::string>> out;
    if (pg_) {
      PGresult* r = PQexec(pg_, sql.c_str());
      if (PQresultStatus(r) != PGRES_TUPLES_OK) {
        ADD_FAILURE() << sql << ": " << PQresultErrorMessage(r);
      } else {
        for (int i = 0; i < PQntuples(r); ++i) {
          std::vector<std::string> row;
          for (int c = 0; c < PQnfields(r); ++c) row.emplace_back(PQgetisnull(r, i, c) ? "NULL" : PQgetvalue(r, i, c));
          out.push_back(std::move(row));
        }
      }
      PQclear(r);
      return out;
    }
    sqlite3_stmt* st = nullptr;
    if (sqlite3_prepare_v2(db_, sql.c_str(), -1, &st, nullptr) != SQLITE_OK) {
      ADD_FAILURE() << sql << ": " << sqlite3_errmsg(db_);
      return out;
    }
    int rc;
    while ((rc = sqlite3_step(st)) == SQLITE_ROW) {
      std::vector<std::string> row;
      for (int c = 0; c < sqlite3_column_count(st); ++c) {
        if (sqlite3_column_type(st, c) == SQLITE_FLOAT) {
          char buf[40];
          std::snprintf(buf, sizeof buf, "%.17g", sqlite3_column_double(st, c));
          row.emplace_back(buf);
          continue;
        }
        const auto* t = reinterpret_cast<const char*>(sqlite3_column_text(st, c));
        row.emplace_back(t ? t : "NULL");
      }
      out.push_back(std::move(row));
    }
    if (rc != SQLITE_DONE) ADD_FAILURE() << sql << ": " << sqlite3_errmsg(db_);
    sqlite3_finalize(st);
    return out;
  }
  // The column names of a query's result.
  std::vector<std::string> columns(const std::string& sql) {
    std::vector<std::string> out;
    if (pg_) {
      PGresult* r = PQexec(pg_, sql.c_str());
      for (int c = 0; c < PQnfields(r); ++c) out.emplace_back(PQfname(r, c));
      PQclear(r);
      return out;
    }
    sqlite3_stmt* st = nullptr;
    if (sqlite3_prepare_v2(db_, sql.c_str(), -1, &st, nullptr) != SQLITE_OK) return out;
    for (int c = 0; c < sqlite3_column_count(st); ++c) out.emplace_back(sqlite3_column_name(st, c));
    sqlite3_finalize(st);
    return out;
  }
  std::string one(const std::string& sql) {
    auto r = rows(sql);
    return r.empty() || r[0].empty() ? std::string("<no row>") : r[0][0];
  }
  std::int64_t count(const std::string& sql) { return std::stoll(one(sql)); }
  // Runs statements; true on success, else errmsg() says why.
  bool exec(const std::string& sql) {
    if (pg_) {
      PGresult* r = PQexec(pg_, sql.c_str());
      const auto s = PQresultStatus(r);
      error_ = (s == PGRES_COMMAND_OK || s == PGRES_TUPLES_OK) ? "" : PQresultErrorMessage(r);
      PQclear(r);
      return error_.empty();
    }
    const bool ok = sqlite3_exec(db_, sql.c_str(), nullptr, nullptr, nullptr) == SQLITE_OK;
    error_ = ok ? "" : sqlite3_errmsg(db_);
    return ok;
  }
  const std::string& errmsg() const { return error_; }

  // The engine's consistency check: "ok" or what is wrong. SQLite: integrity_check and
  // foreign_key_check; PostgreSQL: every constraint validated and no trigger switched off.
  std::string integrity() {
    if (!pg_) {
      const std::string ic = one("PRAGMA integrity_check");
      if (ic != "ok") return ic;
      return rows("PRAGMA foreign_key_check").empty() ? "ok" : "foreign_key_check not empty";
    }
    const auto bad = rows("SELECT c.conname FROM pg_constraint c JOIN pg_namespace n ON n.oid = c.connamespace "
                          "WHERE n.nspname = '" + schema_ + "' AND NOT c.convalidated UNION ALL "
                          "SELECT t.tgname FROM pg_trigger t JOIN pg_class r ON r.oid = t.tgrelid JOIN pg_namespace n "
                          "ON n.oid = r.relnamespace WHERE n.nspname = '" + schema_ + "' AND t.tgenabled = 'D'");
    return bad.empty() ? "ok" : "not validated or disabled: " + bad[0][0];
  }
  // The study exists: the file has its tables, or the schema exists and has them.
  bool has_table(const std::string& name) {
    if (!pg_) return one("SELECT count(*) FROM sqlite_schema WHERE name = '" + name + "'") == "1";
    return one("SELECT count(*) FROM pg_tables WHERE schemaname = '" + schema_ + "' AND tablename = '" + name + "'") == "1";
  }
  // Application id and schema version as the file header (SQLite) or dtlab_header (PostgreSQL) say.
  std::pair<std::string, std::string> header() {
    if (!pg_) return {one("PRAGMA application_id"), one("PRAGMA user_version")};
    return {one("SELECT application_id FROM dtlab_header"), one("SELECT user_version FROM dtlab_header")};
  }
  const std::string& schema() const { return schema_; }

 private:
  sqlite3* db_ = nullptr;
  PGconn* pg_ = nullptr;
  std::string schema_, error_;
};

// The rows of a one-column query joined by ",".
inline std::string joined(RawDb& db, const std::string& sql) {
  std::string out;
  for (const auto& r : db.rows(sql)) out += (out.empty() ? "" : ",") + r[0];
  return out;
}

}  // namespace dtlab::store::testing

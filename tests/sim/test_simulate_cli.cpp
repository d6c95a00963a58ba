// `dtlab simulate` as a user runs it, in child processes: SIGKILLed at
// increasing delays (with two worker processes), rerun until it finishes,
// then PRAGMA integrity_check must be ok after every kill and the final
// per-trial answers, simulated times and questionnaire must equal an
// uninterrupted single-process run (the export minus wall-clock and
// measured-frame-time columns). Also: a finished database is left alone, and
// `dtlab demo` refuses to overwrite another protocol's files; no -wal or -shm
// file is left beside a database after `dtlab simulate` exits.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sqlite3.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <thread>

#include "analysis/stats/csv.h"
#include "study/protocol/protocol.h"
#include "study/session/mapping.h"
#include "study/store/export.h"
#include "study/store/store.h"

namespace {

namespace fs = std::filesystem;

fs::path temp_dir() {
  const fs::path d = fs::temp_directory_path() / ("dtlab_simulate_" + std::to_string(::getpid()));
  fs::create_directories(d);
  return d;
}

struct Child {
  pid_t pid = -1;
  int status = 0;
};

// Starts dtlab with `args`; stdout and stderr go to `log`.
Child start(const std::vector<std::string>& args, const fs::path& log) {
  Child c;
  c.pid = ::fork();
  if (c.pid == 0) {
    const int fd = ::open(log.c_str(), O_WRONLY | O_CREAT | O_APPEND, 0644);
    ::dup2(fd, 1);
    ::dup2(fd, 2);
    std::vector<char*> argv;
    argv.push_back(const_cast<char*>(DTLAB_BINARY));
    for (const auto& a : args) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    ::execv(DTLAB_BINARY, argv.data());
    _exit(127);
  }
  return c;
}

int wait_for(Child& c) {
  ::waitpid(c.pid, &c.status, 0);
  return WIFEXITED(c.status) ? WEXITSTATUS(c.status) : 128 + WTERMSIG(c.status);
}

// Kills after `delay` unless it ended before; returns true if it was killed.
bool kill_after(Child& c, std::chrono::milliseconds delay) {
  const auto until = std::chrono::steady_clock::now() + delay;
  while (std::chrono::steady_clock::now() < until) {
    if (::waitpid(c.pid, &c.status, WNOHANG) == c.pid) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  ::kill(c.pid, SIGKILL);
  ::waitpid(c.pid, &c.status, 0);
  return true;
}

std::string integrity(const fs::path& db) {
  sqlite3* h = nullptr;
  if (sqlite3_open_v2(db.c_str(), &h, SQLITE_OPEN_READONLY, nullptr) != SQLITE_OK) return "cannot open";
  sqlite3_stmt* st = nullptr;
  std::string out;
  if (sqlite3_prepare_v2(h, "PRAGMA integrity_check", -1, &st, nullptr) == SQLITE_OK)
    while (sqlite3_step(st) == SQLITE_ROW) out += reinterpret_cast<const char*>(sqlite3_column_text(st, 0));
  sqlite3_finalize(st);
  sqlite3_close(h);
  return out;
}

// participant|position -> the row's deterministic columns joined.
std::map<std::string, std::string> deterministic_rows(const fs::path& db) {
  std::ostringstream csv;
  auto sum = dtlab::store::export_trials_csv(db.string(), csv);
  EXPECT_TRUE(sum.ok()) << (sum.ok() ? "" : sum.error().to_string());
  auto t = dtlab::stats::parse_csv(csv.str(), db.string());
  EXPECT_TRUE(t.ok());
  // Wall-clock stamps, measured frame times and the session's row id differ between runs.
  const std::set<std::string> skip{"started_at", "ended_at", "frame_ms_mean", "frame_ms_sd", "frame_ms_p95",
                                   "frame_ms_max", "session"};
  std::map<std::string, std::string> out;
  for (const auto& row : t->rows) {
    std::string key = row[static_cast<std::size_t>(t->column("participant"))] + "|" +
                      row[static_cast<std::size_t>(t->column("position"))];
    std::string v;
    for (std::size_t c = 0; c < t->header.size(); ++c)
      if (!skip.count(t->header[c])) v += t->header[c] + "=" + row[c] + ";";
    out[key] = v;
  }
  return out;
}

std::map<std::string, std::string> questionnaires(const fs::path& db) {
  sqlite3* h = nullptr;
  EXPECT_EQ(sqlite3_open_v2(db.c_str(), &h, SQLITE_OPEN_READONLY, nullptr), SQLITE_OK);
  sqlite3_stmt* st = nullptr;
  EXPECT_EQ(sqlite3_prepare_v2(h,
                               "SELECT p.participant, q.item, q.scope, coalesce(q.value_text, q.value_number) FROM "
                               "questionnaire_answers q JOIN sessions s ON s.id = q.session_id JOIN participants p ON "
                               "p.id = s.participant_id",
                               -1, &st, nullptr),
            SQLITE_OK);
  std::map<std::string, std::string> out;
  while (sqlite3_step(st) == SQLITE_ROW) {
    std::string key;
    for (int c = 0; c < 3; ++c) key += std::string(reinterpret_cast<const char*>(sqlite3_column_text(st, c))) + "|";
    out[key] = reinterpret_cast<const char*>(sqlite3_column_text(st, 3));
  }
  sqlite3_finalize(st);
  sqlite3_close(h);
  return out;
}

std::vector<std::string> simulate_args(const fs::path& db, int jobs) {
  return {"simulate", std::string(DTLAB_SOURCE_DIR) + "/protocols/pilot.toml", "--participants", "2", "--db",
          db.string(), "--jobs", std::to_string(jobs), "--width", "96", "--height", "72"};
}

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// Every connection was closed: the last one to close checkpoints the write-ahead log and removes
// it; a -wal or -shm left beside the file means one was not (or the last was read-only). Call before
// the test opens the file itself.
void expect_closed_cleanly(const fs::path& db) {
  EXPECT_TRUE(fs::exists(db));
  EXPECT_FALSE(fs::exists(db.string() + "-wal")) << db << ": a connection was not closed cleanly";
  EXPECT_FALSE(fs::exists(db.string() + "-shm")) << db;
}

// Worker processes end with _exit (no destructors): each must close its connection first, and the
// summary printed at the end must not leave the log behind either.
TEST(SimulateCli, LeavesNoWriteAheadLogBehind) {
  const fs::path dir = temp_dir();
  const fs::path db = dir / "workers.sqlite", log = dir / "workers.txt";
  fs::remove(db);
  Child c = start(simulate_args(db, 2), log);
  ASSERT_EQ(wait_for(c), 0) << slurp(log);
  expect_closed_cleanly(db);
  EXPECT_EQ(integrity(db), "ok");
}

TEST(SimulateCli, KilledAtIncreasingDelaysResumesToTheUninterruptedResult) {
  const fs::path dir = temp_dir();
  const fs::path reference = dir / "reference.sqlite", crashed = dir / "crashed.sqlite", log = dir / "log.txt";
  for (const auto& f : {reference, crashed}) fs::remove(f);

  Child ref = start(simulate_args(reference, 1), log);
  ASSERT_EQ(wait_for(ref), 0) << slurp(log);
  expect_closed_cleanly(reference);
  const auto expected = deterministic_rows(reference);
  ASSERT_EQ(expected.size(), 16u) << "2 participants x 8 pilot trials";

  int kills = 0, rc = -1;
  for (int round = 0; round < 10 && rc < 0; ++round) {
    Child c = start(simulate_args(crashed, 2), log);
    // Increasing delays: early kills land in enrollment and plan creation, later ones mid-trial.
    if (kill_after(c, std::chrono::milliseconds(150 + 350 * round))) {
      ++kills;
      if (fs::exists(crashed)) {
        EXPECT_EQ(integrity(crashed), "ok") << "after kill " << kills;
      }
    } else {
      rc = WIFEXITED(c.status) ? WEXITSTATUS(c.status) : 128 + WTERMSIG(c.status);
    }
  }
  if (rc < 0) {
    Child last = start(simulate_args(crashed, 2), log);
    rc = wait_for(last);
  }
  ASSERT_EQ(rc, 0) << slurp(log);
  EXPECT_GE(kills, 3) << "the loop should have interrupted the run several times";
  EXPECT_EQ(integrity(crashed), "ok");
  const auto got = deterministic_rows(crashed);
  ASSERT_EQ(got.size(), expected.size());
  for (const auto& [key, row] : expected) EXPECT_EQ(got.at(key), row) << key;
  EXPECT_EQ(questionnaires(crashed), questionnaires(reference));

  // A finished database: nothing to run, the JSON says so.
  const fs::path out = dir / "again.json";
  auto args = simulate_args(crashed, 1);
  args.push_back("--json");
  fs::remove(out);
  Child again = start(args, out);
  ASSERT_EQ(wait_for(again), 0) << slurp(out);
  const std::string text = slurp(out);
  const auto j = nlohmann::json::parse(text.substr(text.find('{')));
  EXPECT_EQ(j["trials_run"], 0);
  EXPECT_EQ(j["skipped_finished"], 2);
  EXPECT_EQ(j["finished"], 2);
  EXPECT_EQ(deterministic_rows(crashed), got);
}

// A database recorded under one version of a protocol refuses an edited one (exit 1, file untouched)
// unless --allow-protocol-change; then the new text is recorded as a second study row.
TEST(SimulateCli, AnEditedProtocolNeedsAllowProtocolChange) {
  const fs::path dir = temp_dir();
  const fs::path db = dir / "changed.sqlite", log = dir / "changed.txt", edited = dir / "pilot-edited.toml";
  fs::remove(db);
  {
    auto pilot = dtlab::protocol::load_protocol(std::string(DTLAB_SOURCE_DIR) + "/protocols/pilot.toml");
    ASSERT_TRUE(pilot.ok());
    auto st = dtlab::store::Store::open(db.string(), dtlab::session::study_info(pilot.value()));
    ASSERT_TRUE(st.ok()) << st.error().to_string();
  }
  std::ofstream(edited) << slurp(std::string(DTLAB_SOURCE_DIR) + "/protocols/pilot.toml") << "# edited\n";
  const std::vector<std::string> args{"simulate", edited.string(), "--participants", "1", "--db", db.string(),
                                      "--width", "96", "--height", "72"};
  const std::string before = slurp(db);
  Child refused = start(args, log);
  EXPECT_EQ(wait_for(refused), 1) << slurp(log);
  EXPECT_NE(slurp(log).find("--allow-protocol-change"), std::string::npos) << slurp(log);
  EXPECT_TRUE(slurp(db) == before) << "the refused run modified the database";

  auto allowed = args;
  allowed.push_back("--allow-protocol-change");
  Child c = start(allowed, log);
  ASSERT_EQ(wait_for(c), 0) << slurp(log);
  sqlite3* h = nullptr;
  ASSERT_EQ(sqlite3_open_v2(db.c_str(), &h, SQLITE_OPEN_READONLY, nullptr), SQLITE_OK);
  sqlite3_stmt* st = nullptr;
  ASSERT_EQ(sqlite3_prepare_v2(h, "SELECT count(*) FROM studies", -1, &st, nullptr), SQLITE_OK);
  ASSERT_EQ(sqlite3_step(st), SQLITE_ROW);
  EXPECT_EQ(sqlite3_column_int(st, 0), 2) << "the old and the edited protocol, both recorded";
  sqlite3_finalize(st);
  sqlite3_close(h);
}

TEST(SimulateCli, BadInputIsAClearErrorAndTouchesNothing) {
  const fs::path dir = temp_dir();
  const fs::path log = dir / "bad.txt";
  // A protocol that does not validate: exit 1, no database created.
  const fs::path bad = dir / "bad.toml", db = dir / "never.sqlite";
  std::ofstream(bad) << "format = 1\nid = \"x\"\n";
  fs::remove(db);
  fs::remove(log);
  Child c = start({"simulate", bad.string(), "--participants", "1", "--db", db.string()}, log);
  EXPECT_EQ(wait_for(c), 1) << slurp(log);
  EXPECT_FALSE(fs::exists(db));
  EXPECT_NE(slurp(log).find("bad.toml"), std::string::npos) << slurp(log);

  // The demo refuses a directory whose protocol file is not the reference protocol.
  const fs::path demo = dir / "demo";
  fs::create_directories(demo);
  std::ofstream(demo / "elmqvist2008.toml") << "# something else\n";
  fs::remove(log);
  Child d = start({"demo", "--out", demo.string(), "--participants", "1"}, log);
  EXPECT_EQ(wait_for(d), 1) << slurp(log);
  EXPECT_FALSE(fs::exists(demo / "elmqvist2008.sqlite"));
  EXPECT_EQ(slurp(demo / "elmqvist2008.toml"), "# something else\n");

  // ... and a database of another protocol (the pilot's).
  const fs::path demo2 = dir / "demo2";
  fs::create_directories(demo2);
  {
    auto pilot = dtlab::protocol::load_protocol(std::string(DTLAB_SOURCE_DIR) + "/protocols/pilot.toml");
    ASSERT_TRUE(pilot.ok());
    auto st = dtlab::store::Store::open((demo2 / "elmqvist2008.sqlite").string(), dtlab::session::study_info(pilot.value()));
    ASSERT_TRUE(st.ok()) << st.error().to_string();
    ASSERT_TRUE(st->enroll("someone").ok());
  }
  const std::string before = slurp(demo2 / "elmqvist2008.sqlite");
  ASSERT_FALSE(before.empty());
  fs::remove(log);
  Child d2 = start({"demo", "--out", demo2.string(), "--participants", "1"}, log);
  EXPECT_EQ(wait_for(d2), 1) << slurp(log);
  EXPECT_NE(slurp(log).find("protocol"), std::string::npos) << slurp(log);
  EXPECT_TRUE(slurp(demo2 / "elmqvist2008.sqlite") == before) << "the other protocol's database was modified";
}

}  // namespace

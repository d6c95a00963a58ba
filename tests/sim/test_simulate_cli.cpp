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
#include "study/store/read.h"
#include "study/store/store.h"
#include "tests/common/light_pilot.h"

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
  auto r = dtlab::store::StudyReader::open(db.string());
  if (!r) return r.error().to_string();
  auto ok = r->integrity_check();
  return ok ? *ok : ok.error().to_string();
}

// participant|position -> the row's deterministic columns joined.
std::map<std::string, std::string> deterministic_rows(const fs::path& db) {
  std::ostringstream csv;
  auto sum = dtlab::store::export_trials_csv(db.string(), csv);
  EXPECT_TRUE(sum.ok()) << (sum.ok() ? "" : sum.error().to_string());
  auto t = dtlab::stats::parse_csv(csv.str(), db.string());
  EXPECT_TRUE(t.ok());
  // Wall-clock stamps, measured frame times and the session's row id differ between runs.
  const auto& measured = dtlab::store::measured_columns();
  const std::set<std::string> skip(measured.begin(), measured.end());
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
  auto r = dtlab::store::StudyReader::open(db.string());
  EXPECT_TRUE(r.ok());
  std::map<std::string, std::string> out;
  if (!r) return out;
  auto answers = r->questionnaire();
  EXPECT_TRUE(answers.ok());
  for (const auto& a : *answers) {
    char buf[40];
    if (const double* v = std::get_if<double>(&a.value)) std::snprintf(buf, sizeof buf, "%.17g", *v);
    out[a.participant + "|" + a.item + "|" + a.scope + "|"] =
        std::holds_alternative<double>(a.value) ? std::string(buf) : std::get<std::string>(a.value);
  }
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
      // Killed before the schema's transaction committed, the file holds no table yet: nothing
      // was saved, and the rerun creates the schema. Anything else must be a sound study.
      const std::string state = fs::exists(crashed) ? integrity(crashed) : "ok";
      if (state.find("no session was ever started") == std::string::npos) {
        EXPECT_EQ(state, "ok") << "after kill " << kills;
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

// A protocol edited in its wording only (a comment) continues without any flag and is recorded as
// a new revision of the same design; an edit that changes what runs (the master seed) is refused
// (exit 1, file untouched) unless --allow-protocol-change, and is then design revision 2.
TEST(SimulateCli, ARewordedProtocolContinuesAndAChangedDesignNeedsAllowProtocolChange) {
  const fs::path dir = temp_dir();
  const fs::path db = dir / "changed.sqlite", log = dir / "changed.txt";
  const fs::path reworded = dir / "pilot-reworded.toml", redesigned = dir / "pilot-redesigned.toml";
  fs::remove(db);
  const std::string pilot_text = slurp(std::string(DTLAB_SOURCE_DIR) + "/protocols/pilot.toml");
  {
    auto pilot = dtlab::protocol::load_protocol(std::string(DTLAB_SOURCE_DIR) + "/protocols/pilot.toml");
    ASSERT_TRUE(pilot.ok());
    auto st = dtlab::store::Store::open(db.string(), dtlab::session::study_info(pilot.value()));
    ASSERT_TRUE(st.ok()) << st.error().to_string();
  }
  std::ofstream(reworded) << pilot_text << "# a comment added mid-study\n";
  const std::vector<std::string> args{"simulate", reworded.string(), "--participants", "1", "--db", db.string(),
                                      "--width", "64", "--height", "48"};
  Child c1 = start(args, log);
  ASSERT_EQ(wait_for(c1), 0) << slurp(log);

  std::string changed = pilot_text;
  const auto at = changed.find("master_seed = 1");
  ASSERT_NE(at, std::string::npos);
  changed.replace(at, std::string("master_seed = 1").size(), "master_seed = 2");
  std::ofstream(redesigned) << changed;
  auto args2 = args;
  args2[1] = redesigned.string();
  const std::string before = slurp(db);
  Child refused = start(args2, log);
  EXPECT_EQ(wait_for(refused), 1) << slurp(log);
  EXPECT_NE(slurp(log).find("--allow-protocol-change"), std::string::npos) << slurp(log);
  EXPECT_TRUE(slurp(db) == before) << "the refused run modified the database";

  args2.push_back("--allow-protocol-change");
  Child c = start(args2, log);
  ASSERT_EQ(wait_for(c), 0) << slurp(log);
  auto r = dtlab::store::StudyReader::open(db.string(), dtlab::session::read_options());
  ASSERT_TRUE(r.ok());
  auto revs = r->revisions();
  ASSERT_TRUE(revs.ok());
  ASSERT_EQ(revs->size(), 3u) << "the original, the reworded and the redesigned protocol, all recorded";
  EXPECT_EQ((*revs)[1].design_revision, 1);
  EXPECT_EQ((*revs)[2].design_revision, 2);
}

// Issue 9: several `dtlab simulate` processes on one database share the work. Each session is
// claimed by the process running it; the others skip it. All exit 0, every trial is recorded
// once, and the trials run by the processes add up to the whole study.
TEST(SimulateCli, FourProcessesSplitEightParticipants) {
  const fs::path dir = temp_dir();
  const fs::path db = dir / "shared.sqlite", light = dir / "pilot-light.toml";
  fs::remove(db);
  // The pilot with lighter scenes: the claims, not the rendering, are under test here.
  const std::string text = dtlab::test::light_pilot_text();
  ASSERT_FALSE(text.empty()) << "protocols/pilot.toml no longer has the lines light_pilot_text() lightens";
  std::ofstream(light) << text;
  std::vector<Child> children;
  std::vector<fs::path> logs;
  for (int k = 0; k < 4; ++k) {
    logs.push_back(dir / ("station-" + std::to_string(k) + ".json"));
    fs::remove(logs.back());
    children.push_back(start({"simulate", light.string(), "--participants", "8", "--db", db.string(), "--width", "48",
                              "--height", "36", "--json"},
                             logs.back()));
  }
  long long trials_run = 0;
  for (int k = 0; k < 4; ++k) {
    ASSERT_EQ(wait_for(children[static_cast<std::size_t>(k)]), 0) << slurp(logs[static_cast<std::size_t>(k)]);
    const std::string text = slurp(logs[static_cast<std::size_t>(k)]);
    const auto j = nlohmann::json::parse(text.substr(text.rfind("\n{") + 1));
    trials_run += j["trials_run"].get<long long>();
    EXPECT_TRUE(j["failed"].empty()) << text;
  }
  auto r = dtlab::store::StudyReader::open(db.string());
  ASSERT_TRUE(r.ok());
  auto sessions = r->sessions();
  ASSERT_TRUE(sessions.ok());
  ASSERT_EQ(sessions->size(), 8u);
  for (const auto& s : *sessions) {
    EXPECT_EQ(s.status, dtlab::store::SessionStatus::finished) << s.participant;
    EXPECT_EQ(s.resumes.size(), 0u) << s.participant << " was resumed: two processes ran it";
    EXPECT_TRUE(s.interruptions.empty()) << s.participant;
    EXPECT_FALSE(s.claim.has_value()) << s.participant;
  }
  EXPECT_EQ(r->trials()->size(), 64u);
  EXPECT_EQ(trials_run, 64) << "every trial run exactly once across the four processes";
  EXPECT_EQ(*r->integrity_check(), "ok");
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

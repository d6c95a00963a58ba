// Several real processes (fork) sharing one database, a file or a server's
// schema (on the server each process is a "station" with its own
// connection): they create it at the same moment, enroll at the same moment,
// and run sessions side by side. The ledger must never give one slot
// (enrollment index) twice, every order row must follow the documented rule,
// and a participant id enrolled by two processes at once must get one
// enrollment. Creating one new database from many processes at once always
// succeeds; a running session is claimed by one process, and another takes it
// over only once the holder is gone or expired.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <csignal>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <map>
#include <set>

#include "tests/store/store_fixtures.h"

namespace dtlab::store {
namespace {

using namespace dtlab::store::testing;

struct Slot {
  std::int32_t child, newly, index, row;
  char id[32];
};

constexpr int kChildren = 4;
constexpr int kEach = 12;   // own participants per child
constexpr int kShared = 6;  // participant ids every child enrolls

[[noreturn]] void child(const std::string& path, int k, int go_fd, int out_fd) {
  char c;
  if (::read(go_fd, &c, 1) != 1) ::_exit(3);  // barrier: all children start together
  OpenOptions o;
  o.busy_timeout_ms = 30000;
  auto s = Store::open(path, study_info(), o);
  if (!s) {
    std::fprintf(stderr, "child %d: %s\n", k, s.error().to_string().c_str());
    ::_exit(1);
  }
  auto report = [&](const std::string& id, const Result<Enrollment>& e) {
    if (!e) {
      std::fprintf(stderr, "child %d: %s\n", k, e.error().to_string().c_str());
      ::_exit(1);
    }
    Slot slot{k, e->newly_enrolled ? 1 : 0, e->index, e->order_row, {}};
    std::snprintf(slot.id, sizeof slot.id, "%s", id.c_str());
    if (::write(out_fd, &slot, sizeof slot) != sizeof slot) ::_exit(4);
  };
  for (int i = 0; i < kEach; ++i) {
    const std::string own = "C" + std::to_string(k) + "-" + std::to_string(i);
    report(own, s->enroll(own));
    if (i < kShared) {
      const std::string shared = "shared-" + std::to_string(i);
      report(shared, s->enroll(shared));
    }
  }
  // Then run a session for the child's first participant, side by side with the others.
  const std::string id = "C" + std::to_string(k) + "-0";
  auto e = s->lookup(id);
  auto ses = s->begin_session(id, make_plan(e->index, e->order_row, 2));
  if (!ses) ::_exit(5);
  for (;;) {
    auto t = s->next_trial(*ses);
    if (!t) ::_exit(6);
    if (!*t) break;
    if (auto r = s->record_trial(*ses, make_record(static_cast<std::uint64_t>(k), **t, 100)); !r) {
      std::fprintf(stderr, "child %d: %s\n", k, r.error().to_string().c_str());
      ::_exit(7);
    }
  }
  ::_exit(s->finish_session(*ses) ? 0 : 8);
}

class Processes : public OnBothBackends {};
class Claims : public OnBothBackends {};
DTLAB_ON_BOTH_BACKENDS(Processes);
DTLAB_ON_BOTH_BACKENDS(Claims);

TEST_P(Processes, ConcurrentEnrollmentNeverSharesALedgerSlot) {
  const std::string path = study("shared");  // does not exist yet: created concurrently
  int go[2], out[2];
  ASSERT_EQ(::pipe(go), 0);
  ASSERT_EQ(::pipe(out), 0);
  std::vector<pid_t> pids;
  for (int k = 0; k < kChildren; ++k) {
    const pid_t pid = ::fork();
    ASSERT_GE(pid, 0);
    if (pid == 0) {
      ::close(go[1]);
      ::close(out[0]);
      child(path, k, go[0], out[1]);
    }
    pids.push_back(pid);
  }
  ::close(go[0]);
  ::close(out[1]);
  const char start[kChildren] = {};
  ASSERT_EQ(::write(go[1], start, kChildren), kChildren);
  ::close(go[1]);

  std::vector<Slot> slots;
  Slot s;
  while (::read(out[0], &s, sizeof s) == static_cast<ssize_t>(sizeof s)) slots.push_back(s);
  ::close(out[0]);
  for (pid_t pid : pids) {
    int status = 0;
    ASSERT_EQ(::waitpid(pid, &status, 0), pid);
    EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << "child exit status " << status;
  }

  const int total = kChildren * kEach + kShared;
  ASSERT_EQ(slots.size(), static_cast<std::size_t>(kChildren * (kEach + kShared)));
  std::map<int, std::string> by_index;       // index -> the one id that got it
  std::map<std::string, std::set<int>> seen;  // id -> indexes reported for it
  std::map<std::string, int> newly;
  for (const Slot& x : slots) {
    seen[x.id].insert(x.index);
    newly[x.id] += x.newly;
    EXPECT_EQ(x.row, x.index % 4) << x.id << ": nothing released, so row = index mod rows";
    if (x.newly) {
      EXPECT_TRUE(by_index.emplace(x.index, x.id).second)
          << "index " << x.index << " given to both " << by_index[x.index] << " and " << x.id;
    }
  }
  EXPECT_EQ(static_cast<int>(by_index.size()), total);
  EXPECT_EQ(by_index.begin()->first, 0);
  EXPECT_EQ(by_index.rbegin()->first, total - 1);  // dense: 0 .. total-1, each once
  for (const auto& [id, idx] : seen) {
    EXPECT_EQ(idx.size(), 1u) << id << " got different enrollments in different processes";
    EXPECT_EQ(newly[id], 1) << id << " was newly enrolled " << newly[id] << " times";
  }

  RawDb db(path);
  EXPECT_EQ(db.integrity(), "ok");
  EXPECT_EQ(db.count("SELECT count(DISTINCT enrollment_index) FROM participants"), total);
  EXPECT_EQ(db.count("SELECT max(enrollment_index) FROM participants"), total - 1);
  EXPECT_EQ(db.count("SELECT count(*) FROM studies"), 1);  // created once, not once per process
  EXPECT_EQ(db.count("SELECT count(*) FROM sessions WHERE status = 'finished'"), kChildren);
  EXPECT_EQ(db.count("SELECT count(*) FROM trial_results"), kChildren * 8);
  // Rows stay balanced: 54 participants over 4 rows -> 14, 14, 13, 13.
  EXPECT_EQ(joined(db, "SELECT count(*) FROM participants GROUP BY order_row ORDER BY order_row"), "14,14,13,13");
}

// Regression (issue 9): two processes opening a new file at once sometimes failed with "not a
// dtlab study database (application_id 0x00000000)": the header and the schema were read in two
// snapshots, around the other process's commit. 8 processes, 50 new files in a row (3 new
// schemas on the server, where creating the schema is one transaction under the study's lock).
TEST_P(Processes, EightProcessesCreatingOneNewDatabaseAllSucceed) {
  for (int round = 0; round < (pg() ? 3 : 50); ++round) {
    const std::string path = study("new-" + std::to_string(round));
    const auto codes = race(8, [&](int k) {
      OpenOptions o;
      o.busy_timeout_ms = 30000;
      auto s = Store::open(path, study_info(), o);
      if (!s) {
        std::fprintf(stderr, "round %d child %d: %s\n", round, k, s.error().to_string().c_str());
        return 1;
      }
      return s->enroll("C" + std::to_string(k)) ? 0 : 2;
    });
    ASSERT_EQ(codes, std::vector<int>(8, 0)) << "round " << round;
    RawDb db(path);
    ASSERT_EQ(db.count("SELECT count(*) FROM studies"), 1) << "round " << round;
    ASSERT_EQ(db.count("SELECT count(*) FROM participants"), 8) << "round " << round;
  }
}

// A session begun by one live process is refused to every other process (busy, naming the
// holder) and free again once the holder closes its Store. Both are child processes (SQLite
// connections must not cross fork()); the parent only passes messages.
TEST_P(Claims, ASecondProcessCannotRunAClaimedSession) {
  const std::string path = study();
  const design::Plan plan = make_plan(0, 0, 1);
  int to_holder[2], from_holder[2];
  ASSERT_EQ(::pipe(to_holder), 0);
  ASSERT_EQ(::pipe(from_holder), 0);
  const pid_t holder = ::fork();
  if (holder == 0) {
    char c = 0;
    int rc = 0;
    {
      auto s = Store::open(path, study_info());
      auto b = s && s->enroll("P1") ? s->begin_session("P1", plan) : Result<Session>(Error{});
      c = b ? 'r' : 'x';
      if (::write(from_holder[1], &c, 1) != 1 || ::read(to_holder[0], &c, 1) != 1) ::_exit(91);
      rc = b && s->record_trial(*b, make_record(1, plan.trials[0], 3)) ? 0 : 2;
    }  // closing the Store releases its claim
    c = 'd';
    if (::write(from_holder[1], &c, 1) != 1) ::_exit(92);
    ::_exit(rc);
  }
  char c = 0;
  ASSERT_EQ(::read(from_holder[0], &c, 1), 1);
  ASSERT_EQ(c, 'r');
  const pid_t holder_pid = holder;
  auto attempt = [&] {
    return race(1, [&](int) {
      auto s = Store::open(path, study_info());
      if (!s) return 1;
      auto b = s->begin_session("P1", plan);
      if (b) return 0;
      if (b.error().kind == ErrorKind::busy && b.error().field == kClaimField &&
          b.error().message.find(std::to_string(holder_pid)) != std::string::npos)
        return 10;  // refused, naming the holder's pid
      std::fprintf(stderr, "%s\n", b.error().to_string().c_str());
      return 2;
    })[0];
  };
  EXPECT_EQ(attempt(), 10);
  c = 'g';
  ASSERT_EQ(::write(to_holder[1], &c, 1), 1);
  ASSERT_EQ(::read(from_holder[0], &c, 1), 1);
  EXPECT_EQ(c, 'd');
  int status = 0;
  ::waitpid(holder, &status, 0);
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << status;
  EXPECT_EQ(attempt(), 0);
}

// kill -9 leaves the claim row behind; the dead holder's claim is taken over at once (same
// host, pid gone), and the session resumes where it was. Regression: a killed worker whose
// parent died too stays a zombie until reaped, and kill(pid, 0) succeeds on a zombie: the
// claim was then held "alive" and the rerun skipped the participant. Taken over before reaping.
TEST_P(Claims, AClaimOfAKilledProcessIsTakenOverAtOnceEvenBeforeItIsReaped) {
  const std::string path = study();
  const design::Plan plan = make_plan(0, 0, 1);
  const pid_t pid = ::fork();
  if (pid == 0) {
    auto s = Store::open(path, study_info());
    if (!s || !s->enroll("P1")) ::_exit(1);
    auto b = s->begin_session("P1", plan);
    if (!b || !s->record_trial(*b, make_record(1, plan.trials[0], 3))) ::_exit(2);
    ::kill(::getpid(), SIGKILL);
    ::_exit(3);
  }
  // Wait until the child is dead but not reaped: /proc shows it as a zombie.
  for (int i = 0; i < 500; ++i) {
    std::ifstream stat("/proc/" + std::to_string(pid) + "/stat");
    std::string text((std::istreambuf_iterator<char>(stat)), std::istreambuf_iterator<char>());
    if (text.find(") Z ") != std::string::npos) break;
    ::usleep(10000);
  }
  ASSERT_EQ(RawDb(path).count("SELECT count(*) FROM session_claims"), 1);  // left behind by the dead process
  {
    auto s = Store::open(path, study_info());
    ASSERT_TRUE(s);
    auto b = s->begin_session("P1", plan);
    ASSERT_TRUE(b) << b.error().to_string();
    EXPECT_TRUE(b->resumed);
    EXPECT_TRUE(b->took_over);
    EXPECT_EQ(b->recorded, 1);
  }
  int status = 0;
  ASSERT_EQ(::waitpid(pid, &status, 0), pid);
  EXPECT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == SIGKILL) << status;
}

// A claim from another machine holds until it expires (its heartbeat is the only sign of life);
// the experimenter may take it over at once.
TEST_P(Claims, AClaimFromAnotherHostHoldsUntilItExpires) {
  const std::string path = study();
  const design::Plan plan = make_plan(0, 0, 1);
  {
    auto s = Store::open(path, study_info());
    ASSERT_TRUE(s->enroll("P1"));
    ASSERT_TRUE(s->begin_session("P1", plan));
  }
  RawDb db(path);
  auto claim_until = [&](const std::string& expires) {
    ASSERT_TRUE(db.exec("INSERT INTO session_claims VALUES (1, 'station-7/4242/1/x', 'station-7', 4242, "
                        "'2026-01-01T00:00:00.000Z', '2026-01-01T00:00:00.000Z', '" + expires + "') "
                        "ON CONFLICT (session_id) DO UPDATE SET owner = excluded.owner, host = excluded.host, "
                        "pid = excluded.pid, expires_at = excluded.expires_at"))
        << db.errmsg();
  };
  claim_until("2999-01-01T00:00:00.000Z");
  auto s = Store::open(path, study_info());
  ASSERT_TRUE(s);
  auto refused = s->begin_session("P1", plan);
  ASSERT_FALSE(refused);
  EXPECT_EQ(refused.error().kind, ErrorKind::busy);
  EXPECT_NE(refused.error().message.find("station-7"), std::string::npos) << refused.error().to_string();
  BeginOptions take;
  take.take_over = true;
  auto forced = s->begin_session("P1", plan, take);
  ASSERT_TRUE(forced) << forced.error().to_string();
  EXPECT_TRUE(forced->took_over);
  claim_until("2001-01-01T00:00:00.000Z");  // expired
  auto expired = s->begin_session("P1", plan);
  ASSERT_TRUE(expired) << expired.error().to_string();
  EXPECT_TRUE(expired->took_over);
}

// After a take-over the old holder's writes are refused (conflict), so two processes never
// interleave trials of one session.
TEST_P(Claims, TheOldHolderCannotRecordAfterATakeOver) {
  const std::string path = study();
  const design::Plan plan = make_plan(0, 0, 1);
  auto a = Store::open(path, study_info());
  ASSERT_TRUE(a->enroll("P1"));
  auto sa = a->begin_session("P1", plan);
  ASSERT_TRUE(sa);
  auto b = Store::open(path, study_info());
  BeginOptions take;
  take.take_over = true;
  auto sb = b->begin_session("P1", plan, take);
  ASSERT_TRUE(sb);
  auto refused = a->record_trial(*sa, make_record(1, plan.trials[0], 3));
  ASSERT_FALSE(refused);
  EXPECT_EQ(refused.error().kind, ErrorKind::conflict);
  EXPECT_FALSE(a->heartbeat(*sa));
  EXPECT_TRUE(b->record_trial(*sb, make_record(1, plan.trials[0], 3)));
  EXPECT_TRUE(b->heartbeat(*sb));
  EXPECT_EQ(RawDb(path).count("SELECT count(*) FROM trial_results"), 1);
}

}  // namespace
}  // namespace dtlab::store

// Several real processes (fork) sharing one database file: they create it at
// the same moment, enroll at the same moment, and run sessions side by side.
// The ledger must never give one slot (enrollment index) twice, every order
// row must follow the documented rule, and a participant id enrolled by two
// processes at once must get one enrollment.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
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

TEST(Processes, ConcurrentEnrollmentNeverSharesALedgerSlot) {
  TempDir dir;
  const std::string path = dir.file("shared.sqlite");  // does not exist yet: created concurrently
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
  EXPECT_EQ(db.one("PRAGMA integrity_check"), "ok");
  EXPECT_EQ(db.count("SELECT count(DISTINCT enrollment_index) FROM participants"), total);
  EXPECT_EQ(db.count("SELECT max(enrollment_index) FROM participants"), total - 1);
  EXPECT_EQ(db.count("SELECT count(*) FROM studies"), 1);  // created once, not once per process
  EXPECT_EQ(db.count("SELECT count(*) FROM sessions WHERE status = 'finished'"), kChildren);
  EXPECT_EQ(db.count("SELECT count(*) FROM trial_results"), kChildren * 8);
  // Rows stay balanced: 54 participants over 4 rows -> 14, 14, 13, 13.
  EXPECT_EQ(db.one("SELECT group_concat(n, ',') FROM (SELECT count(*) AS n FROM participants GROUP BY order_row "
                   "ORDER BY order_row)"),
            "14,14,13,13");
}

}  // namespace
}  // namespace dtlab::store

// Crash tests in the manner of SQLite's crash*.test, on both engines (on the
// server a killed client's transaction is rolled back by the server): for
// several seeds, a child process runs a study (create, consent and enroll,
// begin, record a screen and a trial at a time, finish, and a participant who
// declines consent) and is killed with SIGKILL at increasing delays after its
// n-th step began;
// the next child resumes where it died. After every kill, each numbered
// invariant of docs/store.md is checked with raw SQL, the outcome must be one
// of the allowed ones (every step reported done is saved; at most the step
// in progress is lost), and the session must resume with exactly the trials
// it would have run. Finally the study runs to the end and must equal a run
// that never crashed.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <functional>
#include <thread>

#include "study/store/read.h"
#include "tests/store/store_fixtures.h"

namespace dtlab::store {
namespace {

using namespace dtlab::store::testing;

constexpr int kParticipants = 3;     // agree and run their sessions
constexpr int kDecliner = kParticipants;  // then one more declines consent (index 3)
constexpr int kPeople = kParticipants + 1;
constexpr int kPer = 2;              // trials per condition -> 8 trials per participant
constexpr int kTrials = 4 * kPer;

enum Op : std::int32_t { kOpen = 1, kEnroll, kBegin, kRecord, kFinish, kScreen };
struct Msg {
  std::int32_t op, done, participant, position;
};

std::string pid_of(int p) { return "P" + std::to_string(p); }

const std::string kConsentSha = sha256_hex("consent text");

// The screen shown before trial k (screen k of the session), the same in every run.
ScreenRecord screen_of(int k) {
  const auto at = at_ms(1'700'000'000'000LL + k * 100'000LL);
  return ScreenRecord{"trial " + std::to_string(k), "T", at, at + std::chrono::milliseconds(1500), "continue"};
}

// The study as a simulated participant runs it, resuming whatever is saved.
[[noreturn]] void child(const std::string& path, std::uint64_t seed, int fd) {
  auto say = [&](Op op, int done, int p = -1, int pos = 0) {
    const Msg m{op, done, p, pos};
    if (::write(fd, &m, sizeof m) != sizeof m) ::_exit(4);
  };
  auto fail = [](const Error& e) {
    std::fprintf(stderr, "crash child: %s\n", e.to_string().c_str());
    ::_exit(1);
  };
  say(kOpen, 0);
  auto s = Store::open(path, study_info());
  if (!s) fail(s.error());
  say(kOpen, 1);
  for (int p = 0; p < kParticipants; ++p) {
    say(kEnroll, 0, p);
    auto e = s->record_consent(pid_of(p), {{"age", std::to_string(20 + p)}}, true, kConsentSha);
    if (!e) fail(e.error());
    say(kEnroll, 1, p);
    if (auto cur = s->session(pid_of(p)); cur && cur->status == SessionStatus::finished) continue;
    say(kBegin, 0, p);
    auto ses = s->begin_session(pid_of(p), make_plan(e->index, e->order_row, kPer));
    if (!ses) fail(ses.error());
    say(kBegin, 1, p);
    for (;;) {
      auto t = s->next_trial(*ses);
      if (!t) fail(t.error());
      if (!*t) break;
      // Screen k comes before trial k; a resumed run first records the screens a kill lost.
      auto shown = s->read().screens(pid_of(p));
      if (!shown) fail(shown.error());
      for (int k = static_cast<int>(shown->size()) + 1; k <= (*t)->position; ++k) {
        say(kScreen, 0, p, k);
        if (auto st = s->record_screen(*ses, screen_of(k)); !st) fail(st.error());
        say(kScreen, 1, p, k);
      }
      const TrialRecord r = make_record(seed, **t);
      say(kRecord, 0, p, r.position);
      if (auto st = s->record_trial(*ses, r); !st) fail(st.error());
      say(kRecord, 1, p, r.position);
    }
    say(kFinish, 0, p);
    if (auto st = s->finish_session(*ses); !st) fail(st.error());
    say(kFinish, 1, p);
  }
  say(kEnroll, 0, kDecliner);
  if (auto d = s->record_consent(pid_of(kDecliner), {{"age", "70"}}, false, kConsentSha); !d) fail(d.error());
  say(kEnroll, 1, kDecliner);
  ::_exit(0);
}

// What the parent knows from the child's reports, over all runs so far.
struct Known {
  int enroll_done[kPeople] = {}, enroll_begun[kPeople] = {};
  int begin_done[kPeople] = {}, begin_begun[kPeople] = {};
  int rec_done[kPeople] = {}, rec_begun[kPeople] = {};  // highest position
  int fin_done[kPeople] = {}, fin_begun[kPeople] = {};
  int scr_done[kPeople] = {}, scr_begun[kPeople] = {};  // highest screen
  void apply(const Msg& m) {
    if (m.participant < 0) return;
    const int p = m.participant;
    auto mark = [&](int* done, int* begun, int v) { (m.done ? done : begun)[p] = std::max((m.done ? done : begun)[p], v); };
    if (m.op == kEnroll) mark(enroll_done, enroll_begun, 1);
    if (m.op == kBegin) mark(begin_done, begin_begun, 1);
    if (m.op == kRecord) mark(rec_done, rec_begun, m.position);
    // The child begins trial k only after reading that 1..k-1 have results,
    // so a trial saved just before a kill but never reported counts as done
    // once the next run begins the trial after it.
    if (m.op == kRecord && !m.done) rec_done[p] = std::max(rec_done[p], m.position - 1);
    if (m.op == kScreen) mark(scr_done, scr_begun, m.position);
    if (m.op == kScreen && !m.done) scr_done[p] = std::max(scr_done[p], m.position - 1);  // read back first
    if (m.op == kFinish) mark(fin_done, fin_begun, 1);
  }
};

struct ChildRun {
  int status = -1;        // waitpid status
  bool mid_trial = false; // killed after a trial write began and before it was reported done
};

// Runs one child; kills it `delay` after its `trigger`-th "begun" report
// (never, if trigger is 0).
ChildRun run_child(const std::string& path, std::uint64_t seed, int trigger, std::chrono::microseconds delay, Known& known) {
  ChildRun run;
  int fds[2];
  if (::pipe(fds) != 0) return run;
  const pid_t pid = ::fork();
  if (pid == 0) {
    ::close(fds[0]);
    child(path, seed, fds[1]);
  }
  ::close(fds[1]);
  Msg m, last{};
  int begun = 0;
  bool killed = false;
  while (::read(fds[0], &m, sizeof m) == static_cast<ssize_t>(sizeof m)) {
    known.apply(m);
    last = m;
    if (!killed && trigger > 0 && !m.done && ++begun == trigger) {
      std::this_thread::sleep_for(delay);
      ::kill(pid, SIGKILL);
      killed = true;  // keep reading: reports written before the kill still count
    }
  }
  ::close(fds[0]);
  ::waitpid(pid, &run.status, 0);
  run.mid_trial = WIFSIGNALED(run.status) && last.op == kRecord && !last.done;
  return run;
}

// --- the invariants of docs/store.md, checked independently --------------------------------

struct Check {
  const char* name;
  std::function<std::string(RawDb&, const Known&, std::uint64_t seed)> fn;  // "" = holds
};

std::string expect_eq(const std::string& what, const std::string& got, const std::string& want) {
  return got == want ? "" : what + ": got " + got + ", expected " + want;
}

const std::vector<Check>& checks() {
  static const std::vector<Check> list = {
      {"I1 the database is intact (integrity_check and foreign keys; on the server: every guard on)",
       [](RawDb& db, const Known&, std::uint64_t) { return expect_eq("integrity", db.integrity(), "ok"); }},
      {"I2 one study row, the protocol as opened",
       [](RawDb& db, const Known&, std::uint64_t) {
         return expect_eq("studies", db.one("SELECT count(*) || max(protocol_sha256) FROM studies"),
                          "1" + study_info().protocol_sha256);
       }},
      {"I3 enrollment indexes are 0..n-1, each participant once, as reported",
       [](RawDb& db, const Known& k, std::uint64_t) -> std::string {
         const auto rows = db.rows("SELECT participant, enrollment_index, order_row FROM participants ORDER BY enrollment_index");
         for (std::size_t i = 0; i < rows.size(); ++i)
           if (rows[i][0] != pid_of(static_cast<int>(i)) || rows[i][1] != std::to_string(i))
             return "participant " + rows[i][0] + " has index " + rows[i][1] + " at rank " + std::to_string(i);
         for (int p = 0; p < kPeople; ++p) {
           const bool in = static_cast<int>(rows.size()) > p;
           if (k.enroll_done[p] && !in) return pid_of(p) + " was reported enrolled but is missing";
           if (!k.enroll_begun[p] && in) return pid_of(p) + " is enrolled though nobody enrolled it";
         }
         return "";
       }},
      {"I4 order row = index mod rows (nothing released)",
       [](RawDb& db, const Known&, std::uint64_t) {
         return expect_eq("rows off the rule", db.one("SELECT count(*) FROM participants WHERE order_row <> enrollment_index % 4"), "0");
       }},
      {"I5 a session exists with its whole plan or not at all",
       [](RawDb& db, const Known& k, std::uint64_t) -> std::string {
         for (int p = 0; p < kParticipants; ++p) {
           const auto n = db.one("SELECT count(*) FROM sessions s JOIN participants pa ON pa.id = s.participant_id "
                                 "WHERE pa.participant = '" + pid_of(p) + "'");
           if (k.begin_done[p] && n != "1") return pid_of(p) + ": begin_session was reported done, no session";
           if (!k.begin_begun[p] && n != "0") return pid_of(p) + ": a session nobody began";
         }
         return expect_eq("sessions with a partial plan",
                          db.one("SELECT count(*) FROM sessions s WHERE (SELECT count(*) FROM planned_trials p "
                                 "WHERE p.session_id = s.id) <> " + std::to_string(kTrials)),
                          "0");
       }},
      {"I6/I7 results are a prefix of the plan; every reported trial saved, at most the one in progress lost",
       [](RawDb& db, const Known& k, std::uint64_t) -> std::string {
         for (int p = 0; p < kParticipants; ++p) {
           const auto r = db.rows("SELECT count(*), coalesce(max(p.position), 0) FROM trial_results r JOIN planned_trials p "
                                  "ON p.id = r.planned_trial_id JOIN sessions s ON s.id = p.session_id JOIN participants "
                                  "pa ON pa.id = s.participant_id WHERE pa.participant = '" + pid_of(p) + "'")[0];
           const int n = std::stoi(r[0]);
           if (r[0] != r[1]) return pid_of(p) + ": results are not positions 1.." + r[0];
           if (n < k.rec_done[p] || n > std::max(k.rec_done[p], k.rec_begun[p]))
             return pid_of(p) + ": " + r[0] + " results, reported done " + std::to_string(k.rec_done[p]) +
                    ", begun " + std::to_string(k.rec_begun[p]);
         }
         return "";
       }},
      {"I7/I8 every saved trial is intact: result, scores, all events and poses, as written",
       [](RawDb& db, const Known&, std::uint64_t seed) -> std::string {
         const auto rows = db.rows(
             "SELECT pa.enrollment_index, pa.order_row, p.position, r.scene_hash, r.completion_s, r.frame_count, "
             "r.event_count, (SELECT count(*) FROM camera_poses c WHERE c.trial_id = r.planned_trial_id), "
             "(SELECT count(*) FROM input_events e WHERE e.trial_id = r.planned_trial_id), "
             "(SELECT x FROM camera_poses c WHERE c.trial_id = r.planned_trial_id ORDER BY frame DESC LIMIT 1), "
             "coalesce(r.signed_error, r.correct, r.distance) "
             "FROM trial_results r JOIN planned_trials p ON p.id = r.planned_trial_id "
             "JOIN sessions s ON s.id = p.session_id JOIN participants pa ON pa.id = s.participant_id");
         for (const auto& row : rows) {
           const auto plan = make_plan(std::stoi(row[0]), std::stoi(row[1]), kPer);
           const TrialRecord want = make_record(seed, plan.trials[static_cast<std::size_t>(std::stoi(row[2]) - 1)]);
           const Scores sc = score(want.answer, want.truth);
           const double s = sc.signed_error ? static_cast<double>(*sc.signed_error)
                            : sc.correct    ? (*sc.correct ? 1.0 : 0.0)
                                            : *sc.distance;
           const std::string n = std::to_string(want.poses.size());
           if (row[3] != want.scene_hash || std::stod(row[4]) != want.completion_s || row[5] != n || row[7] != n ||
               row[6] != std::to_string(want.events.size()) || row[8] != row[6] ||
               std::stod(row[9]) != want.poses.back().x || std::abs(std::stod(row[10]) - s) > 1e-9)
             return "trial " + row[2] + " of index " + row[0] + " differs from what was written";
         }
         return "";
       }},
      {"I9 a session is finished only if finish was called and all trials are saved",
       [](RawDb& db, const Known& k, std::uint64_t) -> std::string {
         for (int p = 0; p < kParticipants; ++p) {
           const auto st = db.one("SELECT s.status FROM sessions s JOIN participants pa ON pa.id = s.participant_id "
                                  "WHERE pa.participant = '" + pid_of(p) + "'");
           if (k.fin_done[p] && st != "finished") return pid_of(p) + ": finish reported done, status " + st;
           if (!k.fin_begun[p] && st == "finished") return pid_of(p) + ": finished though nobody finished it";
         }
         return "";
       }},
      {"I13 one consent answer per participant, stored with the enrollment; a decline holds only the refusal",
       [](RawDb& db, const Known& k, std::uint64_t) -> std::string {
         if (auto w = expect_eq("participants without their answer",
                                db.one("SELECT count(*) FROM participants p WHERE NOT EXISTS (SELECT 1 FROM consents c "
                                       "WHERE c.participant_id = p.id AND c.text_sha256 = '" + kConsentSha + "')"),
                                "0");
             !w.empty())
           return w;
         if (auto w = expect_eq("agreed", db.one("SELECT count(*) FROM consents WHERE agreed = 0"),
                                db.one("SELECT count(*) FROM participants WHERE participant = '" + pid_of(kDecliner) + "'"));
             !w.empty())
           return w;
         const std::string d = "(SELECT id FROM participants WHERE participant = '" + pid_of(kDecliner) + "')";
         const auto declined = db.rows("SELECT p.demographics, p.released_at = w.withdrawn_at, w.reason, "
                                       "(SELECT count(*) FROM sessions s WHERE s.participant_id = p.id) FROM participants "
                                       "p JOIN withdrawals w ON w.participant_id = p.id WHERE p.id = " + d);
         if (db.count("SELECT count(*) FROM withdrawals") != static_cast<std::int64_t>(declined.size()))
           return "a withdrawal of someone who never declined";
         if (k.enroll_done[kDecliner] && declined.empty()) return "the decline was reported done but is missing";
         if (!declined.empty() &&
             declined[0] != std::vector<std::string>{"{}", db.postgres() ? "t" : "1", "declined consent", "0"})
           return "the decliner holds more than the refusal: " + declined[0][0] + " " + declined[0][1] + " " +
                  declined[0][2] + " " + declined[0][3];
         return "";
       }},
      {"I14 screens are numbered 1..n per session; every reported screen saved, at most the one in progress lost",
       [](RawDb& db, const Known& k, std::uint64_t) -> std::string {
         for (int p = 0; p < kParticipants; ++p) {
           const auto r = db.rows("SELECT count(*), coalesce(max(x.seq), 0), coalesce(min(x.seq), 1) FROM screens x "
                                  "JOIN sessions s ON s.id = x.session_id JOIN participants pa ON pa.id = s.participant_id "
                                  "WHERE pa.participant = '" + pid_of(p) + "'")[0];
           const int n = std::stoi(r[0]);
           if (r[0] != r[1] || r[2] != "1") return pid_of(p) + ": screens are not 1.." + r[0];
           if (n < k.scr_done[p] || n > std::max(k.scr_done[p], k.scr_begun[p]))
             return pid_of(p) + ": " + r[0] + " screens, reported done " + std::to_string(k.scr_done[p]) +
                    ", begun " + std::to_string(k.scr_begun[p]);
         }
         return "";
       }},
  };
  return list;
}

// Invariant 10: a running session resumes with exactly the trials it would have run.
std::string check_resume(const std::string& path) {
  auto s = Store::open(path, study_info());
  if (!s) return s.error().to_string();
  for (int p = 0; p < kParticipants; ++p) {
    auto cur = s->session(pid_of(p));
    if (!cur || cur->status != SessionStatus::running) continue;
    auto e = s->lookup(pid_of(p));
    const design::Plan plan = make_plan(e->index, e->order_row, kPer);
    auto ses = s->begin_session(pid_of(p), plan);
    if (!ses || !ses->resumed) return pid_of(p) + ": cannot resume";
    auto next = s->next_trial(*ses);
    if (!next) return next.error().to_string();
    if (ses->recorded == kTrials) {
      if (*next) return pid_of(p) + ": a trial after the last";
    } else if (!*next || !same_trial(**next, plan.trials[static_cast<std::size_t>(ses->recorded)])) {
      return pid_of(p) + ": resume does not continue with planned trial " + std::to_string(ses->recorded + 1);
    }
  }
  return "";
}

class Crash : public OnBothBackends {};
DTLAB_ON_BOTH_BACKENDS(Crash);

TEST_P(Crash, KilledAtIncreasingDelaysLosesAtMostTheTrialInProgress) {
  using std::chrono::microseconds;
  const microseconds delays[] = {microseconds(0),   microseconds(100),  microseconds(250),  microseconds(500),
                                 microseconds(900), microseconds(1500), microseconds(2500), microseconds(4000),
                                 microseconds(6000), microseconds(9000)};
  int kills = 0, kills_mid_step = 0;
  const std::uint64_t seeds = pg() ? 2 : 3;  // a server round trip per step: fewer seeds keep it to seconds
  for (std::uint64_t seed = 1; seed <= seeds; ++seed) {
    const std::string path = study("crash" + std::to_string(seed));
    Known known;
    int cycle = 0;
    for (const microseconds delay : delays) {
      // The first run of each seed dies while creating the database.
      const int trigger = cycle == 0 ? 1 : 1 + static_cast<int>(mix64(seed, static_cast<std::uint64_t>(cycle)) % 8);
      const ChildRun run = run_child(path, seed, trigger, delay, known);
      const int status = run.status;
      ASSERT_TRUE(WIFSIGNALED(status) || (WIFEXITED(status) && WEXITSTATUS(status) == 0))
          << "the child failed (not killed): status " << status;
      if (WIFSIGNALED(status)) {
        ++kills;
        kills_mid_step += run.mid_trial ? 1 : 0;
      }
      if (!pg() && !std::filesystem::exists(path)) {
        // Killed before SQLite created the file: allowed only if nothing was reported saved.
        EXPECT_EQ(known.enroll_done[0], 0) << "seed " << seed << ": enrollment reported, but no database file";
      } else {
        RawDb db(path);
        const bool has_schema = db.has_table("studies");
        if (!has_schema) {
          EXPECT_EQ(known.enroll_done[0], 0) << "seed " << seed << ": enrollment reported, no schema";
        }
        for (const Check& c : checks()) {
          if (!has_schema && std::string(c.name).rfind("I1 ", 0) != 0) continue;  // nothing created yet (I1 only, not I13)
          const std::string why = c.fn(db, known, seed);
          EXPECT_TRUE(why.empty()) << c.name << "\n  seed " << seed << ", run " << cycle << ", kill after step "
                                   << trigger << " + " << delay.count() << " us: " << why;
        }
      }
      if (const std::string why = check_resume(path); !why.empty())
        ADD_FAILURE() << "I10 resume, seed " << seed << ", run " << cycle << ": " << why;
      ++cycle;
    }
    // Run to the end without a kill: the result equals a run that never crashed.
    const int status = run_child(path, seed, 0, microseconds(0), known).status;
    ASSERT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0);
    const std::string clean = study("clean" + std::to_string(seed));
    Known clean_known;
    ASSERT_EQ(run_child(clean, seed, 0, microseconds(0), clean_known).status, 0);
    const std::string sql =
        "SELECT pa.participant, pa.enrollment_index, pa.order_row, s.status, p.position, p.seed, r.scene_hash, "
        "r.completion_s, r.answer_count, r.answer_letter, r.answer_x, r.rel_error, r.correct, r.distance, "
        "r.frame_count, (SELECT sum(x + y + z + yaw + pitch + t_s) FROM camera_poses c WHERE c.trial_id = r.planned_trial_id) "
        "FROM participants pa JOIN sessions s ON s.participant_id = pa.id JOIN planned_trials p ON p.session_id = s.id "
        "LEFT JOIN trial_results r ON r.planned_trial_id = p.id ORDER BY pa.enrollment_index, p.position";
    RawDb a(path), b(clean);
    const auto got = a.rows(sql), want = b.rows(sql);
    EXPECT_EQ(got.size(), static_cast<std::size_t>(kParticipants * kTrials));
    EXPECT_EQ(got, want) << "seed " << seed << ": the crashed-and-resumed study differs from a clean run";
    const std::string answers =
        "SELECT pa.participant, pa.demographics, pa.released_at IS NULL, c.agreed, c.text_sha256, w.reason, "
        "x.seq, x.screen, x.shown_at, x.ended_at, x.duration_s, x.answer FROM participants pa "
        "LEFT JOIN consents c ON c.participant_id = pa.id LEFT JOIN withdrawals w ON w.participant_id = pa.id "
        "LEFT JOIN sessions s ON s.participant_id = pa.id LEFT JOIN screens x ON x.session_id = s.id "
        "ORDER BY pa.enrollment_index, x.seq";
    EXPECT_EQ(a.rows(answers).size(), static_cast<std::size_t>(kParticipants * kTrials + 1));
    EXPECT_EQ(a.rows(answers), b.rows(answers)) << "seed " << seed << ": consent or screens differ from a clean run";
    for (const Check& c : checks()) EXPECT_EQ(c.fn(a, known, seed), "") << c.name;
  }
  // The loop is only meaningful if kills really landed inside steps.
  EXPECT_GE(kills, static_cast<int>(seeds) * 20 / 3);
  EXPECT_GE(kills_mid_step, 3);
  std::printf("crash test: %d kills, %d inside a trial write\n", kills, kills_mid_step);
}

}  // namespace
}  // namespace dtlab::store

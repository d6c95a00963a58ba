// Session claims (docs/store.md, "Claims"): the one process that runs a
// session holds its row in session_claims, taken in the same transaction that
// begins or resumes the session and renewed by every trial it records. Any
// other process that tries to run the session gets a busy Error naming the
// holder, until the holder is gone (same host: its pid is dead or now another
// process) or its claim expired (no renewal for claim_ttl_s). The claim is
// operational state, not study data: it is the one row the store changes in
// place and deletes (at finish, release, and when its Store is destroyed).
#include <signal.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <chrono>
#include <fstream>
#include <random>
#include <sstream>

#include "study/store/detail/columns.h"
#include "study/store/detail/store_impl.h"
#include "study/store/detail/time.h"

namespace dtlab::store {

using detail::Stmt;

namespace {

// Fields 3 (state) and 22 (start time in clock ticks since boot) of /proc/<pid>/stat; empty where
// there is no such process (or no /proc).
struct ProcStat {
  std::string state, start_time;
};
ProcStat proc_stat(std::int64_t pid) {
  std::ifstream in("/proc/" + std::to_string(pid) + "/stat");
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const auto close = text.rfind(')');  // the command name may hold spaces and parentheses
  ProcStat out;
  if (close == std::string::npos) return out;
  std::istringstream rest(text.substr(close + 2));
  std::string field;
  for (int i = 3; i <= 22 && rest >> field; ++i) {
    if (i == 3) out.state = field;
    if (i == 22) out.start_time = field;
  }
  return out;
}

std::string process_start_time(std::int64_t pid) { return proc_stat(pid).start_time; }

std::string host_name() {
  char buf[256] = {};
  if (::gethostname(buf, sizeof buf - 1) != 0) return "localhost";
  return buf;
}

std::string machine_id() {
  std::ifstream in("/etc/machine-id");
  std::string id;
  in >> id;
  return id.substr(0, 12);
}

// Field `n` (0-based) of an owner string host/pid/start/nonce/machine; "" if it has none
// (owners written before the machine field have four).
std::string owner_field(const std::string& owner, int n) {
  std::size_t from = 0;
  for (int i = 0; i < n; ++i) {
    from = owner.find('/', from);
    if (from == std::string::npos) return "";
    ++from;
  }
  const auto to = owner.find('/', from);
  return owner.substr(from, to == std::string::npos ? std::string::npos : to - from);
}

struct Holder {
  std::string owner, host, claimed_at, heartbeat_at, expires_at;
  std::int64_t pid = 0;
};

// True when the holder can no longer be running the session.
bool gone(const Claimant& me, const Holder& h, const std::string& now) {
  if (h.expires_at < now) return true;
  const std::string machine = owner_field(h.owner, 4);
  if (h.host != me.host || (!machine.empty() && !me.machine.empty() && machine != me.machine))
    return false;  // another machine (or a station cloned with this one's host name): only expiry tells
  if (::kill(static_cast<pid_t>(h.pid), 0) != 0 && errno == ESRCH) return true;
  const ProcStat now_stat = proc_stat(h.pid);
  if (now_stat.state == "Z" || now_stat.state == "X") return true;  // killed, not yet reaped: a zombie runs nothing
  const std::string recorded = owner_field(h.owner, 2);
  return !recorded.empty() && !now_stat.start_time.empty() && recorded != now_stat.start_time;  // pid reused
}

std::string in_future(std::chrono::system_clock::time_point now, double seconds) {
  return detail::iso8601_utc(now + std::chrono::milliseconds(static_cast<std::int64_t>(seconds * 1000)));
}

}  // namespace

Claimant make_claimant() {
  static std::atomic<unsigned> counter{0};
  Claimant c;
  c.host = host_name();
  c.pid = ::getpid();
  c.start_time = process_start_time(c.pid);
  c.machine = machine_id();
  std::random_device rd;
  std::ostringstream owner;
  owner << c.host << '/' << c.pid << '/' << c.start_time << '/' << std::hex << rd() << counter++ << '/' << c.machine;
  c.owner = owner.str();
  return c;
}

Status Store::Impl::take_claim(std::int64_t session_id, const std::string& who, bool take_over, bool* took_over) {
  const char* what = "claiming the session";
  auto q = Stmt::prepare(db,
                         "SELECT " + detail::select_list(*detail::find_table("session_claims"), "", kSchemaVersion) +
                             " FROM session_claims WHERE session_id = :session_id",
                         what);
  if (!q) return q.error();
  q->bind("session_id", session_id);
  auto row = q->step(what);
  if (!row) return row.error();
  auto clock = db.conn().now();  // the server's clock on PostgreSQL: every station judges a claim by one clock
  if (!clock) return clock.error();
  const std::string now = detail::iso8601_utc(*clock);
  if (*row) {
    Holder h{q->text("owner"),        q->text("host"),       q->text("claimed_at"),
             q->text("heartbeat_at"), q->text("expires_at"), q->int64("pid")};
    if (h.owner != me.owner && !take_over && !gone(me, h, now))
      return invalid(kClaimField,
                     "the session of \"" + who + "\" is being run by process " + std::to_string(h.pid) + " on host " +
                         h.host + " (claimed " + h.claimed_at + ", last heartbeat " + h.heartbeat_at +
                         "); wait for it to finish, or take it over once it is gone (its claim expires at " +
                         h.expires_at + " unless renewed)",
                     ErrorKind::busy);
    if (took_over) *took_over = h.owner != me.owner;
  }
  auto up = Stmt::prepare(db,
                          "INSERT INTO session_claims (session_id, owner, host, pid, claimed_at, heartbeat_at, "
                          "expires_at) VALUES (:session_id, :owner, :host, :pid, :claimed_at, :heartbeat_at, "
                          ":expires_at) "
                          "ON CONFLICT (session_id) DO UPDATE SET "
                          "owner = excluded.owner, host = excluded.host, pid = excluded.pid, "
                          "claimed_at = excluded.claimed_at, heartbeat_at = excluded.heartbeat_at, "
                          "expires_at = excluded.expires_at",
                          what);
  if (!up) return up.error();
  up->bind("session_id", session_id).bind("owner", me.owner).bind("host", me.host).bind("pid", me.pid);
  up->bind("claimed_at", now).bind("heartbeat_at", now).bind("expires_at", in_future(*clock, options.claim_ttl_s));
  if (auto s = up->run(what); !s) return s;
  claimed.insert(session_id);
  return {};
}

Status Store::Impl::renew_claim(std::int64_t session_id, const std::string& who) {
  const char* what = "renewing the session claim";
  auto clock = db.conn().now();
  if (!clock) return clock.error();
  auto up = Stmt::prepare(db,
                          "UPDATE session_claims SET heartbeat_at = :heartbeat_at, expires_at = :expires_at "
                          "WHERE session_id = :session_id AND owner = :owner "
                          "RETURNING session_id",
                          what);
  if (!up) return up.error();
  up->bind("heartbeat_at", detail::iso8601_utc(*clock)).bind("expires_at", in_future(*clock, options.claim_ttl_s));
  up->bind("session_id", session_id).bind("owner", me.owner);
  auto renewed = up->step(what);
  if (!renewed) return renewed.error();
  const bool ours = *renewed;
  if (auto s = up->run(what); !s) return s;  // steps past the RETURNING row to the end of the statement
  if (ours) return {};
  claimed.erase(session_id);
  return invalid("session",
                 "the session of \"" + who + "\" is no longer claimed by this process (taken over by another, or "
                 "released); stop running it: the other process or a rerun continues it",
                 ErrorKind::conflict);
}

Status Store::Impl::drop_claim(std::int64_t session_id) {
  auto del = Stmt::prepare(db, "DELETE FROM session_claims WHERE session_id = :session_id AND owner = :owner",
                           "releasing the claim");
  if (!del) return del.error();
  del->bind("session_id", session_id).bind("owner", me.owner);
  if (auto s = del->run("releasing the claim"); !s) return s;
  claimed.erase(session_id);
  return {};
}

Store::Impl::~Impl() {
  // Best effort: a claim left behind is taken over anyway once this process is gone.
  if (claimed.empty() || broken) return;
  db.conn().set_busy_timeout(2000);
  const std::set<std::int64_t> ids = claimed;
  write("releasing the session claims", [&]() -> Status {
    for (std::int64_t id : ids)
      if (auto s = drop_claim(id); !s) return s;
    return {};
  });
}

Status Store::heartbeat(const Session& session) {
  Impl& m = *impl_;
  return m.write("renewing the claim on session " + std::to_string(session.id),
                 [&]() -> Status { return m.renew_claim(session.id, session.participant_id); });
}

Status Store::release_claim(const Session& session) {
  Impl& m = *impl_;
  return m.write("releasing the claim on session " + std::to_string(session.id),
                 [&]() -> Status { return m.drop_claim(session.id); });
}

}  // namespace dtlab::store

// run_simulated (driver.h). Workers talk to the parent over pipes: the parent
// writes one participant number at a time into a worker's own command pipe;
// workers write fixed-size messages (smaller than PIPE_BUF, so writes from
// several workers never interleave) into one shared report pipe. A worker
// exits when its command pipe closes, after closing its database connection
// (_exit skips destructors, so the connection must be gone before it). The
// parent never touches SQLite or GL while workers run.
#include "study/sim/driver.h"

#include <fcntl.h>
#include <sys/wait.h>
#ifdef __linux__
#include <sys/prctl.h>
#endif
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <limits.h>

#include "study/session/mapping.h"
#include "study/session/session.h"
#include "study/store/store.h"

namespace dtlab::sim {

std::string participant_id(int number) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "sim-%03d", number);
  return buf;
}

Result<Roster> enroll_simulated(const std::string& db_path, const protocol::Protocol& p, int participants,
                                store::OpenOptions open) {
  auto store = store::Store::open(db_path, session::study_info(p), open);
  if (!store) return store.error();
  Roster r;
  for (int k = 1; k <= participants; ++k) {
    const std::string id = participant_id(k);
    // Marked as simulated in the ledger (the report names them so).
    auto e = store->enroll(id, {{"simulated", "true"}, {"agent", "dtlab-sim"}});
    if (!e) return e.error();
    if (!e->newly_enrolled) {
      auto s = store->session(id);
      if (s && s->status == store::SessionStatus::finished) {
        ++r.finished;
        continue;
      }
      if (s && s->status == store::SessionStatus::running) ++r.resumable;
    }
    r.to_run.push_back(id);
  }
  return r;
}

namespace {

// One report from a worker; fixed size, written with one write().
struct Message {
  int kind = 0;  // Progress::Kind
  int worker = 0;
  int participant = 0;  // index into RunOptions::participants
  int position = 0, planned = 0;
  int resumed = 0;
  int trials_run = 0;  // finished: trials recorded in this session by this run
  int invalid = 0;     // failed: the error is in the protocol (it names the protocol file)
  double simulated_s = 0;
  char task[16] = {};
  char condition[96] = {};
  char message[768] = {};
};
static_assert(sizeof(Message) < PIPE_BUF, "a report must be written atomically");

void copy(char* dst, std::size_t n, const std::string& s) {
  std::snprintf(dst, n, "%s", s.c_str());
}

bool write_all(int fd, const void* data, std::size_t n) {
  const char* p = static_cast<const char*>(data);
  while (n > 0) {
    const ssize_t w = ::write(fd, p, n);
    if (w < 0 && errno == EINTR) continue;
    if (w <= 0) return false;
    p += w;
    n -= static_cast<std::size_t>(w);
  }
  return true;
}

bool read_all(int fd, void* data, std::size_t n) {
  char* p = static_cast<char*>(data);
  while (n > 0) {
    const ssize_t r = ::read(fd, p, n);
    if (r < 0 && errno == EINTR) continue;
    if (r <= 0) return false;
    p += r;
    n -= static_cast<std::size_t>(r);
  }
  return true;
}

Progress to_progress(const Message& m, const RunOptions& o) {
  Progress p;
  p.kind = static_cast<Progress::Kind>(m.kind);
  p.worker = m.worker;
  p.participant = o.participants[static_cast<std::size_t>(m.participant)];
  p.position = m.position;
  p.planned = m.planned;
  p.task = m.task;
  p.condition = m.condition;
  p.simulated_s = m.simulated_s;
  p.resumed = m.resumed != 0;
  p.message = m.message;
  return p;
}

// Runs participant `k` in this process; every event goes to `report`.
void run_one(const RunOptions& o, store::Store& store, SimulatedParticipant& agent, int worker, int k,
             const std::function<void(const Message&)>& report) {
  const std::string& id = o.participants[static_cast<std::size_t>(k)];
  session::Hooks hooks;
  hooks.on_session_start = [&](const store::Session& s, const design::Plan&) {
    Message m;
    m.kind = static_cast<int>(Progress::Kind::started);
    m.worker = worker;
    m.participant = k;
    m.planned = s.planned;
    m.position = s.recorded;
    m.resumed = s.resumed;
    report(m);
  };
  hooks.on_trial_recorded = [&](const session::TrialSpec& spec, const store::TrialRecord& r) {
    Message m;
    m.kind = static_cast<int>(Progress::Kind::trial);
    m.worker = worker;
    m.participant = k;
    m.position = r.position;
    m.planned = spec.planned_trials;
    m.simulated_s = r.completion_s;
    copy(m.task, sizeof m.task, spec.planned.task);
    copy(m.condition, sizeof m.condition, o.protocol->conditions[static_cast<std::size_t>(spec.setup->condition)].name);
    report(m);
  };
  if (o.stop) hooks.stop_requested = [&] { return *o.stop != 0; };
  auto result = session::run_session(store, *o.protocol, id, agent, hooks);
  Message m;
  m.worker = worker;
  m.participant = k;
  if (!result && result.error().kind == ErrorKind::busy && result.error().field == store::kClaimField) {
    m.kind = static_cast<int>(Progress::Kind::elsewhere);  // another process runs it: not ours to run
    copy(m.message, sizeof m.message, result.error().message);
  } else if (!result) {
    m.kind = static_cast<int>(Progress::Kind::failed);
    m.invalid = !o.protocol->source_path.empty() && result.error().file == o.protocol->source_path;
    copy(m.message, sizeof m.message, result.error().to_string());
  } else if (result->already_finished) {
    m.kind = static_cast<int>(Progress::Kind::elsewhere);  // finished by another process since the roster was made
    copy(m.message, sizeof m.message, "finished by another process");
  } else {
    m.kind = static_cast<int>(result->finished ? Progress::Kind::finished : Progress::Kind::failed);
    m.trials_run = result->trials_run;
    m.planned = static_cast<int>(result->plan.trials.size());
    m.position = result->trials_recorded;
    if (!result->finished) copy(m.message, sizeof m.message, "stopped before the end (rerun to resume)");
  }
  report(m);
}

void tally(RunResult& r, const Message& m, const RunOptions& o) {
  if (m.kind == static_cast<int>(Progress::Kind::trial)) ++r.trials_run;
  if (m.kind == static_cast<int>(Progress::Kind::finished)) ++r.finished;
  if (m.kind == static_cast<int>(Progress::Kind::elsewhere)) ++r.elsewhere;
  if (m.kind == static_cast<int>(Progress::Kind::failed) && !(o.stop && *o.stop)) {
    ++r.failed;
    r.invalid += m.invalid;
    r.errors.push_back(o.participants[static_cast<std::size_t>(m.participant)] + ": " + m.message);
  }
}

Result<RunResult> run_here(const RunOptions& o) {
  RunResult r;
  auto ctx = o.make_context(o.sim.width, o.sim.height);
  if (!ctx) return ctx.error();
  auto store = store::Store::open(o.db_path, session::study_info(*o.protocol), o.open);
  if (!store) return store.error();
  SimulatedParticipant agent(o.sim);
  const auto report = [&](const Message& m) {
    tally(r, m, o);
    if (o.on_progress) o.on_progress(to_progress(m, o));
  };
  for (int k = 0; k < static_cast<int>(o.participants.size()); ++k) {
    if (o.stop && *o.stop) break;
    run_one(o, store.value(), agent, 0, k, report);
  }
  r.stopped = o.stop && *o.stop;
  return r;
}

[[noreturn]] void worker_main(const RunOptions& o, int worker, int command_fd, int report_fd) {
  const auto report = [&](const Message& m) { write_all(report_fd, &m, sizeof m); };
  auto fail_all = [&](const std::string& why) {
    // Tell the parent about every participant it sends, so it can move on.
    int k = 0;
    while (read_all(command_fd, &k, sizeof k)) {
      Message m;
      m.kind = static_cast<int>(Progress::Kind::failed);
      m.worker = worker;
      m.participant = k;
      copy(m.message, sizeof m.message, why);
      report(m);
    }
    _exit(3);
  };
  {
    auto ctx = o.make_context(o.sim.width, o.sim.height);
    if (!ctx) fail_all(ctx.error().to_string());
    auto store = store::Store::open(o.db_path, session::study_info(*o.protocol), o.open);
    if (!store) fail_all(store.error().to_string());
    SimulatedParticipant agent(o.sim);
    int k = 0;
    while (read_all(command_fd, &k, sizeof k)) run_one(o, store.value(), agent, worker, k, report);
  }  // the connection closes here, before _exit: the last one to close checkpoints and removes the -wal
  std::fflush(nullptr);
  _exit(0);
}

Result<RunResult> run_forked(const RunOptions& o) {
  RunResult r;
  const int jobs = std::min<int>(o.jobs, static_cast<int>(o.participants.size()));
  int report_pipe[2];
  if (::pipe(report_pipe) != 0) return Error{"", 0, 0, "jobs", std::string("pipe: ") + std::strerror(errno)};
  struct Worker {
    pid_t pid = -1;
    int command_fd = -1;
    bool busy = false;
  };
  std::vector<Worker> workers;
  [[maybe_unused]] const pid_t parent = ::getpid();
  std::fflush(nullptr);  // nothing buffered may be written twice
  for (int w = 0; w < jobs; ++w) {
    int cmd[2];
    if (::pipe(cmd) != 0) return Error{"", 0, 0, "jobs", std::string("pipe: ") + std::strerror(errno)};
    const pid_t pid = ::fork();
    if (pid < 0) return Error{"", 0, 0, "jobs", std::string("fork: ") + std::strerror(errno)};
    if (pid == 0) {
#ifdef __linux__
      // A worker dies with its parent (Ctrl-C, SIGKILL), so no orphan races a rerun for a session.
      ::prctl(PR_SET_PDEATHSIG, SIGKILL);
      if (::getppid() != parent) _exit(3);
#endif
      ::close(cmd[1]);
      ::close(report_pipe[0]);
      for (const Worker& other : workers) ::close(other.command_fd);
      worker_main(o, w, cmd[0], report_pipe[1]);
    }
    ::close(cmd[0]);
    ::fcntl(cmd[1], F_SETFD, FD_CLOEXEC);
    workers.push_back({pid, cmd[1], false});
  }
  ::close(report_pipe[1]);

  std::size_t next = 0;
  auto assign = [&](Worker& w) {
    if (w.command_fd < 0) return;
    if (next < o.participants.size() && !(o.stop && *o.stop)) {
      const int k = static_cast<int>(next++);
      if (write_all(w.command_fd, &k, sizeof k)) {
        w.busy = true;
        return;
      }
    }
    ::close(w.command_fd);  // nothing more: the worker exits
    w.command_fd = -1;
    w.busy = false;
  };
  for (Worker& w : workers) assign(w);
  Message m;
  while (read_all(report_pipe[0], &m, sizeof m)) {
    tally(r, m, o);
    if (o.on_progress) o.on_progress(to_progress(m, o));
    if (m.kind == static_cast<int>(Progress::Kind::finished) || m.kind == static_cast<int>(Progress::Kind::failed) ||
        m.kind == static_cast<int>(Progress::Kind::elsewhere))
      assign(workers[static_cast<std::size_t>(m.worker)]);
  }
  ::close(report_pipe[0]);
  for (Worker& w : workers) {
    if (w.command_fd >= 0) ::close(w.command_fd);
    int status = 0;
    while (::waitpid(w.pid, &status, 0) < 0 && errno == EINTR) {
    }
    if (WIFSIGNALED(status) || (WIFEXITED(status) && WEXITSTATUS(status) != 0 && WEXITSTATUS(status) != 3)) {
      ++r.failed;
      r.errors.push_back("worker " + std::to_string(w.pid) + " ended abnormally (" +
                         (WIFSIGNALED(status) ? "signal " + std::to_string(WTERMSIG(status))
                                              : "exit " + std::to_string(WEXITSTATUS(status))) +
                         "); rerun to resume its participant");
    }
  }
  r.stopped = o.stop && *o.stop;
  return r;
}

}  // namespace

Result<RunResult> run_simulated(const RunOptions& o) {
  if (!o.protocol || !o.make_context) throw std::invalid_argument("run_simulated: protocol and make_context are required");
  if (o.participants.empty()) return RunResult{};
  if (o.jobs <= 1 || o.participants.size() == 1) return run_here(o);
  return run_forked(o);
}

}  // namespace dtlab::sim

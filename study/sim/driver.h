// Running many simulated participants against one study database, in this
// process or in J forked worker processes (`dtlab simulate`, `dtlab demo`).
// Each worker has its own GL context (from the caller's factory, created
// after the fork) and its own database connection; the store is multi-process
// safe. Participants are handed out one at a time, so a slow one does not
// hold the others back. Several `dtlab simulate` processes may run on one
// database at once: each session is claimed by the one process running it,
// and the others skip it (Progress::Kind::elsewhere), so they share the work.
// Guarantees: every trial a worker reports is committed
// (it reports after record_trial returns); killing any process at any moment
// loses at most the trials in progress, and running again resumes them.
// Never: shares a SQLite connection or a GL context across fork(), or kills
// a process it did not start.
#pragma once
#include <csignal>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "study/common/error.h"
#include "study/protocol/protocol.h"
#include "study/sim/sim.h"
#include "study/store/store.h"

namespace dtlab::sim {

// Simulated participant ids: sim-001, sim-002, ... (1-based, at least three digits).
std::string participant_id(int number);

// Opens (or creates) the database, enrolls sim-001 .. sim-N in that order (existing ids keep
// their enrollment) and returns the ids whose session is not finished, in order.
struct Roster {
  std::vector<std::string> to_run;  // not finished (new, or running: resumed)
  int finished = 0;                 // already finished, skipped
  int resumable = 0;                // of to_run: sessions already running
};
// `open` as Store::open takes it (allow_protocol_change: continue a database of another protocol hash).
Result<Roster> enroll_simulated(const std::string& db_path, const protocol::Protocol& p, int participants,
                                store::OpenOptions open = {});

// A GL 3.3 core context made current in the calling process; kept alive by the returned handle.
using ContextFactory = std::function<Result<std::shared_ptr<void>>(int width, int height)>;

struct Progress {
  // elsewhere: another process runs (or has just finished) this participant's session; skipped here.
  enum class Kind { started, trial, finished, failed, elsewhere } kind = Kind::trial;
  std::string participant;
  int worker = 0;
  int position = 0, planned = 0;  // trial: the recorded trial's position; planned trials
  std::string task, condition;    // trial: task id and condition name ("on/abstract")
  double simulated_s = 0;         // trial: simulated completion time
  bool resumed = false;           // started: the session was running before
  std::string message;            // failed: the error
};

struct RunOptions {
  std::string db_path;
  const protocol::Protocol* protocol = nullptr;
  store::OpenOptions open;                // how every process opens db_path (Store::open)
  std::vector<std::string> participants;  // ids to run (enroll_simulated().to_run)
  int jobs = 1;                           // 1: in this process; > 1: forked workers
  SimOptions sim;
  ContextFactory make_context;
  std::function<void(const Progress&)> on_progress;  // in the calling process, in arrival order
  const volatile std::sig_atomic_t* stop = nullptr;  // non-zero: finish the trial in progress, then stop
};

struct RunResult {
  int finished = 0;     // sessions finished by this run
  int elsewhere = 0;    // sessions another process was running (claimed) or finished meanwhile: skipped
  int trials_run = 0;   // trials recorded by this run
  int failed = 0;       // participants whose session stopped with an error (messages in `errors`)
  int invalid = 0;      // of those, errors in the protocol (the Error names the protocol file), not the environment
  bool stopped = false; // *stop ended the run early
  std::vector<std::string> errors;
};

// Runs every listed participant's session to the end (or until *stop). Errors of single
// participants are collected in RunResult; an Error is returned only when the run itself
// cannot proceed (no GL context, the database cannot be opened, fork fails).
Result<RunResult> run_simulated(const RunOptions& options);

}  // namespace dtlab::sim

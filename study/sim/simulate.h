// A whole simulated study in one call (`dtlab simulate`, `dtlab demo`): the
// protocol checked as `dtlab validate` checks it (at the agents' viewport
// too), sim-001 .. sim-N enrolled into the database, their unfinished
// sessions run to the end (driver.h) and the finished ones counted. The
// caller supplies the GL contexts, the progress display and the stop flag;
// this prints nothing, installs no signal handler and never exits the
// process. Guarantees as driver.h: every reported trial is committed, a rerun
// resumes.
#pragma once
#include <csignal>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "study/common/error.h"
#include "study/protocol/protocol.h"
#include "study/session/runnable.h"
#include "study/sim/driver.h"

namespace dtlab::sim {

// What simulate_study runs.
struct StudyRun {
  std::string db;  // a file or a postgresql:// URI; created if missing
  int participants = 16, jobs = 1, width = 160, height = 120;
  std::uint64_t seed = 0;              // the agents' traits and choices (SimOptions::seed)
  bool allow_protocol_change = false;  // continue a database recorded under another protocol hash
  ContextFactory make_context;         // a GL context per process (driver.h)
  // Called once with the protocol check's diagnostics (warnings, or the errors that stop it), before
  // the database is opened.
  std::function<void(const std::vector<Diagnostic>&)> on_checked;
  // Called once after enrollment, before any session runs: the participants to run and the
  // trials they will record in all (each participant's planned trials).
  std::function<void(const Roster& roster, long long planned_trials)> on_roster;
  std::function<void(const Progress&)> on_progress;  // as RunOptions::on_progress
  const volatile std::sig_atomic_t* stop = nullptr;  // non-zero: finish the trials in progress, then stop
};

// What it did. At most one of protocol_invalid, enroll_error and run_error is set.
struct StudyResult {
  std::vector<Diagnostic> diagnostics;          // the protocol check's warnings (and errors)
  bool protocol_invalid = false;                // the check found errors: nothing was opened or run
  std::optional<Error> enroll_error;             // opening the database or enrolling failed: nothing ran
  std::optional<Error> run_error;                // the run could not proceed (driver.h); what finished is saved
  int finished_total = 0;    // sessions of sim-001 .. sim-N finished now, by any process
  int already_finished = 0;  // finished before this run (skipped)
  int resumed = 0;           // sessions that were running before this run
  int trials_run = 0;        // trials recorded by this run
  int elsewhere = 0;         // sessions another process was running (claimed): skipped here
  int failed = 0, invalid = 0;  // participants whose session stopped with an error; of those, the protocol's
  bool stopped = false;      // *stop ended the run early
  double wall_s = 0;         // from the check to the end of the run
  std::vector<std::string> errors;  // one message per failed participant
};

// Runs the study `p` with run.participants simulated participants into run.db (see above).
StudyResult simulate_study(const protocol::Protocol& p, const StudyRun& run);

}  // namespace dtlab::sim

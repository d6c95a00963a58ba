// simulate_study (simulate.h): the protocol check, enrollment, the run and the
// count of finished sessions, in that order; moved here from the app, which
// keeps only what a process owns (its signals, its stderr, its exit code).
// Prints nothing; an Error never ends the process.
#include "study/sim/simulate.h"

#include <chrono>

#include "study/design/design.h"
#include "study/session/mapping.h"
#include "study/store/read.h"

namespace dtlab::sim {
namespace {

// Sessions of sim-001 .. sim-N the database records as finished now (other processes ran some).
std::optional<int> finished_in_database(const StudyRun& run) {
  auto reader = store::StudyReader::open(run.db, session::read_options());
  auto sessions = reader ? reader->sessions() : Result<std::vector<store::SessionRecord>>(reader.error());
  if (!sessions) return std::nullopt;
  int finished = 0;
  for (int k = 1; k <= run.participants; ++k)
    for (const auto& s : *sessions)
      if (s.participant == participant_id(k) && s.status == store::SessionStatus::finished) ++finished;
  return finished;
}

}  // namespace

StudyResult simulate_study(const protocol::Protocol& p, const StudyRun& run) {
  const auto start = std::chrono::steady_clock::now();
  StudyResult result;
  // What the sessions will hand the generator and the renderer, checked before anything runs.
  result.diagnostics = session::validate_runnable(p, {session::Viewport{run.width, run.height}});
  if (run.on_checked) run.on_checked(result.diagnostics);
  if (protocol::has_errors(result.diagnostics)) {
    result.protocol_invalid = true;
    return result;
  }
  const store::OpenOptions open = session::open_options(run.allow_protocol_change);
  auto roster = enroll_simulated(run.db, p, run.participants, open);
  if (!roster) {
    result.enroll_error = roster.error();
    return result;
  }
  result.already_finished = roster->finished;
  result.resumed = roster->resumable;

  RunOptions o;
  o.db_path = run.db;
  o.protocol = &p;
  o.open = open;
  o.participants = roster->to_run;
  o.jobs = run.jobs;
  o.sim.width = run.width;
  o.sim.height = run.height;
  o.sim.seed = run.seed;
  o.make_context = run.make_context;
  o.on_progress = run.on_progress;
  o.stop = run.stop;
  const long long per = static_cast<long long>(design::make_plan(p, 0).trials.size());
  if (run.on_roster) run.on_roster(*roster, per * static_cast<long long>(roster->to_run.size()));
  auto ran = run_simulated(o);
  result.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (!ran) {
    result.run_error = ran.error();
    return result;
  }
  result.trials_run = ran->trials_run;
  result.elsewhere = ran->elsewhere;
  result.finished_total = roster->finished + ran->finished;
  if (ran->elsewhere > 0)  // other processes ran some: count what the database says now
    if (auto n = finished_in_database(run)) result.finished_total = *n;
  result.failed = ran->failed;
  result.invalid = ran->invalid;
  result.errors = ran->errors;
  result.stopped = ran->stopped;
  return result;
}

}  // namespace dtlab::sim

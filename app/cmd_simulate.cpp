// `dtlab simulate PROTOCOL --participants N --db DB [--seed S] [--width W
// --height H] [--jobs J] [--allow-protocol-change] [--json]`: simulated
// participants (study/sim) run the protocol headless (OSMesa) into a study
// database; progress on stderr, a summary on stdout. Into an existing database it continues: running sessions
// resume, finished ones are skipped, ids up to sim-N are added. Ctrl-C stops
// after the trials in progress (a second Ctrl-C at once); SIGKILL loses at
// most the trials in progress. The protocol is checked first as `dtlab
// validate` does (sim::simulate_study: the check, enrollment and the run are
// the library's; signals, stderr and the exit code are this file's). Exit 0 all finished, 1 bad
// protocol/database, 2 bad command line, 3 environment (GL, database, fork),
// 130 interrupted.
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <chrono>
#include <csignal>
#include <cstdio>
#include <iostream>
#include <memory>
#include <optional>
#include <thread>
#include <unistd.h>

#include "app/commands.h"
#include "app/database_arg.h"
#include "app/platform/gl_context.h"
#include "study/common/text.h"
#include "study/protocol/protocol.h"
#include "study/session/runnable.h"
#include "study/sim/driver.h"
#include "study/sim/simulate.h"
#include "study/sim/summary.h"
#include "study/session/mapping.h"
#include "study/store/read.h"

namespace dtlab::app {

namespace {

volatile std::sig_atomic_t g_stop = 0;

extern "C" void on_interrupt(int) {
  g_stop = 1;
  std::signal(SIGINT, SIG_DFL);  // a second Ctrl-C ends the process at once
  std::signal(SIGTERM, SIG_DFL);
}

std::string clock_text(double seconds) {
  const long s = static_cast<long>(seconds + 0.5);
  char buf[32];
  if (s >= 3600) std::snprintf(buf, sizeof buf, "%ld:%02ld:%02ld", s / 3600, s / 60 % 60, s % 60);
  else std::snprintf(buf, sizeof buf, "%ld:%02ld", s / 60, s % 60);
  return buf;
}

// Progress on stderr: one line per recorded trial, with the run's ETA from its own pace.
class ProgressPrinter {
 public:
  ProgressPrinter(std::string prefix, long long planned_total) : prefix_(std::move(prefix)), total_(planned_total) {}
  void operator()(const sim::Progress& p) {
    using K = sim::Progress::Kind;
    const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    char line[512];
    switch (p.kind) {
      case K::started:
        total_ -= p.position;  // trials recorded before this run are not ahead of us
        if (p.resumed)
          std::fprintf(stderr, "%s: %s resumes at trial %d of %d\n", prefix_.c_str(), p.participant.c_str(),
                       p.position + 1, p.planned);
        break;
      case K::trial: {
        ++done_;
        const double eta = done_ > 0 ? elapsed / static_cast<double>(done_) * static_cast<double>(total_ - done_) : 0;
        std::snprintf(line, sizeof line, "%s: [%lld/%lld] %s trial %d/%d %s %s: %.1f s simulated | %s elapsed, ETA %s",
                      prefix_.c_str(), done_, total_, p.participant.c_str(), p.position, p.planned, p.task.c_str(),
                      p.condition.c_str(), p.simulated_s, clock_text(elapsed).c_str(),
                      clock_text(std::max(0.0, eta)).c_str());
        std::fprintf(stderr, "%s\n", line);
        break;
      }
      case K::finished:
        std::fprintf(stderr, "%s: %s finished\n", prefix_.c_str(), p.participant.c_str());
        break;
      case K::failed:
        if (!g_stop) std::fprintf(stderr, "%s: %s failed: %s\n", prefix_.c_str(), p.participant.c_str(), p.message.c_str());
        break;
      case K::elsewhere:
        std::fprintf(stderr, "%s: %s skipped: %s\n", prefix_.c_str(), p.participant.c_str(), p.message.c_str());
        break;
    }
  }

 private:
  std::string prefix_;
  long long total_ = 0, done_ = 0;
  std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
};

struct SimulateArgs {
  std::string protocol, db;
  sim::StudyRun run;
  bool json = false;
};

void run_simulate(const SimulateArgs& a) {
  auto p = protocol::load_protocol(a.protocol);
  if (!p) {
    std::cerr << "dtlab simulate: " << p.error().to_string() << "\n";
    throw CLI::RuntimeError(kExitInvalid);
  }
  sim::StudyResult r;
  sim::StudyRun run = a.run;
  run.db = a.db;
  const int rc = simulate_with_progress(p.value(), run, "dtlab simulate", r);
  if (rc != kExitOk && rc != kExitInterrupted && rc != kExitFailure) throw CLI::RuntimeError(rc);
  auto reader = store::StudyReader::open(a.db, session::read_options());
  const protocol::Factor* rendering = protocol::factor_with_role(*p, protocol::FactorRole::rendering);
  auto summary = reader ? sim::summarize(*reader, rendering ? rendering->name : "") : Result<sim::Summary>(reader.error());
  if (a.json) {
    nlohmann::json j{{"protocol", p->id},          {"database", store::display_name(a.db)},
                     {"participants", run.participants}, {"finished", r.finished_total},
                     {"skipped_finished", r.already_finished}, {"resumed", r.resumed},
                     {"run_elsewhere", r.elsewhere},
                     {"trials_run", r.trials_run}, {"failed", r.errors},
                     {"interrupted", r.stopped},   {"wall_s", r.wall_s}};
    if (summary) {
      nlohmann::json cells = nlohmann::json::array();
      for (const auto& c : summary->cells)
        cells.push_back({{"task", c.task}, {"rendering", c.rendering}, {"trials", c.trials},
                         {"time_mean_s", c.time_mean}, {"time_sd_s", c.time_sd}, {"measure", c.measure},
                         {"measure_mean", c.measure_mean}});
      j["summary"] = cells;
    }
    std::cout << j.dump(2) << "\n";
  } else {
    std::cout << "dtlab simulate: " << p->id << " -> " << store::display_name(a.db) << ": " << r.finished_total << " of "
              << count(run.participants, "participant") << " finished (" << r.already_finished << " before this run, "
              << r.resumed << " resumed";
    if (r.elsewhere > 0) std::cout << ", " << r.elsewhere << " run by another process";
    std::cout << "); " << count(r.trials_run, "trial") << " in " << clock_text(r.wall_s) << "\n";
    if (summary) std::cout << sim::format_summary(summary.value());
  }
  if (rc != kExitOk) throw CLI::RuntimeError(rc);
}

}  // namespace

int simulate_with_progress(const protocol::Protocol& p, sim::StudyRun run, const std::string& prefix,
                           sim::StudyResult& result) {
  run.make_context = [](int w, int h) -> Result<std::shared_ptr<void>> {
    // Agents look at small frames (160 x 120): llvmpipe's rasterizer threads cost more in hand-offs
    // than they save there (2 participants in one process: 19.1 -> 10.2 s, the same pixels), and
    // the worker processes (--jobs) use the cores.
    auto ctx = platform::create_headless(w, h, 0);
    if (!ctx) return ctx.error();
    return std::shared_ptr<void>(std::move(ctx.value()));
  };
  run.on_checked = [&](const std::vector<Diagnostic>& problems) {
    for (const auto& d : problems) std::cerr << prefix << ": " << d.to_string() << "\n";
  };
  std::optional<ProgressPrinter> printer;
  run.on_roster = [&](const sim::Roster&, long long planned_trials) { printer.emplace(prefix, planned_trials); };
  run.on_progress = [&](const sim::Progress& pr) { (*printer)(pr); };
  g_stop = 0;
  run.stop = &g_stop;
  auto old_int = std::signal(SIGINT, on_interrupt);
  auto old_term = std::signal(SIGTERM, on_interrupt);
  result = sim::simulate_study(p, run);
  std::signal(SIGINT, old_int);
  std::signal(SIGTERM, old_term);
  if (result.protocol_invalid) return kExitInvalid;
  if (result.enroll_error) {
    std::cerr << prefix << ": " << result.enroll_error->to_string() << "\n";
    return exit_code(*result.enroll_error);
  }
  if (result.run_error) {
    std::cerr << prefix << ": " << result.run_error->to_string() << "\n";
    return kExitFailure;
  }
  for (const std::string& e : result.errors) std::cerr << prefix << ": " << e << "\n";
  if (result.stopped) {
    std::cerr << prefix << ": interrupted; every recorded trial is saved in " << store::display_name(run.db)
              << ". Run the same command again to resume.\n";
    return kExitInterrupted;
  }
  if (result.failed == 0) return kExitOk;
  return result.failed == result.invalid ? kExitInvalid : kExitFailure;
}

void add_simulate_command(CLI::App& root) {
  auto a = std::make_shared<SimulateArgs>();
  auto* cmd = root.add_subcommand(
      "simulate",
      "Run simulated participants through a protocol, headless, into a study database. Each one looks at every "
      "trial through the real renderer (the trial's own method) and answers from what it saw; completion times are "
      "simulated seconds from the model in docs/sim.md. An existing database is continued: running sessions resume, "
      "finished ones are skipped, participants sim-001 .. sim-N are added as needed. Ctrl-C stops after the trials "
      "in progress; rerun to resume");
  cmd->footer(
      "Before anything runs, the protocol is checked as `dtlab validate` checks it, at this --width x --height too\n"
      "(errors as FILE:LINE:COLUMN: error: FIELD: MESSAGE; nothing is created).\n"
      "Progress on stderr (one line per recorded trial, with an ETA); a per-task summary on stdout.\n"
      "Exit status: 0 all finished, 1 invalid protocol (also when every failed session failed on it) or database,\n"
      "2 bad command line, 3 environment (GL, database, fork) or a participant failed otherwise, 130 interrupted\n"
      "(rerun to resume).");
  cmd->add_option("protocol", a->protocol, "Protocol file (TOML)")->required()->check(CLI::ExistingFile);
  cmd->add_option("--participants", a->run.participants, "Simulated participants sim-001 .. sim-N")
      ->required()
      ->check(CLI::Range(1, 9999));
  cmd->add_option("--db", a->db, std::string(kDatabaseHelp) + "; created if missing")->required();
  cmd->add_option("--seed", a->run.seed, "Seed of the simulated participants' traits and choices (plans and scenes "
                                         "come from the protocol's master seed)")
      ->capture_default_str();
  cmd->add_option("--width", a->run.width, "Width of every view the agents look at, pixels")
      ->check(CLI::Range(session::kMinViewportSide, session::kMaxViewportSide))
      ->capture_default_str();
  cmd->add_option("--height", a->run.height, "Height of every view, pixels")
      ->check(CLI::Range(session::kMinViewportSide, session::kMaxViewportSide))
      ->capture_default_str();
  cmd->add_option("--jobs", a->run.jobs, "Worker processes (each its own GL context and database connection)")
      ->check(CLI::Range(1, 64))
      ->capture_default_str();
  cmd->add_flag("--allow-protocol-change", a->run.allow_protocol_change,
                "Continue a database recorded under another version of the protocol (its SHA-256 differs): the new "
                "text is recorded as a new study row beside the old; without this flag such a database is refused "
                "(exit 1) and left untouched");
  cmd->add_flag("--json", a->json,
                "Print {protocol, database, participants, finished, skipped_finished, resumed, trials_run, failed, "
                "interrupted, wall_s, summary} as JSON on stdout");
  cmd->callback([a] { run_simulate(*a); });
}

}  // namespace dtlab::app

// The dtlab subcommands. Each add_*_command() registers one subcommand, its
// options and its callback on the root CLI11 app; call each once, before
// parsing. A callback reports failure by throwing CLI::RuntimeError(exit_code)
// after printing its message to stderr; it never calls exit() itself.
#pragma once
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "study/common/error.h"

namespace CLI {
class App;
class Validator;
}
namespace dtlab::protocol {
struct Protocol;
}
namespace dtlab::sim {
struct StudyRun;
struct StudyResult;
}

namespace dtlab::app {

// Exit codes shared by every subcommand.
inline constexpr int kExitOk = 0;
inline constexpr int kExitInvalid = 1;  // the input is wrong (protocol, CSV, database); message on stderr
inline constexpr int kExitUsage = 2;    // the command line is wrong (CLI11's own exit code for parse errors)
inline constexpr int kExitFailure = 3;  // the environment failed (I/O, GL context, SQLite)
inline constexpr int kExitInterrupted = 130;  // Ctrl-C: stopped after the work in progress; rerun to resume

// The exit code of a failure, from its kind (the one place that maps kinds to codes): the
// input's fault (invalid, not found, conflicting with what is stored) 1; the environment's
// (I/O, SQLite, GL, a lock held past its timeout, a session another process runs) and bugs 3.
inline int exit_code(const Error& e) {
  switch (e.kind) {
    case ErrorKind::invalid_input:
    case ErrorKind::not_found:
    case ErrorKind::conflict: return kExitInvalid;
    case ErrorKind::environment:
    case ErrorKind::busy:
    case ErrorKind::internal: return kExitFailure;
  }
  return kExitFailure;
}

// How a subcommand's callback fails: "dtlab COMMAND: error: MESSAGE" on stderr, then
// CLI::RuntimeError(code), which main() turns into the exit status.
[[noreturn]] void fail(std::string_view command, int code, const std::string& message);
// The same for an Error: its text (file:line: field: message), with the exit code of its kind.
[[noreturn]] void fail(std::string_view command, const Error& e);
// The value of `r`, or fail(command, r.error()).
template <class T>
T value_or_fail(std::string_view command, Result<T> r) {
  if (!r) fail(command, r.error());
  return std::move(r).value();
}

void add_version_command(CLI::App& root);  // `dtlab version`: version and commit, --json
void add_render_command(CLI::App& root);   // `dtlab render ... --method M --out FILE.png`: one frame headless, --json
void add_bench_command(CLI::App& root);    // `dtlab bench`: frame-time ratios and image error per method, --json
void add_icons_command(CLI::App& root);    // `dtlab icons --out DIR`: "find this" icons of the WALKTHROUGH kinds + contact sheet, --json
void add_scene_command(CLI::App& root);  // `dtlab scene --scene K --task T --seed S`: one generated scene, --json, --obj
void add_stats_command(CLI::App& root);  // `dtlab stats anova|rm-anova|friedman|wilcoxon|lmm`: statistics on a CSV, --json
void add_stats_lmm_command(CLI::App& stats);  // `dtlab stats lmm` (cmd_stats_lmm.cpp), added by add_stats_command
void add_validate_command(CLI::App& root);  // `dtlab validate PROTOCOL`: every error with file:line:field, --json
void add_plan_command(CLI::App& root);  // `dtlab plan PROTOCOL --index K`: one participant's trials, --json
void add_export_command(CLI::App& root);  // `dtlab export DB --csv FILE`: one tidy CSV row per recorded trial, --json
void add_exclude_command(CLI::App& root);  // `dtlab exclude|include DB --participant ID [--trial N] --reason R`
void add_withdraw_command(CLI::App& root);  // `dtlab withdraw DB --participant ID [--reason R]`: a withdrawal of consent
void add_copy_command(CLI::App& root);  // `dtlab copy SRC DST`: a whole study between databases (file, server), or a merge
void add_analyze_command(CLI::App& root);  // `dtlab analyze DB --out DIR`: study report (report.md, index.html, JSON, CSV)
void add_power_command(CLI::App& root);  // `dtlab power DB --participants 8,12,16`: power planning from a pilot, --json
void add_simulate_command(CLI::App& root);  // `dtlab simulate PROTOCOL --participants N --db FILE`: simulated participants, headless
void add_demo_command(CLI::App& root);  // `dtlab demo [--out DIR]`: the reference study simulated end to end, then its report
void add_run_command(CLI::App& root);  // `dtlab run PROTOCOL --db FILE`: a person's session in a window (app/run)
void add_replay_command(CLI::App& root);  // `dtlab replay DB --participant ID --trial N --out DIR`: what they saw

// A CLI11 check for an unsigned 64-bit integer written as digits only (cmd_render.cpp): CLI11
// itself turns "-1" into 2^64 - 1. Used by `render --seed` and `bench --seed`.
CLI::Validator unsigned_integer();

// The process's side of a simulated study, shared by `dtlab simulate` and `dtlab demo`
// (cmd_simulate.cpp): runs sim::simulate_study (study/sim/simulate.h) on `run` with headless GL
// contexts, Ctrl-C as its stop flag and progress on stderr (lines start with `prefix`), prints the
// protocol's diagnostics and any error there; returns the exit code.
int simulate_with_progress(const protocol::Protocol& p, sim::StudyRun run, const std::string& prefix,
                           sim::StudyResult& result);
}  // namespace dtlab::app

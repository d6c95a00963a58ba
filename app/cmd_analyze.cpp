// `dtlab analyze DB --out DIR [--revision all|latest|N] [--with-excluded]
// [--no-paths] [--json]`: the study report (analysis/report, docs/report.md):
// report.md, a self-contained index.html with inline SVG plots, report.json,
// trials.csv, per-analysis CSVs and the walked-path figures (study/replay) in DIR. Never modifies the database. Progress goes to
// stderr; exit 1 for a database that cannot be analysed, 3 for an
// environment failure (I/O, database, gnuplot).
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <iostream>
#include <memory>

#include "analysis/report/report.h"
#include "app/commands.h"
#include "app/database_arg.h"
#include "study/common/text.h"
#include "app/report_paths.h"

namespace dtlab::app {

namespace {

struct AnalyzeArgs {
  std::string db;
  std::string out;
  std::string gnuplot;
  double frame_threshold_ms = 1000.0 / 30;
  std::string revision = "all";
  bool with_excluded = false;
  bool no_paths = false;
  bool log_time = false;
  bool json = false;
  bool quiet = false;
};

void run_analyze(const AnalyzeArgs& a) {
  report::ReportOptions options;
  options.gnuplot = a.gnuplot;
  options.frame_threshold_ms = a.frame_threshold_ms;
  options.revision = a.revision;
  options.with_excluded = a.with_excluded;
  if (!a.no_paths) options.path_figure = replay_path_figures();
  options.log_time = a.log_time;
  auto progress = [&a](const std::string& step) {
    if (!a.quiet) std::cerr << "dtlab analyze: " << step << "\n";
  };
  auto sum = report::write_report(a.db, a.out, progress, options);
  if (!sum) {
    std::cerr << "dtlab analyze: " << sum.error().to_string() << "\n";
    throw CLI::RuntimeError(exit_code(sum.error()));
  }
  if (a.json) {
    nlohmann::json j{{"database", store::display_name(a.db)},         {"out", a.out},          {"files", sum->files},
                     {"participants", sum->participants}, {"trials", sum->trials}, {"tests", sum->tests},
                     {"excluded_trials", sum->excluded_trials}, {"revisions", sum->revisions},
                     {"simulated", sum->simulated}, {"warnings", sum->warnings}};
    std::cout << j.dump(2) << "\n";
  } else {
    std::cerr << "dtlab analyze: wrote " << a.out << "/index.html, report.md and report.tex (" << count(sum->participants, "participant")
              << ", " << count(sum->trials, "trial") << ", " << count(sum->tests, "test")
              << (sum->excluded_trials ? ", " + count(sum->excluded_trials, "excluded trial") +
                                             (a.with_excluded ? " kept" : " left out")
                                       : std::string())
              << (sum->simulated ? ", simulated participants" : "") << ")\n";
    for (const auto& w : sum->warnings) std::cerr << "dtlab analyze: warning: " << w << "\n";
  }
}

}  // namespace

void add_analyze_command(CLI::App& root) {
  auto args = std::make_shared<AnalyzeArgs>();
  auto* cmd = root.add_subcommand(
      "analyze",
      "Write the study report of a study database into DIR: report.md, a self-contained index.html that prints "
      "whole on A4/Letter, and report.tex (LaTeX, booktabs): RM ANOVA in APA style with follow-ups, rank tests and "
      "Shapiro-Wilk per task and overall, accuracy, speed-accuracy, questionnaire, position effects, frame-time "
      "audit (warns when render cost may confound completion time), power for the next study, published values "
      "beside ours only when the protocol declares them ([reference_results]); figures as SVG, PNG and PDF "
      "(gnuplot with cairo); report.json with every number, trials.csv (as dtlab export), per-analysis CSVs and, "
      "where camera poses were recorded, each participant's walked paths per WALKTHROUGH task (paths/*.svg). "
      "Exit 1: not a dtlab database or nothing to analyse; "
      "3: I/O, database or gnuplot failure");
  cmd->add_option("database", args->db, std::string(kDatabaseHelp) + ", written by dtlab run or dtlab simulate")
      ->required()
      ->check(existing_database());
  cmd->add_option("--out", args->out, "Output directory (created if missing; files of the same names are replaced)")
      ->required();
  cmd->add_option("--gnuplot", args->gnuplot, "gnuplot executable (default: $DTLAB_GNUPLOT, else gnuplot on PATH)");
  cmd->add_option("--frame-threshold-ms", args->frame_threshold_ms,
                  "Frame-time audit: a trial is slow when its 95th-percentile frame time exceeds this, and a condition "
                  "whose median frame rate is below 1000 / this is warned about (default 33.3 = 30 fps)")
      ->check(CLI::PositiveNumber);
  cmd->add_option("--revision", args->revision,
                  "Design revision to analyse when the protocol's design was changed mid-study "
                  "(--allow-protocol-change): all (each its own report in DIR/revision-N/), latest, or N")
      ->capture_default_str();
  cmd->add_flag("--with-excluded", args->with_excluded,
                "Keep excluded participants and trials (dtlab exclude) in the analysis; by default they are left out "
                "and listed with their reasons");
  cmd->add_flag("--no-paths", args->no_paths,
                "Do not draw the walked-path figures (each regenerates the trials' buildings: a few seconds for a "
                "large study)");
  cmd->add_flag("--log-time", args->log_time,
                "Also analyse log completion times (per participant and condition, the mean of the trials' log "
                "seconds: geometric means, ratios between levels), reported beside the analysis in seconds, never "
                "instead of it");
  cmd->add_flag("--json", args->json,
                "Print {database, out, files, participants, trials, tests, excluded_trials, revisions, simulated, "
                "warnings}");
  cmd->add_flag("--quiet", args->quiet, "No progress lines on stderr");
  cmd->callback([args] { run_analyze(*args); });
}

}  // namespace dtlab::app

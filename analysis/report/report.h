// The study report (`dtlab analyze DB --out DIR`, docs/report.md): from a study
// database to the results section of a paper. Reads the study through the
// store's StudyReader (one snapshot): the protocol recorded in the database,
// the recorded trials, the questionnaire and the lab's exclusions; runs the
// statistics of analysis/stats (RM ANOVA, Friedman, paired tests, Holm) per
// task and overall, and writes report.md, a self-contained index.html (inline
// CSS and SVG, no script, no external reference), report.json (every number
// the tables show), the SVG plots (gnuplot, run as a subprocess), trials.csv
// and per-analysis CSVs; with a path-figure function, the walked path of each
// participant's WALKTHROUGH trials per task (paths/*.svg). A database holding several design revisions gets one
// report per revision (each says so at the top). Guarantees: the database is
// never modified; every failure is an Error of a kind (never an abort).
#pragma once
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "study/common/error.h"
#include "study/store/read.h"

namespace dtlab::report {

// A walked-path figure as drawn: the SVG ("" when there is nothing to draw) and the trials left
// out of it, each with why (e.g. "trial 7: this build generates another scene").
struct PathDrawing {
  std::string svg;
  std::vector<std::string> left_out;
};
// Draws the walked paths of a participant's recorded trials `positions` (all of one WALKTHROUGH task).
using PathFigureFn = std::function<Result<PathDrawing>(store::StudyReader& reader, const std::string& participant,
                                                       const std::vector<int>& positions, const std::string& title)>;

struct ReportOptions {
  std::string gnuplot;                       // gnuplot executable; "" = $DTLAB_GNUPLOT, else "gnuplot" on PATH
  double frame_threshold_ms = 1000.0 / 30;   // frame-time audit: a trial is "slow" when its p95 frame time exceeds this
  std::uint64_t seed = 1;                    // seed of Monte Carlo exact p-values (Friedman with many blocks)
  std::string revision = "all";              // design revision(s): "all" (each its own report), "latest", or "N"
  bool with_excluded = false;                // keep excluded participants and trials in the analysis
  // Draws path figures (paths/*.svg, linked from a "Walked paths" section); empty: none. The report
  // never links rendering, so the app passes one built on study/replay's trials_path_svg.
  PathFigureFn path_figure;
  bool log_time = false;                     // also analyse log completion times, beside the seconds
};

struct ReportSummary {
  std::string out_dir;
  std::vector<std::string> files;     // paths written, relative to out_dir
  int participants = 0;               // participants with at least one analysed trial
  long long trials = 0;               // analysed (recorded, non-practice, not excluded) trials
  long long excluded_trials = 0;      // recorded trials left out because they are excluded
  int tests = 0;                      // statistical tests reported
  bool simulated = false;             // every participant is marked simulated in the database
  std::vector<int> revisions;         // the design revisions analysed (one report each)
  std::vector<std::string> warnings;  // also shown in the report
};

// One line of progress for a human ("reading the database", "completion time"); may be empty.
using ProgressFn = std::function<void(const std::string& step)>;

// Analyses the study `reader` reads and writes the report into out_dir
// (created if missing; files of the same names are replaced whole). With
// several design revisions and revision "all", each goes to
// out_dir/revision-N/ and out_dir/index.html lists them. A protocol that does
// not parse or no recorded trial to analyse is an input Error; an unknown
// revision not_found; an unwritable out_dir or a missing or failing gnuplot an
// environment Error.
Result<ReportSummary> write_report(store::StudyReader& reader, const std::string& out_dir,
                                   const ProgressFn& progress = {}, const ReportOptions& options = {});
// The same for the database at db_path, opened read-only (a file that is not a dtlab database is refused).
Result<ReportSummary> write_report(const std::string& db_path, const std::string& out_dir,
                                   const ProgressFn& progress = {}, const ReportOptions& options = {});

}  // namespace dtlab::report

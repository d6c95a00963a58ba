// The study report (`dtlab analyze DB --out DIR`, docs/report.md): from a study
// database to the results section of a paper. Reads the protocol recorded in
// the database and the tidy trial table, runs the statistics of analysis/stats
// (RM ANOVA, Friedman, paired tests, Holm) per task and overall, and writes
// report.md, a self-contained index.html (inline CSS and SVG, no script, no
// external reference), report.json (every number the tables show), the SVG
// plots (gnuplot, run as a subprocess), trials.csv and per-analysis CSVs.
// Guarantees: the database is opened read-only and never modified; every
// failure is an Error (never an abort), and is_environment_error() tells the
// environment's faults (I/O, SQLite, gnuplot) from the input's.
#pragma once
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "study/common/error.h"

namespace dtlab::report {

struct ReportOptions {
  std::string gnuplot;                       // gnuplot executable; "" = $DTLAB_GNUPLOT, else "gnuplot" on PATH
  double frame_threshold_ms = 1000.0 / 30;   // frame-time audit: a trial is "slow" when its p95 frame time exceeds this
  std::uint64_t seed = 1;                    // seed of Monte Carlo exact p-values (Friedman with many blocks)
};

struct ReportSummary {
  std::string out_dir;
  std::vector<std::string> files;     // paths written, relative to out_dir
  int participants = 0;               // participants with at least one analysed trial
  long long trials = 0;               // analysed (recorded, non-practice) trials
  int tests = 0;                      // statistical tests reported
  bool simulated = false;             // every participant is marked simulated in the database
  std::vector<std::string> warnings;  // also shown in the report
};

// One line of progress for a human ("reading the database", "completion time"); may be empty.
using ProgressFn = std::function<void(const std::string& step)>;

// Analyses the database at db_path and writes the report into out_dir
// (created if missing; files of the same names are replaced whole). A file
// that is not a dtlab database, a protocol that does not parse, or a database
// without any recorded trial is an input Error; an unwritable out_dir, a
// failing SQLite read or a missing/failing gnuplot an environment Error.
Result<ReportSummary> write_report(const std::string& db_path, const std::string& out_dir,
                                   const ProgressFn& progress = {}, const ReportOptions& options = {});

// True if `e` is the environment's fault (exit code 3), not the input's (exit code 1).
bool is_environment_error(const Error& e);

}  // namespace dtlab::report

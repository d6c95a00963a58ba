// What `dtlab stats` reads before any test runs: the CSV, the row selection
// (--where, practice rows, rows marked excluded: analysis/stats/select.h), the
// reduction of repeated subject x cell rows (--aggregate) and the column
// roles. Guarantees: every failure is printed as "dtlab stats: file:line:
// column: what was expected" and ends the command with its exit code (1 bad
// CSV or data, 2 bad command line, 3 unreadable file). Never writes a file.
#pragma once
#include <string>
#include <vector>

#include "analysis/stats/long_data.h"
#include "analysis/stats/select.h"

namespace dtlab::app {

// The options every `dtlab stats` test shares to read its table.
struct StatsInput {
  std::string data, dv, subject, aggregate = "none";
  std::vector<std::string> within, between, where;
  bool wide = false;
  bool exclude_practice = false, include_practice = false, with_excluded = false;
};

// The table a test sees and what the row selection did (for the output).
struct Loaded {
  stats::LongData data;
  stats::SelectionReport selection;
};

// Prints "dtlab stats: MESSAGE" on stderr and ends the command with `code`.
[[noreturn]] void stats_fail(int code, const std::string& message);

// The CSV after the row selection (for tests that read more columns than LongData holds).
struct SelectedTable {
  stats::CsvTable table;
  stats::SelectionReport selection;
};

// Reads the CSV and selects rows (--where, practice, excluded); on failure
// prints file:line:column and ends the command.
SelectedTable load_selected_table(const StatsInput& in);

// Reads the CSV, selects rows and assigns the roles (groups_design: one-way
// ANOVA, no subjects); on failure prints file:line:column and ends the command.
Loaded load_stats_input(const StatsInput& in, bool groups_design);

}  // namespace dtlab::app

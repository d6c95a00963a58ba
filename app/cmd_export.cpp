// `dtlab export DB --csv FILE [--json]`: the study database as a tidy CSV,
// one row per recorded trial (columns in README.md, "Study database and
// export"; excluded trials are kept, with the reason in `excluded`; the
// trials of participants who withdrew their consent are left out, and the
// command says how many). Never
// modifies the database (reads work on read-only media); FILE is written
// whole or left untouched.
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <system_error>

#include "app/commands.h"
#include "app/database_arg.h"
#include "study/common/file.h"
#include "study/session/mapping.h"
#include "study/common/text.h"
#include "study/store/export.h"
#include "study/store/read.h"

namespace dtlab::app {

namespace {

struct ExportArgs {
  std::string db;
  std::string csv;
  bool json = false;
};

void run_export(const ExportArgs& a) {
  auto reader = store::StudyReader::open(a.db, session::read_options());
  if (!reader) {
    std::cerr << "dtlab export: " << reader.error().to_string() << "\n";
    throw CLI::RuntimeError(exit_code(reader.error()));
  }
  store::ExportSummary sum;
  Status st = write_file_atomically(a.csv, [&](std::ostream& out) -> Status {
    auto s = store::export_trials_csv(*reader, out);
    if (!s) return s.error();
    sum = std::move(s.value());
    return {};
  });
  if (!st) {
    std::cerr << "dtlab export: " << st.error().to_string() << "\n";
    throw CLI::RuntimeError(exit_code(st.error()));
  }
  if (a.json) {
    nlohmann::json j{{"database", store::display_name(a.db)}, {"csv", a.csv}, {"rows", sum.rows}, {"excluded_rows", sum.excluded},
                     {"withdrawn_participants", sum.withdrawn}, {"withdrawn_rows_left_out", sum.withdrawn_rows},
                     {"columns", sum.columns}};
    std::cout << j.dump(2) << "\n";
  } else {
    std::cerr << "dtlab export: wrote " << count(sum.rows, "trial") << " ("
              << count(static_cast<long long>(sum.columns.size()), "column") << ") to " << a.csv;
    if (sum.excluded > 0)
      std::cerr << "; " << sum.excluded << " of them excluded (their `excluded` column holds the reason)";
    if (sum.withdrawn > 0)
      std::cerr << "; " << count(sum.withdrawn_rows, "trial") << " of " << count(sum.withdrawn, "participant")
                << " who withdrew their consent left out";
    std::cerr << "\n";
  }
}

}  // namespace

void add_export_command(CLI::App& root) {
  auto args = std::make_shared<ExportArgs>();
  auto* cmd = root.add_subcommand(
      "export",
      "Write a study database as a tidy CSV: one row per recorded trial (participant, session, order row, "
      "position, block, one column per factor, task, trial seed, scene hash, answer, truth, scores, completion "
      "time in seconds, ..., design revision, `excluded` with the reason of an exclusion, and one demo_<field> "
      "column per demographic field). Participants who withdrew their consent are left out (the summary counts "
      "them). Readable by R's read.csv and pandas.read_csv as is; NA marks missing values");
  cmd->add_option("database", args->db, std::string(kDatabaseHelp) + ", written by dtlab run or dtlab simulate")
      ->required()
      ->check(existing_database());
  cmd->add_option("--csv", args->csv, "Output CSV file (replaced as a whole)")->required();
  cmd->add_flag("--json", args->json, "Print {database, csv, rows, excluded_rows, withdrawn_participants, withdrawn_rows_left_out, "
                "columns} as JSON on stdout");
  cmd->callback([args] { run_export(*args); });
}

}  // namespace dtlab::app

// `dtlab export DB --csv FILE [--json]`: the study database as a tidy CSV,
// one row per recorded trial (columns in README.md, "Study database and
// export"). Never modifies the database; writes FILE through a temporary
// file renamed into place, so FILE is either the whole table or untouched.
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <system_error>

#include "app/commands.h"
#include "study/common/text.h"
#include "study/store/export.h"
#include "study/store/store.h"

namespace dtlab::app {

namespace {

struct ExportArgs {
  std::string db;
  std::string csv;
  bool json = false;
};

void run_export(const ExportArgs& a) {
  namespace fs = std::filesystem;
  const fs::path target(a.csv);
  const fs::path tmp = target.string() + ".tmp";
  Result<store::ExportSummary> sum = Error{};
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (!out) {
      std::cerr << "dtlab export: " << tmp.string() << ": cannot write the CSV file\n";
      throw CLI::RuntimeError(kExitFailure);
    }
    sum = store::export_trials_csv(a.db, out);
    out.flush();
    if (sum && !out) sum = Error{tmp.string(), 0, 0, "", "writing the CSV file failed"};
  }
  std::error_code ec;
  if (!sum) {
    fs::remove(tmp, ec);
    std::cerr << "dtlab export: " << sum.error().to_string() << "\n";
    throw CLI::RuntimeError(store::is_environment_error(sum.error()) ? kExitFailure : kExitInvalid);
  }
  fs::rename(tmp, target, ec);
  if (ec) {
    fs::remove(tmp, ec);
    std::cerr << "dtlab export: " << target.string() << ": cannot move the CSV into place: " << ec.message() << "\n";
    throw CLI::RuntimeError(kExitFailure);
  }
  if (a.json) {
    nlohmann::json j{{"database", a.db}, {"csv", a.csv}, {"rows", sum->rows}, {"columns", sum->columns}};
    std::cout << j.dump(2) << "\n";
  } else {
    std::cerr << "dtlab export: wrote " << count(sum->rows, "trial") << " (" << count(static_cast<long long>(sum->columns.size()), "column") << ") to "
              << a.csv << "\n";
  }
}

}  // namespace

void add_export_command(CLI::App& root) {
  auto args = std::make_shared<ExportArgs>();
  auto* cmd = root.add_subcommand(
      "export",
      "Write a study database as a tidy CSV: one row per recorded trial (participant, session, order row, "
      "position, block, one column per factor, task, trial seed, scene hash, answer, truth, scores, completion "
      "time in seconds, ...). Readable by R's read.csv and pandas.read_csv as is; NA marks missing values");
  cmd->add_option("database", args->db, "Study database (SQLite) written by dtlab run or dtlab simulate")
      ->required()
      ->check(CLI::ExistingFile);
  cmd->add_option("--csv", args->csv, "Output CSV file (replaced as a whole)")->required();
  cmd->add_flag("--json", args->json, "Print {database, csv, rows, columns} as JSON on stdout");
  cmd->callback([args] { run_export(*args); });
}

}  // namespace dtlab::app

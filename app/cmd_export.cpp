// `dtlab export DB [--csv FILE] [--questionnaires FILE] [--json]`: the study
// database as tidy CSVs: one row per recorded trial (columns in README.md,
// "Study database and export"; excluded trials are kept, with the reason in
// `excluded`), and one row per questionnaire answer with the instruments'
// scores (docs/questionnaires.md, "Export"). Participants who withdrew their
// consent are left out of both, and the command says how many. Never modifies
// the database (reads work on read-only media); each FILE is written whole or
// left untouched.
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
#include "study/session/questionnaire_export.h"
#include "study/common/text.h"
#include "study/store/export.h"
#include "study/store/read.h"

namespace dtlab::app {

namespace {

struct ExportArgs {
  std::string db;
  std::string csv;
  std::string questionnaires;
  bool json = false;
};

nlohmann::json export_questionnaires(store::StudyReader& reader, const ExportArgs& a) {
  session::QuestionnaireExportSummary sum;
  Status st = write_file_atomically(a.questionnaires, [&](std::ostream& out) -> Status {
    auto s = session::export_questionnaire_csv(reader, out);
    if (!s) return s.error();
    sum = std::move(s.value());
    return {};
  });
  if (!st) fail("export", st.error());
  if (!a.json)
    std::cerr << "dtlab export: wrote " << count(sum.answers, "questionnaire answer") << " and "
              << count(sum.scores, "instrument score") << " (" << count(static_cast<long long>(sum.columns.size()), "column")
              << ") to " << a.questionnaires << "\n";
  return {{"file", a.questionnaires}, {"rows", sum.rows}, {"answers", sum.answers}, {"scores", sum.scores},
          {"columns", sum.columns}};
}

void run_export(const ExportArgs& a) {
  if (a.csv.empty() && a.questionnaires.empty()) {
    std::cerr << "dtlab export: nothing to write; give --csv FILE, --questionnaires FILE, or both\n";
    throw CLI::RuntimeError(2);
  }
  auto reader = store::StudyReader::open(a.db, session::read_options());
  if (!reader) fail("export", reader.error());
  nlohmann::json j{{"database", store::display_name(a.db)}};
  if (!a.questionnaires.empty()) j["questionnaires"] = export_questionnaires(reader.value(), a);
  if (a.csv.empty()) {
    if (a.json) std::cout << j.dump(2) << "\n";
    return;
  }
  store::ExportSummary sum;
  Status st = write_file_atomically(a.csv, [&](std::ostream& out) -> Status {
    auto s = store::export_trials_csv(*reader, out);
    if (!s) return s.error();
    sum = std::move(s.value());
    return {};
  });
  if (!st) fail("export", st.error());
  if (a.json) {
    j.update({{"csv", a.csv}, {"rows", sum.rows}, {"excluded_rows", sum.excluded},
              {"withdrawn_participants", sum.withdrawn}, {"withdrawn_rows_left_out", sum.withdrawn_rows},
              {"columns", sum.columns}});
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
      "Write a study database as tidy CSVs: --csv, one row per recorded trial (participant, session, order row, "
      "position, block, one column per factor, task, trial seed, scene hash, answer, truth, scores, completion "
      "time in seconds, ..., design revision, `excluded` with the reason of an exclusion, and one demo_<field> "
      "column per demographic field); --questionnaires, one row per participant x questionnaire item x occasion "
      "(when it was asked, the block, task and factor levels it followed, value, text, label) with each "
      "instrument's scores (NASA-TLX, SUS, SSQ) as rows of type \"score\". Participants who withdrew their "
      "consent are left out of both (the summary counts them). Readable by R's read.csv and pandas.read_csv as "
      "is; NA marks missing values");
  cmd->add_option("database", args->db, std::string(kDatabaseHelp) + ", written by dtlab run or dtlab simulate")
      ->required()
      ->check(existing_database());
  cmd->add_option("--csv", args->csv, "Output CSV file of the trials (replaced as a whole)");
  cmd->add_option("--questionnaires", args->questionnaires,
                  "Output CSV file of the questionnaire answers and instrument scores (replaced as a whole)");
  cmd->add_flag("--json", args->json,
                "Print {database, csv, rows, excluded_rows, withdrawn_participants, withdrawn_rows_left_out, columns, "
                "questionnaires: {file, rows, answers, scores, columns}} as JSON on stdout (the keys of what was "
                "written)");
  cmd->callback([args] { run_export(*args); });
}

}  // namespace dtlab::app

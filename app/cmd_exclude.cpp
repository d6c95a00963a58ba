// `dtlab exclude DB --participant ID [--trial N] --reason TEXT [--by NAME]`
// and `dtlab include ...`: the lab's decision to leave a participant (or one
// of their trials) out of the analysis, or to take that back. Each call
// appends one row with who, why and when (docs/store.md, "Exclusions and
// notes"); nothing recorded is changed or deleted. The analysis and `dtlab
// stats` on the export leave excluded data out by default and list every
// exclusion with its reason. Exit 0 done, 1 unknown participant or trial or
// no reason, 2 bad command line, 3 database or I/O failure.
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <iostream>
#include <memory>
#include <optional>

#include "app/commands.h"
#include "app/database_arg.h"
#include "study/session/mapping.h"
#include "study/store/store.h"

namespace dtlab::app {

namespace {

struct DecisionArgs {
  std::string db, participant, reason, by;
  std::optional<int> trial;
  bool json = false;
};

void run_decision(const DecisionArgs& a, bool exclude) {
  const char* name = exclude ? "exclude" : "include";
  auto store = store::Store::open_existing(a.db, session::open_options());
  if (!store) {
    std::cerr << "dtlab " << name << ": " << store.error().to_string() << "\n";
    throw CLI::RuntimeError(exit_code(store.error()));
  }
  const std::string by = a.by.empty() ? default_experimenter() : a.by;
  Status st = exclude ? store->exclude(a.participant, a.trial, a.reason, by)
                      : store->include(a.participant, a.trial, a.reason, by);
  if (!st) {
    std::cerr << "dtlab " << name << ": " << st.error().to_string() << "\n";
    throw CLI::RuntimeError(exit_code(st.error()));
  }
  const std::string what = "participant " + a.participant + (a.trial ? " trial " + std::to_string(*a.trial) : "");
  if (a.json) {
    nlohmann::json j{{"database", store::display_name(a.db)},   {"participant", a.participant},
                     {"trial", a.trial ? nlohmann::json(*a.trial) : nlohmann::json(nullptr)},
                     {"decision", name},   {"reason", a.reason}, {"by", by}};
    std::cout << j.dump(2) << "\n";
  } else {
    std::cerr << "dtlab " << name << ": " << what << (exclude ? " excluded" : " included again")
              << (a.reason.empty() ? "" : " (" + a.reason + ")") << "; recorded in " << store::display_name(a.db) << "\n";
  }
}

void add_decision(CLI::App& root, bool exclude) {
  auto a = std::make_shared<DecisionArgs>();
  auto* cmd = root.add_subcommand(
      exclude ? "exclude" : "include",
      exclude ? "Leave a participant, or one of their trials, out of the analysis, with a reason. The decision is "
                "appended to the study database (who, why, when); nothing is deleted, and `dtlab include` takes it "
                "back. `dtlab analyze` and `dtlab stats` on the export leave excluded data out and list every "
                "exclusion with its reason"
              : "Take back an exclusion: the participant or trial is analysed again. Appended like the exclusion "
                "itself, which stays in the record");
  cmd->footer("Trials are numbered as in `dtlab plan` and the export's position column (1-based).\n"
              "Exit status: 0 recorded, 1 unknown participant or trial, missing reason, not a dtlab database, "
              "2 bad command line, 3 database or I/O failure.");
  cmd->add_option("database", a->db, kDatabaseHelp)->required();
  cmd->add_option("--participant", a->participant, "Participant id as enrolled")
      ->check(participant_id())->required();
  cmd->add_option("--trial", a->trial, "Only this trial of the participant's session (1-based position)")
      ->check(CLI::PositiveNumber);
  auto* reason = cmd->add_option("--reason", a->reason,
                                 exclude ? "Why (required), e.g. \"misunderstood the task\"" : "Why (optional)");
  if (exclude) reason->required();
  cmd->add_option("--by", a->by, "Who decided (default: $DTLAB_EXPERIMENTER, else $USER)");
  cmd->add_flag("--json", a->json, "Print {database, participant, trial, decision, reason, by} as JSON on stdout");
  cmd->callback([a, exclude] { run_decision(*a, exclude); });
}

}  // namespace

void add_exclude_command(CLI::App& root) {
  add_decision(root, true);
  add_decision(root, false);
}

}  // namespace dtlab::app

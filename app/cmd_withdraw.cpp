// `dtlab withdraw DB --participant ID [--reason TEXT] [--by NAME] [--json]`:
// a participant's later withdrawal of consent (docs/store.md, "Schema v4",
// invariant 13). One appended row with who, why and when, in the transaction
// that also ends their running session (abandoned) and frees their order row,
// so the next enrollment runs that row again; they never run again, the
// export leaves them out. Withdrawing twice keeps the first.
// Never deletes anything. Exit 0 done, 1 unknown participant, empty reason or
// not a dtlab database, 2 bad command line, 3 database or I/O failure (or a
// session another process is running now).
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <iostream>
#include <memory>

#include "app/commands.h"
#include "app/database_arg.h"
#include "study/session/mapping.h"
#include "study/store/read.h"
#include "study/store/store.h"

namespace dtlab::app {

namespace {

struct WithdrawArgs {
  std::string db, participant, reason = "withdrew consent", by;
  bool json = false;
};

void run_withdraw(const WithdrawArgs& a) {
  auto store = store::Store::open_existing(a.db, session::open_options());
  if (!store) fail("withdraw", store.error());
  const std::string by = a.by.empty() ? default_experimenter() : a.by;
  auto before = store->lookup(a.participant);  // unknown: withdraw() says so
  const bool already = before && before->withdrawn;
  if (Status st = store->withdraw(a.participant, a.reason, by); !st) fail("withdraw", st.error());
  // What is stored now: the first withdrawal stays, so a second call reports the first.
  auto withdrawals = store->read().withdrawals();
  if (!withdrawals) fail("withdraw", withdrawals.error());
  store::WithdrawalRecord w;
  for (const auto& x : *withdrawals)
    if (x.participant == a.participant) w = x;
  if (a.json) {
    nlohmann::json j{{"database", store::display_name(a.db)}, {"participant", a.participant},
                     {"withdrawn_at", w.withdrawn_at}, {"reason", w.reason}, {"by", w.by},
                     {"already", already}};
    std::cout << j.dump(2) << "\n";
  } else {
    std::cerr << "dtlab withdraw: participant " << a.participant << (already ? " had withdrawn already" : " withdrew")
              << " (" << w.reason << ", at " << w.withdrawn_at << "); their order row is free, they never run "
              << "again, and the export leaves them out; recorded in " << store::display_name(a.db)
              << "\n";
  }
}

}  // namespace

void add_withdraw_command(CLI::App& root) {
  auto a = std::make_shared<WithdrawArgs>();
  auto* cmd = root.add_subcommand(
      "withdraw",
      "Record that a participant withdrew their consent: appended to the study database with who, why and when, "
      "in one transaction that ends their session if it is running (abandoned) and frees their order row for the "
      "next enrollment. They can never run again, and `dtlab export` leaves them out. Nothing is "
      "deleted; withdrawing twice keeps the first withdrawal");
  cmd->footer("Exit status: 0 recorded (or recorded before), 1 unknown participant, empty reason, not a dtlab "
              "database, 2 bad command line, 3 database or I/O failure, or a session another process runs now "
              "(stop it first).");
  cmd->add_option("database", a->db, kDatabaseHelp)->required();
  cmd->add_option("--participant", a->participant, "Participant id as enrolled")->check(participant_id())->required();
  cmd->add_option("--reason", a->reason, "Why")->capture_default_str();
  cmd->add_option("--by", a->by, "Who records it (default: $DTLAB_EXPERIMENTER, else $USER)");
  cmd->add_flag("--json", a->json, "Print {database, participant, withdrawn_at, reason, by, already} as JSON on stdout "
                "(already: the participant had withdrawn before; the first withdrawal is shown)");
  cmd->callback([a] { run_withdraw(*a); });
}

}  // namespace dtlab::app

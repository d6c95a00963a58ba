// `dtlab copy SRC DST [--json]`: a whole study from one database to another,
// either engine on either side (a file, or a postgresql:// URI naming a
// schema): into an empty or missing DST every row as it is, so the exports
// of both are byte-identical; into a DST holding the study already, a merge
// of what DST lacks (a station's offline file into the lab's server), with
// the rules and refusals of docs/store.md, "Copying and merging". One
// transaction of DST: a refused copy writes nothing. Never writes SRC. Exit 0
// copied, 1 invalid or unmergeable input (the message says what and why), 2
// bad command line, 3 database or I/O failure.
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <iostream>
#include <memory>

#include "app/commands.h"
#include "app/database_arg.h"
#include "study/session/mapping.h"
#include "study/store/copy.h"

namespace dtlab::app {

namespace {

struct CopyArgs {
  std::string src, dst;
  bool json = false;
};

void run_copy(const CopyArgs& a) {
  store::CopyOptions options;
  options.design_hash_of = session::open_options().design_hash_of;
  auto sum = store::copy_study(a.src, a.dst, options);
  if (!sum) {
    std::cerr << "dtlab copy: " << sum.error().to_string() << "\n";
    throw CLI::RuntimeError(exit_code(sum.error()));
  }
  const std::string from = store::display_name(a.src), to = store::display_name(a.dst);
  if (a.json) {
    nlohmann::json rows = nlohmann::json::object();
    for (const auto& [table, n] : sum->rows) rows[table] = n;
    nlohmann::json j{{"source", from},
                     {"destination", to},
                     {"merged", sum->merged},
                     {"participants", sum->participants},
                     {"renumbered", sum->renumbered},
                     {"unchanged", sum->unchanged},
                     {"sessions", sum->sessions},
                     {"trials", sum->trials},
                     {"revisions", sum->revisions},
                     {"decisions", sum->decisions},
                     {"notes", sum->notes},
                     {"changes", sum->changes},
                     {"rows", rows}};
    std::cout << j.dump(2) << "\n";
    return;
  }
  std::cerr << "dtlab copy: " << (sum->merged ? "merged " : "copied ") << from << " into " << to << ": "
            << sum->participants << " participants added";
  if (sum->merged) std::cerr << " (" << sum->renumbered << " given new ledger slots), " << sum->unchanged << " already there";
  std::cerr << ", " << sum->sessions << " sessions, " << sum->trials << " trials, " << sum->decisions << " decisions, "
            << sum->notes << " notes\n";
  for (const std::string& c : sum->changes) std::cerr << "dtlab copy: " << c << "\n";
}

}  // namespace

void add_copy_command(CLI::App& root) {
  auto a = std::make_shared<CopyArgs>();
  auto* cmd = root.add_subcommand(
      "copy",
      "Copy a whole study between databases: a file (SQLite) or a lab's server (postgresql://...). Into an empty or "
      "missing DST every row is copied as it is (ids, timestamps, protocol texts, decisions), so `dtlab export` of "
      "both is identical. Into a DST that holds the study already, the participants it lacks are merged in (a "
      "station that worked offline): a participant who ran a session keeps their ledger slot, one enrolled but "
      "never started takes DST's next slot; anything that cannot be merged without changing data is refused and "
      "nothing is written");
  cmd->footer(
      "Refused (exit 1, nothing written): another design in DST; a participant in both with different data; a "
      "session whose ledger slot DST gave to someone else; a session of SRC running now.\n"
      "Exit status: 0 copied, 1 invalid or unmergeable input, 2 bad command line, 3 database or I/O failure.");
  cmd->add_option("source", a->src, std::string(kDatabaseHelp) + ": the study to copy (read only)")
      ->required()
      ->check(existing_database());
  cmd->add_option("destination", a->dst, std::string(kDatabaseHelp) + ": created if missing, or merged into")->required();
  cmd->add_flag("--json", a->json,
                "Print {source, destination, merged, participants, renumbered, unchanged, sessions, trials, revisions, "
                "decisions, notes, changes, rows} as JSON on stdout");
  cmd->callback([a] { run_copy(*a); });
}

}  // namespace dtlab::app

// `dtlab plan PROTOCOL (--index K | --db FILE --participant ID) [--json]`:
// prints a participant's ordered trials (position, block, factor levels,
// task, trial, seed, method). The plan is a pure function of (protocol, K,
// order row): the same on every machine. With --db, K and the order row come
// from the study database's ledger, read-only. Exit 1 with file:line:field
// when the protocol is invalid, the participant unknown or the database
// belongs to another protocol.
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <charconv>
#include <iostream>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "app/commands.h"
#include "app/database_arg.h"
#include "study/common/text.h"
#include "study/design/design.h"
#include "study/protocol/protocol.h"
#include "study/session/mapping.h"
#include "study/store/read.h"

namespace dtlab::app {

namespace {

nlohmann::ordered_json plan_json(const design::Plan& plan) {
  nlohmann::ordered_json trials = nlohmann::ordered_json::array();
  for (const auto& t : plan.trials) {
    nlohmann::ordered_json levels = nlohmann::ordered_json::object();
    for (const auto& [factor, level] : t.levels) levels[factor] = level;
    trials.push_back({{"position", t.position},
                      {"block", t.block},
                      {"levels", levels},
                      {"task", t.task},
                      {"trial", t.trial},
                      {"seed", t.seed},
                      {"method", t.method},
                      {"practice", t.practice}});
  }
  return {{"protocol", plan.protocol_id}, {"index", plan.index}, {"order_row", plan.order_row}, {"trials", trials}};
}

void print_table(const protocol::Protocol& p, const design::Plan& plan, int rows) {
  std::cout << "protocol " << plan.protocol_id << " (" << p.source_path << "), enrollment index " << plan.index
            << ", order row " << plan.order_row << " of " << rows << " ("
            << protocol::to_string(p.order.scheme) << "), " << count(static_cast<long long>(plan.trials.size()), "trial") << "\n";
  std::vector<std::string> header{"position", "block"};
  for (const auto& f : p.factors) header.push_back(f.name);
  for (const char* h : {"task", "trial", "seed", "method"}) header.emplace_back(h);
  std::vector<std::vector<std::string>> cells;
  for (const auto& t : plan.trials) {
    std::vector<std::string> row{std::to_string(t.position), std::to_string(t.block)};
    for (const auto& lv : t.levels) row.push_back(lv.second);
    row.push_back(t.task);
    row.push_back(t.practice ? "practice " + std::to_string(t.trial) : std::to_string(t.trial));
    row.push_back(std::to_string(t.seed));
    row.push_back(t.method);
    cells.push_back(std::move(row));
  }
  std::vector<std::size_t> width(header.size());
  for (std::size_t c = 0; c < header.size(); ++c) {
    width[c] = header[c].size();
    for (const auto& row : cells) width[c] = std::max(width[c], row[c].size());
  }
  const auto print_row = [&](const std::vector<std::string>& row) {
    std::string line;
    for (std::size_t c = 0; c < row.size(); ++c) {
      std::string cell = row[c];
      cell.resize(width[c], ' ');
      line += cell + (c + 1 < row.size() ? "  " : "");
    }
    line.erase(line.find_last_not_of(' ') + 1);
    std::cout << line << "\n";
  };
  print_row(header);
  for (const auto& row : cells) print_row(row);
}

// --index: an integer 0 .. INT_MAX, said in one message whatever was written (-1, 1e99, "x").
CLI::Validator enrollment_index_check() {
  return CLI::Validator(
      [](const std::string& text) -> std::string {
        long long v = -1;
        const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
        if (ec != std::errc() || end != text.data() + text.size() || v < 0 || v > std::numeric_limits<int>::max())
          return "expected an enrollment index, an integer from 0 to " +
                 std::to_string(std::numeric_limits<int>::max()) + "; got '" + text + "'";
        return {};
      },
      "INDEX");
}

}  // namespace

void add_plan_command(CLI::App& root) {
  auto* cmd = root.add_subcommand("plan", "Print one participant's ordered trial list");
  auto path = std::make_shared<std::string>();
  auto index = std::make_shared<int>(0);
  auto db = std::make_shared<std::string>();
  auto participant = std::make_shared<std::string>();
  auto json = std::make_shared<bool>(false);
  cmd->add_option("protocol", *path, "Protocol file (TOML; format in docs/protocol.md)")->required();
  auto* index_opt = cmd->add_option("--index", *index, "0-based enrollment index K (0 to 2147483647); gets order row K mod rows")
                        ->check(enrollment_index_check());
  auto* db_opt = cmd->add_option("--db", *db,
                                 std::string(kDatabaseHelp) + ": take K and the order row from its participant ledger")
                     ->check(existing_database());
  auto* participant_opt = cmd->add_option("--participant", *participant, "Participant id enrolled in --db")
      ->check(participant_id());
  index_opt->excludes(db_opt)->excludes(participant_opt);
  db_opt->needs(participant_opt);
  participant_opt->needs(db_opt);
  cmd->add_flag("--json", *json,
                "Print {\"protocol\", \"index\", \"order_row\", \"trials\": [{\"position\", \"block\", "
                "\"levels\": {factor: level}, \"task\", \"trial\", \"seed\", \"method\", \"practice\"}]}");
  cmd->footer(
      "Give either --index K or --db DB --participant ID (DB: a file or a postgresql:// URI).\n"
      "Trial seeds: seed = mix64(mix64(mix64(master_seed), K), position), see study/design/seeds.h.\n"
      "Exit status: 0 ok, 1 invalid protocol, unknown participant or a database of another protocol\n"
      "(FILE:LINE:COLUMN: error: FIELD: MESSAGE on stderr), 2 bad command line, 3 database failure.");
  cmd->callback([path, index, db, participant, json, index_opt] {
    if (index_opt->count() == 0 && db->empty()) {
      std::cerr << "dtlab plan: give either --index K or --db FILE --participant ID\n"
                << "Run with --help for more information.\n";
      throw CLI::RuntimeError(kExitUsage);
    }
    const auto p = protocol::load_protocol(*path);
    if (!p.ok()) {
      std::cerr << Diagnostic{Severity::error, p.error()}.to_string() << "\n"
                << "(run `dtlab validate " << *path << "` for every problem)\n";
      throw CLI::RuntimeError(kExitInvalid);
    }
    design::Plan plan;
    if (!db->empty()) {
      auto reader = store::StudyReader::open(*db, session::read_options());
      auto planned = reader ? session::ledger_plan(*reader, *p, *participant) : Result<design::Plan>(reader.error());
      if (!planned.ok()) {
        std::cerr << Diagnostic{Severity::error, planned.error()}.to_string() << "\n";
        throw CLI::RuntimeError(exit_code(planned.error()));
      }
      plan = std::move(planned.value());
    } else {
      plan = design::make_plan(*p, *index);
    }
    if (*json)
      std::cout << plan_json(plan).dump(2) << "\n";
    else
      print_table(*p, plan, design::order_rows(*p));
  });
}

}  // namespace dtlab::app

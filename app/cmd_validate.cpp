// `dtlab validate PROTOCOL [--json]`: checks a protocol file and explains every
// error and warning with file:line:column, the field path and what was
// expected; a file that reads well is then checked as its sessions will run it
// (session::validate_runnable), so "valid" means a session can run it. Exit 0
// when valid (warnings allowed), 1 when invalid; never crashes on any input
// (missing, empty, binary or malformed files).
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <iostream>
#include <memory>
#include <string>
#include <utility>

#include "app/commands.h"
#include "study/common/text.h"
#include "study/design/design.h"
#include "study/protocol/protocol.h"
#include "study/session/runnable.h"

namespace dtlab::app {

namespace {

int trials_per_participant(const protocol::Protocol& p) {
  return static_cast<int>(design::make_plan(p, 0).trials.size());
}

}  // namespace

void add_validate_command(CLI::App& root) {
  auto* cmd = root.add_subcommand("validate", "Check a protocol file; explain each error and warning");
  auto path = std::make_shared<std::string>();
  auto json = std::make_shared<bool>(false);
  cmd->add_option("protocol", *path, "Protocol file (TOML; format in docs/protocol.md)")->required();
  cmd->add_flag("--json", *json,
                "Print {\"file\", \"valid\", \"errors\", \"warnings\", \"diagnostics\": [{\"severity\", \"file\", "
                "\"line\", \"column\", \"field\", \"message\"}], \"summary\"} on stdout");
  cmd->footer(
      "Valid means a session can run it: besides every key, type and range, each task's scene parameters\n"
      "go through the scene generator's checks, each rendering through the renderer's at every viewport\n"
      "a session may use (16x16 to 4096x4096), the work of one frame is bounded, and each depth test's\n"
      "view and pairs are made for the first participants (docs/protocol.md, \"What validate checks\").\n"
      "Exit status: 0 valid (warnings allowed), 1 invalid. Errors and warnings go to stderr as\n"
      "FILE:LINE:COLUMN: error|warning: FIELD: MESSAGE (with --json, on stdout as JSON).");
  cmd->callback([path, json] {
    auto diagnostics = protocol::validate_protocol_file(*path);
    if (!protocol::has_errors(diagnostics)) {
      // The file is well formed: now what the sessions will hand the generator and the renderer.
      if (auto p = protocol::load_protocol(*path); p.ok()) {
        const auto runnable = session::validate_runnable(*p);
        diagnostics.insert(diagnostics.end(), runnable.begin(), runnable.end());
        std::stable_sort(diagnostics.begin(), diagnostics.end(), [](const Diagnostic& a, const Diagnostic& b) {
          return std::pair(a.where.line, a.where.column) < std::pair(b.where.line, b.where.column);
        });
      }
    }
    const bool valid = !protocol::has_errors(diagnostics);
    int errors = 0, warnings = 0;
    for (const auto& d : diagnostics) (d.severity == Severity::error ? errors : warnings)++;

    nlohmann::ordered_json summary;
    std::string summary_text;
    if (valid) {
      auto p = protocol::load_protocol(*path);
      if (p.ok()) {
        const int rows = design::order_rows(*p);
        const int trials = trials_per_participant(*p);
        summary = {{"id", p->id},
                   {"conditions", p->conditions.size()},
                   {"order_rows", rows},
                   {"scheme", std::string(protocol::to_string(p->order.scheme))},
                   {"participants", p->participants},
                   {"trials_per_participant", trials},
                   {"sha256", p->sha256}};
        summary_text = "protocol '" + p->id + "': " + count(static_cast<long long>(p->conditions.size()), "condition") +
                       ", " + count(rows, "order row") + " (" + std::string(protocol::to_string(p->order.scheme)) +
                       "), " + count(trials, "trial") + " per participant, " + count(p->participants, "participant");
      }
    }

    if (*json) {
      nlohmann::ordered_json list = nlohmann::ordered_json::array();
      for (const auto& d : diagnostics)
        list.push_back({{"severity", d.severity == Severity::error ? "error" : "warning"},
                        {"file", d.where.file},
                        {"line", d.where.line},
                        {"column", d.where.column},
                        {"field", d.where.field},
                        {"message", d.where.message}});
      nlohmann::ordered_json out{{"file", *path},
                                 {"valid", valid},
                                 {"errors", errors},
                                 {"warnings", warnings},
                                 {"diagnostics", list}};
      if (!summary.is_null()) out["summary"] = summary;
      // Protocol text may hold invalid UTF-8 that ends up in a message: replace, never throw.
      std::cout << out.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) << "\n";
    } else {
      for (const auto& d : diagnostics) std::cerr << d.to_string() << "\n";
      if (valid) {
        std::cout << *path << ": valid";
        if (warnings) std::cout << " with " << warnings << (warnings == 1 ? " warning" : " warnings");
        if (!summary_text.empty()) std::cout << "; " << summary_text;
        std::cout << "\n";
      } else {
        std::cerr << *path << ": invalid: " << errors << (errors == 1 ? " error" : " errors");
        if (warnings) std::cerr << ", " << warnings << (warnings == 1 ? " warning" : " warnings");
        std::cerr << "\n";
      }
    }
    if (!valid) throw CLI::RuntimeError(kExitInvalid);
  });
}

}  // namespace dtlab::app

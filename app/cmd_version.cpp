// `dtlab version [--json]`: the software version and the git commit it was
// built from (the same identity every study database records).
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <iostream>
#include <memory>

#include "app/commands.h"
#include "study/common/version.h"

namespace dtlab::app {

void add_version_command(CLI::App& root) {
  auto* cmd = root.add_subcommand("version", "Print the version and the git commit of this build");
  auto json = std::make_shared<bool>(false);
  cmd->add_flag("--json", *json, "Print {\"version\", \"commit\"} as JSON");
  cmd->callback([json] {
    if (*json) {
      nlohmann::json j{{"version", std::string(version())}, {"commit", std::string(git_commit())}};
      std::cout << j.dump(2) << "\n";
    } else {
      std::cout << version_string() << "\n";
    }
  });
}

}  // namespace dtlab::app

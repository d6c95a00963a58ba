// dtlab: the one executable (DESIGN.md, "Command line contract"). main() only
// builds the CLI11 tree and maps errors to exit codes; every subcommand lives
// in its own cmd_*.cpp. Subcommands appear here when they work, never before.
#include <CLI/CLI.hpp>

#include <algorithm>
#include <exception>
#include <iostream>
#include <string>
#include <vector>

#include "app/commands.h"
#include "app/platform/malloc_tuning.h"
#include "study/common/text.h"
#include "study/common/version.h"

namespace dtlab::app {

void fail(std::string_view command, int code, const std::string& message) {
  std::cerr << "dtlab " << command << ": error: " << message << "\n";
  throw CLI::RuntimeError(code);
}

void fail(std::string_view command, const Error& e) {
  std::cerr << "dtlab " << command << ": error: " << e.to_string() << "\n";
  throw CLI::RuntimeError(exit_code(e));
}

}  // namespace dtlab::app

namespace {

// `dtlab analyse`: CLI11 would only say that a subcommand is required. Names the word and the
// nearest command; false when argv[1] is an option or a command.
bool unknown_command(const CLI::App& root, int argc, char** argv) {
  if (argc < 2 || argv[1][0] == '-') return false;
  const std::string word = argv[1];
  std::vector<std::string> names;
  for (const CLI::App* sub : root.get_subcommands([](const CLI::App*) { return true; })) names.push_back(sub->get_name());
  if (std::find(names.begin(), names.end(), word) != names.end()) return false;
  std::cerr << "dtlab: unknown command '" << word << "'";
  if (const std::string near = dtlab::nearest(word, names); !near.empty()) std::cerr << "; did you mean '" << near << "'?";
  std::cerr << "\nRun 'dtlab --help' for the list of commands.\n";
  return true;
}

}  // namespace

int main(int argc, char** argv) {
  // Before anything allocates: frame times must not depend on the heap's history (malloc_tuning.cpp).
  dtlab::platform::tune_malloc_for_software_gl();
  CLI::App root{
      "dtlab: run, author and analyse user studies of occlusion management in 3D.\n"
      "The reference study is Elmqvist, Assarsson & Tsigas (2008), protocols/elmqvist2008.toml."};
  root.set_version_flag("--version", std::string(dtlab::version_string()));
  root.require_subcommand(1);
  root.fallthrough(false);

  dtlab::app::add_version_command(root);
  dtlab::app::add_render_command(root);
  dtlab::app::add_bench_command(root);
  dtlab::app::add_scene_command(root);
  dtlab::app::add_icons_command(root);
  dtlab::app::add_stats_command(root);
  dtlab::app::add_validate_command(root);
  dtlab::app::add_plan_command(root);
  dtlab::app::add_export_command(root);
  dtlab::app::add_exclude_command(root);
  dtlab::app::add_withdraw_command(root);
  dtlab::app::add_copy_command(root);
  dtlab::app::add_simulate_command(root);
  dtlab::app::add_demo_command(root);
  dtlab::app::add_analyze_command(root);
  dtlab::app::add_power_command(root);
  dtlab::app::add_run_command(root);
  dtlab::app::add_replay_command(root);

  if (unknown_command(root, argc, argv)) return dtlab::app::kExitUsage;
  try {
    root.parse(argc, argv);
  } catch (const CLI::RuntimeError& e) {
    return e.get_exit_code();  // a subcommand failed; it has printed its message
  } catch (const CLI::ParseError& e) {
    const int rc = root.exit(e);  // prints help, version or the usage error
    return rc == 0 ? dtlab::app::kExitOk : dtlab::app::kExitUsage;
  } catch (const std::exception& e) {
    std::cerr << "dtlab: internal error: " << e.what() << "\n";
    return dtlab::app::kExitFailure;
  }
  return dtlab::app::kExitOk;
}

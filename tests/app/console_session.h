// What the experimenter-console window tests share: `dtlab run` with the
// pilot protocol and a script as a child process (killed if it hangs, so a
// hang fails the test instead of stalling the suite), and the lines of its
// $DTLAB_RUN_ITEMS_LOG (which UI items each window showed, in order).
// Never: reads the answer key (the scripts answer blind, as a person does).
#pragma once
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <set>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "tests/common/run_cli.h"

namespace dtlab::test {

// A session's directory under the temp directory, empty.
inline std::filesystem::path fresh_dir(const std::string& name) {
  const auto d = std::filesystem::temp_directory_path() / ("dtlab_console_" + std::to_string(::getpid()) + "_" + name);
  std::filesystem::remove_all(d);
  std::filesystem::create_directories(d);
  return d;
}

// Runs `dtlab run PILOT --db DB --size 640x480 EXTRA...` with $DTLAB_RUN_ITEMS_LOG set to `items_log`,
// stdout and stderr into `log`; its exit code (128 + signal when killed), -1 when it ran past
// `seconds` (it is killed then).
inline int run_pilot(const std::filesystem::path& db, const std::filesystem::path& log,
                     const std::filesystem::path& items_log, const std::vector<std::string>& extra, double seconds) {
  std::vector<std::string> args{"run", std::string(DTLAB_SOURCE_DIR) + "/protocols/pilot.toml", "--db", db.string(),
                                "--size", "640x480"};
  args.insert(args.end(), extra.begin(), extra.end());
  return run_dtlab_for(args, log, seconds, {{"DTLAB_RUN_ITEMS_LOG", items_log.string()}});
}

// One line of $DTLAB_RUN_ITEMS_LOG: the names of the UI items a window showed from one frame on.
struct Shown {
  std::string window, screen;
  std::set<std::string> items;
  bool has(const std::string& item) const { return items.count(item) > 0; }
};

inline std::vector<Shown> read_items_log(const std::filesystem::path& path) {
  std::vector<Shown> out;
  std::ifstream in(path);
  for (std::string line; std::getline(in, line);) {
    const auto j = nlohmann::json::parse(line);
    out.push_back(Shown{j["window"], j["screen"], j["items"].get<std::set<std::string>>()});
  }
  return out;
}

}  // namespace dtlab::test

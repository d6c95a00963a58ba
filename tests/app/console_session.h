// What the experimenter-console window tests share: `dtlab run` with the
// pilot protocol and a script as a child process (killed if it hangs, so a
// hang fails the test instead of stalling the suite), and the lines of its
// $DTLAB_RUN_ITEMS_LOG (which UI items each window showed, in order).
// Never: reads the answer key (the scripts answer blind, as a person does).
#pragma once
#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <set>
#include <string>
#include <thread>
#include <vector>

#include <nlohmann/json.hpp>

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
  std::vector<std::string> args{DTLAB_BINARY, "run", std::string(DTLAB_SOURCE_DIR) + "/protocols/pilot.toml",
                                "--db", db.string(), "--size", "640x480"};
  args.insert(args.end(), extra.begin(), extra.end());
  const pid_t pid = ::fork();
  if (pid == 0) {
    const int fd = ::open(log.c_str(), O_WRONLY | O_CREAT | O_APPEND, 0644);
    ::dup2(fd, 1);
    ::dup2(fd, 2);
    ::setenv("DTLAB_RUN_ITEMS_LOG", items_log.c_str(), 1);
    std::vector<char*> argv;
    for (auto& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);
    ::execv(DTLAB_BINARY, argv.data());
    ::_exit(127);
  }
  const auto until = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
  int status = 0;
  while (std::chrono::steady_clock::now() < until) {
    if (::waitpid(pid, &status, WNOHANG) == pid) return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  ::kill(pid, SIGKILL);
  ::waitpid(pid, &status, 0);
  return -1;
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

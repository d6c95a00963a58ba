// Runs the dtlab executable under test (DTLAB_BINARY, set by dtlab_add_test)
// as a separate process, the way a user or a script does, and captures its
// exit status, stdout and stderr. Shared by every CLI test.
// Guarantees: rc is the exit status, or 128 + signal if the process was
// killed (a crash never reads as success); capture files are unique per
// process and call (ctest runs tests in parallel) and are removed afterwards.
// Never: passes arguments through anything but /bin/sh (quote paths yourself),
// except run_dtlab_for, which execs the binary with its arguments as given.
#pragma once
#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <thread>
#include <utility>
#include <vector>

namespace dtlab::test {

struct CliOutcome {
  int rc = -1;
  std::string out, err;
};

// The whole file as bytes; empty if it cannot be read.
inline std::string read_text(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// `dtlab <args>` through the shell; args are pasted as written.
inline CliOutcome run_dtlab(const std::string& args) {
  static std::atomic<int> calls{0};
  const std::filesystem::path dir = std::filesystem::temp_directory_path();
  const std::string tag = "dtlab_cli_" + std::to_string(getpid()) + "_" + std::to_string(calls++);
  const std::filesystem::path out = dir / (tag + ".out"), err = dir / (tag + ".err");
  const std::string cmd = std::string("'") + DTLAB_BINARY + "' " + args + " >'" + out.string() + "' 2>'" +
                          err.string() + "'";
  const int status = std::system(cmd.c_str());
  CliOutcome r;
  r.rc = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + (WIFSIGNALED(status) ? WTERMSIG(status) : 0);
  r.out = read_text(out);
  r.err = read_text(err);
  std::filesystem::remove(out);
  std::filesystem::remove(err);
  return r;
}

// Runs DTLAB_BINARY with `args` (argv[1...]), `env` set, stdout and stderr appended to `log`; its
// exit code (128 + signal when killed), or -1 when it ran past `seconds` (it is killed then, so a
// hang fails the test instead of stalling the suite).
inline int run_dtlab_for(const std::vector<std::string>& args, const std::filesystem::path& log, double seconds,
                         const std::vector<std::pair<std::string, std::string>>& env = {}) {
  std::vector<std::string> argv_text{DTLAB_BINARY};
  argv_text.insert(argv_text.end(), args.begin(), args.end());
  const pid_t pid = ::fork();
  if (pid == 0) {
    const int fd = ::open(log.c_str(), O_WRONLY | O_CREAT | O_APPEND, 0644);
    ::dup2(fd, 1);
    ::dup2(fd, 2);
    for (const auto& [k, v] : env) ::setenv(k.c_str(), v.c_str(), 1);
    std::vector<char*> argv;
    for (auto& a : argv_text) argv.push_back(a.data());
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

}  // namespace dtlab::test

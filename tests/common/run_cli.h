// Runs the dtlab executable under test (DTLAB_BINARY, set by dtlab_add_test)
// as a separate process, the way a user or a script does, and captures its
// exit status, stdout and stderr. Shared by every CLI test.
// Guarantees: rc is the exit status, or 128 + signal if the process was
// killed (a crash never reads as success); capture files are unique per
// process and call (ctest runs tests in parallel) and are removed afterwards.
// Never: passes arguments through anything but /bin/sh (quote paths yourself).
#pragma once
#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

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

}  // namespace dtlab::test

// Shared fixtures of the store tests: the study data (study_fixtures.h), a
// fresh temporary directory per test, child processes started at one
// instant, a fixture that runs a test on both engines (backends.h), and
// independent SQL reads through the engines' own C APIs (the checks never go
// through the code under test).
#pragma once
#include <gtest/gtest.h>

#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "tests/store/backends.h"
#include "tests/store/study_fixtures.h"

namespace dtlab::store::testing {

// A fresh directory under the system temp dir, removed at the end.
class TempDir {
 public:
  TempDir() {
    static int counter = 0;
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    std::string name = info ? info->name() : "x";
    for (char& c : name)
      if (c == '/') c = '-';  // a parameterized test's name: RoundTrip/SQLite
    dir_ = std::filesystem::temp_directory_path() /
           ("dtlab-store-" + name + "-" + std::to_string(::getpid()) + "-" + std::to_string(counter++));
    std::filesystem::remove_all(dir_);
    std::filesystem::create_directories(dir_);
  }
  ~TempDir() { std::filesystem::remove_all(dir_); }
  std::string file(const std::string& name) const { return (dir_ / name).string(); }
  std::string path() const { return dir_.string(); }

 private:
  std::filesystem::path dir_;
};

// Forks `n` children that wait on one pipe and then run body(k); returns their exit statuses.
template <class F>
inline std::vector<int> race(int n, F&& body) {
  int go[2];
  if (::pipe(go) != 0) return {};
  std::vector<pid_t> pids;
  for (int k = 0; k < n; ++k) {
    const pid_t pid = ::fork();
    if (pid == 0) {
      ::close(go[1]);
      char c;
      if (::read(go[0], &c, 1) != 1) ::_exit(90);
      ::_exit(body(k));
    }
    pids.push_back(pid);
  }
  ::close(go[0]);
  const std::string start(static_cast<std::size_t>(n), 'g');
  if (::write(go[1], start.data(), start.size()) != static_cast<ssize_t>(start.size())) ADD_FAILURE() << "barrier";
  ::close(go[1]);
  std::vector<int> out;
  for (pid_t pid : pids) {
    int status = 0;
    ::waitpid(pid, &status, 0);
    out.push_back(WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status));
  }
  return out;
}

// Store::open that must succeed: the test stops at once (with the Error) if it does not.
inline Store open_ok(const std::string& where, const StudyInfo& info = study_info(), OpenOptions o = {}) {
  auto s = Store::open(where, info, o);
  if (!s) {
    ADD_FAILURE() << s.error().to_string();
    std::abort();
  }
  return std::move(*s);
}

// A test that runs on both engines: study() is a new file (SQLite) or a new schema on the
// test server (PostgreSQL). Instantiate with DTLAB_ON_BOTH_BACKENDS(Suite).
class OnBothBackends : public ::testing::TestWithParam<Backend> {
 protected:
  void SetUp() override { DTLAB_SKIP_WITHOUT_SERVER(GetParam()); }
  std::string study(const std::string& name = "s") const { return new_study(GetParam(), dir_.path(), name); }
  bool pg() const { return GetParam() == Backend::postgresql; }
  TempDir dir_;
};

#define DTLAB_ON_BOTH_BACKENDS(Suite)                                                                         \
  INSTANTIATE_TEST_SUITE_P(, Suite,                                                                           \
                           ::testing::Values(::dtlab::store::testing::Backend::sqlite,                        \
                                             ::dtlab::store::testing::Backend::postgresql),                   \
                           ::dtlab::store::testing::backend_param_name)

}  // namespace dtlab::store::testing

// Shared fixtures of the store tests: the study data (study_fixtures.h), a
// fresh temporary directory per test, a fixture that runs a test on both
// engines (backends.h), and independent SQL reads through the engines' own C
// APIs (the checks never go through the code under test).
#pragma once
#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <string>

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

// `dtlab` itself (app/main.cpp), run as a user runs it: an unknown command is
// named, with the nearest real one when there is one, and exits 2 (a bad
// command line); known commands and --help still work.
#include <gtest/gtest.h>

#include <string>

#include "tests/common/run_cli.h"

namespace {

using dtlab::test::run_dtlab;

// Issue 12: `dtlab analyse` and `dtlab foo` said only "A subcommand is required".
TEST(MainCli, UnknownCommandsAreNamedWithTheNearestOne) {
  auto r = run_dtlab("analyse x.sqlite");
  EXPECT_EQ(r.rc, 2);
  EXPECT_NE(r.err.find("unknown command 'analyse'; did you mean 'analyze'?"), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find("A subcommand is required"), std::string::npos) << r.err;
  r = run_dtlab("foo");
  EXPECT_EQ(r.rc, 2);
  EXPECT_NE(r.err.find("unknown command 'foo'"), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find("did you mean"), std::string::npos) << r.err;
  r = run_dtlab("simlate");
  EXPECT_NE(r.err.find("did you mean 'simulate'?"), std::string::npos) << r.err;
}

TEST(MainCli, KnownCommandsAndOptionsStillParse) {
  EXPECT_EQ(run_dtlab("--help").rc, 0);
  EXPECT_EQ(run_dtlab("--version").rc, 0);
  EXPECT_EQ(run_dtlab("version").rc, 0);
  const auto none = run_dtlab("");
  EXPECT_EQ(none.rc, 2);  // a command is required
}

}  // namespace

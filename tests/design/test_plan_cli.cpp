// `dtlab plan` run as separate processes (DTLAB_BINARY): two runs give
// byte-identical JSON, the JSON has the documented field names other scripts
// read, enrollment index k gets row k mod 4, and over 16 participants every
// condition is equally often at every position. Invalid input exits 1.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>

#include "tests/common/run_cli.h"

namespace {

namespace fs = std::filesystem;

using Outcome = dtlab::test::CliOutcome;

Outcome dtlab(const std::string& args) { return dtlab::test::run_dtlab(args); }

const std::string kReference = std::string("'") + DTLAB_SOURCE_DIR + "/protocols/elmqvist2008.toml'";

TEST(PlanCli, TwoProcessesPrintTheSameJson) {
  const Outcome a = dtlab("plan " + kReference + " --index 3 --json");
  const Outcome b = dtlab("plan " + kReference + " --index 3 --json");
  ASSERT_EQ(a.rc, 0) << a.err;
  ASSERT_EQ(b.rc, 0) << b.err;
  EXPECT_FALSE(a.out.empty());
  EXPECT_EQ(a.out, b.out);
}

TEST(PlanCli, JsonHasTheDocumentedFields) {
  const Outcome r = dtlab("plan " + kReference + " --index 0 --json");
  ASSERT_EQ(r.rc, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["protocol"], "elmqvist2008");
  EXPECT_EQ(j["index"], 0);
  EXPECT_EQ(j["order_row"], 0);
  ASSERT_EQ(j["trials"].size(), 24u);
  const auto& t = j["trials"][0];
  for (const char* key : {"position", "block", "levels", "task", "trial", "seed", "method"})
    EXPECT_TRUE(t.contains(key)) << key;
  EXPECT_EQ(t["position"], 1);
  EXPECT_EQ(t["block"], 1);
  EXPECT_TRUE(t["levels"].contains("transparency"));
  EXPECT_TRUE(t["levels"].contains("scenario"));
  EXPECT_EQ(t["seed"].get<std::uint64_t>(), 13947942700548049222ULL);  // see test_plan.cpp, Seeds
}

TEST(PlanCli, SixteenParticipantsBalanceEveryPosition) {
  std::map<std::pair<int, std::string>, int> count;
  for (int k = 0; k < 16; ++k) {
    const Outcome r = dtlab("plan " + kReference + " --index " + std::to_string(k) + " --json");
    ASSERT_EQ(r.rc, 0) << r.err;
    const auto j = nlohmann::json::parse(r.out);
    EXPECT_EQ(j["order_row"], k % 4);
    ASSERT_EQ(j["trials"].size(), 24u);
    for (const auto& t : j["trials"]) {
      const std::string cond =
          t["levels"]["transparency"].get<std::string>() + "/" + t["levels"]["scenario"].get<std::string>();
      ++count[{t["position"].get<int>(), cond}];
    }
  }
  ASSERT_EQ(count.size(), 96u);
  for (const auto& [key, n] : count) EXPECT_EQ(n, 4) << key.first << " " << key.second;
}

TEST(PlanCli, TextTableListsEveryTrial) {
  const Outcome r = dtlab("plan " + kReference + " --index 1");
  ASSERT_EQ(r.rc, 0) << r.err;
  EXPECT_NE(r.out.find("order row 1 of 4"), std::string::npos) << r.out;
  int lines = 0;
  for (char c : r.out) lines += c == '\n';
  EXPECT_EQ(lines, 2 + 24);  // summary, header, trials
}

TEST(PlanCli, BadInputExitsNonZeroWithoutCrashing) {
  const fs::path bad = fs::temp_directory_path() / ("dtlab_plan_cli_bad_" + std::to_string(getpid()) + ".toml");
  std::ofstream(bad) << "id = \"x\"\nparticipants = -3\n";
  Outcome r = dtlab("plan '" + bad.string() + "' --index 0");
  EXPECT_EQ(r.rc, 1);
  EXPECT_EQ(r.err.rfind(bad.string() + ":", 0), 0u) << r.err;
  fs::remove(bad);
  r = dtlab("plan /nonexistent/p.toml --index 0");
  EXPECT_EQ(r.rc, 1);
  // Issue 12: -1 was refused with a 300-digit bound, and the missing option in broken grammar.
  for (const char* index : {"-1", "2147483648", "99999999999999999999", "1e3", "x"}) {
    r = dtlab("plan " + kReference + " --index " + index);
    EXPECT_EQ(r.rc, 2) << index;  // usage error
    EXPECT_NE(r.err.find("expected an enrollment index, an integer from 0 to 2147483647; got '" + std::string(index) +
                         "'"),
              std::string::npos)
        << r.err;
    EXPECT_LT(r.err.size(), 300u) << r.err;
  }
  r = dtlab("plan " + kReference + " --index 2147483647 --json");
  EXPECT_EQ(r.rc, 0) << r.err;
  r = dtlab("plan " + kReference);
  EXPECT_EQ(r.rc, 2);  // --index or --db is required
  EXPECT_NE(r.err.find("give either --index K or --db FILE --participant ID\n"), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find("is required"), std::string::npos) << r.err;
}

}  // namespace

// `dtlab validate` as a user runs it (the dtlab binary, DTLAB_BINARY): exit 0
// for the shipped protocols, exit 1 with FILE:LINE:COLUMN: error: FIELD on
// stderr for broken ones, never a crash (exit codes above 3 or signals), and
// --json listing the same diagnostics.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "tests/common/run_cli.h"

namespace {

namespace fs = std::filesystem;

using Outcome = dtlab::test::CliOutcome;
using dtlab::test::read_text;

Outcome dtlab(const std::string& args) { return dtlab::test::run_dtlab(args); }

fs::path write_temp(const std::string& name, const std::string& text) {
  const fs::path p = fs::temp_directory_path() / ("dtlab_validate_cli_" + std::to_string(getpid()) + "_" + name);
  std::ofstream(p, std::ios::binary) << text;
  return p;
}

// protocols/<shipped> with `from` replaced by `to`, written to a temporary file; *line = the line of the edit.
fs::path edited(const std::string& shipped, const std::string& name, const std::string& from, const std::string& to,
                int* line = nullptr) {
  std::string text = read_text(fs::path(DTLAB_SOURCE_DIR) / "protocols" / shipped);
  const auto at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  if (at == std::string::npos) return write_temp(name, text);
  text.replace(at, from.size(), to);
  if (line) *line = 1 + static_cast<int>(std::count(text.begin(), text.begin() + static_cast<long>(at), '\n'));
  return write_temp(name, text);
}

TEST(ValidateCli, ShippedProtocolsExitZero) {
  for (const char* name : {"elmqvist2008.toml", "pilot.toml", "lens-vs-dt.toml", "screen-door-vs-dt.toml",
                           "vdt-vs-dt.toml"}) {
    const Outcome r = dtlab(std::string("validate '") + DTLAB_SOURCE_DIR + "/protocols/" + name + "'");
    EXPECT_EQ(r.rc, 0) << name << "\n" << r.err;
    EXPECT_NE(r.out.find("valid"), std::string::npos) << r.out;
    EXPECT_EQ(r.err, "") << name;
  }
  const Outcome r = dtlab(std::string("validate '") + DTLAB_SOURCE_DIR + "/protocols/elmqvist2008.toml'");
  EXPECT_NE(r.out.find("24 trials per participant"), std::string::npos) << r.out;
}

TEST(ValidateCli, BrokenProtocolExitsOneNamingLineAndField) {
  int line = 0;
  const fs::path p = edited("pilot.toml", "typo.toml", "trials = 1\ncount_range", "trails = 1\ncount_range", &line);
  const Outcome r = dtlab("validate '" + p.string() + "'");
  EXPECT_EQ(r.rc, 1);
  const std::string expected =
      p.string() + ":" + std::to_string(line) + ":1: error: scenarios.walkthrough.tasks.T4.trails: unknown key";
  EXPECT_NE(r.err.find(expected), std::string::npos) << "expected: " << expected << "\ngot:\n" << r.err;
  fs::remove(p);
}

TEST(ValidateCli, JsonListsEveryDiagnostic) {
  const fs::path p = write_temp("json.toml", "id = \"x\"\ntitle = 3\nparticipants = 0\n");
  const Outcome r = dtlab("validate --json '" + p.string() + "'");
  EXPECT_EQ(r.rc, 1);
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["valid"], false);
  EXPECT_EQ(j["file"], p.string());
  ASSERT_TRUE(j["diagnostics"].is_array());
  EXPECT_EQ(j["errors"].get<int>(), static_cast<int>(j["diagnostics"].size()));
  bool title = false, participants = false;
  for (const auto& d : j["diagnostics"]) {
    for (const char* key : {"severity", "file", "line", "column", "field", "message"})
      EXPECT_TRUE(d.contains(key)) << d.dump();
    if (d["field"] == "title") title = d["line"] == 2 && d["severity"] == "error";
    if (d["field"] == "participants") participants = d["line"] == 3;
  }
  EXPECT_TRUE(title) << r.out;
  EXPECT_TRUE(participants) << r.out;
  fs::remove(p);

  const Outcome ok = dtlab(std::string("validate --json '") + DTLAB_SOURCE_DIR + "/protocols/elmqvist2008.toml'");
  EXPECT_EQ(ok.rc, 0);
  const auto jo = nlohmann::json::parse(ok.out);
  EXPECT_EQ(jo["valid"], true);
  EXPECT_EQ(jo["summary"]["trials_per_participant"], 24);
  EXPECT_EQ(jo["summary"]["order_rows"], 4);
}

TEST(ValidateCli, BadFilesExitOneWithoutCrashing) {
  const fs::path empty = write_temp("empty.toml", "");
  std::string garbage;
  std::uint64_t x = 0x243f6a8885a308d3ULL;
  for (int i = 0; i < 4096; ++i) {
    x ^= x << 13, x ^= x >> 7, x ^= x << 17;  // xorshift64: fixed pseudo-random bytes
    garbage += static_cast<char>(x & 0xff);
  }
  const fs::path binary = write_temp("garbage.toml", garbage);
  const fs::path dir = fs::temp_directory_path();
  for (const std::string& path : {empty.string(), binary.string(), std::string("/nonexistent/p.toml"), dir.string()}) {
    const Outcome r = dtlab("validate '" + path + "'");
    EXPECT_EQ(r.rc, 1) << path << "\n" << r.err;
    EXPECT_EQ(r.err.rfind(path + ":", 0), 0u) << "stderr should start with the file name:\n" << r.err;
    EXPECT_NE(r.err.find("error:"), std::string::npos) << r.err;
  }
  fs::remove(empty);
  fs::remove(binary);
}

TEST(ValidateCli, WarningsKeepExitZero) {
  const fs::path p = edited("elmqvist2008.toml", "ten.toml", "participants = 16", "participants = 10");
  const Outcome r = dtlab("validate '" + p.string() + "'");
  EXPECT_EQ(r.rc, 0) << r.err;
  EXPECT_NE(r.err.find("warning: participants: participants = 10 is not a multiple of the 4 order rows"),
            std::string::npos)
      << r.err;
  fs::remove(p);
}

// Issue 12: protocols `dtlab validate` called valid and `dtlab simulate` then failed on (exit 3
// "environment failure") or never finished. Each is now refused by both commands with exit 1 and
// FILE:LINE:COLUMN: error: FIELD at the key at fault, before simulate creates its database.
TEST(ValidateCli, WhatASessionWouldRefuseIsInvalid) {
  struct Case {
    const char* name;
    const char* from;
    const char* to;
    const char* field;
  };
  const Case cases[] = {
      {"radius", "object_radius = [3.0, 6.0]", "object_radius = [3.0, 60.0]",
       "scenarios.abstract.tasks.T1.object_radius"},
      {"ratio", "target_ratio = [0.10, 0.20]", "target_ratio = [0.001, 0.001]",
       "scenarios.abstract.tasks.T1.target_ratio"},
      {"cell", "cell_size = 4.0", "cell_size = 3.0", "scenarios.walkthrough.tasks.T3.cell_size"},
      {"mask", "mask_resolution = 128", "mask_resolution = 4096", "rendering.on.mask_resolution"},
      {"depth", "scenario = \"walkthrough\"     # one", "scenario = \"abstract\"     # one",
       "questionnaire.depth_test.scenario"},
      {"pairs", "pairs = 3", "pairs = 20", "questionnaire.depth_test.pairs"},
  };
  for (const Case& c : cases) {
    int line = 0;
    const fs::path p = edited("elmqvist2008.toml", std::string(c.name) + ".toml", c.from, c.to, &line);
    const std::string where = p.string() + ":" + std::to_string(line) + ":";
    const Outcome v = dtlab("validate '" + p.string() + "'");
    EXPECT_EQ(v.rc, 1) << c.name << "\n" << v.err;
    EXPECT_NE(v.err.find(where), std::string::npos) << c.name << ": expected " << where << "\n" << v.err;
    EXPECT_NE(v.err.find(std::string("error: ") + c.field + ":"), std::string::npos) << c.name << "\n" << v.err;
    const fs::path db = fs::temp_directory_path() / ("dtlab_validate_cli_" + std::to_string(getpid()) + ".sqlite");
    const Outcome s = dtlab("simulate '" + p.string() + "' --participants 1 --db '" + db.string() + "'");
    EXPECT_EQ(s.rc, 1) << c.name << "\n" << s.err;
    EXPECT_NE(s.err.find(where), std::string::npos) << c.name << "\n" << s.err;
    EXPECT_FALSE(fs::exists(db)) << c.name << ": nothing may be created for a protocol that cannot run";
    fs::remove(db);
    fs::remove(p);
  }
}

// Issue 12: "1 participants". Counts agree with their noun in the summary line.
TEST(ValidateCli, SummaryCountsAgreeWithTheirNoun) {
  const fs::path p = edited("pilot.toml", "one.toml", "participants = 4 ", "participants = 1 ");
  const Outcome r = dtlab("validate '" + p.string() + "'");
  EXPECT_EQ(r.rc, 0) << r.err;
  EXPECT_NE(r.out.find("8 trials per participant, 1 participant\n"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("valid with 1 warning;"), std::string::npos) << r.out;
  fs::remove(p);
}

TEST(ValidateCli, MissingArgumentIsAUsageError) {
  const Outcome r = dtlab("validate");
  EXPECT_EQ(r.rc, 2);
}

}  // namespace

// Every command that takes a study database treats a damaged one the same
// way: a truncated file, a directory, or a file missing one of its schema's
// tables is invalid input (exit 1) with the file named, found when the
// database is opened, and nothing is written. Regression: a truncated file
// exited 3 (as if the machine were at fault), a directory exited 1, 2 or 3
// depending on the command, and a missing table was found by whichever query
// first needed it (`dtlab simulate` then left a session running).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "study/store/read.h"
#include "tests/common/run_cli.h"
#include "tests/store/store_fixtures.h"

namespace dtlab::store {
namespace {

using namespace dtlab::store::testing;
using dtlab::test::read_text;
using dtlab::test::run_dtlab;
namespace fs = std::filesystem;

const std::string kPilot = std::string(DTLAB_SOURCE_DIR) + "/protocols/pilot.toml";

TEST(DamagedDatabase, EveryCommandExitsOneAndWritesNothing) {
  TempDir dir;
  const std::string good = dir.file("good.sqlite");
  ASSERT_EQ(run_dtlab("simulate '" + kPilot + "' --participants 1 --jobs 1 --db '" + good + "'").rc, 0);
  const std::string bytes = read_text(good);
  const std::string truncated = dir.file("truncated.sqlite"), folder = dir.file("folder.sqlite"),
                    missing = dir.file("missing.sqlite");
  { std::ofstream(truncated, std::ios::binary) << bytes.substr(0, bytes.size() / 3); }
  fs::create_directories(folder);
  fs::copy_file(good, missing);
  { RawDb db(missing); ASSERT_TRUE(db.exec("DROP TABLE notes")) << db.errmsg(); }
  const std::string missing_bytes = read_text(missing);

  const std::vector<std::string> commands = {
      "export DB --csv OUT/x.csv",
      "analyze DB --out OUT/report",
      "exclude DB --participant sim-001 --reason x",
      "include DB --participant sim-001",
      "plan '" + kPilot + "' --db DB --participant sim-001",
      "replay DB --participant sim-001 --trial 1 --out OUT/replay",
      "power DB --replications 5",
      "copy DB OUT/copy.sqlite",
      "render --protocol '" + kPilot + "' --db DB --participant sim-001 --trial 1 --out OUT/r.png",
      "simulate '" + kPilot + "' --participants 2 --jobs 1 --db DB",
  };
  const std::vector<std::pair<std::string, std::string>> files = {
      {truncated, "damaged"}, {folder, "is a directory"}, {missing, "lacks the table(s) notes"}};
  for (const auto& [db, says] : files)
    for (std::string c : commands) {
      for (std::size_t at; (at = c.find("DB")) != std::string::npos;) c.replace(at, 2, "'" + db + "'");
      for (std::size_t at; (at = c.find("OUT")) != std::string::npos;) c.replace(at, 3, dir.path());
      const auto r = run_dtlab(c);
      EXPECT_EQ(r.rc, 1) << c << "\n" << r.err;
      EXPECT_NE(r.err.find(says), std::string::npos) << c << "\n" << r.err;
      EXPECT_NE(r.err.find(db), std::string::npos) << "names the file: " << c << "\n" << r.err;
    }
  EXPECT_EQ(read_text(missing), missing_bytes) << "nothing was written to the damaged study";
  EXPECT_FALSE(fs::exists(dir.file("copy.sqlite")));
}

}  // namespace
}  // namespace dtlab::store

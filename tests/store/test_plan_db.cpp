// `dtlab plan PROTOCOL --db DB --participant ID` (DB a file or a server URI):
// the index and order row come from the database's ledger, so a participant whose row was assigned
// after a release gets the plan of that row, not of index mod rows. The
// database is read, never written; an unknown participant or a database of
// another protocol exits 1 naming the file (and both hashes).
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "study/common/version.h"
#include "study/design/design.h"
#include "study/protocol/protocol.h"
#include "tests/common/run_cli.h"
#include "tests/store/store_fixtures.h"

namespace dtlab::store {
namespace {

using namespace dtlab::store::testing;

const std::string kReference = std::string(DTLAB_SOURCE_DIR) + "/protocols/elmqvist2008.toml";

StudyInfo info_of(const protocol::Protocol& p) {
  StudyInfo s;
  s.protocol_id = p.id;
  s.protocol_text = p.source_text;
  s.protocol_sha256 = p.sha256;
  s.design_sha256 = protocol::design_sha256(p);
  s.software_version = std::string(version_string());
  s.order_rows = design::order_rows(p);
  for (const auto& f : p.factors) s.factors.push_back(f.name);
  return s;
}

using Outcome = dtlab::test::CliOutcome;

Outcome dtlab(const TempDir&, const std::string& args) { return dtlab::test::run_dtlab(args); }

class PlanDb : public OnBothBackends {};
DTLAB_ON_BOTH_BACKENDS(PlanDb);

TEST_P(PlanDb, TakesIndexAndRowFromTheLedger) {
  auto p = protocol::load_protocol(kReference);
  ASSERT_TRUE(p) << p.error().to_string();
  const TempDir& dir = dir_;
  const std::string db = study();
  {
    auto s = Store::open(db, info_of(*p));
    ASSERT_TRUE(s) << s.error().to_string();
    // Rows 0 1 2 3 0; release B (row 1); F and G fill row 1 twice over (fewest, then lowest);
    // release A: row 0 holds only E, so H (index 7, 7 mod 4 = 3) gets row 0.
    for (const char* id : {"A", "B", "C", "D", "E"}) ASSERT_TRUE(s->enroll(id));
    ASSERT_TRUE(s->release("B"));
    ASSERT_EQ(s->enroll("F")->order_row, 1);
    ASSERT_EQ(s->enroll("G")->order_row, 1);
    ASSERT_TRUE(s->release("A"));
    auto h = s->enroll("H");
    ASSERT_TRUE(h);
    ASSERT_EQ(h->index, 7);
    ASSERT_EQ(h->order_row, 0);
  }
  const std::string quoted_db = "'" + db + "'";
  const Outcome r = dtlab(dir, "plan '" + kReference + "' --db " + quoted_db + " --participant H --json");
  ASSERT_EQ(r.rc, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["index"], 7);
  EXPECT_EQ(j["order_row"], 0);
  // The same trials as the design stage gives for (index 7, row 0).
  const design::Plan want = design::make_plan(*p, 7, 0);
  ASSERT_EQ(j["trials"].size(), want.trials.size());
  for (std::size_t i = 0; i < want.trials.size(); ++i) {
    EXPECT_EQ(j["trials"][i]["seed"].get<std::uint64_t>(), want.trials[i].seed);
    EXPECT_EQ(j["trials"][i]["task"], want.trials[i].task);
  }

  const Outcome unknown = dtlab(dir, "plan '" + kReference + "' --db " + quoted_db + " --participant nobody");
  EXPECT_EQ(unknown.rc, 1);
  EXPECT_NE(unknown.err.find(display_name(db)), std::string::npos) << unknown.err;
  EXPECT_NE(unknown.err.find("unknown participant \"nobody\""), std::string::npos) << unknown.err;

  const Outcome both = dtlab(dir, "plan '" + kReference + "' --index 1 --db " + quoted_db + " --participant H");
  EXPECT_EQ(both.rc, 2);  // --index excludes --db
  const Outcome neither = dtlab(dir, "plan '" + kReference + "'");
  EXPECT_EQ(neither.rc, 2);
}

TEST_P(PlanDb, RefusesADatabaseOfAnotherProtocolAndNeverWritesIt) {
  auto p = protocol::load_protocol(kReference);
  ASSERT_TRUE(p);
  const TempDir& dir = dir_;
  const std::string db = study("other");
  {
    StudyInfo other = study_info();  // the 2x2 test protocol
    auto s = Store::open(db, other);
    ASSERT_TRUE(s);
    ASSERT_TRUE(s->enroll("H"));
  }
  const auto before = pg() ? std::filesystem::file_time_type() : std::filesystem::last_write_time(db);
  const Outcome r = dtlab(dir, "plan '" + kReference + "' --db '" + db + "' --participant H");
  EXPECT_EQ(r.rc, 1);
  EXPECT_NE(r.err.find(p->sha256), std::string::npos) << r.err;
  EXPECT_NE(r.err.find(study_info().protocol_sha256), std::string::npos) << r.err;
  if (!pg()) {
    EXPECT_EQ(std::filesystem::last_write_time(db), before);
  }
  EXPECT_EQ(RawDb(db).count("SELECT count(*) FROM studies"), 1);  // nothing recorded
}

}  // namespace
}  // namespace dtlab::store

// `dtlab withdraw` as a user runs it, on both engines: the withdrawal is
// appended with who and why (the defaults: "withdrew consent", by
// $DTLAB_EXPERIMENTER), the participant's running session ends abandoned and
// the export leaves them out; a second call keeps the first; unknown
// participants, an empty reason and a file that is not a study database are
// clear errors with exit 1, a bad command line exits 2, and a session another
// process runs now exits 3 (busy) -- each leaving the database as it was.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "study/store/export.h"
#include "study/store/read.h"
#include "tests/common/run_cli.h"
#include "tests/store/store_fixtures.h"

namespace dtlab::store {
namespace {

using namespace dtlab::store::testing;
using dtlab::test::run_dtlab;

// P1 finished (4 trials), P2 running (2 trials).
std::string make_db(const std::string& path) {
  Store s = open_ok(path);
  for (const std::string id : {"P1", "P2"}) {
    auto e = s.enroll(id, {{"age", id == "P1" ? "30" : "41"}});
    const design::Plan plan = make_plan(e->index, e->order_row, 1);
    auto ses = s.begin_session(id, plan);
    const int n = id == "P1" ? 4 : 2;
    for (int i = 0; i < n; ++i) EXPECT_TRUE(s.record_trial(*ses, make_record(2, plan.trials[i], 4)));
    if (id == "P1") {
      EXPECT_TRUE(s.finish_session(*ses));
    }
    if (id == "P2") {
      EXPECT_TRUE(s.release_claim(*ses));  // the station's process quit
    }
  }
  return path;
}

class WithdrawCli : public OnBothBackends {};
DTLAB_ON_BOTH_BACKENDS(WithdrawCli);

TEST_P(WithdrawCli, RecordsTheWithdrawalAndTheExportLeavesThemOut) {
  const std::string db = make_db(study());
  const std::string q = "'" + db + "'";
  auto a = run_dtlab("withdraw " + q + " --participant P2 --json");
  ASSERT_EQ(a.rc, 0) << a.err;
  auto j = nlohmann::json::parse(a.out);
  EXPECT_EQ(j["participant"], "P2");
  EXPECT_EQ(j["reason"], "withdrew consent");  // the default
  EXPECT_EQ(j["already"], false);
  EXPECT_EQ(j["withdrawn_at"].get<std::string>().size(), 24u);
  ::setenv("DTLAB_EXPERIMENTER", "MK", 1);  // the default of --by
  auto b = run_dtlab("withdraw " + q + " --participant P1 --reason 'asked by email'");
  ::unsetenv("DTLAB_EXPERIMENTER");
  ASSERT_EQ(b.rc, 0) << b.err;
  EXPECT_NE(b.err.find("P1 withdrew"), std::string::npos) << b.err;
  auto c = run_dtlab("withdraw " + q + " --participant P1 --reason 'again' --json");  // harmless; the first stays
  ASSERT_EQ(c.rc, 0) << c.err;
  j = nlohmann::json::parse(c.out);
  EXPECT_EQ(j["already"], true);
  EXPECT_EQ(j["reason"], "asked by email");
  EXPECT_EQ(j["by"], "MK");

  auto r = StudyReader::open(db);
  ASSERT_TRUE(r);
  auto w = r->withdrawals();
  ASSERT_EQ(w->size(), 2u);
  EXPECT_EQ((*w)[0].participant, "P1");  // by enrollment index
  EXPECT_EQ((*w)[0].by, "MK");
  auto sessions = r->sessions();
  EXPECT_EQ((*sessions)[0].status, SessionStatus::finished);
  EXPECT_EQ((*sessions)[1].status, SessionStatus::abandoned);
  EXPECT_TRUE((*sessions)[0].withdrawn && (*sessions)[1].withdrawn);
  const std::string csv = dir_.file("t.csv");
  auto x = run_dtlab("export " + q + " --csv '" + csv + "' --json");
  ASSERT_EQ(x.rc, 0) << x.err;
  j = nlohmann::json::parse(x.out);
  EXPECT_EQ(j["rows"], 0);
  EXPECT_EQ(j["withdrawn_participants"], 2);
  EXPECT_EQ(j["withdrawn_rows_left_out"], 6);
}

TEST_P(WithdrawCli, BadRequestsAreClearErrorsAndChangeNothing) {
  const std::string db = make_db(study());
  const std::string q = "'" + db + "'";
  struct Case {
    std::string args;
    int rc;
    const char* says;
  };
  const std::vector<Case> cases = {
      {"withdraw " + q + " --participant nobody", 1, "unknown participant \"nobody\""},
      {"withdraw " + q + " --participant P1 --reason '   '", 1, "needs a reason"},
      {"withdraw " + q, 2, "--participant"},
      {"withdraw " + q + " --participant " + std::string(65, 'x'), 2, "at most 64"},
      {"withdraw '" + dir_.file("missing.sqlite") + "' --participant P1", 1, "no such file"},
  };
  for (const Case& c : cases) {
    const auto out = run_dtlab(c.args);
    EXPECT_EQ(out.rc, c.rc) << c.args << "\n" << out.err;
    EXPECT_NE(out.err.find(c.says), std::string::npos) << c.args << "\n" << out.err;
  }
  EXPECT_FALSE(std::filesystem::exists(dir_.file("missing.sqlite")));
  const std::string junk = dir_.file("junk.sqlite");
  std::ofstream(junk) << std::string(4096, 'j');
  const auto j = run_dtlab("withdraw '" + junk + "' --participant P1");
  EXPECT_EQ(j.rc, 1) << j.err;
  EXPECT_EQ(dtlab::test::read_text(junk), std::string(4096, 'j'));
  // A session another live process runs: busy (exit 3), stop it first.
  {
    RawDb raw(db);
    ASSERT_TRUE(raw.exec("INSERT INTO session_claims (session_id, owner, host, pid, claimed_at, heartbeat_at, "
                         "expires_at) SELECT s.id, 'elsewhere', 'station-9', 1, '2030-01-01T00:00:00.000Z', "
                         "'2030-01-01T00:00:00.000Z', '2999-01-01T00:00:00.000Z' FROM sessions s WHERE "
                         "s.status = 'running'"))
        << raw.errmsg();
  }
  const auto busy = run_dtlab("withdraw " + q + " --participant P2");
  EXPECT_EQ(busy.rc, 3) << busy.err;
  EXPECT_NE(busy.err.find("being run by process"), std::string::npos) << busy.err;
  auto r = StudyReader::open(db);
  EXPECT_TRUE(r->withdrawals()->empty());
  EXPECT_EQ((*r->sessions())[1].status, SessionStatus::running);
}

}  // namespace
}  // namespace dtlab::store

// A lab with several testing stations on one database: four processes (four
// "stations", each with its own connection) enroll participants and run their
// sessions side by side. No ledger slot is given twice, every order row of the
// Latin square is filled evenly, every planned trial is recorded once. Then
// the same with four `dtlab simulate` processes on the PostgreSQL server, as a
// lab runs them, and the server's study copied to a file exports the same.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>

#include "study/store/copy.h"
#include "study/store/export.h"
#include "study/store/read.h"
#include "tests/common/light_pilot.h"
#include "tests/common/run_cli.h"
#include "tests/store/store_fixtures.h"

namespace dtlab::store {
namespace {

using namespace dtlab::store::testing;

constexpr int kStations = 4;
constexpr int kEach = 4;  // participants per station

// One station: enrolls its participants one by one and runs each session to the end.
int station(const std::string& where, int k) {
  OpenOptions o;
  o.busy_timeout_ms = 30000;
  auto s = Store::open(where, study_info(), o);
  if (!s) {
    std::fprintf(stderr, "station %d: %s\n", k, s.error().to_string().c_str());
    return 1;
  }
  for (int i = 0; i < kEach; ++i) {
    const std::string id = "st" + std::to_string(k) + "-" + std::to_string(i);
    auto e = s->enroll(id);
    if (!e) return 2;
    auto ses = s->begin_session(id, make_plan(e->index, e->order_row, 1));
    if (!ses) return 3;
    for (;;) {
      auto t = s->next_trial(*ses);
      if (!t) return 4;
      if (!*t) break;
      if (!s->begin_trial(*ses, (*t)->position)) return 5;
      if (auto r = s->record_trial(*ses, make_record(static_cast<std::uint64_t>(e->index), **t, 40)); !r) {
        std::fprintf(stderr, "station %d: %s\n", k, r.error().to_string().c_str());
        return 6;
      }
    }
    if (!s->finish_session(*ses)) return 7;
  }
  return 0;
}

class Stations : public OnBothBackends {};
DTLAB_ON_BOTH_BACKENDS(Stations);

TEST_P(Stations, FourStationsFillEveryOrderRowEvenlyAndNeverShareASlot) {
  const std::string where = study("lab");  // created by whichever station comes first
  EXPECT_EQ(race(kStations, [&](int k) { return station(where, k); }), std::vector<int>(kStations, 0))
      << "station exit codes";

  RawDb db(where);
  const int total = kStations * kEach;
  EXPECT_EQ(db.count("SELECT count(*) FROM participants"), total);
  EXPECT_EQ(db.count("SELECT count(DISTINCT enrollment_index) FROM participants"), total);  // no slot twice
  EXPECT_EQ(db.count("SELECT max(enrollment_index) FROM participants"), total - 1);         // and no gap
  EXPECT_EQ(joined(db, "SELECT count(*) FROM participants GROUP BY order_row ORDER BY order_row"), "4,4,4,4");
  EXPECT_EQ(db.count("SELECT count(*) FROM participants WHERE order_row <> enrollment_index % 4"), 0);
  EXPECT_EQ(db.count("SELECT count(*) FROM sessions WHERE status = 'finished'"), total);
  EXPECT_EQ(db.count("SELECT count(*) FROM trial_results"), total * 4);  // every planned trial once
  EXPECT_EQ(db.count("SELECT count(*) FROM trial_attempts"), total * 4);  // and run once
  EXPECT_EQ(db.count("SELECT count(*) FROM session_claims"), 0);
  EXPECT_EQ(db.integrity(), "ok");
  // Each session holds the plan of its own slot (seeds from its own index).
  auto r = StudyReader::open(where);
  ASSERT_TRUE(r);
  auto ledger = r->ledger();
  for (const auto& e : *ledger) {
    auto planned = r->planned(e.participant);
    ASSERT_EQ(planned->size(), 4u);
    const design::Plan want = make_plan(e.index, e.order_row, 1);
    for (std::size_t i = 0; i < 4; ++i) EXPECT_TRUE(same_trial((*planned)[i].trial, want.trials[i])) << e.participant;
  }
}

std::string slurp(const std::string& path) { return dtlab::test::read_text(path); }

// As a lab runs it: four `dtlab simulate` processes on one server, sharing eight participants of
// the pilot (lighter scenes: the stations, not the rendering, are under test).
TEST(PgStations, FourSimulateProcessesOnOneServer) {
  DTLAB_SKIP_WITHOUT_SERVER(Backend::postgresql);
  TempDir dir;
  const std::string where = new_study(Backend::postgresql, dir.path(), "pilot");
  const std::string text = dtlab::test::light_pilot_text();
  ASSERT_FALSE(text.empty()) << "protocols/pilot.toml no longer has the lines light_pilot_text() lightens";
  const std::string protocol = dir.file("pilot-light.toml");
  std::ofstream(protocol) << text;
  std::string script;
  for (int k = 0; k < kStations; ++k) {
    const std::string out = dir.file("station" + std::to_string(k));
    script += "('" + std::string(DTLAB_BINARY) + "' simulate '" + protocol + "' --participants 8 --db '" + where +
              "' --width 48 --height 36 --json >'" + out + ".json' 2>'" + out + ".err'; echo $? >'" + out + ".rc') & ";
  }
  ASSERT_EQ(std::system(("/bin/sh -c \"" + script + "wait\"").c_str()), 0);
  long long trials_run = 0;
  for (int k = 0; k < kStations; ++k) {
    const std::string out = dir.file("station" + std::to_string(k));
    ASSERT_EQ(slurp(out + ".rc"), "0\n") << slurp(out + ".err");
    const std::string json = slurp(out + ".json");
    const auto j = nlohmann::json::parse(json.substr(json.rfind("\n{") + 1));
    trials_run += j["trials_run"].get<long long>();
    EXPECT_TRUE(j["failed"].empty()) << json;
    EXPECT_EQ(j["database"].get<std::string>().find("password"), std::string::npos);
  }
  auto r = StudyReader::open(where);
  ASSERT_TRUE(r) << r.error().to_string();
  auto sessions = r->sessions();
  ASSERT_EQ(sessions->size(), 8u);
  for (const auto& s : *sessions) {
    EXPECT_EQ(s.status, SessionStatus::finished) << s.participant;
    EXPECT_TRUE(s.resumes.empty()) << s.participant << " was resumed: two stations ran it";
  }
  std::map<int, int> per_row;
  std::set<int> slots;
  auto ledger = r->ledger();
  ASSERT_TRUE(ledger);
  for (const auto& e : *ledger) {
    ++per_row[e.order_row];
    EXPECT_TRUE(slots.insert(e.index).second) << "slot " << e.index << " given twice";
  }
  EXPECT_EQ(per_row, (std::map<int, int>{{0, 2}, {1, 2}, {2, 2}, {3, 2}}));
  EXPECT_EQ(static_cast<long long>(r->trials()->size()), trials_run) << "every trial run exactly once";
  // The lab archives the study in a file: the export is the same bytes.
  const std::string archive = dir.file("pilot.sqlite");
  ASSERT_TRUE(copy_study(where, archive));
  std::ostringstream a, b;
  ASSERT_TRUE(export_trials_csv(where, a));
  ASSERT_TRUE(export_trials_csv(archive, b));
  EXPECT_EQ(a.str(), b.str());
}

}  // namespace
}  // namespace dtlab::store

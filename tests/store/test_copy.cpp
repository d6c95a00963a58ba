// `dtlab copy` and store::copy_study: a whole study from one engine to the
// other and back, every row of every table as it was (compared through the
// engines' own C APIs) and the exports byte-identical; and merging a
// station's offline file into a database that holds the study already: what
// may be added is added, a participant never started takes the next free
// ledger slot, and everything that would change data is refused with a
// message saying what, leaving DST exactly as it was.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <charconv>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <sstream>

#include "study/store/copy.h"
#include "study/store/export.h"
#include "study/store/read.h"
#include "tests/common/run_cli.h"
#include "tests/store/store_fixtures.h"

namespace dtlab::store {
namespace {

using namespace dtlab::store::testing;

// The display of a station's window (schema v3), with a monitor name CSV and SQL would quote.
const DisplayInfo kWindow{"window", 1920, 1080, 143.98, "4.6 (Core Profile) Mesa 22.3.6 / llvmpipe", "DELL U2720Q, \"left\""};

// Runs one participant's session on kWindow: `n` trials recorded (all: finished), with an
// interrupted attempt and a pause in trial 2; every other trial knows the display's refresh rate.
void run_participant(Store& s, const std::string& id, int n, Demographics demo = {}) {
  auto e = s.enroll(id, demo);
  ASSERT_TRUE(e) << e.error().to_string();
  const design::Plan plan = make_plan(e->index, e->order_row, 1);
  auto ses = s.begin_session(id, plan);
  ASSERT_TRUE(ses) << ses.error().to_string();
  ASSERT_TRUE(s.record_display(*ses, kWindow));
  for (int i = 0; i < n; ++i) {
    const auto& t = plan.trials[static_cast<std::size_t>(i)];
    ASSERT_TRUE(s.begin_trial(*ses, t.position));
    if (i == 1) {
      ASSERT_TRUE(s.begin_trial(*ses, t.position));  // the first attempt reads as interrupted
      ASSERT_TRUE(s.record_pause(*ses, t.position, at_ms(1'700'000'500'000), at_ms(1'700'000'507'250)));
    }
    const std::optional<double> hz = i % 2 ? std::nullopt : kWindow.refresh_hz;
    ASSERT_TRUE(s.record_trial(*ses, make_record(static_cast<std::uint64_t>(e->index) + 3, t, 7 + i, hz)));
  }
  if (n == static_cast<int>(plan.trials.size())) {
    ASSERT_TRUE(s.finish_session(*ses));
    ASSERT_TRUE(s.record_questionnaire(*ses, {{"rating", "transparency=on", 4.0}, {"comment", "", std::string("ok, \"fine\"")}}));
  }
}

// A study with everything a study holds: two protocol texts of one design, finished, running,
// resumed and released sessions, a participant never started, exclusions and an inclusion, notes,
// the displays sessions ran on and frame times with and without the display's refresh rate.
void write_rich_study(const std::string& where) {
  StudyInfo a = study_info("id = \"test2x2\"\n# first wording\n");
  a.design_sha256 = std::string(64, 'd');
  StudyInfo b = study_info("id = \"test2x2\"\n# second wording\n");
  b.design_sha256 = a.design_sha256;
  {
    Store s = open_ok(where, a);
    run_participant(s, "P1", 4, {{"age", "31"}, {"hand", "left"}});
    run_participant(s, "P2", 2);
    run_participant(s, "P,3 \"q\"", 1);
    ASSERT_TRUE(s.release("P,3 \"q\""));
  }
  Store s = open_ok(where, b);  // a reworded protocol: a second study row, same design
  auto e = s.lookup("P2");
  auto ses = s.begin_session("P2", make_plan(e->index, e->order_row, 1));  // resumed
  ASSERT_TRUE(ses && ses->resumed);
  ASSERT_TRUE(s.record_display(*ses, DisplayInfo{"headless", 800, 600, std::nullopt, "OSMesa", ""}));
  ASSERT_TRUE(s.record_trial(*ses, make_record(9, **s.next_trial(*ses), 3)));
  ASSERT_TRUE(s.release_claim(*ses));
  run_participant(s, "P4", 4);
  ASSERT_TRUE(s.enroll("P5", {{"simulated", "true"}}));  // never started
  ASSERT_TRUE(s.exclude("P1", std::nullopt, "misunderstood", "RA"));
  ASSERT_TRUE(s.include("P1", std::nullopt, "", "PI"));
  ASSERT_TRUE(s.exclude("P4", 3, "fire alarm", "RA"));
  ASSERT_TRUE(s.add_note("P1", 2, "RA", "sneezed"));
  ASSERT_TRUE(s.add_note("", std::nullopt, "PI", "room too warm"));
}

// Every table of the schema with an order that is the same on both engines.
const std::vector<std::pair<std::string, std::string>> kTables = {
    {"schema_migrations", "version"},
    {"studies", "id"},
    {"study_factors", "study_id, position"},
    {"study_designs", "study_id"},
    {"participants", "id"},
    {"sessions", "id"},
    {"session_resumes", "session_id, resumed_at"},
    {"planned_trials", "id"},
    {"planned_levels", "planned_trial_id, factor_position"},
    {"trial_results", "planned_trial_id"},
    {"input_events", "trial_id, seq"},
    {"camera_poses", "trial_id, frame"},
    {"questionnaire_answers", "session_id, item, scope"},
    {"exclusions", "id"},
    {"notes", "id"},
    {"session_pauses", "session_id, paused_at"},
    {"trial_attempts", "session_id, position, attempt"},
    {"session_displays", "session_id, recorded_at, kind"},
};

// A table's rows with every real spelled the same way on both engines (17 significant digits).
std::vector<std::vector<std::string>> table(RawDb& db, const std::string& name, const std::string& order) {
  auto rows = db.rows("SELECT * FROM " + name + " ORDER BY " + order);
  for (auto& row : rows)
    for (std::string& v : row) {
      if (v.find_first_of(".eE") == std::string::npos || v.find_first_not_of("0123456789.eE+-") != std::string::npos)
        continue;
      double d = 0;
      if (std::from_chars(v.data(), v.data() + v.size(), d).ec != std::errc()) continue;
      char buf[40];
      std::snprintf(buf, sizeof buf, "%.17g", d);
      v = buf;
    }
  return rows;
}

std::string exported(const std::string& where) {
  std::ostringstream out;
  auto sum = export_trials_csv(where, out);
  EXPECT_TRUE(sum) << sum.error().to_string();
  return out.str();
}

// Parameter: the engine of the source; the copy goes to the other engine and back.
class Copy : public OnBothBackends {
 protected:
  void SetUp() override {
    OnBothBackends::SetUp();
    DTLAB_SKIP_WITHOUT_SERVER(Backend::postgresql);  // a copy between engines needs both
  }
  std::string other(const std::string& name) const {
    return new_study(pg() ? Backend::sqlite : Backend::postgresql, dir_.path(), name);
  }
};
DTLAB_ON_BOTH_BACKENDS(Copy);

TEST_P(Copy, EveryRowOfEveryTableToTheOtherEngineAndBack) {
  const std::string src = study("src"), there = other("there"), back = study("back");
  write_rich_study(src);
  auto first = copy_study(src, there);
  ASSERT_TRUE(first) << first.error().to_string();
  EXPECT_FALSE(first->merged);
  EXPECT_EQ(first->participants, 5);
  EXPECT_EQ(first->trials, 4 + 3 + 1 + 4);
  auto second = copy_study(there, back);
  ASSERT_TRUE(second) << second.error().to_string();

  RawDb a(src), b(there), c(back);
  for (const auto& [name, order] : kTables) {
    const auto want = table(a, name, order);
    EXPECT_FALSE(want.empty()) << name << ": the study should exercise every table";
    EXPECT_EQ(table(b, name, order), want) << name << " differs after the copy to the other engine";
    EXPECT_EQ(table(c, name, order), want) << name << " differs after the copy back";
  }
  EXPECT_EQ(b.integrity(), "ok");
  EXPECT_EQ(c.integrity(), "ok");
  // The export is the same bytes from all three, and the copies behave as studies: a reader sees
  // the resumed session, the interruption, the pause and the decisions.
  const std::string csv = exported(src);
  EXPECT_EQ(exported(there), csv);
  EXPECT_EQ(exported(back), csv);
  auto r = StudyReader::open(there);
  ASSERT_TRUE(r);
  auto sessions = r->sessions();
  ASSERT_EQ(sessions->size(), 4u);
  EXPECT_EQ((*sessions)[1].resumes.size(), 1u);
  EXPECT_EQ((*sessions)[0].interruptions.size(), 1u);
  EXPECT_DOUBLE_EQ((*sessions)[0].paused_s(), 7.25);
  EXPECT_EQ((*sessions)[2].status, SessionStatus::abandoned);
  ASSERT_EQ((*sessions)[1].displays.size(), 2u);  // the start and the resume
  EXPECT_EQ((*sessions)[1].displays[0].info.monitor, kWindow.monitor);
  EXPECT_EQ((*sessions)[1].displays[0].info.refresh_hz, kWindow.refresh_hz);
  EXPECT_EQ((*sessions)[1].displays[1].info.kind, "headless");
  EXPECT_FALSE((*sessions)[1].displays[1].info.refresh_hz);
  auto trials = r->trials("P1");
  ASSERT_EQ(trials->size(), 4u);
  EXPECT_EQ((*trials)[0].frames.refresh_hz, kWindow.refresh_hz);
  EXPECT_FALSE((*trials)[1].frames.refresh_hz);
  EXPECT_TRUE((*trials)[1].frames.first_ms && (*trials)[1].frames.late);
  // And the copy is a study one can go on writing to: P5 starts there.
  Store s = open_ok(there, study_info("id = \"test2x2\"\n# second wording\n"));
  auto e = s.lookup("P5");
  ASSERT_TRUE(e);
  EXPECT_TRUE(s.begin_session("P5", make_plan(e->index, e->order_row, 1)));
}

TEST_P(Copy, RefusesTheSameDatabaseAndWhatIsNotAStudy) {
  const std::string src = study("src");
  write_rich_study(src);
  auto same = copy_study(src, src);
  ASSERT_FALSE(same);
  EXPECT_EQ(same.error().kind, ErrorKind::invalid_input);
  EXPECT_NE(same.error().message.find("same database"), std::string::npos) << same.error().to_string();
  auto missing = copy_study(dir_.file("missing.sqlite"), other("x"));
  ASSERT_FALSE(missing);
  EXPECT_EQ(missing.error().kind, ErrorKind::not_found);
  const std::string junk = dir_.file("junk.sqlite");
  std::ofstream(junk) << std::string(4096, 'j');
  auto into_junk = copy_study(src, junk);
  ASSERT_FALSE(into_junk);
  EXPECT_EQ(dtlab::test::read_text(junk), std::string(4096, 'j'));  // untouched
  // A failed copy into a new file leaves no file behind.
  const std::string fresh = dir_.file("fresh.sqlite");
  auto from_junk = copy_study(junk, fresh);
  ASSERT_FALSE(from_junk);
  EXPECT_FALSE(std::filesystem::exists(fresh));
}

// --- merging ---------------------------------------------------------------------------

// Parameter: the engine of DST (the lab's database); the station's file is SQLite.
class Merge : public OnBothBackends {};
DTLAB_ON_BOTH_BACKENDS(Merge);

// Everything in a database, for "nothing was written".
std::vector<std::vector<std::vector<std::string>>> dump(const std::string& where) {
  RawDb db(where);
  std::vector<std::vector<std::vector<std::string>>> out;
  for (const auto& [name, order] : kTables) out.push_back(table(db, name, order));
  return out;
}

// The lab's server before a station goes offline: `n` participants P1.. finished, rows 0..n-1.
std::string lab_with(const std::string& where, int n = 3) {
  Store s = open_ok(where);
  for (int i = 1; i <= n; ++i) run_participant(s, "P" + std::to_string(i), 4);
  return where;
}

TEST_P(Merge, AStationsOfflineParticipantsJoinTheLab) {
  const std::string lab = lab_with(study("lab"));
  const std::string station = dir_.file("station.sqlite");
  ASSERT_TRUE(copy_study(lab, station));  // the station takes the study with it
  {
    Store s = open_ok(station);
    ASSERT_TRUE(s.enroll("S0"));            // slot 3 at the station, never started
    run_participant(s, "S1", 4);            // slot 4: ran the plan of slot 4
    ASSERT_TRUE(s.add_note("S1", 1, "RA", "station 2, offline"));
  }
  {
    Store s = open_ok(lab);                 // meanwhile the lab enrolls Q1 into slot 3
    ASSERT_TRUE(s.enroll("Q1"));
    ASSERT_TRUE(s.exclude("P2", std::nullopt, "left early", "PI"));
  }
  auto sum = copy_study(station, lab);
  ASSERT_TRUE(sum) << sum.error().to_string();
  EXPECT_TRUE(sum->merged);
  EXPECT_EQ(sum->participants, 2);
  EXPECT_EQ(sum->renumbered, 1);
  EXPECT_EQ(sum->unchanged, 3);
  EXPECT_EQ(sum->trials, 4);
  EXPECT_EQ(sum->notes, 1);
  ASSERT_EQ(sum->changes.size(), 1u);
  EXPECT_NE(sum->changes[0].find("\"S0\""), std::string::npos) << sum->changes[0];

  auto r = StudyReader::open(lab);
  ASSERT_TRUE(r);
  auto ledger = r->ledger();
  ASSERT_EQ(ledger->size(), 6u);
  std::map<std::string, std::pair<int, int>> slot;
  for (const auto& e : *ledger) slot[e.participant] = {e.index, e.order_row};
  EXPECT_EQ(slot["Q1"], std::make_pair(3, 3));
  EXPECT_EQ(slot["S1"], std::make_pair(4, 0));  // kept: its trials were planned from slot 4
  EXPECT_EQ(slot["S0"].first, 5);               // the next free slot ...
  EXPECT_EQ(slot["S0"].second, 1);              // ... and the row the rule gives (row 0 holds two)
  for (std::size_t i = 0; i < ledger->size(); ++i) EXPECT_EQ((*ledger)[i].index, static_cast<int>(i));
  // S1's trials are the station's, value for value.
  auto at_lab = r->trials("S1");
  auto st = StudyReader::open(station);
  auto at_station = st->trials("S1");
  ASSERT_EQ(at_lab->size(), 4u);
  ASSERT_EQ(at_station->size(), 4u);
  for (std::size_t i = 0; i < 4; ++i) {
    EXPECT_TRUE(same_trial((*at_lab)[i].planned, (*at_station)[i].planned));
    EXPECT_EQ((*at_lab)[i].completion_s, (*at_station)[i].completion_s);
    EXPECT_EQ((*at_lab)[i].scene_hash, (*at_station)[i].scene_hash);
  }
  EXPECT_EQ(r->poses("S1", 2)->size(), st->poses("S1", 2)->size());
  EXPECT_EQ(r->exclusions()->size(), 1u);  // the lab's decision stays
  EXPECT_EQ(*r->integrity_check(), "ok");
  r = Result<StudyReader>(Error{});

  // Merging the same file again adds nothing and changes nothing.
  const auto before = dump(lab);
  auto again = copy_study(station, lab);
  ASSERT_TRUE(again) << again.error().to_string();
  EXPECT_EQ(again->participants, 0);
  EXPECT_EQ(again->unchanged, 5);
  EXPECT_EQ(dump(lab), before);
}

TEST_P(Merge, RefusesWhatWouldChangeDataAndWritesNothing) {
  struct Case {
    const char* name;
    void (*station)(const std::string& station_file);  // what the station did offline
    void (*lab)(const std::string& lab);                // what the lab did meanwhile
    const char* says;
  };
  const Case cases[] = {
      {"another design",
       [](const std::string& f) {
         StudyInfo other = study_info("id = \"test2x2\"\n# changed what runs\n");
         other.design_sha256 = std::string(64, 'e');
         OpenOptions allow;
         allow.allow_protocol_change = true;
         Store s = open_ok(f, other, allow);
         run_participant(s, "S1", 4);
       },
       [](const std::string&) {}, "another design"},
      {"a slot the lab gave away",
       [](const std::string& f) {
         Store s = open_ok(f);
         run_participant(s, "S1", 2);
       },
       [](const std::string& lab) {
         Store s = open_ok(lab);
         ASSERT_TRUE(s.enroll("Q1"));
       },
       "which DST gives to participant \"Q1\""},
      {"one participant, two sessions",
       [](const std::string& f) {
         Store s = open_ok(f);
         run_participant(s, "S1", 1);
       },
       [](const std::string& lab) {
         Store s = open_ok(lab);
         run_participant(s, "S1", 2);
       },
       "\"S1\" is in both"},
      {"diverging decisions",
       [](const std::string& f) {
         Store s = open_ok(f);
         ASSERT_TRUE(s.exclude("P1", std::nullopt, "at the station", "RA"));
       },
       [](const std::string& lab) {
         Store s = open_ok(lab);
         ASSERT_TRUE(s.exclude("P1", std::nullopt, "at the lab", "PI"));
       },
       "decisions about participant \"P1\""},
      {"a session running now",
       [](const std::string& f) {
         // A claim that has not expired, left as a live station process leaves it.
         Store s = open_ok(f);
         auto e = s.enroll("S1");
         ASSERT_TRUE(s.begin_session("S1", make_plan(e->index, e->order_row, 1)));
         RawDb db(f);
         ASSERT_TRUE(db.exec("UPDATE session_claims SET owner = 'elsewhere', host = 'station-9', "
                             "expires_at = '2999-01-01T00:00:00.000Z'")) << db.errmsg();
       },
       [](const std::string&) {}, "being run now"},
  };
  int n = 0;
  for (const Case& c : cases) {
    const std::string lab = lab_with(study("lab" + std::to_string(n)), 1);
    const std::string station = dir_.file("station" + std::to_string(n++) + ".sqlite");
    ASSERT_TRUE(copy_study(lab, station));
    c.station(station);
    c.lab(lab);
    const auto before = dump(lab);
    auto refused = copy_study(station, lab);
    ASSERT_FALSE(refused) << c.name;
    EXPECT_EQ(refused.error().kind, ErrorKind::conflict) << c.name;
    EXPECT_NE(refused.error().message.find(c.says), std::string::npos) << c.name << ": " << refused.error().to_string();
    EXPECT_EQ(dump(lab), before) << c.name << ": a refused merge wrote to DST";
  }
}

// Turns a SQLite study file into what a dtlab of schema v2 wrote: without the v3 columns and table,
// header and migration history at v2 (the trial_table view is left out: a copy never reads it).
void downgrade_to_v2(const std::string& file) {
  RawDb db(file);
  for (const char* sql : {"DROP VIEW trial_table", "DROP TABLE session_displays",
                          "ALTER TABLE trial_results DROP COLUMN frame_first_ms",
                          "ALTER TABLE trial_results DROP COLUMN frame_ms_median",
                          "ALTER TABLE trial_results DROP COLUMN late_frames",
                          "ALTER TABLE trial_results DROP COLUMN refresh_hz",
                          "DELETE FROM schema_migrations WHERE version = 3", "PRAGMA user_version = 2"})
    ASSERT_TRUE(db.exec(sql)) << sql << ": " << db.errmsg();
}

// A station's file of schema v2 (recorded before the display timing existed) copies into an
// empty database of either engine, which gets schema v3 with the v3 columns NULL, and merges into
// a lab whose sessions have v3 data: the sessions both hold compare on what v2 records.
TEST_P(Merge, AFileOfSchemaV2CopiesAndMerges) {
  const std::string lab = lab_with(study("lab"));
  const std::string station = dir_.file("station.sqlite");
  ASSERT_TRUE(copy_study(lab, station));
  {
    Store s = open_ok(station);
    run_participant(s, "S1", 4);
  }
  downgrade_to_v2(station);

  const std::string fresh = study("fresh");
  auto full = copy_study(station, fresh);
  ASSERT_TRUE(full) << full.error().to_string();
  EXPECT_EQ(full->trials, 16);
  EXPECT_EQ(exported(fresh), exported(station));
  {
    RawDb from(station), to(fresh);
    EXPECT_EQ(to.header().second, "3");
    EXPECT_EQ(joined(to, "SELECT version FROM schema_migrations ORDER BY version"), "1,2,3");
    auto history = table(to, "schema_migrations", "version");  // SRC's v1 and v2 rows as they were, then v3
    ASSERT_EQ(history.size(), 3u);
    history.pop_back();
    EXPECT_EQ(history, table(from, "schema_migrations", "version"));
    for (const auto& [name, order] : kTables)
      if (name != "trial_results" && name != "session_displays" && name != "schema_migrations")
        EXPECT_EQ(table(to, name, order), table(from, name, order)) << name;
    EXPECT_EQ(to.count("SELECT count(*) FROM trial_results"), 16);
    EXPECT_EQ(to.count("SELECT count(*) FROM trial_results WHERE frame_first_ms IS NOT NULL OR frame_ms_median IS NOT "
                       "NULL OR late_frames IS NOT NULL OR refresh_hz IS NOT NULL"),
              0);
    EXPECT_EQ(to.count("SELECT count(*) FROM session_displays"), 0);
    EXPECT_EQ(to.integrity(), "ok");
  }

  auto merged = copy_study(station, lab);
  ASSERT_TRUE(merged) << merged.error().to_string();
  EXPECT_TRUE(merged->merged);
  EXPECT_EQ(merged->participants, 1);
  EXPECT_EQ(merged->unchanged, 3);
  auto r = StudyReader::open(lab);
  ASSERT_TRUE(r);
  auto s1 = r->trials("S1");
  auto p1 = r->trials("P1");
  ASSERT_EQ(s1->size(), 4u);
  EXPECT_FALSE((*s1)[0].frames.first_ms || (*s1)[0].frames.late || (*s1)[0].frames.refresh_hz);
  EXPECT_TRUE((*p1)[0].frames.first_ms && (*p1)[0].frames.refresh_hz);
  auto sessions = r->sessions();
  ASSERT_EQ(sessions->size(), 4u);
  EXPECT_EQ((*sessions)[0].displays.size(), 1u);  // P1's, recorded at the lab
  EXPECT_TRUE((*sessions)[3].displays.empty());   // S1's: the station's v2 file had none
  EXPECT_EQ(*r->integrity_check(), "ok");

  // And the station's dtlab, updated, opens the file at v3.
  { Store s = open_ok(station); }
  RawDb db(station);
  EXPECT_EQ(db.header().second, "3");
  EXPECT_EQ(db.count("SELECT count(*) FROM trial_table"), 16);
}

// The command line: JSON summary, exit codes.
TEST_P(Merge, CommandLineCopiesAndReportsRefusals) {
  const std::string lab = lab_with(study("lab"));
  const std::string archive = dir_.file("archive.sqlite");
  auto ok = dtlab::test::run_dtlab("copy '" + lab + "' '" + archive + "' --json");
  ASSERT_EQ(ok.rc, 0) << ok.err;
  const auto j = nlohmann::json::parse(ok.out);
  EXPECT_EQ(j["participants"], 3);
  EXPECT_EQ(j["merged"], false);
  EXPECT_EQ(j["rows"]["trial_results"], 12);
  EXPECT_EQ(j["destination"], archive);
  EXPECT_EQ(exported(archive), exported(lab));
  auto same = dtlab::test::run_dtlab("copy '" + archive + "' '" + archive + "'");
  EXPECT_EQ(same.rc, 1) << same.err;
  {
    Store s = open_ok(lab);
    ASSERT_TRUE(s.enroll("Q1"));
  }
  {
    Store s = open_ok(archive);
    run_participant(s, "S1", 1);
  }
  auto refused = dtlab::test::run_dtlab("copy '" + archive + "' '" + lab + "'");
  EXPECT_EQ(refused.rc, 1) << refused.err;
  EXPECT_NE(refused.err.find("nothing was written"), std::string::npos) << refused.err;
  auto usage = dtlab::test::run_dtlab("copy '" + lab + "'");
  EXPECT_EQ(usage.rc, 2);
}

}  // namespace
}  // namespace dtlab::store

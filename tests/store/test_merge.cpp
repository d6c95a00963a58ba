// Merging a station's offline file into a database that holds the study
// already (`dtlab copy` into a non-empty DST): what may be added is added, a
// participant never started takes the next free ledger slot, consent,
// withdrawal and the screen log join the lab (a withdrawal with its effects),
// a file of an older schema merges, and everything that would change data is
// refused with a message saying what, leaving DST exactly as it was.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <map>

#include "study/store/copy.h"
#include "study/store/read.h"
#include "tests/common/run_cli.h"
#include "tests/store/copy_fixtures.h"

namespace dtlab::store {
namespace {

using namespace dtlab::store::testing;

// Parameter: the engine of DST (the lab's database); the station's file is SQLite.
class Merge : public OnBothBackends {};
DTLAB_ON_BOTH_BACKENDS(Merge);

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
    void (*before)(const std::string& lab) = nullptr;   // what the lab held before the station took its copy
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
      {"two answers on the consent page",
       [](const std::string& f) {
         Store s = open_ok(f);
         ASSERT_TRUE(s.record_consent("P1", {}, true, kConsentText));
       },
       [](const std::string& lab) {
         Store s = open_ok(lab);
         ASSERT_TRUE(s.record_consent("P1", {}, false, kConsentText));
       },
       "answered the consent page differently"},
      {"two withdrawals",
       [](const std::string& f) {
         Store s = open_ok(f);
         ASSERT_TRUE(s.withdraw("P1", "told the station", "RA"));
       },
       [](const std::string& lab) {
         Store s = open_ok(lab);
         ASSERT_TRUE(s.withdraw("P1", "wrote to the lab", "PI"));
       },
       "one withdrawal per participant"},
      {"screen logs that fork",
       [](const std::string& f) {
         Store s = open_ok(f);
         ASSERT_TRUE(s.record_screen(*s.session("P1"), {"page thanks", "a", at_ms(0), at_ms(1), std::nullopt}));
       },
       [](const std::string& lab) {
         Store s = open_ok(lab);
         ASSERT_TRUE(s.record_screen(*s.session("P1"), {"page thanks", "b", at_ms(0), at_ms(1), std::nullopt}));
       },
       "screen logs of participant \"P1\"'s session differ at screen 3"},
      {"a session of someone who withdrew in DST",
       [](const std::string& f) {
         Store s = open_ok(f);
         run_participant(s, "S1", 2);
       },
       [](const std::string& lab) {
         Store s = open_ok(lab);
         ASSERT_TRUE(s.withdraw("S1", "withdrew consent", "PI"));
       },
       "withdrew their consent in DST",
       [](const std::string& lab) {
         Store s = open_ok(lab);
         ASSERT_TRUE(s.enroll("S1"));
       }},
      {"a withdrawal of a session DST runs now",
       [](const std::string& f) {
         Store s = open_ok(f);
         ASSERT_TRUE(s.withdraw("S1", "withdrew consent", "RA"));
       },
       [](const std::string& lab) {
         RawDb db(lab);
         ASSERT_TRUE(db.exec("INSERT INTO session_claims (session_id, owner, host, pid, claimed_at, heartbeat_at, "
                             "expires_at) SELECT s.id, 'elsewhere', 'station-9', 1, '2030-01-01T00:00:00.000Z', "
                             "'2030-01-01T00:00:00.000Z', '2999-01-01T00:00:00.000Z' FROM sessions s JOIN participants "
                             "p ON p.id = s.participant_id WHERE p.participant = 'S1'"))
             << db.errmsg();
       },
       "being run in DST now",
       [](const std::string& lab) {
         Store s = open_ok(lab);
         auto e = s.enroll("S1");
         ASSERT_TRUE(s.begin_session("S1", make_plan(e->index, e->order_row, 1)));
       }},
  };
  int n = 0;
  for (const Case& c : cases) {
    const std::string lab = lab_with(study("lab" + std::to_string(n)), 1);
    const std::string station = dir_.file("station" + std::to_string(n++) + ".sqlite");
    if (c.before) c.before(lab);
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

// Schema v4 in a merge: what the station recorded of consent, withdrawal and screens joins the lab.
// S1 consents and runs, D declines, P2 (who ran at the lab) withdraws at the station and P1's
// session gains a screen there; meanwhile P3 withdraws at the lab. The station's withdrawal of P2
// takes effect at the lab (row freed at the withdrawal's instant), the lab's own of P3 stays.
TEST_P(Merge, ConsentWithdrawalsAndScreensJoinTheLab) {
  const std::string lab = lab_with(study("lab"));
  const std::string station = dir_.file("station.sqlite");
  ASSERT_TRUE(copy_study(lab, station));
  {
    Store s = open_ok(station);
    ASSERT_TRUE(s.record_consent("S1", {{"age", "25"}}, true, kConsentText));
    run_participant(s, "S1", 4);
    ASSERT_TRUE(s.record_consent("D", {{"age", "60"}}, false, kConsentText));
    ASSERT_TRUE(s.withdraw("P2", "wrote to the station", "RA"));
    ASSERT_TRUE(s.record_screen(*s.session("P1"), {"page thanks", "thanks", at_ms(5), at_ms(9), std::nullopt}));
  }
  {
    Store s = open_ok(lab);
    ASSERT_TRUE(s.withdraw("P3", "wrote to the lab", "PI"));
  }
  auto sum = copy_study(station, lab);
  ASSERT_TRUE(sum) << sum.error().to_string();
  EXPECT_EQ(sum->participants, 2);   // S1, D
  EXPECT_EQ(sum->consents, 2);
  EXPECT_EQ(sum->withdrawals, 2);    // D's refusal, P2's
  EXPECT_EQ(sum->screens, 2 + 1);    // S1's instructions and debrief, P1's thanks
  EXPECT_EQ(sum->unchanged, 1);      // P3: the lab's withdrawal stays
  auto r = StudyReader::open(lab);
  ASSERT_TRUE(r);
  auto w = r->withdrawals();
  ASSERT_EQ(w->size(), 3u);
  EXPECT_EQ((*w)[0].participant, "P2");
  EXPECT_EQ((*w)[0].reason, "wrote to the station");
  EXPECT_EQ((*w)[1].participant, "P3");
  EXPECT_EQ((*w)[2].participant, "D");
  auto ledger = r->ledger();
  std::map<std::string, LedgerEntry> by;
  for (const auto& e : *ledger) by[e.participant] = e;
  EXPECT_EQ(by["P2"].released_at, (*w)[0].withdrawn_at);
  EXPECT_TRUE(by["D"].withdrawn && by["D"].demographics.empty());
  EXPECT_EQ(r->sessions()->at(1).status, SessionStatus::finished);  // P2's finished session stays finished
  EXPECT_EQ(r->screens("P1")->size(), 3u);
  EXPECT_EQ(r->screens("P1")->back().screen, "page thanks");
  EXPECT_EQ(r->screens("S1")->size(), 2u);
  auto consents = r->consents();
  ASSERT_EQ(consents->size(), 2u);
  EXPECT_FALSE(consents->at(1).agreed);
  EXPECT_EQ(*r->integrity_check(), "ok");
  r = Result<StudyReader>(Error{});
  // The freed rows are run again: P2's row 1 and P3's row 2.
  {
    Store s = open_ok(lab);
    EXPECT_EQ(s.enroll("Q1")->order_row, 1);
    EXPECT_EQ(s.enroll("Q2")->order_row, 2);
  }
  // Merging the same file again adds nothing.
  const auto before = dump(lab);
  auto again = copy_study(station, lab);
  ASSERT_TRUE(again) << again.error().to_string();
  EXPECT_EQ(again->participants + again->consents + again->withdrawals + again->screens, 0);
  EXPECT_EQ(dump(lab), before);
}

// Turns a SQLite study file into what a dtlab of schema v2 wrote: without the v3 and v4 columns and
// tables, header and migration history at v2 (the trial_table view is left out: a copy never reads it).
void downgrade_to_v2(const std::string& file) {
  RawDb db(file);
  for (const char* sql : {"DROP VIEW trial_table", "DROP TRIGGER sessions_not_after_withdrawal", "DROP TABLE consents",
                          "DROP TABLE withdrawals", "DROP TABLE screens", "DELETE FROM schema_migrations WHERE version = 4",
                          "DROP TABLE session_displays",
                          "ALTER TABLE trial_results DROP COLUMN frame_first_ms",
                          "ALTER TABLE trial_results DROP COLUMN frame_ms_median",
                          "ALTER TABLE trial_results DROP COLUMN late_frames",
                          "ALTER TABLE trial_results DROP COLUMN refresh_hz",
                          "DELETE FROM schema_migrations WHERE version = 3", "PRAGMA user_version = 2"})
    ASSERT_TRUE(db.exec(sql)) << sql << ": " << db.errmsg();
}

// A station's file of schema v2 (recorded before the display timing existed) copies into an
// empty database of either engine, which gets schema v4 with the v3 columns NULL, and merges into
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
    EXPECT_EQ(to.header().second, "4");
    EXPECT_EQ(joined(to, "SELECT version FROM schema_migrations ORDER BY version"), "1,2,3,4");
    auto history = table(to, "schema_migrations", "version");  // SRC's v1 and v2 rows as they were, then v3, v4
    ASSERT_EQ(history.size(), 4u);
    history.resize(2);
    EXPECT_EQ(history, table(from, "schema_migrations", "version"));
    for (const auto& [name, order] : kTables)
      if (name != "trial_results" && name != "session_displays" && name != "schema_migrations" &&
          name != "consents" && name != "withdrawals" && name != "screens")
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

  // And the station's dtlab, updated, opens the file at v4.
  { Store s = open_ok(station); }
  RawDb db(station);
  EXPECT_EQ(db.header().second, "4");
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

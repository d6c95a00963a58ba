// Consent, withdrawal and the screen log (schema v4, docs/store.md invariants
// 13 and 14), on both engines: an agreement enrolls with the demographics and
// stores the answer; a decline stores only the refusal (no demographics, no
// session, no screen), frees the row for the next enrollment and is counted as
// withdrawn; a later withdrawal ends a running session and frees the row of a
// finished one; a withdrawn participant never runs again, even through SQL
// written by hand; the new tables are append-only; screens are numbered
// 1, 2, ... per session. Values are read back through the engines' own C APIs.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <sstream>

#include "study/common/hash.h"
#include "study/store/export.h"
#include "study/store/read.h"
#include "tests/store/store_fixtures.h"

namespace dtlab::store {
namespace {

using namespace dtlab::store::testing;

const std::string kText = sha256_hex("I agree to take part in this study.");

std::string q(const std::string& participant) { return "(SELECT id FROM participants WHERE participant = '" + participant + "')"; }

class Consent : public OnBothBackends {};
class Withdraw : public OnBothBackends {};
class Screens : public OnBothBackends {};
DTLAB_ON_BOTH_BACKENDS(Consent);
DTLAB_ON_BOTH_BACKENDS(Withdraw);
DTLAB_ON_BOTH_BACKENDS(Screens);

TEST_P(Consent, AnAgreementEnrollsWithTheDemographicsAndKeepsTheFirstAnswer) {
  const std::string path = study();
  Store s = open_ok(path);
  auto e = s.record_consent("P1", {{"age", "27"}, {"gender", "f"}}, true, kText);
  ASSERT_TRUE(e) << e.error().to_string();
  EXPECT_TRUE(e->newly_enrolled);
  EXPECT_EQ(e->index, 0);
  EXPECT_EQ(e->order_row, 0);
  EXPECT_FALSE(e->released || e->withdrawn);
  auto again = s.record_consent("P1", {{"age", "99"}}, true, sha256_hex("another wording"));  // a resumed run
  ASSERT_TRUE(again) << again.error().to_string();
  EXPECT_FALSE(again->newly_enrolled);
  EXPECT_EQ(again->index, 0);
  auto changed = s.record_consent("P1", {}, false, kText);
  ASSERT_FALSE(changed);
  EXPECT_EQ(changed.error().kind, ErrorKind::conflict);
  EXPECT_NE(changed.error().message.find("agreed at"), std::string::npos) << changed.error().to_string();
  auto bad = s.record_consent("P2", {}, true, "ABC");
  ASSERT_FALSE(bad);
  EXPECT_EQ(bad.error().field, "consent.text_sha256");

  RawDb db(path);
  EXPECT_EQ(db.rows("SELECT agreed, text_sha256 FROM consents"), (std::vector<std::vector<std::string>>{{"1", kText}}));
  EXPECT_EQ(db.one("SELECT demographics FROM participants"), R"({"age":"27","gender":"f"})");
  EXPECT_EQ(db.one("SELECT answered_at = enrolled_at FROM consents c JOIN participants p ON p.id = c.participant_id"),
            pg() ? "t" : "1");  // one transaction: one instant
  EXPECT_EQ(db.count("SELECT count(*) FROM withdrawals"), 0);
  EXPECT_EQ(db.count("SELECT count(*) FROM participants"), 1);  // the refused P2 left nothing
  auto r = s.read().consents();
  ASSERT_TRUE(r);
  ASSERT_EQ(r->size(), 1u);
  EXPECT_EQ((*r)[0].participant, "P1");
  EXPECT_TRUE((*r)[0].agreed);
  EXPECT_EQ((*r)[0].text_sha256, kText);
  EXPECT_EQ((*r)[0].answered_at.size(), 24u);
}

TEST_P(Consent, ADeclineStoresOnlyTheRefusalAndFreesTheRow) {
  const std::string path = study();
  Store s = open_ok(path);
  ASSERT_TRUE(s.record_consent("P1", {{"age", "30"}}, true, kText));  // index 0, row 0
  auto d = s.record_consent("D", {{"age", "41"}, {"gender", "m"}}, false, kText);
  ASSERT_TRUE(d) << d.error().to_string();
  EXPECT_EQ(d->index, 1);
  EXPECT_EQ(d->order_row, 1);
  EXPECT_TRUE(d->newly_enrolled && d->released && d->withdrawn);
  // Counted as withdrawn, never as abandoned: there is no session to abandon.
  EXPECT_FALSE(s.session("D"));
  auto begin = s.begin_session("D", make_plan(1, 1, 1));
  ASSERT_FALSE(begin);
  EXPECT_EQ(begin.error().kind, ErrorKind::conflict);
  EXPECT_NE(begin.error().message.find("withdrew their consent"), std::string::npos) << begin.error().to_string();
  EXPECT_NE(begin.error().message.find("declined consent"), std::string::npos) << begin.error().to_string();
  auto enroll = s.enroll("D");
  ASSERT_FALSE(enroll);
  EXPECT_EQ(enroll.error().kind, ErrorKind::conflict);
  EXPECT_FALSE(s.record_consent("D", {}, true, kText));  // a different answer: refused
  auto same = s.record_consent("D", {}, false, kText);   // the same answer again: unchanged
  ASSERT_TRUE(same) << same.error().to_string();
  EXPECT_TRUE(same->withdrawn && !same->newly_enrolled);
  // The next enrollment takes the freed row.
  auto n = s.enroll("N");
  ASSERT_TRUE(n);
  EXPECT_EQ(n->index, 2);
  EXPECT_EQ(n->order_row, 1);

  RawDb db(path);
  const std::string d_id = q("D");
  EXPECT_EQ(db.one("SELECT demographics FROM participants WHERE participant = 'D'"), "{}");
  EXPECT_EQ(db.rows("SELECT agreed, text_sha256 FROM consents WHERE participant_id = " + d_id),
            (std::vector<std::vector<std::string>>{{"0", kText}}));
  EXPECT_EQ(db.rows("SELECT reason, decided_by FROM withdrawals WHERE participant_id = " + d_id),
            (std::vector<std::vector<std::string>>{{"declined consent", "participant"}}));
  EXPECT_EQ(db.one("SELECT count(*) FROM participants p JOIN consents c ON c.participant_id = p.id JOIN withdrawals w "
                   "ON w.participant_id = p.id WHERE p.participant = 'D' AND p.released_at = w.withdrawn_at AND "
                   "c.answered_at = w.withdrawn_at AND p.enrolled_at = w.withdrawn_at"),
            "1");
  for (const char* table : {"sessions", "exclusions", "notes"})
    EXPECT_EQ(db.count(std::string("SELECT count(*) FROM ") + table + " WHERE participant_id = " + d_id), 0) << table;
  EXPECT_EQ(db.count("SELECT count(*) FROM screens"), 0);
  EXPECT_EQ(db.integrity(), "ok");
  auto w = s.read().withdrawals();
  ASSERT_TRUE(w);
  ASSERT_EQ(w->size(), 1u);
  EXPECT_EQ((*w)[0].participant, "D");
  EXPECT_EQ((*w)[0].reason, "declined consent");
  auto ledger = s.read().ledger();
  ASSERT_EQ(ledger->size(), 3u);
  EXPECT_FALSE((*ledger)[0].withdrawn);
  EXPECT_TRUE((*ledger)[1].withdrawn);
  EXPECT_TRUE((*ledger)[1].demographics.empty());
}

// A participant enrolled before consent was asked (enroll(), e.g. a protocol that gained a
// consent page): an agreement is stored beside the enrollment as it was; a decline withdraws them.
TEST_P(Consent, AParticipantEnrolledBeforeGetsTheirAnswerStored) {
  const std::string path = study();
  Store s = open_ok(path);
  ASSERT_TRUE(s.enroll("P1", {{"age", "30"}}));
  auto a = s.record_consent("P1", {{"age", "31"}}, true, kText);
  ASSERT_TRUE(a) << a.error().to_string();
  EXPECT_FALSE(a->newly_enrolled || a->withdrawn);
  auto e = s.enroll("P2");
  auto ses = s.begin_session("P2", make_plan(e->index, e->order_row, 1));
  ASSERT_TRUE(ses);
  auto d = s.record_consent("P2", {}, false, kText);
  ASSERT_TRUE(d) << d.error().to_string();
  EXPECT_TRUE(d->withdrawn && d->released);
  EXPECT_EQ(s.session("P2")->status, SessionStatus::abandoned);
  RawDb db(path);
  EXPECT_EQ(db.one("SELECT demographics FROM participants WHERE participant = 'P1'"), R"({"age":"30"})");
  EXPECT_EQ(db.count("SELECT count(*) FROM consents"), 2);
}

TEST_P(Withdraw, ARunningSessionEndsAbandonedAndTheParticipantNeverRunsAgain) {
  const std::string path = study();
  Store s = open_ok(path);
  auto e = s.record_consent("P1", {{"age", "30"}}, true, kText);
  const design::Plan plan = make_plan(e->index, e->order_row, 1);
  auto ses = s.begin_session("P1", plan);
  ASSERT_TRUE(ses);
  ASSERT_TRUE(s.record_trial(*ses, make_record(1, plan.trials[0], 3)));
  ASSERT_TRUE(s.withdraw("P1", "  asked to stop  ", "RA"));
  EXPECT_EQ(s.session("P1")->status, SessionStatus::abandoned);
  EXPECT_TRUE(s.lookup("P1")->withdrawn);
  auto rec = s.record_trial(*ses, make_record(1, plan.trials[1], 3));
  ASSERT_FALSE(rec);
  EXPECT_EQ(rec.error().kind, ErrorKind::conflict);
  auto again = s.begin_session("P1", plan);
  ASSERT_FALSE(again);
  EXPECT_NE(again.error().message.find("withdrew their consent"), std::string::npos) << again.error().to_string();
  EXPECT_FALSE(s.enroll("P1"));
  ASSERT_TRUE(s.withdraw("P1", "another reason", "PI"));  // harmless; the first stays
  auto e2 = s.enroll("P2");
  EXPECT_EQ(e2->order_row, 0);  // the freed row

  RawDb db(path);
  EXPECT_EQ(db.rows("SELECT reason, decided_by FROM withdrawals"),
            (std::vector<std::vector<std::string>>{{"asked to stop", "RA"}}));
  EXPECT_EQ(db.one("SELECT count(*) FROM sessions s JOIN participants p ON p.id = s.participant_id JOIN withdrawals w "
                   "ON w.participant_id = p.id WHERE s.ended_at = w.withdrawn_at AND p.released_at = w.withdrawn_at"),
            "1");
  EXPECT_EQ(db.count("SELECT count(*) FROM session_claims"), 0);
  EXPECT_EQ(db.count("SELECT count(*) FROM trial_results"), 1);  // recorded data stays, left out of the analysis
  // By hand, too: the trigger refuses a session to a participant who withdrew.
  const std::string insert = "INSERT INTO sessions (id, participant_id, study_id, software_version, status, started_at) "
                             "VALUES (99, " + q("P1") + ", 1, 'x', 'running', '2030-01-01T00:00:00.000Z')";
  EXPECT_FALSE(db.exec(insert));
  EXPECT_NE(db.errmsg().find("withdrew"), std::string::npos) << db.errmsg();

  auto sessions = s.read().sessions();
  ASSERT_EQ(sessions->size(), 1u);
  EXPECT_TRUE((*sessions)[0].withdrawn);
  EXPECT_EQ((*sessions)[0].status, SessionStatus::abandoned);
  auto trials = s.read().trials();
  ASSERT_EQ(trials->size(), 1u);
  EXPECT_TRUE((*trials)[0].withdrawn);
  std::ostringstream csv;
  auto sum = export_trials_csv(s.read(), csv);
  ASSERT_TRUE(sum);
  EXPECT_EQ(sum->rows, 0);
  EXPECT_EQ(sum->withdrawn, 1);
  EXPECT_EQ(sum->withdrawn_rows, 1);
  EXPECT_EQ(db.count("SELECT count(*) FROM trial_table"), 0);
}

TEST_P(Withdraw, AFinishedSessionStaysFinishedAndItsRowIsRunAgain) {
  const std::string path = study();
  Store s = open_ok(path);
  for (const char* id : {"P0", "P1"}) {
    auto e = s.enroll(id);
    const design::Plan plan = make_plan(e->index, e->order_row, 1);
    auto ses = s.begin_session(id, plan);
    for (const auto& t : plan.trials) ASSERT_TRUE(s.record_trial(*ses, make_record(2, t, 2)));
    ASSERT_TRUE(s.finish_session(*ses));
  }
  ASSERT_TRUE(s.withdraw("P1", "withdrew consent", "RA"));
  EXPECT_EQ(s.session("P1")->status, SessionStatus::finished);
  EXPECT_TRUE(s.lookup("P1")->released);
  EXPECT_EQ(s.enroll("P2")->order_row, 1);  // P1's row, run again by the next participant
  EXPECT_EQ(s.enroll("P3")->order_row, 2);
  auto rows = s.read().withdrawals();
  ASSERT_EQ(rows->size(), 1u);
  EXPECT_EQ((*rows)[0].by, "RA");
}

TEST_P(Withdraw, ASessionAnotherProcessRunsIsBusyAndNothingIsWritten) {
  const std::string path = study();
  Store s = open_ok(path);
  auto e = s.enroll("P1");
  ASSERT_TRUE(s.begin_session("P1", make_plan(e->index, e->order_row, 1)));
  RawDb db(path);
  ASSERT_TRUE(db.exec("UPDATE session_claims SET owner = 'elsewhere', host = 'station-9', "
                      "expires_at = '2999-01-01T00:00:00.000Z'")) << db.errmsg();
  auto busy = s.withdraw("P1", "withdrew consent", "RA");
  ASSERT_FALSE(busy);
  EXPECT_EQ(busy.error().kind, ErrorKind::busy);
  EXPECT_EQ(busy.error().field, kClaimField);
  EXPECT_EQ(db.count("SELECT count(*) FROM withdrawals"), 0);
  EXPECT_EQ(db.one("SELECT status FROM sessions"), "running");
  EXPECT_EQ(db.one("SELECT released_at FROM participants"), "NULL");
  auto unknown = s.withdraw("nobody", "x", "RA");
  ASSERT_FALSE(unknown);
  EXPECT_EQ(unknown.error().kind, ErrorKind::not_found);
  auto empty = s.withdraw("P1", " \t", "RA");
  ASSERT_FALSE(empty);
  EXPECT_EQ(empty.error().field, "reason");
}

TEST_P(Screens, AreNumberedPerSessionWithTheirDurations) {
  const std::string path = study();
  Store s = open_ok(path);
  auto e1 = s.record_consent("P1", {}, true, kText);
  auto s1 = s.begin_session("P1", make_plan(e1->index, e1->order_row, 1));
  auto e2 = s.enroll("P2");
  auto s2 = s.begin_session("P2", make_plan(e2->index, e2->order_row, 1));
  const auto t0 = at_ms(1'700'000'000'000);
  ASSERT_TRUE(s.record_screen(*s1, {"consent", kText, t0, t0 + std::chrono::milliseconds(12'345), "agree"}));
  ASSERT_TRUE(s.record_screen(*s2, {"page welcome", "welcome", t0, t0 + std::chrono::seconds(3), "continue"}));
  ASSERT_TRUE(s.record_screen(*s1, {"level technique=lens", "technique=lens", t0 + std::chrono::seconds(20),
                                    t0 + std::chrono::seconds(20), std::nullopt}));
  ASSERT_TRUE(s.record_screen(*s1, {"break", "", t0 + std::chrono::seconds(30), t0 + std::chrono::seconds(90),
                                    "timed out"}));
  struct Bad {
    ScreenRecord r;
    const char* field;
  };
  const Bad bad[] = {{{" ", "", t0, t0, std::nullopt}, "screen.screen"},
                     {{"break", "", t0, t0 - std::chrono::milliseconds(1), std::nullopt}, "screen.ended_at"}};
  for (const Bad& b : bad) {
    auto st = s.record_screen(*s1, b.r);
    ASSERT_FALSE(st);
    EXPECT_EQ(st.error().field, b.field);
  }
  Session ghost = *s1;
  ghost.id = 999;
  auto none = s.record_screen(ghost, {"break", "", t0, t0, std::nullopt});
  ASSERT_FALSE(none);
  EXPECT_EQ(none.error().kind, ErrorKind::not_found);

  RawDb db(path);
  EXPECT_EQ(db.rows("SELECT seq, screen, shown, shown_at, ended_at, answer FROM screens WHERE session_id = " +
                    std::to_string(s1->id) + " ORDER BY seq"),
            (std::vector<std::vector<std::string>>{
                {"1", "consent", kText, "2023-11-14T22:13:20.000Z", "2023-11-14T22:13:32.345Z", "agree"},
                {"2", "level technique=lens", "technique=lens", "2023-11-14T22:13:40.000Z", "2023-11-14T22:13:40.000Z",
                 "NULL"},
                {"3", "break", "", "2023-11-14T22:13:50.000Z", "2023-11-14T22:14:50.000Z", "timed out"}}));
  EXPECT_EQ(db.one("SELECT seq FROM screens WHERE session_id = " + std::to_string(s2->id)), "1");
  auto rows = s.read().screens("P1");
  ASSERT_TRUE(rows);
  ASSERT_EQ(rows->size(), 3u);
  EXPECT_EQ((*rows)[0].participant, "P1");
  EXPECT_DOUBLE_EQ((*rows)[0].duration_s, 12.345);
  EXPECT_DOUBLE_EQ((*rows)[2].duration_s, 60.0);
  EXPECT_FALSE((*rows)[1].answer);
  EXPECT_EQ(*(*rows)[2].answer, "timed out");
  auto all = s.read().screens();
  ASSERT_EQ(all->size(), 4u);
  EXPECT_EQ((*all)[3].participant, "P2");  // by enrollment index, then seq
  // A screen recorded after the session ended (a debrief after finish, the screen of a withdrawal).
  ASSERT_TRUE(s.withdraw("P2", "withdrew consent", "participant"));
  EXPECT_TRUE(s.record_screen(*s2, {"withdrawn", "", t0, t0, "withdraw"}));
}

// Turns a database written by this build into what a build of schema v3 wrote: the v4 tables,
// trigger and migration row removed, the header at 3 (the trial_table view goes too; v4 creates
// it again). Written before any v4 row exists, so nothing of the study is lost.
void downgrade_to_v3(const std::string& where) {
  RawDb db(where);
  const std::vector<std::string> sql =
      db.postgres()
          ? std::vector<std::string>{"DROP VIEW trial_table", "DROP TRIGGER sessions_not_after_withdrawal ON sessions",
                                     "DROP FUNCTION dtlab_sessions_not_after_withdrawal()",
                                     "DROP TABLE consents, withdrawals, screens",
                                     "ALTER TABLE schema_migrations DISABLE TRIGGER schema_migrations_no_delete",
                                     "DELETE FROM schema_migrations WHERE version = 4",
                                     "ALTER TABLE schema_migrations ENABLE TRIGGER schema_migrations_no_delete",
                                     "UPDATE dtlab_header SET user_version = 3"}
          : std::vector<std::string>{"DROP VIEW trial_table", "DROP TRIGGER sessions_not_after_withdrawal",
                                     "DROP TABLE consents", "DROP TABLE withdrawals", "DROP TABLE screens",
                                     "DELETE FROM schema_migrations WHERE version = 4", "PRAGMA user_version = 3"};
  for (const std::string& s : sql) ASSERT_TRUE(db.exec(s)) << s << ": " << db.errmsg();
}

// Every table of schema v3 with an order, for "the data is intact".
std::vector<std::vector<std::vector<std::string>>> v3_tables(const std::string& where) {
  static const char* tables[][2] = {
      {"studies", "id"}, {"study_factors", "study_id, position"}, {"study_designs", "study_id"},
      {"participants", "id"}, {"sessions", "id"}, {"session_resumes", "session_id, resumed_at"},
      {"planned_trials", "id"}, {"planned_levels", "planned_trial_id, factor_position"},
      {"trial_results", "planned_trial_id"}, {"input_events", "trial_id, seq"}, {"camera_poses", "trial_id, frame"},
      {"questionnaire_answers", "session_id, item, scope"}, {"exclusions", "id"}, {"notes", "id"},
      {"session_pauses", "session_id, paused_at"}, {"trial_attempts", "session_id, position, attempt"},
      {"session_displays", "session_id, recorded_at"}};
  RawDb db(where);
  std::vector<std::vector<std::vector<std::string>>> out;
  for (const auto& t : tables) out.push_back(db.rows(std::string("SELECT * FROM ") + t[0] + " ORDER BY " + t[1]));
  return out;
}

std::string exported(const std::string& where) {
  std::ostringstream out;
  auto sum = export_trials_csv(where, out);
  EXPECT_TRUE(sum) << sum.error().to_string();
  return out.str();
}

// A database of schema v3 (a study run before consent existed) is read as it is, and the first
// Store::open of this build migrates it to v4 in its write transaction with every row intact; the
// export is the same bytes before and after; consent and withdrawal then work on it.
TEST_P(Consent, ASchemaV3DatabaseUpgradesWithItsDataIntact) {
  const std::string path = study();
  {
    Store s = open_ok(path);
    auto e = s.enroll("P1", {{"age", "31"}});
    const design::Plan plan = make_plan(e->index, e->order_row, 1);
    auto ses = s.begin_session("P1", plan);
    ASSERT_TRUE(s.record_display(*ses, DisplayInfo{"headless", 160, 120, std::nullopt, "OSMesa", ""}));
    for (const auto& t : plan.trials) ASSERT_TRUE(s.record_trial(*ses, make_record(4, t, 3, 60.0)));
    ASSERT_TRUE(s.finish_session(*ses));
    ASSERT_TRUE(s.record_questionnaire(*ses, {{"rating", "", 4.0}}));
    auto e2 = s.enroll("P2", {{"age", "44"}});
    auto ses2 = s.begin_session("P2", make_plan(e2->index, e2->order_row, 1));
    ASSERT_TRUE(s.record_pause(*ses2, std::nullopt, at_ms(1'000), at_ms(2'500)));
    ASSERT_TRUE(s.exclude("P1", 2, "looked away", "RA"));
    ASSERT_TRUE(s.add_note("P2", std::nullopt, "RA", "left early"));
  }
  downgrade_to_v3(path);
  const auto before = v3_tables(path);
  std::string csv_before;
  {
    auto r = StudyReader::open(path);  // a reader never migrates
    ASSERT_TRUE(r) << r.error().to_string();
    EXPECT_EQ(r->schema_version(), 3);
    EXPECT_TRUE(r->consents()->empty());
    EXPECT_TRUE(r->withdrawals()->empty());
    EXPECT_TRUE(r->screens()->empty());
    EXPECT_FALSE((*r->ledger())[0].withdrawn);
    std::ostringstream csv;
    ASSERT_TRUE(export_trials_csv(*r, csv));
    csv_before = csv.str();
    EXPECT_NE(csv_before.find("demo_age"), std::string::npos);
  }
  {
    RawDb db(path);
    EXPECT_EQ(db.header().second, "3");
    EXPECT_FALSE(db.has_table("consents"));
  }
  Store s = open_ok(path);
  RawDb db(path);
  EXPECT_EQ(db.header().second, "4");
  EXPECT_EQ(joined(db, "SELECT version FROM schema_migrations ORDER BY version"), "1,2,3,4");
  EXPECT_NE(db.one("SELECT description FROM schema_migrations WHERE version = 4").find("consent"), std::string::npos);
  EXPECT_EQ(v3_tables(path), before);
  EXPECT_EQ(exported(path), csv_before);
  EXPECT_EQ(db.count("SELECT count(*) FROM trial_table"), 4);
  // The upgraded database takes what v4 records.
  ASSERT_TRUE(s.withdraw("P2", "withdrew consent", "RA"));
  EXPECT_EQ(s.session("P2")->status, SessionStatus::abandoned);
  ASSERT_TRUE(s.record_consent("P3", {}, true, kText));
  auto ses = s.session("P3");
  EXPECT_FALSE(ses);
  EXPECT_EQ(db.integrity(), "ok");
}

TEST_P(Consent, TheNewTablesAreAppendOnly) {
  const std::string path = study();
  {
    Store s = open_ok(path);
    auto e = s.record_consent("P1", {}, true, kText);
    auto ses = s.begin_session("P1", make_plan(e->index, e->order_row, 1));
    ASSERT_TRUE(s.record_screen(*ses, {"consent", kText, at_ms(0), at_ms(5), "agree"}));
    ASSERT_TRUE(s.record_consent("D", {}, false, kText));
    ASSERT_TRUE(s.enroll("P3"));
  }
  RawDb db(path);
  const char* refused[] = {
      "UPDATE consents SET agreed = 0",         "DELETE FROM consents",
      "UPDATE withdrawals SET reason = 'none'", "DELETE FROM withdrawals",
      "UPDATE screens SET answer = 'skipped'",  "DELETE FROM screens",
  };
  for (const char* sql : refused) {
    EXPECT_FALSE(db.exec(sql)) << sql;
    EXPECT_NE(db.errmsg().find("dtlab: "), std::string::npos) << sql << ": " << db.errmsg();
  }
  if (pg()) {
    for (const char* table : {"consents", "withdrawals", "screens"})
      EXPECT_FALSE(db.exec(std::string("TRUNCATE ") + table + " CASCADE")) << table;
  }
  EXPECT_EQ(db.count("SELECT count(*) FROM consents"), 2);
  EXPECT_EQ(db.count("SELECT count(*) FROM withdrawals"), 1);
  EXPECT_EQ(db.count("SELECT count(*) FROM screens"), 1);
  // And the CHECKs: a hash that is not 64 lowercase hex digits, an empty reason, a negative duration.
  for (const std::string& sql :
       {"INSERT INTO consents VALUES (" + q("P3") + ", 1, 'ABC', '2030-01-01T00:00:00.000Z')",
        "INSERT INTO withdrawals VALUES (9, " + q("P3") + ", '2030-01-01T00:00:00.000Z', '  ', 'RA')",
        std::string("INSERT INTO screens VALUES (1, 9, 'x', '', '2030-01-01T00:00:00.000Z', "
                    "'2030-01-01T00:00:00.000Z', -1, NULL)")})
    EXPECT_FALSE(db.exec(sql)) << sql;
  EXPECT_EQ(db.integrity(), "ok");
}

}  // namespace
}  // namespace dtlab::store

// The study database in one process, on both engines: round trip of
// everything a session writes, the databases open() refuses (and leaves
// untouched), the ledger rule, the session state machine, and that a failed
// write saves nothing and damages nothing. Values are read back through raw
// SQL (the engines' own C APIs), not the store.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "study/store/export.h"
#include "study/store/read.h"
#include "tests/store/store_fixtures.h"

namespace dtlab::store {
namespace {

using namespace dtlab::store::testing;

std::string read_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

std::string lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

// One demographic field as stored (the column is a JSON object's text).
std::string demographic(RawDb& db, const std::string& field) {
  const auto j = nlohmann::json::parse(db.one("SELECT demographics FROM participants"));
  return j.value(field, std::string("<missing>"));
}

class StoreSchema : public OnBothBackends {};
class StoreOpen : public OnBothBackends {};
class Ledger : public OnBothBackends {};
class Sessions : public OnBothBackends {};
DTLAB_ON_BOTH_BACKENDS(StoreSchema);
DTLAB_ON_BOTH_BACKENDS(StoreOpen);
DTLAB_ON_BOTH_BACKENDS(Ledger);
DTLAB_ON_BOTH_BACKENDS(Sessions);

TEST_P(StoreSchema, CreatesTheNewestSchemaWithItsHeaderAndProtocol) {
  const auto path = study();
  { Store s = open_ok(path); }
  RawDb db(path);
  if (!pg()) {
    EXPECT_EQ(db.one("PRAGMA journal_mode"), "wal");
  }
  EXPECT_EQ(db.header(), std::make_pair(std::to_string(kApplicationId), std::string("4")));
  EXPECT_EQ(db.one("SELECT max(version) FROM schema_migrations"), "4");
  EXPECT_EQ(db.count("SELECT count(*) FROM schema_migrations"), 4);  // v1, then v2, v3 and v4 on top of it
  const StudyInfo info = study_info();
  EXPECT_EQ(db.one("SELECT protocol_text FROM studies"), info.protocol_text);
  EXPECT_EQ(db.one("SELECT protocol_sha256 FROM studies"), info.protocol_sha256);
  EXPECT_EQ(db.one("SELECT software_version FROM studies"), "dtlab test");
  EXPECT_EQ(joined(db, "SELECT name FROM study_factors ORDER BY position"), "transparency,scenario");
  EXPECT_EQ(db.integrity(), "ok");
}

TEST_P(StoreSchema, RoundTripOfASession) {
  const auto path = study();
  Store s = open_ok(path);
  auto e = s.enroll("P01", {{"age", "27"}, {"gender", "f"}});
  ASSERT_TRUE(e) << e.error().to_string();
  EXPECT_EQ(e->index, 0);
  EXPECT_EQ(e->order_row, 0);
  EXPECT_TRUE(e->newly_enrolled);
  const design::Plan plan = make_plan(e->index, e->order_row);
  auto ses = s.begin_session("P01", plan);
  ASSERT_TRUE(ses) << ses.error().to_string();
  EXPECT_EQ(ses->planned, 12);
  EXPECT_FALSE(ses->resumed);
  std::vector<TrialRecord> written;
  for (;;) {
    auto next = s.next_trial(*ses);
    ASSERT_TRUE(next);
    if (!*next) break;
    EXPECT_TRUE(same_trial(**next, plan.trials[static_cast<std::size_t>((*next)->position - 1)]));
    written.push_back(make_record(7, **next));
    ASSERT_TRUE(s.record_trial(*ses, written.back()));
  }
  ASSERT_EQ(written.size(), 12u);
  ASSERT_TRUE(s.finish_session(*ses));
  ASSERT_TRUE(s.record_questionnaire(*ses, {{"rating", "scenario=ABSTRACT;transparency=on", 3.0},
                                            {"preference", "", std::string("on")}}));

  RawDb db(path);
  EXPECT_EQ(demographic(db, "age"), "27");
  EXPECT_EQ(db.one("SELECT status FROM sessions"), "finished");
  EXPECT_EQ(db.one("SELECT count(*) FROM sessions WHERE ended_at IS NOT NULL"), "1");
  EXPECT_EQ(db.count("SELECT count(*) FROM trial_results"), 12);
  for (const TrialRecord& r : written) {
    const std::string where = " WHERE planned_trial_id = (SELECT id FROM planned_trials WHERE position = " +
                              std::to_string(r.position) + ")";
    const auto row = db.rows("SELECT scene_hash, completion_s, frame_count, event_count, started_at, "
                             "answer_count, truth_count, rel_error, signed_error, answer_letter, correct, "
                             "answer_x, truth_x, distance FROM trial_results" + where)[0];
    EXPECT_EQ(row[0], r.scene_hash);
    EXPECT_DOUBLE_EQ(std::stod(row[1]), r.completion_s);
    EXPECT_EQ(std::stoll(row[2]), static_cast<std::int64_t>(r.poses.size()));
    EXPECT_EQ(std::stoll(row[3]), static_cast<std::int64_t>(r.events.size()));
    EXPECT_EQ(row[4].size(), 24u);
    EXPECT_EQ(row[4].back(), 'Z');
    if (const auto* c = std::get_if<Count>(&r.truth)) {
      const auto a = std::get<Count>(*r.answer).n;
      EXPECT_EQ(std::stoll(row[5]), a);
      EXPECT_EQ(std::stoll(row[6]), c->n);
      EXPECT_DOUBLE_EQ(std::stod(row[7]), std::abs(static_cast<double>(a - c->n)) / static_cast<double>(c->n));
      EXPECT_EQ(std::stoll(row[8]), a - c->n);
    } else if (std::holds_alternative<Letter>(r.truth)) {
      EXPECT_EQ(row[9], std::get<Letter>(*r.answer).letter);
      EXPECT_EQ(row[10], std::get<Letter>(*r.answer).letter == "K" ? "1" : "0");
    } else {
      const auto a = std::get<Position>(*r.answer), t = std::get<Position>(r.truth);
      EXPECT_DOUBLE_EQ(std::stod(row[11]), a.x);
      EXPECT_DOUBLE_EQ(std::stod(row[12]), t.x);
      EXPECT_NEAR(std::stod(row[13]), std::hypot(a.x - t.x, a.z - t.z), 1e-12);
    }
    const auto last = db.rows("SELECT frame, t_s, x, yaw FROM camera_poses WHERE trial_id = (SELECT id FROM "
                              "planned_trials WHERE position = " + std::to_string(r.position) +
                              ") ORDER BY frame DESC LIMIT 1")[0];
    EXPECT_EQ(std::stoll(last[0]), static_cast<std::int64_t>(r.poses.size()));
    EXPECT_DOUBLE_EQ(std::stod(last[2]), r.poses.back().x);
    EXPECT_EQ(db.one("SELECT detail FROM input_events WHERE seq = 1 AND trial_id = (SELECT id FROM planned_trials "
                     "WHERE position = " + std::to_string(r.position) + ")"),
              r.events[0].detail);
  }
  // The seed is stored exactly, all 64 bits, as decimal text.
  EXPECT_EQ(db.one("SELECT seed FROM planned_trials WHERE position = 1"), std::to_string(plan.trials[0].seed));
  EXPECT_EQ(db.one("SELECT value_number FROM questionnaire_answers WHERE item = 'rating'"), "3");
  EXPECT_EQ(db.one("SELECT recorded_trials || '/' || planned_trials FROM session_table"), "12/12");
  EXPECT_EQ(db.integrity(), "ok");
}

TEST_P(StoreSchema, UnansweredTrialStoresNAScores) {
  const auto path = study();
  Store s = open_ok(path);
  auto e = s.enroll("P1");
  auto ses = s.begin_session("P1", make_plan(e->index, e->order_row));
  auto t = s.next_trial(*ses);
  TrialRecord r = make_record(1, **t);
  r.answer.reset();
  ASSERT_TRUE(s.record_trial(*ses, r));
  RawDb db(path);
  EXPECT_EQ(db.rows("SELECT answered, answer_count, rel_error, signed_error FROM trial_results")[0],
            (std::vector<std::string>{"0", "NULL", "NULL", "NULL"}));
}

TEST_P(StoreSchema, RejectsScoresThatDisagreeWithTheAnswer) {
  const auto path = study();
  Store s = open_ok(path);
  auto e = s.enroll("P1");
  auto ses = s.begin_session("P1", make_plan(e->index, e->order_row));
  ASSERT_TRUE(s.record_trial(*ses, make_record(1, **s.next_trial(*ses))));  // T1, a count
  RawDb db(path);
  // Invariant 8: a row whose rel_error is not |a - t| / t cannot exist.
  const std::string insert =
      "INSERT INTO trial_results (planned_trial_id, scene_hash, answer_kind, answered, answer_count, truth_count, "
      "rel_error, signed_error, completion_s, started_at, ended_at, frame_count, event_count, recorded_at) VALUES "
      "((SELECT id FROM planned_trials WHERE position = 2), '" + std::string(64, 'a') +
      "', 'count', 1, 10, 20, %s, -10, 1.0, '2024-01-01T00:00:00.000Z', '2024-01-01T00:00:01.000Z', 0, 0, "
      "'2024-01-01T00:00:01.000Z')";
  char buf[1024];
  std::snprintf(buf, sizeof buf, insert.c_str(), "0.4");
  EXPECT_FALSE(db.exec(buf));
  EXPECT_NE(lower(db.errmsg()).find("check constraint"), std::string::npos) << db.errmsg();
  std::snprintf(buf, sizeof buf, insert.c_str(), "0.5");  // the same row with the right score is accepted
  EXPECT_TRUE(db.exec(buf)) << db.errmsg();
  // Invariant 7: saved results are never changed or deleted, even by hand.
  EXPECT_FALSE(db.exec("UPDATE trial_results SET completion_s = 0"));
  EXPECT_FALSE(db.exec("DELETE FROM trial_results"));
  if (pg()) {  // a server's client could try this too
    EXPECT_FALSE(db.exec("TRUNCATE trial_results CASCADE"));
  }
  EXPECT_EQ(db.count("SELECT count(*) FROM trial_results"), 2);
}

// --- files open() refuses ------------------------------------------------------------

TEST(StoreFile, RefusesANonSqliteFileUntouched) {
  TempDir dir;
  const auto path = dir.file("notes.sqlite");
  { std::ofstream(path) << "participant,time\nP1,12.5\n" << std::string(200, 'x'); }
  const std::string before = read_bytes(path);
  auto s = Store::open(path, study_info());
  ASSERT_FALSE(s);
  EXPECT_EQ(s.error().file, path);
  EXPECT_NE(s.error().message.find("not an SQLite database"), std::string::npos) << s.error().to_string();
  EXPECT_EQ(read_bytes(path), before);
}

TEST(StoreFile, RefusesAForeignSqliteDatabaseUntouched) {
  TempDir dir;
  const auto path = dir.file("other.db");
  { RawDb db(path, SQLITE_OPEN_READWRITE | SQLITE_OPEN_CREATE); db.exec("CREATE TABLE t(x); INSERT INTO t VALUES (1)"); }
  const std::string before = read_bytes(path);
  auto s = Store::open(path, study_info());
  ASSERT_FALSE(s);
  EXPECT_NE(s.error().message.find("not a dtlab study database"), std::string::npos) << s.error().to_string();
  EXPECT_EQ(read_bytes(path), before);
  EXPECT_FALSE(std::filesystem::exists(path + "-wal"));
}

TEST_P(StoreOpen, RefusesANewerSchemaVersion) {
  const auto path = study();
  { Store s = open_ok(path); }
  {
    RawDb db(path);
    ASSERT_TRUE(db.exec(pg() ? "UPDATE dtlab_header SET user_version = 5" : "PRAGMA user_version = 5")) << db.errmsg();
    ASSERT_TRUE(db.exec("INSERT INTO schema_migrations VALUES (5, 'future', '2030-01-01T00:00:00.000Z', 'dtlab 9')"));
  }
  const std::string before = pg() ? "" : read_bytes(path);
  auto s = Store::open(path, study_info());
  ASSERT_FALSE(s);
  EXPECT_EQ(s.error().field, "schema_migrations.version");
  EXPECT_NE(s.error().message.find("schema version 5"), std::string::npos) << s.error().to_string();
  if (!pg()) {
    EXPECT_EQ(read_bytes(path), before);
  }
  RawDb db(path);
  EXPECT_EQ(db.count("SELECT count(*) FROM studies"), 1);  // nothing was recorded
}

TEST_P(StoreOpen, RefusesAnotherProtocolUnlessAllowed) {
  const auto path = study();
  const StudyInfo a = study_info("protocol A");
  const StudyInfo b = study_info("protocol B");
  { Store s = open_ok(path, a); ASSERT_TRUE(s.enroll("P1")); }
  auto refused = Store::open(path, b);
  ASSERT_FALSE(refused);
  EXPECT_NE(refused.error().message.find(a.protocol_sha256), std::string::npos);
  EXPECT_NE(refused.error().message.find(b.protocol_sha256), std::string::npos);
  EXPECT_EQ(refused.error().kind, ErrorKind::conflict);
  { RawDb db(path); EXPECT_EQ(db.count("SELECT count(*) FROM studies"), 1); }

  OpenOptions allow;
  allow.allow_protocol_change = true;
  { Store s = open_ok(path, b, allow); }
  RawDb db(path);
  EXPECT_EQ(db.count("SELECT count(*) FROM studies"), 2);  // the old protocol is kept, the new one is current
  EXPECT_EQ(db.one("SELECT protocol_text FROM studies ORDER BY id DESC LIMIT 1"), "protocol B");
  // Now B is current: A is refused in turn.
  EXPECT_FALSE(Store::open(path, a));
}

// Protocol revisions (issue 9): a new text with the same design hash is recorded as a new
// revision without any option, and a session begun under the old text resumes under the new;
// a new design is refused (conflict) unless allowed, then it is design revision 2.
TEST_P(StoreOpen, ARewordedProtocolContinuesAndANewDesignNeedsPermission) {
  const auto path = study();
  StudyInfo a = study_info("protocol A\n");
  a.design_sha256 = std::string(64, '1');
  StudyInfo a2 = study_info("protocol A\n# a comment added mid-study\n");
  a2.design_sha256 = a.design_sha256;
  StudyInfo b = study_info("protocol B\n");
  b.design_sha256 = std::string(64, '2');
  const design::Plan plan = make_plan(0, 0, 1);
  {
    Store s = open_ok(path, a);
    ASSERT_TRUE(s.enroll("P1"));
    auto ses = s.begin_session("P1", plan);
    ASSERT_TRUE(s.record_trial(*ses, make_record(1, plan.trials[0], 3)));
  }
  {
    Store s = open_ok(path, a2);  // no allow_protocol_change needed
    auto ses = s.begin_session("P1", plan);
    ASSERT_TRUE(ses) << ses.error().to_string();
    EXPECT_TRUE(ses->resumed);
    ASSERT_TRUE(s.record_trial(*ses, make_record(1, plan.trials[1], 3)));
    ASSERT_TRUE(s.enroll("P2"));
  }
  auto refused = Store::open(path, b);
  ASSERT_FALSE(refused);
  EXPECT_EQ(refused.error().kind, ErrorKind::conflict);
  EXPECT_NE(refused.error().message.find("design"), std::string::npos) << refused.error().to_string();
  OpenOptions allow;
  allow.allow_protocol_change = true;
  { Store s = open_ok(path, b, allow); }
  auto r = StudyReader::open(path);
  ASSERT_TRUE(r);
  auto revs = r->revisions();
  ASSERT_EQ(revs->size(), 3u);
  EXPECT_EQ((*revs)[0].design_revision, 1);
  EXPECT_EQ((*revs)[1].design_revision, 1);  // the reworded text shares the design
  EXPECT_EQ((*revs)[2].design_revision, 2);
  auto trials = r->trials();
  ASSERT_EQ(trials->size(), 2u);
  EXPECT_EQ((*trials)[0].design_revision, 1);
  EXPECT_EQ((*trials)[1].design_revision, 1);  // the session keeps the revision it began under
}

// Regression guard for "never an abort": a database whose pages after the
// header were overwritten gives Errors naming the file, from open() or from
// the first call that reads a damaged page, and from the export.
TEST(StoreFile, CorruptedPagesGiveErrorsNotCrashes) {
  TempDir dir;
  const auto path = dir.file("s.sqlite");
  {
    Store s = open_ok(path);
    for (int i = 0; i < 30; ++i) ASSERT_TRUE(s.enroll("P" + std::to_string(i)));
  }  // the last connection closes: the log is checkpointed into the file
  ASSERT_FALSE(std::filesystem::exists(path + "-wal"));
  std::string bytes = read_bytes(path);
  ASSERT_GT(bytes.size(), 8192u);
  for (std::size_t i = 4096; i < bytes.size(); ++i) bytes[i] = static_cast<char>(0xA5 ^ (i * 31));
  { std::ofstream(path, std::ios::binary | std::ios::trunc) << bytes; }

  auto s = Store::open(path, study_info());
  if (s) {
    auto e = s->lookup("P3");
    ASSERT_FALSE(e) << "a damaged ledger page was read as data";
    EXPECT_EQ(e.error().file, path);
  } else {
    EXPECT_EQ(s.error().file, path);
    EXPECT_FALSE(s.error().message.empty());
  }
  std::ostringstream out;
  auto x = export_trials_csv(path, out);
  ASSERT_FALSE(x);
  EXPECT_EQ(x.error().file, path);
}

TEST_P(StoreOpen, RefusesBadStudyInfoBeforeCreatingAnything) {
  const auto path = study();
  StudyInfo bad = study_info();
  bad.factors = {"transparency", "task"};  // collides with the fixed export column "task"
  auto s = Store::open(path, bad);
  ASSERT_FALSE(s);
  EXPECT_EQ(s.error().field, "study.factors");
  if (pg()) {
    EXPECT_FALSE(RawDb(path).has_table("studies"));
  } else {
    EXPECT_FALSE(std::filesystem::exists(path));
  }
}

// --- the ledger --------------------------------------------------------------------------

TEST_P(Ledger, RowIsIndexModRowsWhileNothingIsReleased) {
  Store s = open_ok(study());
  for (int i = 0; i < 10; ++i) {
    auto e = s.enroll("P" + std::to_string(i));
    ASSERT_TRUE(e);
    EXPECT_EQ(e->index, i);
    EXPECT_EQ(e->order_row, i % 4);
  }
  auto again = s.enroll("P3");
  ASSERT_TRUE(again);
  EXPECT_FALSE(again->newly_enrolled);
  EXPECT_EQ(again->index, 3);
  EXPECT_EQ(again->order_row, 3);
  EXPECT_EQ(s.lookup("P7")->order_row, 3);
  auto unknown = s.lookup("nobody");
  ASSERT_FALSE(unknown);
  EXPECT_EQ(unknown.error().field, "participant");
}

TEST_P(Ledger, DemographicsAreAJsonObjectEvenFromBadInput) {
  const auto path = study();
  Store s = open_ok(path);
  // Regression: invalid UTF-8 made the JSON writer throw out of enroll().
  ASSERT_TRUE(s.enroll("P1", {{"note", "caf\xe9"}, {"age", "31"}}));
  auto dup = s.enroll("P2", {{"age", "1"}, {"age", "2"}});
  ASSERT_FALSE(dup);
  EXPECT_EQ(dup.error().field, "demographics.age");
  RawDb db(path);
  EXPECT_EQ(demographic(db, "note"), "caf\xef\xbf\xbd");
  EXPECT_EQ(db.count("SELECT count(*) FROM participants"), 1);
}

TEST_P(Ledger, ReleasedRowGoesToTheNextParticipant) {
  // Table: after enrolling P0..P5 (rows 0 1 2 3 0 1) and releasing some, the
  // next rows follow "fewest active participants, ties to the lowest row".
  struct Case {
    std::vector<std::string> release;
    std::vector<int> next_rows;  // rows given to the next enrollments, in order
  };
  const Case cases[] = {
      {{}, {2, 3, 0, 1}},                  // nothing released: index mod 4
      {{"P5"}, {1, 2, 3, 0}},              // P5's row 1 is least filled (with 2, 3): lowest first
      {{"P0", "P4"}, {0, 0, 2, 3}},        // row 0 empty: it is filled twice first
      {{"P2"}, {2, 2, 3, 0}},              // row 2 empty, then rows 2 and 3 tie at 1
  };
  int n = 0;
  for (const Case& c : cases) {
    Store s = open_ok(study("s" + std::to_string(n++)));
    for (int i = 0; i < 6; ++i) ASSERT_TRUE(s.enroll("P" + std::to_string(i)));
    for (const auto& id : c.release) ASSERT_TRUE(s.release(id));
    for (std::size_t k = 0; k < c.next_rows.size(); ++k) {
      auto e = s.enroll("N" + std::to_string(k));
      ASSERT_TRUE(e);
      EXPECT_EQ(e->index, static_cast<int>(6 + k)) << "indexes are never reused";
      EXPECT_EQ(e->order_row, c.next_rows[k]) << "case " << n << ", enrollment " << k;
    }
  }
}

TEST_P(Ledger, ReleaseAbandonsTheSessionAndRefusesFinishedOnes) {
  const auto path = study();
  Store s = open_ok(path);
  auto e = s.enroll("P1");
  auto ses = s.begin_session("P1", make_plan(e->index, e->order_row, 1));
  ASSERT_TRUE(s.record_trial(*ses, make_record(1, **s.next_trial(*ses))));
  ASSERT_TRUE(s.release("P1"));
  ASSERT_TRUE(s.release("P1"));  // idempotent
  EXPECT_EQ(s.session("P1")->status, SessionStatus::abandoned);
  EXPECT_TRUE(s.lookup("P1")->released);
  auto rec = s.record_trial(*ses, make_record(1, **s.next_trial(*ses)));
  ASSERT_FALSE(rec);
  EXPECT_NE(rec.error().message.find("abandoned"), std::string::npos);
  EXPECT_FALSE(s.enroll("P1"));              // a released id is not re-enrolled
  EXPECT_FALSE(s.begin_session("P1", make_plan(0, 0, 1)));
  { RawDb db(path); EXPECT_EQ(db.count("SELECT count(*) FROM trial_results"), 1); }  // its data stays

  auto e2 = s.enroll("P2");
  auto s2 = s.begin_session("P2", make_plan(e2->index, e2->order_row, 1));
  for (int i = 0; i < 4; ++i) ASSERT_TRUE(s.record_trial(*s2, make_record(1, **s.next_trial(*s2))));
  ASSERT_TRUE(s.finish_session(*s2));
  auto r = s.release("P2");
  ASSERT_FALSE(r);
  EXPECT_NE(r.error().message.find("finished"), std::string::npos);
  EXPECT_FALSE(s.lookup("P2")->released);
}

// --- the session state machine -------------------------------------------------------------

TEST_P(Sessions, BeginChecksThePlanAgainstTheEnrollment) {
  Store s = open_ok(study());
  auto e = s.enroll("P1");
  struct Case {
    const char* name;
    design::Plan plan;
    const char* field;
  };
  design::Plan wrong_protocol = make_plan(0, 0);
  wrong_protocol.protocol_id = "other";
  design::Plan gap = make_plan(0, 0);
  gap.trials[3].position = 7;
  design::Plan factors = make_plan(0, 0);
  factors.trials[0].levels[0].first = "xray";
  const Case cases[] = {
      {"wrong index", make_plan(1, 0), "plan.index"},
      {"wrong row", make_plan(0, 2), "plan.index"},
      {"wrong protocol", wrong_protocol, "plan.protocol_id"},
      {"position gap", gap, "plan.trials[3].position"},
      {"unknown factor", factors, "plan.trials[0].levels"},
      {"empty", design::Plan{"test2x2", 0, 0, {}}, "plan.trials"},
  };
  for (const Case& c : cases) {
    auto r = s.begin_session("P1", c.plan);
    ASSERT_FALSE(r) << c.name;
    EXPECT_EQ(r.error().field, c.field) << c.name << ": " << r.error().to_string();
  }
  EXPECT_FALSE(s.session("P1"));  // nothing was created
  EXPECT_FALSE(s.begin_session("ghost", make_plan(0, 0)));
}

TEST_P(Sessions, ResumeContinuesWithTheStoredPlanAndRefusesAnother) {
  const auto path = study();
  const design::Plan plan = make_plan(0, 0);
  {
    Store s = open_ok(path);
    auto e = s.enroll("P1");
    auto ses = s.begin_session("P1", plan);
    for (int i = 0; i < 5; ++i) ASSERT_TRUE(s.record_trial(*ses, make_record(3, **s.next_trial(*ses))));
  }  // the process "quits" here
  Store s = open_ok(path);
  design::Plan changed = plan;
  changed.trials[8].seed ^= 1;
  auto refused = s.begin_session("P1", changed);
  ASSERT_FALSE(refused);
  EXPECT_EQ(refused.error().field, "plan.trials[8].seed");
  auto ses = s.begin_session("P1", plan);
  ASSERT_TRUE(ses);
  EXPECT_TRUE(ses->resumed);
  EXPECT_EQ(ses->recorded, 5);
  auto next = s.next_trial(*ses);
  ASSERT_TRUE(next && *next);
  EXPECT_EQ((*next)->position, 6);
  EXPECT_TRUE(same_trial(**next, plan.trials[5]));
  RawDb db(path);
  EXPECT_EQ(db.one("SELECT next_position FROM session_resumes"), "6");
}

TEST_P(Sessions, RecordsOnlyTheNextTrialOnceAndFinishesOnlyWhenDone) {
  const auto path = study();
  Store s = open_ok(path);
  auto e = s.enroll("P1");
  const design::Plan plan = make_plan(0, 0, 1);
  auto ses = s.begin_session("P1", plan);
  auto skip = s.record_trial(*ses, make_record(1, plan.trials[1]));
  ASSERT_FALSE(skip);
  EXPECT_NE(skip.error().message.find("trial 1 is next"), std::string::npos) << skip.error().to_string();
  ASSERT_TRUE(s.record_trial(*ses, make_record(1, plan.trials[0])));
  EXPECT_FALSE(s.record_trial(*ses, make_record(1, plan.trials[0])));  // twice
  auto early = s.finish_session(*ses);
  ASSERT_FALSE(early);
  EXPECT_NE(early.error().message.find("3 planned trials"), std::string::npos) << early.error().to_string();
  for (int i = 1; i < 4; ++i) ASSERT_TRUE(s.record_trial(*ses, make_record(1, plan.trials[static_cast<std::size_t>(i)])));
  EXPECT_FALSE(*s.next_trial(*ses));
  EXPECT_FALSE(s.record_trial(*ses, make_record(1, plan.trials[3])));
  ASSERT_TRUE(s.finish_session(*ses));
  EXPECT_FALSE(s.finish_session(*ses));
  EXPECT_FALSE(s.begin_session("P1", plan));  // finished is final
  ASSERT_TRUE(s.record_questionnaire(*ses, {{"depth", "", 2.0}}));
  auto twice = s.record_questionnaire(*ses, {{"depth", "", 3.0}});
  ASSERT_FALSE(twice);
  EXPECT_EQ(twice.error().field, "questionnaire.depth");
  RawDb db(path);
  EXPECT_EQ(db.count("SELECT count(*) FROM trial_results"), 4);
  EXPECT_EQ(db.one("SELECT value_number FROM questionnaire_answers"), "2");
}

TEST_P(Sessions, InvalidRecordsAreRefusedWithTheFieldAtFault) {
  Store s = open_ok(study());
  auto e = s.enroll("P1");
  const design::Plan plan = make_plan(0, 0);
  auto ses = s.begin_session("P1", plan);
  const TrialRecord good = make_record(1, plan.trials[0]);
  struct Case {
    const char* name;
    void (*mutate)(TrialRecord&);
    const char* field;
  };
  const Case cases[] = {
      {"bad hash", [](TrialRecord& r) { r.scene_hash = "xyz"; }, "trial 1.scene_hash"},
      {"kind mismatch", [](TrialRecord& r) { r.answer = Letter{"K"}; }, "trial 1.answer"},
      {"negative count", [](TrialRecord& r) { r.answer = Count{-1}; }, "trial 1.answer"},
      {"NaN time", [](TrialRecord& r) { r.completion_s = std::nan(""); }, "trial 1.completion_s"},
      {"end before start", [](TrialRecord& r) { r.ended_at = r.started_at - std::chrono::seconds(1); }, "trial 1.ended_at"},
      {"pose missing", [](TrialRecord& r) { r.poses.pop_back(); }, "trial 1.frames"},
      {"inf pose", [](TrialRecord& r) { r.poses[0].yaw = INFINITY; }, "trial 1.poses[0]"},
      {"negative event time", [](TrialRecord& r) { r.events[0].t_s = -1; }, "trial 1.events[0]"},
  };
  for (const Case& c : cases) {
    TrialRecord r = good;
    c.mutate(r);
    auto st = s.record_trial(*ses, r);
    ASSERT_FALSE(st) << c.name;
    EXPECT_EQ(st.error().field, c.field) << c.name << ": " << st.error().to_string();
  }
  EXPECT_EQ(s.session("P1")->recorded, 0);
  EXPECT_TRUE(s.record_trial(*ses, good));
}

// ERROR state: a write that fails (here: another process holds the write
// lock -- SQLite's, or a lock on the results table on the server -- past the
// busy timeout) rolls back; the store stays usable and the retry succeeds;
// trials saved before are untouched.
TEST_P(Sessions, FailedWriteSavesNothingAndTheRetrySucceeds) {
  const auto path = study();
  OpenOptions quick;
  quick.busy_timeout_ms = 50;
  Store s = open_ok(path, study_info(), quick);
  auto e = s.enroll("P1");
  const design::Plan plan = make_plan(0, 0);
  auto ses = s.begin_session("P1", plan);
  ASSERT_TRUE(s.record_trial(*ses, make_record(1, plan.trials[0])));
  RawDb other(path);
  ASSERT_TRUE(other.exec(pg() ? "BEGIN; LOCK TABLE trial_results IN EXCLUSIVE MODE" : "BEGIN IMMEDIATE")) << other.errmsg();
  auto busy = s.record_trial(*ses, make_record(1, plan.trials[1]));
  ASSERT_FALSE(busy);
  EXPECT_EQ(busy.error().kind, ErrorKind::busy) << busy.error().to_string();
  EXPECT_EQ(busy.error().file, display_name(path));
  ASSERT_TRUE(other.exec("ROLLBACK"));
  EXPECT_EQ((*s.next_trial(*ses))->position, 2);
  ASSERT_TRUE(s.record_trial(*ses, make_record(1, plan.trials[1])));
  EXPECT_EQ(other.count("SELECT count(*) FROM trial_results"), 2);
  EXPECT_EQ(other.integrity(), "ok");
}

}  // namespace
}  // namespace dtlab::store

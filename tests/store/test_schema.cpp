// The schema both engines create, against what the build before the one
// schema description created (tests/store/data, written by
// make_schema_golden.sh from databases of commit a7efacc): SQLite's schema
// text byte for byte, PostgreSQL's catalogue (columns, types, collations,
// defaults, constraints, indexes, triggers, functions, the session_table
// view) as the queries of schema_pg.sql read it. Both for a new database and
// for a schema v1 database upgraded by Store::open, whose v1 rows stay. And
// the rows bound and read by column name (detail/columns.h) land in and come
// from the columns they name, read back with the engine's own API; and
// parameters bound by name (detail/db.h) on both engines.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "study/store/detail/columns.h"
#include "tests/store/store_fixtures.h"

namespace dtlab::store {
namespace {

using namespace dtlab::store::testing;

std::string data_file(const std::string& name) {
  std::ifstream in(std::string(DTLAB_SOURCE_DIR) + "/tests/store/data/" + name, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// The schema as the golden files hold it: SQLite's objects' SQL in creation order, or every row of
// schema_pg.sql's queries as "a | b | c".
std::string schema_of(const std::string& where, bool pg) {
  RawDb db(where);
  std::string out;
  if (!pg) {
    for (const auto& row : db.rows("SELECT sql || ';' FROM sqlite_schema WHERE sql IS NOT NULL "
                                   "AND name <> 'trial_table' ORDER BY rowid"))
      out += row[0] + "\n";
    return out;
  }
  std::istringstream queries(data_file("schema_pg.sql"));
  for (std::string q; std::getline(queries, q);) {
    if (q.empty()) continue;
    for (const auto& row : db.rows(q)) {
      for (std::size_t c = 0; c < row.size(); ++c) out += (c ? " | " : "") + row[c];
      out += "\n";
    }
  }
  return out;
}

// Turns a new database into what a build of schema v1 wrote: every table, column, trigger and
// migration row of v2 to v4 removed, the header at 1, the trial_table view gone (an upgrade creates it).
void downgrade_to_v1(const std::string& where, bool pg) {
  RawDb db(where);
  const char* v3_columns[] = {"frame_first_ms", "frame_ms_median", "late_frames", "refresh_hz"};
  std::vector<std::string> sql{"DROP VIEW trial_table"};
  if (pg) {
    sql.push_back("DROP TABLE study_designs, exclusions, notes, session_pauses, trial_attempts, session_claims, "
                  "session_displays, consents, withdrawals, screens");
    sql.push_back("DROP TRIGGER sessions_not_after_withdrawal ON sessions");
    sql.push_back("DROP FUNCTION dtlab_sessions_not_after_withdrawal()");
    sql.push_back("ALTER TABLE schema_migrations DISABLE TRIGGER schema_migrations_no_delete");
    sql.push_back("DELETE FROM schema_migrations WHERE version > 1");
    sql.push_back("ALTER TABLE schema_migrations ENABLE TRIGGER schema_migrations_no_delete");
    sql.push_back("UPDATE dtlab_header SET user_version = 1");
  } else {
    for (const char* t : {"study_designs", "exclusions", "notes", "session_pauses", "trial_attempts", "session_claims",
                          "session_displays", "consents", "withdrawals", "screens"})
      sql.push_back(std::string("DROP TABLE ") + t);  // their triggers go with them
    sql.push_back("DROP TRIGGER sessions_not_after_withdrawal");
    sql.push_back("DELETE FROM schema_migrations WHERE version > 1");
    sql.push_back("PRAGMA user_version = 1");
  }
  for (const char* c : v3_columns) sql.push_back(std::string("ALTER TABLE trial_results DROP COLUMN ") + c);
  for (const std::string& s : sql) ASSERT_TRUE(db.exec(s)) << s << ": " << db.errmsg();
}

class Schema : public OnBothBackends {
 protected:
  std::string golden() const { return data_file(pg() ? "schema_pg.txt" : "schema_sqlite.sql"); }
};
DTLAB_ON_BOTH_BACKENDS(Schema);

TEST_P(Schema, ANewDatabaseHasTheSchemaEarlierBuildsCreated) {
  const auto path = study();
  { Store s = open_ok(path); }
  ASSERT_FALSE(golden().empty());
  EXPECT_EQ(schema_of(path, pg()), golden());
}

TEST_P(Schema, ASchemaV1DatabaseUpgradesToTheSameSchemaWithItsRowsIntact) {
  const auto path = study();
  {
    Store s = open_ok(path);
    auto e = s.enroll("P1", {{"age", "31"}});
    ASSERT_TRUE(e);
    const design::Plan plan = make_plan(e->index, e->order_row, 1);
    auto ses = s.begin_session("P1", plan);
    ASSERT_TRUE(ses);
    for (const auto& t : plan.trials) ASSERT_TRUE(s.record_trial(*ses, make_record(4, t, 3, 60.0)));
  }
  downgrade_to_v1(path, pg());
  const char* v1_rows = "SELECT planned_trial_id, scene_hash, answer_count, truth_count, rel_error, completion_s, "
                        "frame_count, frame_ms_mean, recorded_at FROM trial_results ORDER BY planned_trial_id";
  const auto before = RawDb(path).rows(v1_rows);
  ASSERT_EQ(before.size(), 4u);
  EXPECT_EQ(RawDb(path).header().second, "1");
  { Store s = open_ok(path); }
  RawDb db(path);
  EXPECT_EQ(db.header().second, "4");
  EXPECT_EQ(joined(db, "SELECT version FROM schema_migrations ORDER BY version"), "1,2,3,4");
  EXPECT_EQ(db.rows(v1_rows), before);
  EXPECT_EQ(db.count("SELECT count(*) FROM trial_results WHERE frame_first_ms IS NULL"), 4);  // v3 columns: NULL
  EXPECT_EQ(schema_of(path, pg()), golden());
  EXPECT_EQ(db.integrity(), "ok");
}

// Cells set by name in another order than the table's land in the columns they name; a name the
// description lacks is an internal Error and writes nothing; a result row is read by name.
TEST_P(Schema, RowsAreBoundAndReadByColumnName) {
  const auto path = study();
  { Store s = open_ok(path); }
  auto conn = detail::open_connection(path, detail::Access::write, 1000);
  ASSERT_TRUE(conn) << conn.error().to_string();
  detail::Db db(std::move(*conn));
  const std::string at = "2024-05-01T12:34:56.789Z";
  detail::RowInsert note("notes");
  note.set("written_at", at).set("text", "the lights flickered").set("author", "RA").set("id", 7);
  ASSERT_TRUE(note.run(db, "test"));
  RawDb raw(path);
  EXPECT_EQ(raw.rows("SELECT id, participant_id, position, author, text, written_at FROM notes"),
            (std::vector<std::vector<std::string>>{{"7", "NULL", "NULL", "RA", "the lights flickered", at}}));

  auto bad = detail::RowInsert("notes").set("id", 8).set("txet", "typo").run(db, "test");
  ASSERT_FALSE(bad);
  EXPECT_EQ(bad.error().kind, ErrorKind::internal);
  EXPECT_EQ(bad.error().field, "notes.txet");
  auto no_table = detail::RowInsert("nodes").set("id", 8).run(db, "test");
  ASSERT_FALSE(no_table);
  EXPECT_EQ(no_table.error().kind, ErrorKind::internal);
  EXPECT_EQ(raw.count("SELECT count(*) FROM notes"), 1);

  auto q = detail::Stmt::prepare(db, "SELECT " + detail::select_list(*detail::find_table("notes"), "", 4) +
                                         " FROM notes", "test");
  ASSERT_TRUE(q);
  ASSERT_TRUE(*q->step("test"));
  const detail::NamedColumns col(*q);
  EXPECT_EQ(col.text(*q, "author"), "RA");
  EXPECT_EQ(col.text(*q, "text"), "the lights flickered");
  EXPECT_EQ(col.int64(*q, "id"), 7);
  EXPECT_EQ(col.opt_int(*q, "position"), std::nullopt);
  EXPECT_TRUE(col.is_null(*q, "participant_id"));
  EXPECT_FALSE(col.has("txet"));
  EXPECT_TRUE(col.is_null(*q, "txet"));
  // A column an older schema lacks is selected as NULL under its name.
  const std::string v2 = detail::select_list(*detail::find_table("trial_results"), "r.", 2);
  const std::string v3 = detail::select_list(*detail::find_table("trial_results"), "r.", 3);
  EXPECT_NE(v2.find("r.scene_hash AS scene_hash, "), std::string::npos);
  EXPECT_NE(v2.find("NULL AS frame_first_ms"), std::string::npos);
  EXPECT_EQ(v2.find("r.frame_first_ms"), std::string::npos);
  EXPECT_NE(v3.find("r.frame_first_ms AS frame_first_ms"), std::string::npos);
}

// Parameters are bound by name on both engines (PostgreSQL numbers them only; the store names
// them): in any order, one name used twice gets one value, a `:word` inside a quoted literal stays
// text, and a name the SQL lacks is an internal Error that runs nothing. query_int reads the
// column named n, and a query without one is an internal Error, never a wrong column's value.
TEST_P(Schema, ParametersAreBoundByName) {
  const auto path = study();
  { Store s = open_ok(path); }
  auto conn = detail::open_connection(path, detail::Access::write, 1000);
  ASSERT_TRUE(conn) << conn.error().to_string();
  detail::Db db(std::move(*conn));
  const std::string at = "2024-05-01T12:34:56.789Z";
  auto ins = detail::Stmt::prepare(db,
                                   "INSERT INTO notes (id, author, text, written_at) "
                                   "VALUES (:id, :who, :who || ' said :id', :at)",
                                   "test");
  ASSERT_TRUE(ins) << ins.error().to_string();
  ins->bind("at", at).bind("who", "RA").bind("id", 7);
  ASSERT_TRUE(ins->run("test"));
  RawDb raw(path);
  EXPECT_EQ(raw.rows("SELECT id, author, text, written_at FROM notes"),
            (std::vector<std::vector<std::string>>{{"7", "RA", "RA said :id", at}}));

  ins->bind("at", at).bind("who", "RA").bind("id", 8).bind("txet", "typo");
  auto bad = ins->run("test");
  ASSERT_FALSE(bad);
  EXPECT_EQ(bad.error().kind, ErrorKind::internal);
  EXPECT_EQ(bad.error().field, "txet");
  EXPECT_EQ(raw.count("SELECT count(*) FROM notes"), 1);

  auto n = db.query_int("SELECT count(*) AS n FROM notes WHERE author = :author AND id >= :id", "test",
                        {{"id", detail::Value{std::int64_t{7}}}, {"author", detail::Value{std::string("RA")}}});
  ASSERT_TRUE(n) << n.error().to_string();
  EXPECT_EQ(*n, std::optional<std::int64_t>(1));
  auto unnamed = db.query_int("SELECT count(*) FROM notes", "test");
  ASSERT_FALSE(unnamed);
  EXPECT_EQ(unnamed.error().kind, ErrorKind::internal);
  if (pg()) {  // a cast's :: is no parameter
    auto cast = db.query_text("SELECT (:v)::text || '::x' AS n", "test", {{"v", detail::Value{std::int64_t{5}}}});
    ASSERT_TRUE(cast) << cast.error().to_string();
    EXPECT_EQ(*cast, std::optional<std::string>("5::x"));
  }
}

}  // namespace
}  // namespace dtlab::store

// The schema migrations v1 to v4 on either engine (docs/store.md, "Schema"):
// each is the described tables' DDL (schema_tables.h: STRICT tables with
// CHECK constraints that make malformed rows impossible) and the engine's
// triggers (results append-only and in plan order), plus the trial_table
// view. Migrations are applied in the caller's write transaction, so a crash
// leaves either no schema or the whole of it. Never drops or rewrites a
// table holding data.
#include "study/store/detail/schema.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <charconv>
#include <cctype>
#include <string_view>

#include "study/store/detail/columns.h"
#include "study/store/detail/schema_sql.h"
#include "study/store/detail/schema_tables.h"
#include "study/store/detail/time.h"
#include "study/store/store.h"

namespace dtlab::store::detail {

std::uint64_t parse_seed(const std::string& s) {
  std::uint64_t v = 0;
  std::from_chars(s.data(), s.data() + s.size(), v);  // the schema guarantees 1-20 digits
  return v;
}

SessionStatus parse_status(const std::string& s) {
  if (s == "finished") return SessionStatus::finished;
  if (s == "abandoned") return SessionStatus::abandoned;
  return SessionStatus::running;
}

namespace {

const char* const kDescriptions[] = {
    "schema v1: studies, ledger, sessions, planned trials, results, events, poses, questionnaire",
    "schema v2: design hashes, exclusions, notes, pauses, trial attempts, session claims",
    "schema v3: warm-up and late frames per trial, the display of each session",
    "schema v4: consent answers, withdrawals, the screen log"};

// Migration `version`'s DDL on the database's engine (0: the migrations table and its bookkeeping):
// the described tables first, then the engine's triggers (and v1's view).
std::string migration_sql(Backend b, int version) {
  std::string s = table_ddl(b, version) + (b == Backend::postgresql ? pg_triggers(version) : sqlite_triggers(version));
  if (version == 1) s += session_table_view();
  return s;
}

std::string quote_identifier(const std::string& name) {
  std::string q = "\"";
  for (char c : name) q += c == '"' ? std::string("\"\"") : std::string(1, c);
  return q + "\"";
}

std::string quote_literal(const std::string& text) {
  std::string q = "'";
  for (char c : text) q += c == '\'' ? std::string("''") : std::string(1, c);
  return q + "'";
}

}  // namespace

const std::vector<std::string>& fixed_trial_columns_before_factors() {
  static const std::vector<std::string> c = {"participant", "enrollment_index", "session", "session_status",
                                             "order_row",   "position",         "block"};
  return c;
}

const std::vector<std::string>& fixed_trial_columns_after_factors() {
  static const std::vector<std::string> c = {
      "task",          "trial",         "practice",     "method",        "trial_seed",    "scene_hash",
      "answer_count",  "answer_letter", "answer_x",     "answer_z",      "truth_count",   "truth_letter",
      "truth_x",       "truth_z",       "rel_error",    "signed_error",  "correct",       "distance",
      "completion_time_s", "started_at", "ended_at",    "frame_count",   "frame_ms_mean", "frame_ms_sd",
      "frame_ms_p95",  "frame_ms_max",  "frame_first_ms", "frame_ms_median", "late_frames", "refresh_hz",
      "protocol_sha256", "design_revision", "excluded"};
  return c;
}

Result<int> applied_schema_version(Db& db) {
  auto has = db.conn().has_table("schema_migrations");
  if (!has) return has.error();
  if (!*has) return 0;
  auto v = db.query_int("SELECT max(version) AS n FROM schema_migrations", "reading the schema version");
  if (!v) return v.error();
  return static_cast<int>(v->value_or(0));
}

Status check_tables(Db& db, int version) {
  if (version < 1) return {};
  const std::vector<std::string> tables = table_names(version);
  std::string missing;
  for (const std::string& t : tables) {
    auto has = db.conn().has_table(t);
    if (!has) return has.error();
    if (!*has) missing += (missing.empty() ? "" : ", ") + t;
  }
  if (missing.empty()) return {};
  return Error{db.path(), 0, 0, "schema",
               "a damaged dtlab study database: schema version " + std::to_string(version) + " lacks the table(s) " +
                   missing + "; nothing was read or written (restore it from a copy)",
               ErrorKind::invalid_input};
}

Status migrate(Db& db, int from, const std::string& software_version, const std::map<int, AppliedMigration>& history) {
  if (from == 0) {
    if (auto s = db.conn().create_namespace(); !s) return s;
    if (auto s = db.exec(migration_sql(db.backend(), 0), "creating schema_migrations"); !s) return s;
  }
  for (int version = from + 1; version <= kSchemaVersion; ++version) {
    const std::string what = "applying schema migration " + std::to_string(version);
    if (auto s = db.exec(migration_sql(db.backend(), version), what); !s) return s;
    AppliedMigration row{kDescriptions[version - 1], "", software_version};
    if (auto h = history.find(version); h != history.end()) {
      row = h->second;
    } else {
      auto now = db.now_iso();
      if (!now) return now.error();
      row.applied_at = *now;
    }
    RowInsert ins("schema_migrations");
    ins.set("version", version).set("description", row.description).set("applied_at", row.applied_at);
    ins.set("software_version", row.software_version);
    if (auto s = ins.run(db, what); !s) return s;
  }
  if (from >= 1)  // an older view lacks the newer columns; a new database gets its view with the first study
    if (auto s = create_trial_table_view(db); !s) return s;
  return db.conn().mark_as_dtlab(kSchemaVersion);
}

Result<std::vector<std::string>> demographic_fields(Db& db) {
  const char* what = "reading the demographic fields";
  auto st = Stmt::prepare(db, "SELECT demographics AS demographics FROM participants ORDER BY enrollment_index", what);
  if (!st) return st.error();
  std::vector<std::string> fields;
  for (;;) {
    auto row = st->step(what);
    if (!row) return row.error();
    if (!*row) break;
    const auto j = nlohmann::ordered_json::parse(st->text("demographics"), nullptr, false);
    if (!j.is_object()) continue;  // the schema's CHECK makes it an object
    for (const auto& [k, v] : j.items())
      if (std::find(fields.begin(), fields.end(), k) == fields.end()) fields.push_back(k);
  }
  return fields;
}

Status create_trial_table_view(Db& db) {
  const std::string what = "creating the trial_table view";
  auto st = Stmt::prepare(
      db, "SELECT name AS name FROM study_factors GROUP BY name ORDER BY min(study_id), min(position)", what);
  if (!st) return st.error();
  std::vector<std::string> factors;
  for (;;) {
    auto row = st->step(what);
    if (!row) return row.error();
    if (!*row) break;
    factors.push_back(st->text("name"));
  }
  auto fields = demographic_fields(db);
  if (!fields) return fields.error();
  // A field's value as text, looked up by its exact name (any characters) on either engine.
  auto field_value = [&](const std::string& f) {
    return db.backend() == Backend::postgresql
               ? "(pa.demographics::json ->> " + quote_literal(f) + ")"
               : "(SELECT j.value FROM json_each(pa.demographics) j WHERE j.key = " + quote_literal(f) + ")";
  };
  std::string sql = "DROP VIEW IF EXISTS trial_table;\nCREATE VIEW trial_table AS SELECT\n"
                    "  pa.participant AS participant, pa.enrollment_index AS enrollment_index,\n"
                    "  s.id AS session, s.status AS session_status, pa.order_row AS order_row,\n"
                    "  p.position AS position, p.block AS block,\n";
  for (const std::string& f : factors)
    sql += "  (SELECT l.level FROM planned_levels l WHERE l.planned_trial_id = p.id AND l.factor = " +
           quote_literal(f) + ") AS " + quote_identifier(f) + ",\n";
  sql +=
      "  p.task AS task, p.trial AS trial, p.practice AS practice, p.method AS method,\n"
      "  p.seed AS trial_seed, r.scene_hash AS scene_hash,\n"
      "  r.answer_count AS answer_count, r.answer_letter AS answer_letter, r.answer_x AS answer_x,\n"
      "  r.answer_z AS answer_z, r.truth_count AS truth_count, r.truth_letter AS truth_letter,\n"
      "  r.truth_x AS truth_x, r.truth_z AS truth_z, r.rel_error AS rel_error,\n"
      "  r.signed_error AS signed_error, r.correct AS correct, r.distance AS distance,\n"
      "  r.completion_s AS completion_time_s, r.started_at AS started_at, r.ended_at AS ended_at,\n"
      "  r.frame_count AS frame_count, r.frame_ms_mean AS frame_ms_mean, r.frame_ms_sd AS frame_ms_sd,\n"
      "  r.frame_ms_p95 AS frame_ms_p95, r.frame_ms_max AS frame_ms_max,\n"
      "  r.frame_first_ms AS frame_first_ms, r.frame_ms_median AS frame_ms_median,\n"
      "  r.late_frames AS late_frames, r.refresh_hz AS refresh_hz,\n"
      "  st.protocol_sha256 AS protocol_sha256,\n"
      // Design revision: 1 + the number of distinct design hashes first recorded before this one's.
      "  (SELECT count(*) FROM (SELECT 1 FROM study_designs d2 GROUP BY d2.design_sha256\n"
      "     HAVING min(d2.study_id) <= (SELECT min(d3.study_id) FROM study_designs d3\n"
      "                                 WHERE d3.design_sha256 = sd.design_sha256)) AS earlier)\n"
      "    AS design_revision,\n"
      // The latest decision about the participant wins over the trial's; an inclusion reads as NULL.
      "  coalesce((SELECT CASE x.action WHEN 'exclude' THEN x.reason END FROM exclusions x\n"
      "            WHERE x.participant_id = pa.id AND x.position IS NULL ORDER BY x.id DESC LIMIT 1),\n"
      "           (SELECT CASE x.action WHEN 'exclude' THEN x.reason END FROM exclusions x\n"
      "            WHERE x.participant_id = pa.id AND x.position = p.position ORDER BY x.id DESC LIMIT 1))\n"
      "    AS excluded";
  for (const std::string& f : *fields) sql += ",\n  " + field_value(f) + " AS " + quote_identifier(kDemographicPrefix + f);
  sql +=
      "\nFROM trial_results r\n"
      "JOIN planned_trials p ON p.id = r.planned_trial_id\n"
      "JOIN sessions s ON s.id = p.session_id\n"
      "JOIN participants pa ON pa.id = s.participant_id\n"
      "JOIN studies st ON st.id = s.study_id\n"
      "LEFT JOIN study_designs sd ON sd.study_id = st.id\n"
      // Invariant 13: a participant who withdrew their consent is left out of the table.
      "WHERE NOT EXISTS (SELECT 1 FROM withdrawals w WHERE w.participant_id = pa.id);";
  return db.exec(sql, what);
}

}  // namespace dtlab::store::detail

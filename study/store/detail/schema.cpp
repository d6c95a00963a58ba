// Schema v1 (docs/store.md, "Schema"): STRICT tables with CHECK constraints
// that make malformed rows impossible, triggers that make results
// append-only and in plan order, and the trial_table view. Migrations are
// applied in the caller's write transaction, so a crash leaves either no
// schema or the whole of it. Never drops or rewrites a table holding data.
#include "study/store/detail/schema.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <charconv>
#include <cctype>
#include <regex>
#include <string_view>

#include "study/store/detail/schema_sql.h"
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

std::string iso_check(std::string_view column) {
  return std::string("CHECK (") + std::string(column) + " GLOB " + kIsoGlob + ")";
}

std::string iso_check_nullable(std::string_view column) {
  return std::string("CHECK (") + std::string(column) + " IS NULL OR " + std::string(column) + " GLOB " + kIsoGlob + ")";
}

std::string hex_check(std::string_view column, int length) {
  const std::string c(column);
  return "CHECK (length(" + c + ") = " + std::to_string(length) + " AND " + c + " NOT GLOB '*[^0-9a-f]*')";
}

namespace {

std::string schema_v1() {
  std::string s;
  s += R"sql(
CREATE TABLE studies (
  id INTEGER PRIMARY KEY,
  protocol_id TEXT NOT NULL CHECK (length(protocol_id) > 0),
  protocol_text TEXT NOT NULL,
  protocol_sha256 TEXT NOT NULL )sql" + hex_check("protocol_sha256", 64) + R"sql(,
  software_version TEXT NOT NULL,
  order_rows INTEGER NOT NULL CHECK (order_rows >= 1),
  created_at TEXT NOT NULL )sql" + iso_check("created_at") + R"sql(
) STRICT;

CREATE TABLE study_factors (
  study_id INTEGER NOT NULL REFERENCES studies(id),
  position INTEGER NOT NULL CHECK (position >= 1),
  name TEXT NOT NULL CHECK (length(name) > 0),
  PRIMARY KEY (study_id, position),
  UNIQUE (study_id, name)
) STRICT, WITHOUT ROWID;

CREATE TABLE participants (
  id INTEGER PRIMARY KEY,
  participant TEXT NOT NULL UNIQUE CHECK (length(participant) BETWEEN 1 AND 64),
  enrollment_index INTEGER NOT NULL UNIQUE CHECK (enrollment_index >= 0),
  order_row INTEGER NOT NULL CHECK (order_row >= 0),
  study_id INTEGER NOT NULL REFERENCES studies(id),
  demographics TEXT NOT NULL DEFAULT '{}' CHECK (json_valid(demographics) AND json_type(demographics) = 'object'),
  enrolled_at TEXT NOT NULL )sql" + iso_check("enrolled_at") + R"sql(,
  released_at TEXT )sql" + iso_check_nullable("released_at") + R"sql(
) STRICT;
CREATE INDEX participants_active_by_row ON participants(order_row) WHERE released_at IS NULL;

CREATE TABLE sessions (
  id INTEGER PRIMARY KEY,
  participant_id INTEGER NOT NULL UNIQUE REFERENCES participants(id),
  study_id INTEGER NOT NULL REFERENCES studies(id),
  software_version TEXT NOT NULL,
  status TEXT NOT NULL CHECK (status IN ('running', 'finished', 'abandoned')),
  started_at TEXT NOT NULL )sql" + iso_check("started_at") + R"sql(,
  ended_at TEXT )sql" + iso_check_nullable("ended_at") + R"sql(,
  CHECK ((status = 'running') = (ended_at IS NULL))
) STRICT;

CREATE TABLE session_resumes (
  session_id INTEGER NOT NULL REFERENCES sessions(id),
  resumed_at TEXT NOT NULL )sql" + iso_check("resumed_at") + R"sql(,
  software_version TEXT NOT NULL,
  next_position INTEGER CHECK (next_position IS NULL OR next_position >= 1)
) STRICT;
CREATE INDEX session_resumes_by_session ON session_resumes(session_id);

CREATE TABLE planned_trials (
  id INTEGER PRIMARY KEY,
  session_id INTEGER NOT NULL REFERENCES sessions(id),
  position INTEGER NOT NULL CHECK (position >= 1),
  block INTEGER NOT NULL CHECK (block >= 1),
  task TEXT NOT NULL CHECK (length(task) > 0),
  trial INTEGER NOT NULL CHECK (trial >= 1),
  seed TEXT NOT NULL CHECK (length(seed) BETWEEN 1 AND 20 AND seed NOT GLOB '*[^0-9]*'),
  method TEXT NOT NULL,
  practice INTEGER NOT NULL CHECK (practice IN (0, 1)),
  UNIQUE (session_id, position)
) STRICT;

CREATE TABLE planned_levels (
  planned_trial_id INTEGER NOT NULL REFERENCES planned_trials(id),
  factor_position INTEGER NOT NULL CHECK (factor_position >= 1),
  factor TEXT NOT NULL CHECK (length(factor) > 0),
  level TEXT NOT NULL,
  PRIMARY KEY (planned_trial_id, factor_position),
  UNIQUE (planned_trial_id, factor)
) STRICT, WITHOUT ROWID;

CREATE TABLE trial_results (
  planned_trial_id INTEGER PRIMARY KEY REFERENCES planned_trials(id),
  scene_hash TEXT NOT NULL )sql" + hex_check("scene_hash", 64) + R"sql(,
  answer_kind TEXT NOT NULL CHECK (answer_kind IN ('count', 'letter', 'position')),
  answered INTEGER NOT NULL CHECK (answered IN (0, 1)),
  answer_count INTEGER CHECK (answer_count >= 0),
  answer_letter TEXT CHECK (length(answer_letter) > 0),
  answer_x REAL,
  answer_z REAL,
  truth_count INTEGER CHECK (truth_count >= 0),
  truth_letter TEXT CHECK (length(truth_letter) > 0),
  truth_x REAL,
  truth_z REAL,
  rel_error REAL,
  signed_error INTEGER,
  correct INTEGER CHECK (correct IN (0, 1)),
  distance REAL CHECK (distance >= 0),
  completion_s REAL NOT NULL CHECK (completion_s >= 0),
  started_at TEXT NOT NULL )sql" + iso_check("started_at") + R"sql(,
  ended_at TEXT NOT NULL )sql" + iso_check("ended_at") + R"sql(,
  frame_count INTEGER NOT NULL CHECK (frame_count >= 0),
  frame_ms_mean REAL CHECK (frame_ms_mean >= 0),
  frame_ms_sd REAL CHECK (frame_ms_sd >= 0),
  frame_ms_p95 REAL CHECK (frame_ms_p95 >= 0),
  frame_ms_max REAL CHECK (frame_ms_max >= 0),
  event_count INTEGER NOT NULL CHECK (event_count >= 0),
  recorded_at TEXT NOT NULL )sql" + iso_check("recorded_at") + R"sql(,
  CHECK (ended_at >= started_at),
  CHECK ((frame_count > 0) = (frame_ms_mean IS NOT NULL) AND (frame_count > 0) = (frame_ms_p95 IS NOT NULL)
         AND (frame_count > 0) = (frame_ms_max IS NOT NULL) AND (frame_count > 1) = (frame_ms_sd IS NOT NULL)),
  -- The answer's shape follows its kind, and the score columns are exactly
  -- what store::score() computes (score.h); see docs/store.md, invariant 8.
  CHECK (CASE answer_kind
    WHEN 'count' THEN
      truth_count IS NOT NULL AND truth_letter IS NULL AND truth_x IS NULL AND truth_z IS NULL
      AND answer_letter IS NULL AND answer_x IS NULL AND answer_z IS NULL
      AND answered = (answer_count IS NOT NULL)
      AND correct IS NULL AND distance IS NULL
      AND signed_error IS answer_count - truth_count
      AND rel_error IS (CASE WHEN truth_count <> 0 THEN abs(answer_count - truth_count) * 1.0 / truth_count END)
    WHEN 'letter' THEN
      truth_letter IS NOT NULL AND truth_count IS NULL AND truth_x IS NULL AND truth_z IS NULL
      AND answer_count IS NULL AND answer_x IS NULL AND answer_z IS NULL
      AND answered = (answer_letter IS NOT NULL)
      AND rel_error IS NULL AND signed_error IS NULL AND distance IS NULL
      AND correct IS (answer_letter = truth_letter)
    WHEN 'position' THEN
      truth_x IS NOT NULL AND truth_z IS NOT NULL AND truth_count IS NULL AND truth_letter IS NULL
      AND answer_count IS NULL AND answer_letter IS NULL
      AND (answer_x IS NULL) = (answer_z IS NULL) AND answered = (answer_x IS NOT NULL)
      AND rel_error IS NULL AND signed_error IS NULL AND correct IS NULL
      AND (distance IS NOT NULL) = answered
      AND (distance IS NULL OR abs(distance * distance - ((answer_x - truth_x) * (answer_x - truth_x)
            + (answer_z - truth_z) * (answer_z - truth_z)))
          <= 1e-9 * (1 + (answer_x - truth_x) * (answer_x - truth_x) + (answer_z - truth_z) * (answer_z - truth_z)))
  END)
) STRICT;

CREATE TABLE input_events (
  trial_id INTEGER NOT NULL REFERENCES trial_results(planned_trial_id),
  seq INTEGER NOT NULL CHECK (seq >= 1),
  t_s REAL NOT NULL CHECK (t_s >= 0),
  kind TEXT NOT NULL CHECK (kind IN ('key_down', 'key_up', 'button_down', 'button_up', 'cursor', 'scroll', 'answer')),
  detail TEXT NOT NULL,
  x REAL NOT NULL,
  y REAL NOT NULL,
  PRIMARY KEY (trial_id, seq)
) STRICT, WITHOUT ROWID;

CREATE TABLE camera_poses (
  trial_id INTEGER NOT NULL REFERENCES trial_results(planned_trial_id),
  frame INTEGER NOT NULL CHECK (frame >= 1),
  t_s REAL NOT NULL CHECK (t_s >= 0),
  x REAL NOT NULL,
  y REAL NOT NULL,
  z REAL NOT NULL,
  yaw REAL NOT NULL,
  pitch REAL NOT NULL,
  PRIMARY KEY (trial_id, frame)
) STRICT, WITHOUT ROWID;

CREATE TABLE questionnaire_answers (
  session_id INTEGER NOT NULL REFERENCES sessions(id),
  item TEXT NOT NULL CHECK (length(item) > 0),
  scope TEXT NOT NULL,
  value_number REAL,
  value_text TEXT,
  answered_at TEXT NOT NULL )sql" + iso_check("answered_at") + R"sql(,
  CHECK ((value_number IS NULL) <> (value_text IS NULL)),
  PRIMARY KEY (session_id, item, scope)
) STRICT, WITHOUT ROWID;

-- Invariant 6: the results of a session are a prefix of its plan, and only a
-- running session takes results.
CREATE TRIGGER trial_results_in_plan_order BEFORE INSERT ON trial_results
BEGIN
  SELECT RAISE(ABORT, 'dtlab: trial results must be recorded in plan order')
  WHERE EXISTS (
    SELECT 1 FROM planned_trials q JOIN planned_trials p ON p.session_id = q.session_id
    WHERE q.id = NEW.planned_trial_id AND p.position < q.position
      AND NOT EXISTS (SELECT 1 FROM trial_results r WHERE r.planned_trial_id = p.id));
  SELECT RAISE(ABORT, 'dtlab: the session is not running')
  WHERE (SELECT s.status FROM sessions s JOIN planned_trials q ON q.session_id = s.id
         WHERE q.id = NEW.planned_trial_id) IS NOT 'running';
END;

-- Invariants 2, 3, 5, 7: what is saved is never rewritten or deleted.
CREATE TRIGGER trial_results_no_update BEFORE UPDATE ON trial_results
BEGIN SELECT RAISE(ABORT, 'dtlab: trial results are never changed'); END;
CREATE TRIGGER trial_results_no_delete BEFORE DELETE ON trial_results
BEGIN SELECT RAISE(ABORT, 'dtlab: trial results are never deleted'); END;
CREATE TRIGGER planned_trials_no_update BEFORE UPDATE ON planned_trials
BEGIN SELECT RAISE(ABORT, 'dtlab: planned trials are never changed'); END;
CREATE TRIGGER planned_trials_no_delete BEFORE DELETE ON planned_trials
BEGIN SELECT RAISE(ABORT, 'dtlab: planned trials are never deleted'); END;
CREATE TRIGGER planned_levels_no_update BEFORE UPDATE ON planned_levels
BEGIN SELECT RAISE(ABORT, 'dtlab: planned trials are never changed'); END;
CREATE TRIGGER planned_levels_no_delete BEFORE DELETE ON planned_levels
BEGIN SELECT RAISE(ABORT, 'dtlab: planned trials are never deleted'); END;
CREATE TRIGGER studies_no_update BEFORE UPDATE ON studies
BEGIN SELECT RAISE(ABORT, 'dtlab: a study row is never changed; a new protocol adds a row'); END;
CREATE TRIGGER studies_no_delete BEFORE DELETE ON studies
BEGIN SELECT RAISE(ABORT, 'dtlab: studies are never deleted'); END;
CREATE TRIGGER participants_no_delete BEFORE DELETE ON participants
BEGIN SELECT RAISE(ABORT, 'dtlab: participants are never deleted; release() frees their row'); END;
CREATE TRIGGER sessions_no_delete BEFORE DELETE ON sessions
BEGIN SELECT RAISE(ABORT, 'dtlab: sessions are never deleted'); END;

-- Invariant 3: an enrollment never changes, except that it may be released once.
CREATE TRIGGER participants_ledger_fixed BEFORE UPDATE ON participants
WHEN NEW.participant IS NOT OLD.participant OR NEW.enrollment_index IS NOT OLD.enrollment_index
  OR NEW.order_row IS NOT OLD.order_row OR NEW.study_id IS NOT OLD.study_id
  OR NEW.demographics IS NOT OLD.demographics OR NEW.enrolled_at IS NOT OLD.enrolled_at
  OR OLD.released_at IS NOT NULL
BEGIN SELECT RAISE(ABORT, 'dtlab: an enrollment is never changed, only released once'); END;

-- Invariant 9: running -> finished | abandoned; both are final. Finished
-- needs a result for every planned trial.
CREATE TRIGGER sessions_status_transitions BEFORE UPDATE ON sessions
BEGIN
  SELECT RAISE(ABORT, 'dtlab: a finished or abandoned session is final')
  WHERE OLD.status <> 'running';
  SELECT RAISE(ABORT, 'dtlab: only a session''s status and end time change')
  WHERE NEW.participant_id IS NOT OLD.participant_id OR NEW.study_id IS NOT OLD.study_id
     OR NEW.software_version IS NOT OLD.software_version OR NEW.started_at IS NOT OLD.started_at;
  SELECT RAISE(ABORT, 'dtlab: a session finishes only when every planned trial has a result')
  WHERE NEW.status = 'finished' AND EXISTS (
    SELECT 1 FROM planned_trials p WHERE p.session_id = OLD.id
      AND NOT EXISTS (SELECT 1 FROM trial_results r WHERE r.planned_trial_id = p.id));
END;

CREATE VIEW session_table AS
SELECT pa.participant AS participant, pa.enrollment_index AS enrollment_index, pa.order_row AS order_row,
       s.id AS session, s.status AS status, s.started_at AS started_at, s.ended_at AS ended_at,
       s.software_version AS software_version,
       (SELECT count(*) FROM planned_trials p WHERE p.session_id = s.id) AS planned_trials,
       (SELECT count(*) FROM planned_trials p JOIN trial_results r ON r.planned_trial_id = p.id
        WHERE p.session_id = s.id) AS recorded_trials,
       (SELECT count(*) FROM session_resumes x WHERE x.session_id = s.id) AS resumes
FROM sessions s JOIN participants pa ON pa.id = s.participant_id;
)sql";
  return s;
}

struct Migration {
  int version;
  const char* description;
  std::string (*sql)();
};

const char* const kV1 = "schema v1: studies, ledger, sessions, planned trials, results, events, poses, questionnaire";
const char* const kV2 = "schema v2: design hashes, exclusions, notes, pauses, trial attempts, session claims";
const char* const kV3 = "schema v3: warm-up and late frames per trial, the display of each session";
const char* const kV4 = "schema v4: consent answers, withdrawals, the screen log";

const std::vector<Migration>& migrations(Backend backend) {
  static const std::vector<Migration> sqlite = {
      {1, kV1, &schema_v1}, {2, kV2, &schema_v2}, {3, kV3, &schema_v3}, {4, kV4, &schema_v4}};
  static const std::vector<Migration> postgres = {
      {1, kV1, &pg_schema_v1}, {2, kV2, &pg_schema_v2}, {3, kV3, &pg_schema_v3}, {4, kV4, &pg_schema_v4}};
  return backend == Backend::postgresql ? postgres : sqlite;
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
  auto v = db.query_int("SELECT max(version) FROM schema_migrations", "reading the schema version");
  if (!v) return v.error();
  return static_cast<int>(v->value_or(0));
}

Status check_tables(Db& db, int version) {
  if (version < 1) return {};
  std::vector<std::string> tables{"schema_migrations"};
  static const std::regex create(R"(CREATE TABLE ([A-Za-z_][A-Za-z0-9_]*))");
  for (const Migration& m : migrations(db.backend())) {
    if (m.version > version) continue;
    const std::string sql = m.sql();
    for (auto it = std::sregex_iterator(sql.begin(), sql.end(), create); it != std::sregex_iterator(); ++it)
      tables.push_back((*it)[1].str());
  }
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
    const std::string sql =
        db.backend() == Backend::postgresql
            ? pg_bookkeeping()
            : "CREATE TABLE schema_migrations (\n"
              "  version INTEGER PRIMARY KEY CHECK (version >= 1),\n"
              "  description TEXT NOT NULL,\n"
              "  applied_at TEXT NOT NULL " + iso_check("applied_at") + ",\n"
              "  software_version TEXT NOT NULL\n"
              ") STRICT;";
    if (auto s = db.conn().create_namespace(); !s) return s;
    if (auto s = db.exec(sql, "creating schema_migrations"); !s) return s;
  }
  for (const Migration& m : migrations(db.backend())) {
    if (m.version <= from) continue;
    const std::string what = "applying schema migration " + std::to_string(m.version);
    if (auto s = db.exec(m.sql(), what); !s) return s;
    auto st = Stmt::prepare(db,
                            "INSERT INTO schema_migrations (version, description, applied_at, software_version) "
                            "VALUES (?, ?, ?, ?)",
                            what);
    if (!st) return st.error();
    AppliedMigration row{m.description, "", software_version};
    if (auto h = history.find(m.version); h != history.end()) {
      row = h->second;
    } else {
      auto now = db.now_iso();
      if (!now) return now.error();
      row.applied_at = *now;
    }
    st->bind(1, m.version).bind(2, row.description).bind(3, row.applied_at).bind(4, row.software_version);
    if (auto s = st->run(what); !s) return s;
  }
  if (from >= 1)  // an older view lacks the newer columns; a new database gets its view with the first study
    if (auto s = create_trial_table_view(db); !s) return s;
  return db.conn().mark_as_dtlab(kSchemaVersion);
}

Result<std::vector<std::string>> demographic_fields(Db& db) {
  const char* what = "reading the demographic fields";
  auto st = Stmt::prepare(db, "SELECT demographics FROM participants ORDER BY enrollment_index", what);
  if (!st) return st.error();
  std::vector<std::string> fields;
  for (;;) {
    auto row = st->step(what);
    if (!row) return row.error();
    if (!*row) break;
    const auto j = nlohmann::ordered_json::parse(st->text(0), nullptr, false);
    if (!j.is_object()) continue;  // the schema's CHECK makes it an object
    for (const auto& [k, v] : j.items())
      if (std::find(fields.begin(), fields.end(), k) == fields.end()) fields.push_back(k);
  }
  return fields;
}

Status create_trial_table_view(Db& db) {
  const std::string what = "creating the trial_table view";
  auto st = Stmt::prepare(db, "SELECT name FROM study_factors GROUP BY name ORDER BY min(study_id), min(position)", what);
  if (!st) return st.error();
  std::vector<std::string> factors;
  for (;;) {
    auto row = st->step(what);
    if (!row) return row.error();
    if (!*row) break;
    factors.push_back(st->text(0));
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

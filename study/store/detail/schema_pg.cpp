// Schema v1 to v4 on PostgreSQL (docs/store.md, "Schema v1" to "Schema v4",
// "PostgreSQL"): the same tables, columns, constraints and views as the
// SQLite text in schema.cpp and schema_v2.cpp to schema_v4.cpp, in
// PostgreSQL's dialect.
// SQLite's STRICT INTEGER/REAL/TEXT are BIGINT/DOUBLE PRECISION/TEXT COLLATE
// "C" (byte order, as SQLite compares); GLOB checks are regular expressions;
// SQLite's RAISE(ABORT) triggers are PL/pgSQL functions raising SQLSTATE 23000.
// A shared server has many clients, so every append-only table also refuses
// TRUNCATE, and the tables SQLite leaves unguarded (factors, resumes, events,
// poses, questionnaire answers) refuse UPDATE and DELETE here. Nothing here
// runs a statement; the caller runs the text inside its write transaction.
#include <string>
#include <string_view>

#include "study/store/detail/schema_sql.h"

namespace dtlab::store::detail {
namespace {

constexpr const char* kIsoRegex = "'^[0-9]{4}-[0-1][0-9]-[0-3][0-9]T[0-2][0-9]:[0-5][0-9]:[0-6][0-9][.][0-9]{3}Z$'";

std::string iso(std::string_view c) { return "CHECK (" + std::string(c) + " ~ " + kIsoRegex + ")"; }
std::string iso_null(std::string_view c) {
  return "CHECK (" + std::string(c) + " IS NULL OR " + std::string(c) + " ~ " + kIsoRegex + ")";
}
std::string hex(std::string_view c, int length) {
  const std::string s(c);
  return "CHECK (length(" + s + ") = " + std::to_string(length) + " AND " + s + " !~ '[^0-9a-f]')";
}

// Every TEXT column compares bytes, as SQLite's BINARY collation does (order of ORDER BY, UNIQUE).
std::string c_collated(std::string ddl) {
  std::string out;
  std::size_t from = 0;
  for (std::size_t at; (at = ddl.find(" TEXT", from)) != std::string::npos; from = at + 5) {
    out += ddl.substr(from, at - from) + " TEXT COLLATE \"C\"";
  }
  return out + ddl.substr(from);
}

// BEFORE UPDATE, DELETE (per row) and TRUNCATE (per statement) triggers refusing with `message`.
std::string append_only(const std::string& table, const std::string& changed, const std::string& deleted) {
  return "CREATE TRIGGER " + table + "_no_update BEFORE UPDATE ON " + table +
         " FOR EACH ROW EXECUTE FUNCTION dtlab_refuse('" + changed + "');\n"
         "CREATE TRIGGER " + table + "_no_delete BEFORE DELETE ON " + table +
         " FOR EACH ROW EXECUTE FUNCTION dtlab_refuse('" + deleted + "');\n"
         "CREATE TRIGGER " + table + "_no_truncate BEFORE TRUNCATE ON " + table +
         " FOR EACH STATEMENT EXECUTE FUNCTION dtlab_refuse('" + deleted + "');\n";
}

}  // namespace

std::string pg_bookkeeping() {
  return c_collated(R"sql(
CREATE TABLE dtlab_header (
  one BOOLEAN PRIMARY KEY DEFAULT TRUE CHECK (one),
  application_id BIGINT NOT NULL,
  user_version BIGINT NOT NULL
);
CREATE TABLE schema_migrations (
  version BIGINT PRIMARY KEY CHECK (version >= 1),
  description TEXT NOT NULL,
  applied_at TEXT NOT NULL )sql" + iso("applied_at") + R"sql(,
  software_version TEXT NOT NULL
);
CREATE FUNCTION dtlab_refuse() RETURNS trigger LANGUAGE plpgsql SET search_path FROM CURRENT AS $$
BEGIN
  RAISE EXCEPTION USING ERRCODE = 'integrity_constraint_violation', MESSAGE = TG_ARGV[0];
END $$;
)sql" + append_only("schema_migrations", "dtlab: applied migrations are never changed",
                    "dtlab: applied migrations are never deleted"));
}

std::string pg_schema_v1() {
  std::string s = R"sql(
CREATE TABLE studies (
  id BIGINT PRIMARY KEY,
  protocol_id TEXT NOT NULL CHECK (length(protocol_id) > 0),
  protocol_text TEXT NOT NULL,
  protocol_sha256 TEXT NOT NULL )sql" + hex("protocol_sha256", 64) + R"sql(,
  software_version TEXT NOT NULL,
  order_rows BIGINT NOT NULL CHECK (order_rows >= 1),
  created_at TEXT NOT NULL )sql" + iso("created_at") + R"sql(
);

CREATE TABLE study_factors (
  study_id BIGINT NOT NULL REFERENCES studies(id),
  position BIGINT NOT NULL CHECK (position >= 1),
  name TEXT NOT NULL CHECK (length(name) > 0),
  PRIMARY KEY (study_id, position),
  UNIQUE (study_id, name)
);

CREATE TABLE participants (
  id BIGINT PRIMARY KEY,
  participant TEXT NOT NULL UNIQUE CHECK (length(participant) BETWEEN 1 AND 64),
  enrollment_index BIGINT NOT NULL UNIQUE CHECK (enrollment_index >= 0),
  order_row BIGINT NOT NULL CHECK (order_row >= 0),
  study_id BIGINT NOT NULL REFERENCES studies(id),
  demographics TEXT NOT NULL DEFAULT '{}' CHECK (json_typeof(demographics::json) = 'object'),
  enrolled_at TEXT NOT NULL )sql" + iso("enrolled_at") + R"sql(,
  released_at TEXT )sql" + iso_null("released_at") + R"sql(
);
CREATE INDEX participants_active_by_row ON participants(order_row) WHERE released_at IS NULL;

CREATE TABLE sessions (
  id BIGINT PRIMARY KEY,
  participant_id BIGINT NOT NULL UNIQUE REFERENCES participants(id),
  study_id BIGINT NOT NULL REFERENCES studies(id),
  software_version TEXT NOT NULL,
  status TEXT NOT NULL CHECK (status IN ('running', 'finished', 'abandoned')),
  started_at TEXT NOT NULL )sql" + iso("started_at") + R"sql(,
  ended_at TEXT )sql" + iso_null("ended_at") + R"sql(,
  CHECK ((status = 'running') = (ended_at IS NULL))
);

CREATE TABLE session_resumes (
  session_id BIGINT NOT NULL REFERENCES sessions(id),
  resumed_at TEXT NOT NULL )sql" + iso("resumed_at") + R"sql(,
  software_version TEXT NOT NULL,
  next_position BIGINT CHECK (next_position IS NULL OR next_position >= 1)
);
CREATE INDEX session_resumes_by_session ON session_resumes(session_id);

CREATE TABLE planned_trials (
  id BIGINT PRIMARY KEY,
  session_id BIGINT NOT NULL REFERENCES sessions(id),
  position BIGINT NOT NULL CHECK (position >= 1),
  block BIGINT NOT NULL CHECK (block >= 1),
  task TEXT NOT NULL CHECK (length(task) > 0),
  trial BIGINT NOT NULL CHECK (trial >= 1),
  seed TEXT NOT NULL CHECK (length(seed) BETWEEN 1 AND 20 AND seed !~ '[^0-9]'),
  method TEXT NOT NULL,
  practice BIGINT NOT NULL CHECK (practice IN (0, 1)),
  UNIQUE (session_id, position)
);

CREATE TABLE planned_levels (
  planned_trial_id BIGINT NOT NULL REFERENCES planned_trials(id),
  factor_position BIGINT NOT NULL CHECK (factor_position >= 1),
  factor TEXT NOT NULL CHECK (length(factor) > 0),
  level TEXT NOT NULL,
  PRIMARY KEY (planned_trial_id, factor_position),
  UNIQUE (planned_trial_id, factor)
);

CREATE TABLE trial_results (
  planned_trial_id BIGINT PRIMARY KEY REFERENCES planned_trials(id),
  scene_hash TEXT NOT NULL )sql" + hex("scene_hash", 64) + R"sql(,
  answer_kind TEXT NOT NULL CHECK (answer_kind IN ('count', 'letter', 'position')),
  answered BIGINT NOT NULL CHECK (answered IN (0, 1)),
  answer_count BIGINT CHECK (answer_count >= 0),
  answer_letter TEXT CHECK (length(answer_letter) > 0),
  answer_x DOUBLE PRECISION,
  answer_z DOUBLE PRECISION,
  truth_count BIGINT CHECK (truth_count >= 0),
  truth_letter TEXT CHECK (length(truth_letter) > 0),
  truth_x DOUBLE PRECISION,
  truth_z DOUBLE PRECISION,
  rel_error DOUBLE PRECISION,
  signed_error BIGINT,
  correct BIGINT CHECK (correct IN (0, 1)),
  distance DOUBLE PRECISION CHECK (distance >= 0),
  completion_s DOUBLE PRECISION NOT NULL CHECK (completion_s >= 0),
  started_at TEXT NOT NULL )sql" + iso("started_at") + R"sql(,
  ended_at TEXT NOT NULL )sql" + iso("ended_at") + R"sql(,
  frame_count BIGINT NOT NULL CHECK (frame_count >= 0),
  frame_ms_mean DOUBLE PRECISION CHECK (frame_ms_mean >= 0),
  frame_ms_sd DOUBLE PRECISION CHECK (frame_ms_sd >= 0),
  frame_ms_p95 DOUBLE PRECISION CHECK (frame_ms_p95 >= 0),
  frame_ms_max DOUBLE PRECISION CHECK (frame_ms_max >= 0),
  event_count BIGINT NOT NULL CHECK (event_count >= 0),
  recorded_at TEXT NOT NULL )sql" + iso("recorded_at") + R"sql(,
  CHECK (ended_at >= started_at),
  CHECK ((frame_count > 0) = (frame_ms_mean IS NOT NULL) AND (frame_count > 0) = (frame_ms_p95 IS NOT NULL)
         AND (frame_count > 0) = (frame_ms_max IS NOT NULL) AND (frame_count > 1) = (frame_ms_sd IS NOT NULL)),
  -- docs/store.md, invariant 8: the score columns are exactly what store::score() computes
  -- (IEEE double division and the same tolerance on the distance as on SQLite).
  CHECK (CASE answer_kind
    WHEN 'count' THEN
      truth_count IS NOT NULL AND truth_letter IS NULL AND truth_x IS NULL AND truth_z IS NULL
      AND answer_letter IS NULL AND answer_x IS NULL AND answer_z IS NULL
      AND (answered = 1) = (answer_count IS NOT NULL)
      AND correct IS NULL AND distance IS NULL
      AND signed_error IS NOT DISTINCT FROM answer_count - truth_count
      AND rel_error IS NOT DISTINCT FROM (CASE WHEN truth_count <> 0
            THEN abs(answer_count - truth_count)::double precision / truth_count::double precision END)
    WHEN 'letter' THEN
      truth_letter IS NOT NULL AND truth_count IS NULL AND truth_x IS NULL AND truth_z IS NULL
      AND answer_count IS NULL AND answer_x IS NULL AND answer_z IS NULL
      AND (answered = 1) = (answer_letter IS NOT NULL)
      AND rel_error IS NULL AND signed_error IS NULL AND distance IS NULL
      AND correct IS NOT DISTINCT FROM (CASE WHEN answer_letter IS NULL THEN NULL
                                             WHEN answer_letter = truth_letter THEN 1 ELSE 0 END)
    WHEN 'position' THEN
      truth_x IS NOT NULL AND truth_z IS NOT NULL AND truth_count IS NULL AND truth_letter IS NULL
      AND answer_count IS NULL AND answer_letter IS NULL
      AND (answer_x IS NULL) = (answer_z IS NULL) AND (answered = 1) = (answer_x IS NOT NULL)
      AND rel_error IS NULL AND signed_error IS NULL AND correct IS NULL
      AND (distance IS NOT NULL) = (answered = 1)
      AND (distance IS NULL OR abs(distance * distance - ((answer_x - truth_x) * (answer_x - truth_x)
            + (answer_z - truth_z) * (answer_z - truth_z)))
          <= 1e-9 * (1 + (answer_x - truth_x) * (answer_x - truth_x) + (answer_z - truth_z) * (answer_z - truth_z)))
  END)
);

CREATE TABLE input_events (
  trial_id BIGINT NOT NULL REFERENCES trial_results(planned_trial_id),
  seq BIGINT NOT NULL CHECK (seq >= 1),
  t_s DOUBLE PRECISION NOT NULL CHECK (t_s >= 0),
  kind TEXT NOT NULL CHECK (kind IN ('key_down', 'key_up', 'button_down', 'button_up', 'cursor', 'scroll', 'answer')),
  detail TEXT NOT NULL,
  x DOUBLE PRECISION NOT NULL,
  y DOUBLE PRECISION NOT NULL,
  PRIMARY KEY (trial_id, seq)
);

CREATE TABLE camera_poses (
  trial_id BIGINT NOT NULL REFERENCES trial_results(planned_trial_id),
  frame BIGINT NOT NULL CHECK (frame >= 1),
  t_s DOUBLE PRECISION NOT NULL CHECK (t_s >= 0),
  x DOUBLE PRECISION NOT NULL,
  y DOUBLE PRECISION NOT NULL,
  z DOUBLE PRECISION NOT NULL,
  yaw DOUBLE PRECISION NOT NULL,
  pitch DOUBLE PRECISION NOT NULL,
  PRIMARY KEY (trial_id, frame)
);

CREATE TABLE questionnaire_answers (
  session_id BIGINT NOT NULL REFERENCES sessions(id),
  item TEXT NOT NULL CHECK (length(item) > 0),
  scope TEXT NOT NULL,
  value_number DOUBLE PRECISION,
  value_text TEXT,
  answered_at TEXT NOT NULL )sql" + iso("answered_at") + R"sql(,
  CHECK ((value_number IS NULL) <> (value_text IS NULL)),
  PRIMARY KEY (session_id, item, scope)
);

-- Invariant 6: the results of a session are a prefix of its plan, and only a running session takes results.
CREATE FUNCTION dtlab_trial_results_in_plan_order() RETURNS trigger LANGUAGE plpgsql SET search_path FROM CURRENT AS $$
BEGIN
  IF EXISTS (SELECT 1 FROM planned_trials q JOIN planned_trials p ON p.session_id = q.session_id
             WHERE q.id = NEW.planned_trial_id AND p.position < q.position
               AND NOT EXISTS (SELECT 1 FROM trial_results r WHERE r.planned_trial_id = p.id)) THEN
    RAISE EXCEPTION USING ERRCODE = 'integrity_constraint_violation',
      MESSAGE = 'dtlab: trial results must be recorded in plan order';
  END IF;
  IF (SELECT s.status FROM sessions s JOIN planned_trials q ON q.session_id = s.id
      WHERE q.id = NEW.planned_trial_id) IS DISTINCT FROM 'running' THEN
    RAISE EXCEPTION USING ERRCODE = 'integrity_constraint_violation', MESSAGE = 'dtlab: the session is not running';
  END IF;
  RETURN NEW;
END $$;
CREATE TRIGGER trial_results_in_plan_order BEFORE INSERT ON trial_results
  FOR EACH ROW EXECUTE FUNCTION dtlab_trial_results_in_plan_order();

-- Invariant 3: an enrollment never changes, except that it may be released once.
CREATE TRIGGER participants_ledger_fixed BEFORE UPDATE ON participants FOR EACH ROW
  WHEN (NEW.id IS DISTINCT FROM OLD.id OR NEW.participant IS DISTINCT FROM OLD.participant
    OR NEW.enrollment_index IS DISTINCT FROM OLD.enrollment_index OR NEW.order_row IS DISTINCT FROM OLD.order_row
    OR NEW.study_id IS DISTINCT FROM OLD.study_id OR NEW.demographics IS DISTINCT FROM OLD.demographics
    OR NEW.enrolled_at IS DISTINCT FROM OLD.enrolled_at OR OLD.released_at IS NOT NULL)
  EXECUTE FUNCTION dtlab_refuse('dtlab: an enrollment is never changed, only released once');

-- Invariant 9: running -> finished | abandoned; both are final. Finished needs a result for every planned trial.
CREATE FUNCTION dtlab_sessions_status_transitions() RETURNS trigger LANGUAGE plpgsql SET search_path FROM CURRENT AS $$
BEGIN
  IF OLD.status <> 'running' THEN
    RAISE EXCEPTION USING ERRCODE = 'integrity_constraint_violation',
      MESSAGE = 'dtlab: a finished or abandoned session is final';
  END IF;
  IF NEW.id IS DISTINCT FROM OLD.id OR NEW.participant_id IS DISTINCT FROM OLD.participant_id
     OR NEW.study_id IS DISTINCT FROM OLD.study_id OR NEW.software_version IS DISTINCT FROM OLD.software_version
     OR NEW.started_at IS DISTINCT FROM OLD.started_at THEN
    RAISE EXCEPTION USING ERRCODE = 'integrity_constraint_violation',
      MESSAGE = 'dtlab: only a session''s status and end time change';
  END IF;
  IF NEW.status = 'finished' AND EXISTS (
      SELECT 1 FROM planned_trials p WHERE p.session_id = OLD.id
        AND NOT EXISTS (SELECT 1 FROM trial_results r WHERE r.planned_trial_id = p.id)) THEN
    RAISE EXCEPTION USING ERRCODE = 'integrity_constraint_violation',
      MESSAGE = 'dtlab: a session finishes only when every planned trial has a result';
  END IF;
  RETURN NEW;
END $$;
CREATE TRIGGER sessions_status_transitions BEFORE UPDATE ON sessions
  FOR EACH ROW EXECUTE FUNCTION dtlab_sessions_status_transitions();
CREATE TRIGGER participants_no_delete BEFORE DELETE ON participants
  FOR EACH ROW EXECUTE FUNCTION dtlab_refuse('dtlab: participants are never deleted; release() frees their row');
CREATE TRIGGER participants_no_truncate BEFORE TRUNCATE ON participants
  FOR EACH STATEMENT EXECUTE FUNCTION dtlab_refuse('dtlab: participants are never deleted');
CREATE TRIGGER sessions_no_delete BEFORE DELETE ON sessions
  FOR EACH ROW EXECUTE FUNCTION dtlab_refuse('dtlab: sessions are never deleted');
CREATE TRIGGER sessions_no_truncate BEFORE TRUNCATE ON sessions
  FOR EACH STATEMENT EXECUTE FUNCTION dtlab_refuse('dtlab: sessions are never deleted');

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
  s += append_only("trial_results", "dtlab: trial results are never changed", "dtlab: trial results are never deleted");
  s += append_only("planned_trials", "dtlab: planned trials are never changed", "dtlab: planned trials are never deleted");
  s += append_only("planned_levels", "dtlab: planned trials are never changed", "dtlab: planned trials are never deleted");
  s += append_only("studies", "dtlab: a study row is never changed; a new protocol adds a row",
                   "dtlab: studies are never deleted");
  s += append_only("study_factors", "dtlab: factors are never changed", "dtlab: factors are never deleted");
  s += append_only("session_resumes", "dtlab: resumes are never changed", "dtlab: resumes are never deleted");
  s += append_only("input_events", "dtlab: input events are never changed", "dtlab: input events are never deleted");
  s += append_only("camera_poses", "dtlab: camera poses are never changed", "dtlab: camera poses are never deleted");
  s += append_only("questionnaire_answers", "dtlab: questionnaire answers are never changed",
                   "dtlab: questionnaire answers are never deleted");
  return c_collated(s);
}

std::string pg_schema_v2() {
  std::string s = R"sql(
CREATE TABLE study_designs (
  study_id BIGINT PRIMARY KEY REFERENCES studies(id),
  design_sha256 TEXT NOT NULL )sql" + hex("design_sha256", 64) + R"sql(
);

CREATE TABLE exclusions (
  id BIGINT PRIMARY KEY,
  participant_id BIGINT NOT NULL REFERENCES participants(id),
  position BIGINT CHECK (position IS NULL OR position >= 1),
  action TEXT NOT NULL CHECK (action IN ('exclude', 'include')),
  reason TEXT NOT NULL,
  decided_by TEXT NOT NULL,
  decided_at TEXT NOT NULL )sql" + iso("decided_at") + R"sql(,
  CHECK (action = 'include' OR length(trim(reason)) > 0)
);
CREATE INDEX exclusions_by_participant ON exclusions(participant_id, position);

CREATE TABLE notes (
  id BIGINT PRIMARY KEY,
  participant_id BIGINT REFERENCES participants(id),
  position BIGINT CHECK (position IS NULL OR position >= 1),
  author TEXT NOT NULL,
  text TEXT NOT NULL CHECK (length(trim(text)) > 0),
  written_at TEXT NOT NULL )sql" + iso("written_at") + R"sql(,
  CHECK (position IS NULL OR participant_id IS NOT NULL)
);

CREATE TABLE session_pauses (
  session_id BIGINT NOT NULL REFERENCES sessions(id),
  position BIGINT CHECK (position IS NULL OR position >= 1),
  paused_at TEXT NOT NULL )sql" + iso("paused_at") + R"sql(,
  resumed_at TEXT NOT NULL )sql" + iso("resumed_at") + R"sql(,
  duration_s DOUBLE PRECISION NOT NULL CHECK (duration_s >= 0),
  CHECK (resumed_at >= paused_at)
);
CREATE INDEX session_pauses_by_session ON session_pauses(session_id);

CREATE TABLE trial_attempts (
  session_id BIGINT NOT NULL REFERENCES sessions(id),
  position BIGINT NOT NULL CHECK (position >= 1),
  attempt BIGINT NOT NULL CHECK (attempt >= 1),
  started_at TEXT NOT NULL )sql" + iso("started_at") + R"sql(,
  owner TEXT NOT NULL,
  PRIMARY KEY (session_id, position, attempt)
);

CREATE TABLE session_claims (
  session_id BIGINT PRIMARY KEY REFERENCES sessions(id),
  owner TEXT NOT NULL CHECK (length(owner) > 0),
  host TEXT NOT NULL,
  pid BIGINT NOT NULL,
  claimed_at TEXT NOT NULL )sql" + iso("claimed_at") + R"sql(,
  heartbeat_at TEXT NOT NULL )sql" + iso("heartbeat_at") + R"sql(,
  expires_at TEXT NOT NULL )sql" + iso("expires_at") + R"sql(
);
)sql";
  s += append_only("study_designs", "dtlab: a design hash is never changed", "dtlab: a design hash is never deleted");
  s += append_only("exclusions", "dtlab: an exclusion is never changed; include the participant or trial again",
                   "dtlab: an exclusion is never deleted; include the participant or trial again");
  s += append_only("notes", "dtlab: notes are never changed; add another", "dtlab: notes are never deleted");
  s += append_only("session_pauses", "dtlab: pauses are never changed", "dtlab: pauses are never deleted");
  s += append_only("trial_attempts", "dtlab: trial attempts are never changed", "dtlab: trial attempts are never deleted");
  return c_collated(s);
}

std::string pg_schema_v3() {
  std::string s = R"sql(
ALTER TABLE trial_results ADD COLUMN frame_first_ms DOUBLE PRECISION CHECK (frame_first_ms IS NULL OR frame_first_ms >= 0);
ALTER TABLE trial_results ADD COLUMN frame_ms_median DOUBLE PRECISION CHECK (frame_ms_median IS NULL OR frame_ms_median >= 0);
ALTER TABLE trial_results ADD COLUMN late_frames BIGINT CHECK (late_frames IS NULL OR late_frames >= 0);
ALTER TABLE trial_results ADD COLUMN refresh_hz DOUBLE PRECISION CHECK (refresh_hz IS NULL OR refresh_hz > 0);

CREATE TABLE session_displays (
  session_id BIGINT NOT NULL REFERENCES sessions(id),
  recorded_at TEXT NOT NULL )sql" + iso("recorded_at") + R"sql(,
  kind TEXT NOT NULL CHECK (kind IN ('window', 'headless')),
  width BIGINT NOT NULL CHECK (width >= 1),
  height BIGINT NOT NULL CHECK (height >= 1),
  refresh_hz DOUBLE PRECISION CHECK (refresh_hz IS NULL OR refresh_hz > 0),
  renderer TEXT NOT NULL,
  monitor TEXT NOT NULL
);
CREATE INDEX session_displays_by_session ON session_displays(session_id);
)sql";
  s += append_only("session_displays", "dtlab: a display record is never changed",
                   "dtlab: a display record is never deleted");
  return c_collated(s);
}

std::string pg_schema_v4() {
  std::string s = R"sql(
CREATE TABLE consents (
  participant_id BIGINT PRIMARY KEY REFERENCES participants(id),
  agreed BIGINT NOT NULL CHECK (agreed IN (0, 1)),
  text_sha256 TEXT NOT NULL )sql" + hex("text_sha256", 64) + R"sql(,
  answered_at TEXT NOT NULL )sql" + iso("answered_at") + R"sql(
);

CREATE TABLE withdrawals (
  id BIGINT PRIMARY KEY,
  participant_id BIGINT NOT NULL UNIQUE REFERENCES participants(id),
  withdrawn_at TEXT NOT NULL )sql" + iso("withdrawn_at") + R"sql(,
  reason TEXT NOT NULL CHECK (length(trim(reason)) > 0),
  decided_by TEXT NOT NULL
);

CREATE TABLE screens (
  session_id BIGINT NOT NULL REFERENCES sessions(id),
  seq BIGINT NOT NULL CHECK (seq >= 1),
  screen TEXT NOT NULL CHECK (length(screen) > 0),
  shown TEXT NOT NULL,
  shown_at TEXT NOT NULL )sql" + iso("shown_at") + R"sql(,
  ended_at TEXT NOT NULL )sql" + iso("ended_at") + R"sql(,
  duration_s DOUBLE PRECISION NOT NULL CHECK (duration_s >= 0),
  answer TEXT,
  CHECK (ended_at >= shown_at),
  PRIMARY KEY (session_id, seq)
);

-- Invariant 13: a participant who withdrew (or declined consent) never gets a session.
CREATE FUNCTION dtlab_sessions_not_after_withdrawal() RETURNS trigger LANGUAGE plpgsql
  SET search_path FROM CURRENT AS $$
BEGIN
  IF EXISTS (SELECT 1 FROM withdrawals w WHERE w.participant_id = NEW.participant_id) THEN
    RAISE EXCEPTION USING ERRCODE = 'integrity_constraint_violation',
      MESSAGE = 'dtlab: the participant withdrew their consent; they never run a session';
  END IF;
  RETURN NEW;
END $$;
CREATE TRIGGER sessions_not_after_withdrawal BEFORE INSERT ON sessions
  FOR EACH ROW EXECUTE FUNCTION dtlab_sessions_not_after_withdrawal();
)sql";
  s += append_only("consents", "dtlab: a consent answer is never changed; withdraw instead",
                   "dtlab: a consent answer is never deleted");
  s += append_only("withdrawals", "dtlab: a withdrawal is never changed",
                   "dtlab: a withdrawal is never deleted; the participant withdrew");
  s += append_only("screens", "dtlab: the screen log is never changed", "dtlab: the screen log is never deleted");
  return c_collated(s);
}

}  // namespace dtlab::store::detail

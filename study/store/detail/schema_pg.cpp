// The PostgreSQL half of the schema that is not table description
// (schema_tables.h holds the tables, columns, constraints and indexes of
// both engines): the header table that stands in for SQLite's file header,
// the trigger function that refuses changes, and the triggers of schema v1 to
// v4 (docs/store.md, "PostgreSQL"). SQLite's RAISE(ABORT) triggers are
// PL/pgSQL functions raising SQLSTATE 23000 here. A shared server has many
// clients, so every append-only table also refuses TRUNCATE, and the tables
// SQLite leaves unguarded (factors, resumes, events, poses, questionnaire
// answers) refuse UPDATE and DELETE here. Nothing here runs a statement; the
// caller runs the text inside its write transaction.
#include <string>
#include <string_view>

#include "study/store/detail/schema_sql.h"

namespace dtlab::store::detail {
namespace {

// BEFORE UPDATE, DELETE (per row) and TRUNCATE (per statement) triggers refusing with `message`.
std::string append_only(const std::string& table, const std::string& changed, const std::string& deleted) {
  return "CREATE TRIGGER " + table + "_no_update BEFORE UPDATE ON " + table +
         " FOR EACH ROW EXECUTE FUNCTION dtlab_refuse('" + changed + "');\n"
         "CREATE TRIGGER " + table + "_no_delete BEFORE DELETE ON " + table +
         " FOR EACH ROW EXECUTE FUNCTION dtlab_refuse('" + deleted + "');\n"
         "CREATE TRIGGER " + table + "_no_truncate BEFORE TRUNCATE ON " + table +
         " FOR EACH STATEMENT EXECUTE FUNCTION dtlab_refuse('" + deleted + "');\n";
}


// What SQLite keeps in its file header, the trigger function that refuses changes, and the
// migrations table's guards.
std::string bookkeeping() {
  std::string s = R"sql(
CREATE TABLE dtlab_header (
  one BOOLEAN PRIMARY KEY DEFAULT TRUE CHECK (one),
  application_id BIGINT NOT NULL,
  user_version BIGINT NOT NULL
);
CREATE FUNCTION dtlab_refuse() RETURNS trigger LANGUAGE plpgsql SET search_path FROM CURRENT AS $$
BEGIN
  RAISE EXCEPTION USING ERRCODE = 'integrity_constraint_violation', MESSAGE = TG_ARGV[0];
END $$;
)sql";
  s += append_only("schema_migrations", "dtlab: applied migrations are never changed",
                   "dtlab: applied migrations are never deleted");
  return s;
}

// Invariants 3, 6 and 9, and every v1 table append-only.
std::string v1() {
  std::string s = R"sql(
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
  return s;
}

// The lab's decisions and records are appended, never changed or deleted.
std::string v2() {
  std::string s;
  s += append_only("study_designs", "dtlab: a design hash is never changed", "dtlab: a design hash is never deleted");
  s += append_only("exclusions", "dtlab: an exclusion is never changed; include the participant or trial again",
                   "dtlab: an exclusion is never deleted; include the participant or trial again");
  s += append_only("notes", "dtlab: notes are never changed; add another", "dtlab: notes are never deleted");
  s += append_only("session_pauses", "dtlab: pauses are never changed", "dtlab: pauses are never deleted");
  s += append_only("trial_attempts", "dtlab: trial attempts are never changed", "dtlab: trial attempts are never deleted");
  return s;
}

// Display records are append-only.
std::string v3() {
  std::string s;
  s += append_only("session_displays", "dtlab: a display record is never changed",
                   "dtlab: a display record is never deleted");
  return s;
}

// Invariant 13, and consents, withdrawals and the screen log append-only.
std::string v4() {
  std::string s = R"sql(
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
  return s;
}

}  // namespace

std::string pg_triggers(int version) {
  switch (version) {
    case 0: return bookkeeping();
    case 1: return v1();
    case 2: return v2();
    case 3: return v3();
    case 4: return v4();
    default: return "";
  }
}

}  // namespace dtlab::store::detail

// The SQLite half of the schema that is not table description
// (schema_tables.h holds the tables, columns, constraints and indexes of
// both engines): the triggers of schema v1 to v4, which make results
// append-only and in plan order, enrollments fixed, session status
// transitions one-way and a withdrawn participant's session impossible
// (docs/store.md, invariants 2-9 and 13). PostgreSQL's are in schema_pg.cpp.
// Returns DDL only; nothing here runs a statement.
#include <string>

#include "study/store/detail/schema_sql.h"

namespace dtlab::store::detail {

namespace {

// Invariants 2, 3, 5, 6, 7 and 9: results in plan order and append-only, enrollments fixed,
// session status one-way.
std::string v1() {
  return R"sql(
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
)sql";
}

// The lab's decisions and records are appended, never changed or deleted.
std::string v2() {
  return R"sql(
-- Decisions and records are appended, never changed or deleted.
CREATE TRIGGER study_designs_no_update BEFORE UPDATE ON study_designs
BEGIN SELECT RAISE(ABORT, 'dtlab: a design hash is never changed'); END;
CREATE TRIGGER study_designs_no_delete BEFORE DELETE ON study_designs
BEGIN SELECT RAISE(ABORT, 'dtlab: a design hash is never deleted'); END;
CREATE TRIGGER exclusions_no_update BEFORE UPDATE ON exclusions
BEGIN SELECT RAISE(ABORT, 'dtlab: an exclusion is never changed; include the participant or trial again'); END;
CREATE TRIGGER exclusions_no_delete BEFORE DELETE ON exclusions
BEGIN SELECT RAISE(ABORT, 'dtlab: an exclusion is never deleted; include the participant or trial again'); END;
CREATE TRIGGER notes_no_update BEFORE UPDATE ON notes
BEGIN SELECT RAISE(ABORT, 'dtlab: notes are never changed; add another'); END;
CREATE TRIGGER notes_no_delete BEFORE DELETE ON notes
BEGIN SELECT RAISE(ABORT, 'dtlab: notes are never deleted'); END;
CREATE TRIGGER session_pauses_no_update BEFORE UPDATE ON session_pauses
BEGIN SELECT RAISE(ABORT, 'dtlab: pauses are never changed'); END;
CREATE TRIGGER session_pauses_no_delete BEFORE DELETE ON session_pauses
BEGIN SELECT RAISE(ABORT, 'dtlab: pauses are never deleted'); END;
CREATE TRIGGER trial_attempts_no_update BEFORE UPDATE ON trial_attempts
BEGIN SELECT RAISE(ABORT, 'dtlab: trial attempts are never changed'); END;
CREATE TRIGGER trial_attempts_no_delete BEFORE DELETE ON trial_attempts
BEGIN SELECT RAISE(ABORT, 'dtlab: trial attempts are never deleted'); END;
)sql";
}

// Display records are append-only.
std::string v3() {
  return R"sql(
CREATE TRIGGER session_displays_no_update BEFORE UPDATE ON session_displays
BEGIN SELECT RAISE(ABORT, 'dtlab: a display record is never changed'); END;
CREATE TRIGGER session_displays_no_delete BEFORE DELETE ON session_displays
BEGIN SELECT RAISE(ABORT, 'dtlab: a display record is never deleted'); END;
)sql";
}

// Invariant 13, and consents, withdrawals and the screen log append-only.
std::string v4() {
  return R"sql(
-- Invariant 13: a participant who withdrew (or declined consent) never gets a session.
CREATE TRIGGER sessions_not_after_withdrawal BEFORE INSERT ON sessions
BEGIN
  SELECT RAISE(ABORT, 'dtlab: the participant withdrew their consent; they never run a session')
  WHERE EXISTS (SELECT 1 FROM withdrawals w WHERE w.participant_id = NEW.participant_id);
END;

CREATE TRIGGER consents_no_update BEFORE UPDATE ON consents
BEGIN SELECT RAISE(ABORT, 'dtlab: a consent answer is never changed; withdraw instead'); END;
CREATE TRIGGER consents_no_delete BEFORE DELETE ON consents
BEGIN SELECT RAISE(ABORT, 'dtlab: a consent answer is never deleted'); END;
CREATE TRIGGER withdrawals_no_update BEFORE UPDATE ON withdrawals
BEGIN SELECT RAISE(ABORT, 'dtlab: a withdrawal is never changed'); END;
CREATE TRIGGER withdrawals_no_delete BEFORE DELETE ON withdrawals
BEGIN SELECT RAISE(ABORT, 'dtlab: a withdrawal is never deleted; the participant withdrew'); END;
CREATE TRIGGER screens_no_update BEFORE UPDATE ON screens
BEGIN SELECT RAISE(ABORT, 'dtlab: the screen log is never changed'); END;
CREATE TRIGGER screens_no_delete BEFORE DELETE ON screens
BEGIN SELECT RAISE(ABORT, 'dtlab: the screen log is never deleted'); END;
)sql";
}

}  // namespace

std::string sqlite_triggers(int version) {
  switch (version) {
    case 1: return v1();
    case 2: return v2();
    case 3: return v3();
    case 4: return v4();
    default: return "";
  }
}

std::string session_table_view() {
  return R"sql(
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
}

}  // namespace dtlab::store::detail

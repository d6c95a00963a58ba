CREATE TABLE schema_migrations (
  version INTEGER PRIMARY KEY CHECK (version >= 1),
  description TEXT NOT NULL,
  applied_at TEXT NOT NULL CHECK (applied_at GLOB '[0-9][0-9][0-9][0-9]-[0-1][0-9]-[0-3][0-9]T[0-2][0-9]:[0-5][0-9]:[0-6][0-9].[0-9][0-9][0-9]Z'),
  software_version TEXT NOT NULL
) STRICT;
CREATE TABLE studies (
  id INTEGER PRIMARY KEY,
  protocol_id TEXT NOT NULL CHECK (length(protocol_id) > 0),
  protocol_text TEXT NOT NULL,
  protocol_sha256 TEXT NOT NULL CHECK (length(protocol_sha256) = 64 AND protocol_sha256 NOT GLOB '*[^0-9a-f]*'),
  software_version TEXT NOT NULL,
  order_rows INTEGER NOT NULL CHECK (order_rows >= 1),
  created_at TEXT NOT NULL CHECK (created_at GLOB '[0-9][0-9][0-9][0-9]-[0-1][0-9]-[0-3][0-9]T[0-2][0-9]:[0-5][0-9]:[0-6][0-9].[0-9][0-9][0-9]Z')
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
  enrolled_at TEXT NOT NULL CHECK (enrolled_at GLOB '[0-9][0-9][0-9][0-9]-[0-1][0-9]-[0-3][0-9]T[0-2][0-9]:[0-5][0-9]:[0-6][0-9].[0-9][0-9][0-9]Z'),
  released_at TEXT CHECK (released_at IS NULL OR released_at GLOB '[0-9][0-9][0-9][0-9]-[0-1][0-9]-[0-3][0-9]T[0-2][0-9]:[0-5][0-9]:[0-6][0-9].[0-9][0-9][0-9]Z')
) STRICT;
CREATE INDEX participants_active_by_row ON participants(order_row) WHERE released_at IS NULL;
CREATE TABLE sessions (
  id INTEGER PRIMARY KEY,
  participant_id INTEGER NOT NULL UNIQUE REFERENCES participants(id),
  study_id INTEGER NOT NULL REFERENCES studies(id),
  software_version TEXT NOT NULL,
  status TEXT NOT NULL CHECK (status IN ('running', 'finished', 'abandoned')),
  started_at TEXT NOT NULL CHECK (started_at GLOB '[0-9][0-9][0-9][0-9]-[0-1][0-9]-[0-3][0-9]T[0-2][0-9]:[0-5][0-9]:[0-6][0-9].[0-9][0-9][0-9]Z'),
  ended_at TEXT CHECK (ended_at IS NULL OR ended_at GLOB '[0-9][0-9][0-9][0-9]-[0-1][0-9]-[0-3][0-9]T[0-2][0-9]:[0-5][0-9]:[0-6][0-9].[0-9][0-9][0-9]Z'),
  CHECK ((status = 'running') = (ended_at IS NULL))
) STRICT;
CREATE TABLE session_resumes (
  session_id INTEGER NOT NULL REFERENCES sessions(id),
  resumed_at TEXT NOT NULL CHECK (resumed_at GLOB '[0-9][0-9][0-9][0-9]-[0-1][0-9]-[0-3][0-9]T[0-2][0-9]:[0-5][0-9]:[0-6][0-9].[0-9][0-9][0-9]Z'),
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
  scene_hash TEXT NOT NULL CHECK (length(scene_hash) = 64 AND scene_hash NOT GLOB '*[^0-9a-f]*'),
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
  started_at TEXT NOT NULL CHECK (started_at GLOB '[0-9][0-9][0-9][0-9]-[0-1][0-9]-[0-3][0-9]T[0-2][0-9]:[0-5][0-9]:[0-6][0-9].[0-9][0-9][0-9]Z'),
  ended_at TEXT NOT NULL CHECK (ended_at GLOB '[0-9][0-9][0-9][0-9]-[0-1][0-9]-[0-3][0-9]T[0-2][0-9]:[0-5][0-9]:[0-6][0-9].[0-9][0-9][0-9]Z'),
  frame_count INTEGER NOT NULL CHECK (frame_count >= 0),
  frame_ms_mean REAL CHECK (frame_ms_mean >= 0),
  frame_ms_sd REAL CHECK (frame_ms_sd >= 0),
  frame_ms_p95 REAL CHECK (frame_ms_p95 >= 0),
  frame_ms_max REAL CHECK (frame_ms_max >= 0),
  event_count INTEGER NOT NULL CHECK (event_count >= 0),
  recorded_at TEXT NOT NULL CHECK (recorded_at GLOB '[0-9][0-9][0-9][0-9]-[0-1][0-9]-[0-3][0-9]T[0-2][0-9]:[0-5][0-9]:[0-6][0-9].[0-9][0-9][0-9]Z'), frame_first_ms REAL CHECK (frame_first_ms IS NULL OR frame_first_ms >= 0), frame_ms_median REAL CHECK (frame_ms_median IS NULL OR frame_ms_median >= 0), late_frames INTEGER CHECK (late_frames IS NULL OR late_frames >= 0), refresh_hz REAL CHECK (refresh_hz IS NULL OR refresh_hz > 0),
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
  answered_at TEXT NOT NULL CHECK (answered_at GLOB '[0-9][0-9][0-9][0-9]-[0-1][0-9]-[0-3][0-9]T[0-2][0-9]:[0-5][0-9]:[0-6][0-9].[0-9][0-9][0-9]Z'),
  CHECK ((value_number IS NULL) <> (value_text IS NULL)),
  PRIMARY KEY (session_id, item, scope)
) STRICT, WITHOUT ROWID;
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
CREATE TRIGGER participants_ledger_fixed BEFORE UPDATE ON participants
WHEN NEW.participant IS NOT OLD.participant OR NEW.enrollment_index IS NOT OLD.enrollment_index
  OR NEW.order_row IS NOT OLD.order_row OR NEW.study_id IS NOT OLD.study_id
  OR NEW.demographics IS NOT OLD.demographics OR NEW.enrolled_at IS NOT OLD.enrolled_at
  OR OLD.released_at IS NOT NULL
BEGIN SELECT RAISE(ABORT, 'dtlab: an enrollment is never changed, only released once'); END;
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
CREATE TABLE study_designs (
  study_id INTEGER PRIMARY KEY REFERENCES studies(id),
  design_sha256 TEXT NOT NULL CHECK (length(design_sha256) = 64 AND design_sha256 NOT GLOB '*[^0-9a-f]*')
) STRICT;
CREATE TABLE exclusions (
  id INTEGER PRIMARY KEY,
  participant_id INTEGER NOT NULL REFERENCES participants(id),
  position INTEGER CHECK (position IS NULL OR position >= 1),
  action TEXT NOT NULL CHECK (action IN ('exclude', 'include')),
  reason TEXT NOT NULL,
  decided_by TEXT NOT NULL,
  decided_at TEXT NOT NULL CHECK (decided_at GLOB '[0-9][0-9][0-9][0-9]-[0-1][0-9]-[0-3][0-9]T[0-2][0-9]:[0-5][0-9]:[0-6][0-9].[0-9][0-9][0-9]Z'),
  CHECK (action = 'include' OR length(trim(reason)) > 0)
) STRICT;
CREATE INDEX exclusions_by_participant ON exclusions(participant_id, position);
CREATE TABLE notes (
  id INTEGER PRIMARY KEY,
  participant_id INTEGER REFERENCES participants(id),
  position INTEGER CHECK (position IS NULL OR position >= 1),
  author TEXT NOT NULL,
  text TEXT NOT NULL CHECK (length(trim(text)) > 0),
  written_at TEXT NOT NULL CHECK (written_at GLOB '[0-9][0-9][0-9][0-9]-[0-1][0-9]-[0-3][0-9]T[0-2][0-9]:[0-5][0-9]:[0-6][0-9].[0-9][0-9][0-9]Z'),
  CHECK (position IS NULL OR participant_id IS NOT NULL)
) STRICT;
CREATE TABLE session_pauses (
  session_id INTEGER NOT NULL REFERENCES sessions(id),
  position INTEGER CHECK (position IS NULL OR position >= 1),
  paused_at TEXT NOT NULL CHECK (paused_at GLOB '[0-9][0-9][0-9][0-9]-[0-1][0-9]-[0-3][0-9]T[0-2][0-9]:[0-5][0-9]:[0-6][0-9].[0-9][0-9][0-9]Z'),
  resumed_at TEXT NOT NULL CHECK (resumed_at GLOB '[0-9][0-9][0-9][0-9]-[0-1][0-9]-[0-3][0-9]T[0-2][0-9]:[0-5][0-9]:[0-6][0-9].[0-9][0-9][0-9]Z'),
  duration_s REAL NOT NULL CHECK (duration_s >= 0),
  CHECK (resumed_at >= paused_at)
) STRICT;
CREATE INDEX session_pauses_by_session ON session_pauses(session_id);
CREATE TABLE trial_attempts (
  session_id INTEGER NOT NULL REFERENCES sessions(id),
  position INTEGER NOT NULL CHECK (position >= 1),
  attempt INTEGER NOT NULL CHECK (attempt >= 1),
  started_at TEXT NOT NULL CHECK (started_at GLOB '[0-9][0-9][0-9][0-9]-[0-1][0-9]-[0-3][0-9]T[0-2][0-9]:[0-5][0-9]:[0-6][0-9].[0-9][0-9][0-9]Z'),
  owner TEXT NOT NULL,
  PRIMARY KEY (session_id, position, attempt)
) STRICT, WITHOUT ROWID;
CREATE TABLE session_claims (
  session_id INTEGER PRIMARY KEY REFERENCES sessions(id),
  owner TEXT NOT NULL CHECK (length(owner) > 0),
  host TEXT NOT NULL,
  pid INTEGER NOT NULL,
  claimed_at TEXT NOT NULL CHECK (claimed_at GLOB '[0-9][0-9][0-9][0-9]-[0-1][0-9]-[0-3][0-9]T[0-2][0-9]:[0-5][0-9]:[0-6][0-9].[0-9][0-9][0-9]Z'),
  heartbeat_at TEXT NOT NULL CHECK (heartbeat_at GLOB '[0-9][0-9][0-9][0-9]-[0-1][0-9]-[0-3][0-9]T[0-2][0-9]:[0-5][0-9]:[0-6][0-9].[0-9][0-9][0-9]Z'),
  expires_at TEXT NOT NULL CHECK (expires_at GLOB '[0-9][0-9][0-9][0-9]-[0-1][0-9]-[0-3][0-9]T[0-2][0-9]:[0-5][0-9]:[0-6][0-9].[0-9][0-9][0-9]Z')
) STRICT;
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
CREATE TABLE session_displays (
  session_id INTEGER NOT NULL REFERENCES sessions(id),
  recorded_at TEXT NOT NULL CHECK (recorded_at GLOB '[0-9][0-9][0-9][0-9]-[0-1][0-9]-[0-3][0-9]T[0-2][0-9]:[0-5][0-9]:[0-6][0-9].[0-9][0-9][0-9]Z'),
  kind TEXT NOT NULL CHECK (kind IN ('window', 'headless')),
  width INTEGER NOT NULL CHECK (width >= 1),
  height INTEGER NOT NULL CHECK (height >= 1),
  refresh_hz REAL CHECK (refresh_hz IS NULL OR refresh_hz > 0),
  renderer TEXT NOT NULL,
  monitor TEXT NOT NULL
) STRICT;
CREATE INDEX session_displays_by_session ON session_displays(session_id);
CREATE TRIGGER session_displays_no_update BEFORE UPDATE ON session_displays
BEGIN SELECT RAISE(ABORT, 'dtlab: a display record is never changed'); END;
CREATE TRIGGER session_displays_no_delete BEFORE DELETE ON session_displays
BEGIN SELECT RAISE(ABORT, 'dtlab: a display record is never deleted'); END;
CREATE TABLE consents (
  participant_id INTEGER PRIMARY KEY REFERENCES participants(id),
  agreed INTEGER NOT NULL CHECK (agreed IN (0, 1)),
  text_sha256 TEXT NOT NULL CHECK (length(text_sha256) = 64 AND text_sha256 NOT GLOB '*[^0-9a-f]*'),
  answered_at TEXT NOT NULL CHECK (answered_at GLOB '[0-9][0-9][0-9][0-9]-[0-1][0-9]-[0-3][0-9]T[0-2][0-9]:[0-5][0-9]:[0-6][0-9].[0-9][0-9][0-9]Z')
) STRICT;
CREATE TABLE withdrawals (
  id INTEGER PRIMARY KEY,
  participant_id INTEGER NOT NULL UNIQUE REFERENCES participants(id),
  withdrawn_at TEXT NOT NULL CHECK (withdrawn_at GLOB '[0-9][0-9][0-9][0-9]-[0-1][0-9]-[0-3][0-9]T[0-2][0-9]:[0-5][0-9]:[0-6][0-9].[0-9][0-9][0-9]Z'),
  reason TEXT NOT NULL CHECK (length(trim(reason)) > 0),
  decided_by TEXT NOT NULL
) STRICT;
CREATE TABLE screens (
  session_id INTEGER NOT NULL REFERENCES sessions(id),
  seq INTEGER NOT NULL CHECK (seq >= 1),
  screen TEXT NOT NULL CHECK (length(screen) > 0),
  shown TEXT NOT NULL,
  shown_at TEXT NOT NULL CHECK (shown_at GLOB '[0-9][0-9][0-9][0-9]-[0-1][0-9]-[0-3][0-9]T[0-2][0-9]:[0-5][0-9]:[0-6][0-9].[0-9][0-9][0-9]Z'),
  ended_at TEXT NOT NULL CHECK (ended_at GLOB '[0-9][0-9][0-9][0-9]-[0-1][0-9]-[0-3][0-9]T[0-2][0-9]:[0-5][0-9]:[0-6][0-9].[0-9][0-9][0-9]Z'),
  duration_s REAL NOT NULL CHECK (duration_s >= 0),
  answer TEXT,
  CHECK (ended_at >= shown_at),
  PRIMARY KEY (session_id, seq)
) STRICT, WITHOUT ROWID;
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

// Schema v2 (docs/store.md, "Schema v2"): what a lab needs beside the trials.
// Design hashes tell a protocol revision that changes nothing that runs from
// one that does; exclusions and notes are decisions appended with who, why
// and when (an inclusion appends a row that undoes an exclusion; nothing is
// deleted); pauses and trial attempts make the console's pauses and a
// crash's interrupted trial part of the record. Only session_claims changes
// in place: it is operational state (who runs a session now), not data.
#include "study/store/detail/schema_sql.h"

namespace dtlab::store::detail {

std::string schema_v2() {
  return R"sql(
CREATE TABLE study_designs (
  study_id INTEGER PRIMARY KEY REFERENCES studies(id),
  design_sha256 TEXT NOT NULL )sql" + hex_check("design_sha256", 64) + R"sql(
) STRICT;

CREATE TABLE exclusions (
  id INTEGER PRIMARY KEY,
  participant_id INTEGER NOT NULL REFERENCES participants(id),
  position INTEGER CHECK (position IS NULL OR position >= 1),
  action TEXT NOT NULL CHECK (action IN ('exclude', 'include')),
  reason TEXT NOT NULL,
  decided_by TEXT NOT NULL,
  decided_at TEXT NOT NULL )sql" + iso_check("decided_at") + R"sql(,
  CHECK (action = 'include' OR length(trim(reason)) > 0)
) STRICT;
CREATE INDEX exclusions_by_participant ON exclusions(participant_id, position);

CREATE TABLE notes (
  id INTEGER PRIMARY KEY,
  participant_id INTEGER REFERENCES participants(id),
  position INTEGER CHECK (position IS NULL OR position >= 1),
  author TEXT NOT NULL,
  text TEXT NOT NULL CHECK (length(trim(text)) > 0),
  written_at TEXT NOT NULL )sql" + iso_check("written_at") + R"sql(,
  CHECK (position IS NULL OR participant_id IS NOT NULL)
) STRICT;

CREATE TABLE session_pauses (
  session_id INTEGER NOT NULL REFERENCES sessions(id),
  position INTEGER CHECK (position IS NULL OR position >= 1),
  paused_at TEXT NOT NULL )sql" + iso_check("paused_at") + R"sql(,
  resumed_at TEXT NOT NULL )sql" + iso_check("resumed_at") + R"sql(,
  duration_s REAL NOT NULL CHECK (duration_s >= 0),
  CHECK (resumed_at >= paused_at)
) STRICT;
CREATE INDEX session_pauses_by_session ON session_pauses(session_id);

CREATE TABLE trial_attempts (
  session_id INTEGER NOT NULL REFERENCES sessions(id),
  position INTEGER NOT NULL CHECK (position >= 1),
  attempt INTEGER NOT NULL CHECK (attempt >= 1),
  started_at TEXT NOT NULL )sql" + iso_check("started_at") + R"sql(,
  owner TEXT NOT NULL,
  PRIMARY KEY (session_id, position, attempt)
) STRICT, WITHOUT ROWID;

CREATE TABLE session_claims (
  session_id INTEGER PRIMARY KEY REFERENCES sessions(id),
  owner TEXT NOT NULL CHECK (length(owner) > 0),
  host TEXT NOT NULL,
  pid INTEGER NOT NULL,
  claimed_at TEXT NOT NULL )sql" + iso_check("claimed_at") + R"sql(,
  heartbeat_at TEXT NOT NULL )sql" + iso_check("heartbeat_at") + R"sql(,
  expires_at TEXT NOT NULL )sql" + iso_check("expires_at") + R"sql(
) STRICT;

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

}  // namespace dtlab::store::detail

// Schema v4 (docs/store.md, "Schema v4"), on both engines: consent,
// withdrawal and the screen log. A participant's answer on the consent page
// (with the SHA-256 of the text shown) is one row per participant; a
// withdrawal of consent is at most one row per participant, and a trigger
// refuses a session to anyone who withdrew, so a withdrawn participant never
// runs again whatever writes the database; every screen of a session is one
// row numbered 1, 2, ... Only adds tables: sessions.status keeps its three
// values (a withdrawn running session ends as 'abandoned'; readers say
// withdrawn where a withdrawal exists). All three tables are append-only.
#include <string>

#include "study/store/detail/schema_sql.h"

namespace dtlab::store::detail {

std::string schema_v4() {
  return R"sql(
CREATE TABLE consents (
  participant_id INTEGER PRIMARY KEY REFERENCES participants(id),
  agreed INTEGER NOT NULL CHECK (agreed IN (0, 1)),
  text_sha256 TEXT NOT NULL )sql" + hex_check("text_sha256", 64) + R"sql(,
  answered_at TEXT NOT NULL )sql" + iso_check("answered_at") + R"sql(
) STRICT;

CREATE TABLE withdrawals (
  id INTEGER PRIMARY KEY,
  participant_id INTEGER NOT NULL UNIQUE REFERENCES participants(id),
  withdrawn_at TEXT NOT NULL )sql" + iso_check("withdrawn_at") + R"sql(,
  reason TEXT NOT NULL CHECK (length(trim(reason)) > 0),
  decided_by TEXT NOT NULL
) STRICT;

CREATE TABLE screens (
  session_id INTEGER NOT NULL REFERENCES sessions(id),
  seq INTEGER NOT NULL CHECK (seq >= 1),
  screen TEXT NOT NULL CHECK (length(screen) > 0),
  shown TEXT NOT NULL,
  shown_at TEXT NOT NULL )sql" + iso_check("shown_at") + R"sql(,
  ended_at TEXT NOT NULL )sql" + iso_check("ended_at") + R"sql(,
  duration_s REAL NOT NULL CHECK (duration_s >= 0),
  answer TEXT,
  CHECK (ended_at >= shown_at),
  PRIMARY KEY (session_id, seq)
) STRICT, WITHOUT ROWID;

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

}  // namespace dtlab::store::detail

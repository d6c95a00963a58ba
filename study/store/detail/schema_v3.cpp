// Schema v3 (docs/store.md, "Schema v3"): what the display did. Each trial
// gets its warm-up frame apart from the steady frames (the first frame pays
// for scene upload and the first present), the median of the steady frames,
// how many of them were late for the display, and the display's refresh
// rate; each session start records the display it ran on (window or
// headless, size, refresh rate, GL renderer), so an analysis can tell
// whether render cost may have confounded completion time. Only adds.
#include "study/store/detail/schema_sql.h"

namespace dtlab::store::detail {

std::string schema_v3() {
  return R"sql(
ALTER TABLE trial_results ADD COLUMN frame_first_ms REAL CHECK (frame_first_ms IS NULL OR frame_first_ms >= 0);
ALTER TABLE trial_results ADD COLUMN frame_ms_median REAL CHECK (frame_ms_median IS NULL OR frame_ms_median >= 0);
ALTER TABLE trial_results ADD COLUMN late_frames INTEGER CHECK (late_frames IS NULL OR late_frames >= 0);
ALTER TABLE trial_results ADD COLUMN refresh_hz REAL CHECK (refresh_hz IS NULL OR refresh_hz > 0);

CREATE TABLE session_displays (
  session_id INTEGER NOT NULL REFERENCES sessions(id),
  recorded_at TEXT NOT NULL )sql" + iso_check("recorded_at") + R"sql(,
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
)sql";
}

}  // namespace dtlab::store::detail

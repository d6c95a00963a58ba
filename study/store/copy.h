// Copying a whole study between databases, whatever the engines (`dtlab copy
// SRC DST`): a file to a lab's server, the server to a file for archiving, a
// station's offline file into the server that already holds other
// participants. Guarantees: into an empty DST every row of every table is
// copied as it is (ids, timestamps, protocol texts, design hashes, decisions,
// pauses, attempts, consents, withdrawals, screens), so the export of DST
// equals the export of SRC byte for byte; a merge into a DST that holds the
// study already adds what DST lacks without changing any plan (docs/store.md,
// "Copying and merging"). All of it
// is written in ONE transaction of DST: a refused or failed copy writes
// nothing. Never: writes SRC, copies session claims (who runs a session now
// is not data), or renumbers a participant whose plan is stored.
#pragma once
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "study/common/error.h"

namespace dtlab::store {

struct CopyOptions {
  int busy_timeout_ms = 10000;
  // Design hash of a protocol text recorded before schema v2 (as OpenOptions::design_hash_of).
  std::function<std::optional<std::string>(const std::string& protocol_text)> design_hash_of;
};

struct CopySummary {
  bool merged = false;            // DST held the study already: participants were merged into it
  int participants = 0;           // participants added to DST
  int renumbered = 0;             // ... of them enrolled without a session, given DST's next ledger slot
  int unchanged = 0;              // participants DST held already with the same data: left as they were
  int sessions = 0;               // sessions added (a participant DST had enrolled may gain SRC's session)
  int trials = 0;                 // trial results added
  int revisions = 0;              // protocol texts added
  int decisions = 0, notes = 0;   // exclusion/inclusion decisions and notes added
  int consents = 0, withdrawals = 0, screens = 0;  // consent answers, withdrawals and screens added (schema v4)
  std::vector<std::string> changes;  // one line per renumbered participant or added revision
  std::vector<std::pair<std::string, std::int64_t>> rows;  // rows written per table, in copy order
};

// Copies the study in `src` (a file or a postgresql:// URI, read in one snapshot) into `dst`
// (created if missing: a new file, or a new schema on the server). Errors: not_found (no SRC),
// invalid_input (SRC or DST not a dtlab database, or the same database), conflict (what cannot be
// merged without changing data: another design, a participant in both with different data, a
// stored plan whose ledger slot DST gave to someone else, a session of SRC running now),
// busy/environment from the engines. Nothing is written to DST unless everything is.
Result<CopySummary> copy_study(const std::string& src, const std::string& dst, const CopyOptions& options = {});

}  // namespace dtlab::store

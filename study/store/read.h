// Reading a study back: the one typed door to everything a study database
// holds (docs/store.md). A StudyReader opens and validates the
// file once -- a dtlab database of a schema this build reads, by the same
// check Store::open makes -- then every read is a plain struct taken from
// ONE snapshot (a read transaction), consistent even while sessions write.
// Guarantees: never creates, migrates or writes the file, leaves no -wal or
// -shm behind, and reads files on read-only media. Never: hands out SQL,
// statements or connections; callers see values only.
#pragma once
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "study/common/error.h"
#include "study/design/plan.h"
#include "study/store/score.h"
#include "study/store/store.h"

namespace dtlab::store {
namespace detail {
class Db;
}

// One protocol text the database was opened with (a row of `studies`), in recording order.
struct Revision {
  std::int64_t study_id = 0;
  std::string protocol_id, protocol_text, protocol_sha256;
  std::string design_sha256;   // canonical hash of what runs; "" when unknown (a v1 row nobody hashed)
  int design_revision = 0;     // 1-based: 1 + distinct design hashes recorded before this one's first row
  std::string software_version;
  int order_rows = 1;
  std::vector<std::string> factors;  // protocol order
  std::string created_at;            // ISO-8601 UTC
};

// A participant's place in the ledger, with what was recorded at enrollment.
struct LedgerEntry {
  std::string participant;
  int index = 0, order_row = 0;
  std::int64_t study_id = 0;         // the protocol revision current at enrollment
  Demographics demographics;         // in stored key order
  std::string enrolled_at;
  std::optional<std::string> released_at;
  bool withdrawn = false;            // a withdrawal exists (declined consent, or withdrew later; schema v4)
  bool simulated() const;            // demographics has simulated = true|1|yes (dtlab simulate marks its agents)
};

struct Resume {
  std::string at, software_version;
  std::optional<int> next_position;  // nullopt: nothing was left to run
};

struct Pause {
  std::optional<int> position;       // the trial in progress, nullopt between trials
  std::string paused_at, resumed_at;
  double duration_s = 0;
};

// A trial attempt that ended without a result: the process died, or the session was abandoned mid-trial.
struct Interruption {
  int position = 0;
  int attempt = 0;                   // 1-based; the trial's next attempt re-ran it from its start
  std::string started_at;
};

struct Claim {
  std::string owner, host;
  std::int64_t pid = 0;
  std::string claimed_at, heartbeat_at, expires_at;
};

struct Display {
  std::string recorded_at;
  DisplayInfo info;
};

struct SessionRecord {
  std::int64_t id = 0;
  std::string participant;
  std::int64_t study_id = 0;         // the protocol revision the session began under
  std::string software_version;
  SessionStatus status = SessionStatus::running;
  std::string started_at;
  std::optional<std::string> ended_at;
  int planned = 0, recorded = 0;
  std::vector<Resume> resumes;
  std::vector<Pause> pauses;
  std::vector<Interruption> interruptions;
  std::vector<Display> displays;     // one per start or resume that recorded it (schema v3)
  std::optional<Claim> claim;        // who runs it now, if anyone holds it
  bool withdrawn = false;            // the participant withdrew (status says abandoned if it was running then)
  double paused_s() const;           // sum of the pauses' durations
};

// A planned trial of a session, in position order.
struct PlannedRow {
  std::int64_t session_id = 0;
  std::string participant;
  design::PlannedTrial trial;
};

// One recorded trial (the TrialResult the session recorded, store.h) joined with its plan, session,
// ledger and protocol revision: the export's row (README, "Study database and export") and the
// report's. Levels are the trial's own, in its study's factor order.
struct TrialRow : TrialResult {
  std::string participant;
  int enrollment_index = 0, order_row = 0;
  std::int64_t session_id = 0;
  SessionStatus session_status = SessionStatus::running;
  design::PlannedTrial planned;
  Scores scores;                     // as stored (the schema holds them to score(answer, truth))
  std::string started_at, ended_at;  // ISO-8601 UTC, as stored
  std::int64_t event_count = 0;
  std::int64_t study_id = 0;
  std::string protocol_sha256;
  int design_revision = 0;           // 0 when the design hash is unknown
  std::optional<std::string> excluded;  // the reason, while the trial or its participant is excluded
  bool withdrawn = false;            // the participant withdrew their consent (the export leaves the row out)
  std::string level(const std::string& factor) const;  // "" if the trial has no such factor
};

// A decision to leave a participant (position nullopt) or one trial out of the analysis, or to take it back.
struct Exclusion {
  std::int64_t id = 0;               // recording order
  std::string participant;
  std::optional<int> position;
  bool exclude = true;               // false: an inclusion undoing an earlier exclusion
  std::string reason, by, at;
};

struct Note {
  std::int64_t id = 0;
  std::string participant;           // "" for a note about the study
  std::optional<int> position;
  std::string author, text, at;
};

struct QuestionnaireRecord {
  std::string participant;
  std::int64_t session_id = 0;
  std::string item, scope;
  std::variant<double, std::string> value;
  std::string answered_at;
};

// A participant's answer on the consent page (schema v4): the first and only one.
struct ConsentRecord {
  std::string participant;
  bool agreed = false;
  std::string text_sha256;           // SHA-256 of the consent text shown
  std::string answered_at;           // ISO-8601 UTC
};

// A withdrawal of consent (schema v4): declined on the consent page (reason "declined consent",
// by "participant") or withdrawn later (`dtlab withdraw`); at most one per participant.
struct WithdrawalRecord {
  std::string participant, withdrawn_at, reason, by;
};

// A screen of a session as it happened (schema v4; store.h, ScreenRecord).
struct ScreenRow {
  std::string participant;
  int seq = 0;                       // 1, 2, ... in the order recorded
  std::string screen, shown, shown_at, ended_at;
  double duration_s = 0;
  std::optional<std::string> answer;
};

struct ReadOptions {
  // Design hash of a protocol text, for revisions recorded before schema v2 (the store knows no
  // protocol format; callers pass protocol::design_sha256 of the parsed text). Empty: unknown.
  std::function<std::optional<std::string>(const std::string& protocol_text)> design_hash_of;
  int busy_timeout_ms = 10000;
};

// A read-only view of one study database. Move-only; one per thread.
class StudyReader {
 public:
  // Opens and validates `path`. Errors: not_found (no such file), invalid_input (not SQLite,
  // not dtlab, a schema newer than this build), environment (I/O). Never creates the file.
  static Result<StudyReader> open(const std::string& path, ReadOptions options = {});

  StudyReader(StudyReader&&) noexcept;
  StudyReader& operator=(StudyReader&&) noexcept;
  ~StudyReader();

  const std::string& path() const;
  int schema_version() const;

  // Ends the snapshot and takes a new one (a console that watches a running study).
  Status refresh();

  Result<std::vector<Revision>> revisions();            // recording order; the last is current
  Result<std::vector<LedgerEntry>> ledger();            // enrollment order
  Result<std::vector<SessionRecord>> sessions();        // enrollment order of their participants
  Result<std::vector<PlannedRow>> planned(const std::string& participant = "");  // "" = every session
  Result<std::vector<TrialRow>> trials(const std::string& participant = "");     // by index, then position
  Result<std::vector<QuestionnaireRecord>> questionnaire(const std::string& participant = "");  // by item, scope
  Result<std::vector<Exclusion>> exclusions();          // recording order (the latest decision wins)
  Result<std::vector<Note>> notes();
  // Consent, withdrawal and the screen log (schema v4; empty lists on an older database, which the
  // reader never migrates). Consents and withdrawals by enrollment index; screens by participant
  // (enrollment index), then seq; "" = every participant.
  Result<std::vector<ConsentRecord>> consents();
  Result<std::vector<WithdrawalRecord>> withdrawals();
  Result<std::vector<ScreenRow>> screens(const std::string& participant = "");
  // Per-frame camera poses and input events of one recorded trial; not_found if none is recorded there.
  Result<std::vector<CameraPose>> poses(const std::string& participant, int position);
  Result<std::vector<InputEvent>> events(const std::string& participant, int position);
  // PRAGMA integrity_check and foreign_key_check: "ok", or what they report.
  Result<std::string> integrity_check();

  struct Impl;

 private:
  friend class Store;
  explicit StudyReader(std::unique_ptr<Impl> impl);
  static StudyReader borrow(detail::Db& db, ReadOptions options);  // Store::read(): reads on the Store's connection
  std::unique_ptr<Impl> impl_;
};

}  // namespace dtlab::store

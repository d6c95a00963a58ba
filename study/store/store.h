// The study database (schema v4; docs/store.md is the reference) in a file
// (SQLite, the embedded default) or on a lab's PostgreSQL server (a
// postgresql:// URI, several stations at once):
// participants and their order rows (the ledger), consent answers and
// withdrawals, sessions, planned trials, trial results with events and camera
// poses, the screens a session showed, questionnaire answers, and the lab's
// decisions (exclusions, notes, pauses). This is the writing half; read.h is
// the reading half (StudyReader, also lent by Store::read()).
// Guarantees: a finished trial is committed in one transaction with all its
// data, so a crash loses at most the trial in progress; enrollment is atomic
// across processes and stations sharing the database; a running session is
// claimed by the one process that runs it; a session resumes with exactly the trials it would
// have run; a participant who declined or withdrew consent never runs again. It never aborts on
// bad input or a failing disk (every failure is a dtlab::Error of a kind, naming the file or the
// URI without its password) and never writes to a database that is not a dtlab database of a
// schema version it knows.
#pragma once
#include <chrono>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include "study/common/error.h"
#include "study/design/plan.h"
#include "study/store/score.h"

namespace dtlab::store {

inline constexpr int kSchemaVersion = 4;                 // the newest schema this build reads and writes
inline constexpr std::int32_t kApplicationId = 0x64746c62;  // PRAGMA application_id of every dtlab database ("dtlb")

// Where a study is: a file path (SQLite) or a postgresql:// / postgres:// URI (PostgreSQL; its
// `schema` parameter names the study's schema, default public; docs/store.md, "PostgreSQL").
bool is_server_uri(const std::string& where);  // true for a PostgreSQL URI
std::string display_name(const std::string& where);  // what messages show: the path, or the URI without password

// A participant ID as the store keeps it: 1 to kMaxParticipantId bytes, no control character, no
// space at either end. Never cut to fit: a longer ID is refused (field "participant").
inline constexpr std::size_t kMaxParticipantId = 64;
Status check_participant_id(const std::string& id);

// The study a database belongs to, as plain values (no Protocol type, so the
// store builds on its own). Callers pass what the protocol stage computed.
struct StudyInfo {
  std::string protocol_id;       // e.g. "elmqvist2008"
  std::string protocol_text;     // the protocol file, byte for byte
  std::string protocol_sha256;   // SHA-256 of protocol_text, 64 lowercase hex digits
  std::string design_sha256;     // canonical hash of what runs (protocol::design_sha256); "" = unknown: then
                                 // every text change counts as a design change
  std::string software_version;  // dtlab::version_string()
  int order_rows = 1;            // rows of the condition-ordering scheme (Latin square), >= 1
  std::vector<std::string> factors;  // factor names in protocol order; they become export columns
};

struct OpenOptions {
  bool allow_protocol_change = false;  // accept a protocol whose DESIGN differs from the database's current one
  int busy_timeout_ms = 10000;         // how long to wait for another process's write lock
  double claim_ttl_s = 30;             // a session claim not renewed for this long may be taken over
  // Design hash of a recorded protocol text, for rows recorded before schema v2 (see ReadOptions).
  std::function<std::optional<std::string>(const std::string& protocol_text)> design_hash_of;
};

// A participant's place in the ledger.
struct Enrollment {
  std::string participant_id;
  int index = 0;        // 0-based enrollment index: 0, 1, 2, ... in enrollment order, never reused
  int order_row = 0;    // 0-based row of the ordering scheme
  bool released = false;       // the participant's session was abandoned; the row counts as free
  bool newly_enrolled = false; // true only from the enroll() call that created it
  bool withdrawn = false;      // a withdrawal exists (declined consent, or withdrew later): never runs again
};

using Demographics = std::vector<std::pair<std::string, std::string>>;  // e.g. {"age","27"}, {"gender","f"}

enum class SessionStatus { running, finished, abandoned };
const char* to_string(SessionStatus s);  // "running", "finished", "abandoned" (the stored values)

// A snapshot of a session as stored when the call returned.
struct Session {
  std::int64_t id = 0;
  std::string participant_id;
  SessionStatus status = SessionStatus::running;
  int planned = 0;           // planned trials
  int recorded = 0;          // trials with a result (always positions 1..recorded)
  bool resumed = false;      // begin_session found the session already running (after a crash or quit)
  bool took_over = false;    // begin_session took the claim from a process that is gone or expired
};

// The Error::field of begin_session's busy Error when another live process claims the session.
inline constexpr const char* kClaimField = "session.claim";

struct BeginOptions {
  bool take_over = false;    // the experimenter's override: take the claim even from a live process
};

// One input event of a trial; t_s is seconds since the trial started.
struct InputEvent {
  enum class Kind { key_down, key_up, button_down, button_up, cursor, scroll, answer };
  double t_s = 0;
  Kind kind = Kind::key_down;
  std::string detail;   // key name, button name or answer text; may be empty
  double x = 0, y = 0;  // cursor position in pixels (cursor, button_*) or scroll offsets (scroll)
};
const char* to_string(InputEvent::Kind k);  // the stored value, e.g. "key_down"

// The camera of one rendered frame: eye position and view direction.
struct CameraPose {
  double t_s = 0;          // seconds since the trial started, non-decreasing
  double x = 0, y = 0, z = 0;
  double yaw = 0, pitch = 0;  // radians; yaw 0 looks along -z (scene.h's convention)
};

// The one trial result: the participant's answer beside the answer key and what the session
// measured, the same type from the session (TrialRecord, written) through the store to the
// report (read.h's TrialRow, read back; the report's row is a TrialRow). Stored as one
// trial_results row.
struct TrialResult {
  std::string scene_hash;             // scene::Scene::hash, 64 hex digits
  std::optional<Answer> answer;       // nullopt: no answer given (timed out, skipped)
  Answer truth;                       // the answer key; same alternative as answer
  double completion_s = 0;            // completion time in seconds (steady clock), >= 0
  FrameStats frames;                  // see frame_stats()
};

// Everything the session measured for one finished trial: the result, when, and every event and pose.
struct TrialRecord : TrialResult {
  int position = 0;                   // the planned trial's position; must be the next one (next_trial)
  std::chrono::system_clock::time_point started_at, ended_at;  // wall clock, stored as ISO-8601 UTC
  std::vector<InputEvent> events;     // in time order
  std::vector<CameraPose> poses;      // one per rendered frame, in frame order
};

// The display a session runs on, recorded at each (re)start of the session.
struct DisplayInfo {
  std::string kind = "headless";       // "window" (a person's screen) or "headless" (simulated, offscreen)
  int width = 0, height = 0;           // framebuffer pixels of the trial views
  std::optional<double> refresh_hz;    // the monitor's refresh rate; nullopt when unknown or headless
  std::string renderer;                // "GL_VERSION / GL_RENDERER"
  std::string monitor;                 // the monitor's name; "" for a window on the default one or headless
};

// A screen of the session as it happened (docs/store.md, "Schema v4"): which screen ("consent",
// "page welcome", "announce 2", "level technique=lens", "instructions T1", "break",
// "feedback T1 3", ...), what it showed (a page id, a text's SHA-256, the levels announced; may be
// empty), when it was shown and left, and what was answered ("continue", "skipped",
// "timed out", ...; nullopt: nothing to answer).
struct ScreenRecord {
  std::string screen, shown;
  std::chrono::system_clock::time_point shown_at, ended_at;  // wall clock; ended_at >= shown_at
  std::optional<std::string> answer;
};

// One questionnaire answer: item id, the condition it is about ("" if none,
// else e.g. "scenario=ABSTRACT;transparency=on"), and a number or a text.
struct QuestionnaireAnswer {
  std::string item;
  std::string scope;
  std::variant<double, std::string> value;
};

class StudyReader;

// An open study database. Move-only; one per thread (it owns one connection). Any number of
// processes (on any number of stations, for a server) may open the same database at once.
class Store {
 public:
  // Creates the database (a file, or a schema on the server) or opens it. `path` is a file or a
  // postgresql:// URI. Refuses: a non-SQLite or non-dtlab file (or schema), a newer schema,
  // and -- unless options allow it -- a protocol whose SHA-256 differs from the current one.
  // A protocol with a new text but the same design hash is recorded as a new revision without
  // any option; a different design needs allow_protocol_change (else a conflict Error).
  static Result<Store> open(const std::string& path, const StudyInfo& study, OpenOptions options = {});

  // Opens an existing database under its current protocol, for the experimenter's decisions
  // (exclude, include, add_note, release) when no protocol file is at hand. not_found if missing.
  static Result<Store> open_existing(const std::string& path, OpenOptions options = {});

  Store(Store&&) noexcept;
  Store& operator=(Store&&) noexcept;
  ~Store();

  const std::string& path() const;  // the file, or the URI without its password

  // Reads on this connection (each call one short read transaction); valid while the Store lives.
  StudyReader& read();

  // Gives the participant the next enrollment index and an order row (rule:
  // the row with the fewest participants not released, ties to the lowest
  // row; equal to index mod order_rows while nothing is released). Atomic
  // across processes. An existing id returns its enrollment unchanged
  // (newly_enrolled = false); a released id is refused, and so is one who withdrew (conflict).
  Result<Enrollment> enroll(const std::string& participant_id, const Demographics& demographics = {});

  // The participant's answer on the consent page, with the SHA-256 of the text shown (64 lowercase
  // hex), in ONE transaction with their enrollment (invariant 13). Agreed: enrolled as enroll() does,
  // with `demographics`, and the consent stored. Declined: enrolled with NO demographics, the refusal
  // stored, a withdrawal (reason "declined consent", by "participant") appended and the order row
  // freed, so the next enrollment takes the row; nothing else of theirs is ever stored (no session,
  // no screen); `withdrawn` comes back set. The first answer stays: the same answer again returns the
  // enrollment unchanged (a resumed run, whatever text it names), but an agreement from one who
  // withdrew since is refused, as enroll() refuses them; a different answer: conflict. One enrolled
  // before without a consent (enroll()) gets it stored now (demographics stay as enrolled; a decline
  // withdraws them as withdraw() does); one released or withdrawn without one is refused (enroll()).
  Result<Enrollment> record_consent(const std::string& participant_id, const Demographics& demographics, bool agreed,
                                    const std::string& text_sha256);

  // A later withdrawal of consent, appended with who decided (`by`, e.g. the experimenter) and why
  // (non-empty), in ONE transaction with its effects: a running session ends (status abandoned,
  // its claim dropped; another live process's claim: busy, as release() does), the order row is
  // freed if it was not (finished sessions too: the analysis leaves the participant out, so the
  // row is run again), and the participant never runs again (begin_session and enroll refuse
  // them: conflict, saying they withdrew). Withdrawing twice is harmless (the first stays).
  // not_found: unknown participant; invalid_input: empty reason.
  Status withdraw(const std::string& participant_id, const std::string& reason, const std::string& by);

  // The enrollment of `participant_id`; Error if unknown.
  Result<Enrollment> lookup(const std::string& participant_id);

  // Abandons the participant's session (if running) and frees the order row
  // for the next enrollment. Refused if the session finished.
  Status release(const std::string& participant_id);

  // Starts the participant's session with `plan` (stored once, in one
  // transaction), or resumes it if it is running: then `plan` must equal the
  // stored one. Refused (conflict) for a participant who was released or withdrew. Either way the session is CLAIMED by this Store in the same
  // transaction; a session claimed by another live process is refused (busy)
  // unless options.take_over. A claim whose process is gone (same host) or
  // whose heartbeat expired is taken over. Refused (conflict) for finished or
  // abandoned sessions, and when the plan's index/order row/protocol differ.
  Result<Session> begin_session(const std::string& participant_id, const design::Plan& plan,
                                BeginOptions options = {});

  // The first planned trial without a result; nullopt when all have one.
  Result<std::optional<design::PlannedTrial>> next_trial(const Session& session);

  // Records that the trial at `position` (the next_trial()) starts now: an attempt. An attempt
  // that never gets a result is an interruption (read.h). Renews the claim.
  Status begin_trial(const Session& session, int position);

  // Stores one finished trial -- result, scores (score()), frame stats,
  // events and poses -- in ONE transaction. record.position must be the
  // next_trial() position; the session must be running and claimed by this
  // Store (conflict if another process took it over). Renews the claim.
  Status record_trial(const Session& session, const TrialRecord& record);

  // Renews this Store's claim on the session; conflict if the claim was taken over. Call it at
  // least every claim_ttl_s / 3 while a trial runs long (a person's trial).
  Status heartbeat(const Session& session);

  // Records a pause of the session (the experimenter paused it; `position`: the trial it
  // interrupted, nullopt between trials). Paused time is not completion time: the caller
  // subtracts it; this row says how long it was.
  Status record_pause(const Session& session, std::optional<int> position,
                      std::chrono::system_clock::time_point paused_at,
                      std::chrono::system_clock::time_point resumed_at);

  // Records the display the session runs on now (once per start or resume of the session).
  Status record_display(const Session& session, const DisplayInfo& display);

  // Marks a running session finished (and releases its claim); refused while planned trials remain.
  Status finish_session(const Session& session);

  // Appends a screen of the session as it happened, numbered with the session's next seq (1, 2,
  // ...) in ONE transaction; duration_s is ended_at - shown_at. Any status: a screen shown before
  // the session ended may be recorded after (a debrief after finish_session, the screen on which a
  // participant withdrew). invalid_input: empty screen, ended before shown.
  Status record_screen(const Session& session, const ScreenRecord& screen);

  // Stores questionnaire answers in one transaction (running or finished
  // session). An (item, scope) pair answered before is refused.
  Status record_questionnaire(const Session& session, const std::vector<QuestionnaireAnswer>& answers);

  // The session as stored now (status and counts), e.g. after another process wrote.
  Result<Session> session(const std::string& participant_id);

  // Gives up this Store's claim on the session (it stays running, resumable by anyone).
  // The destructor releases every claim the Store holds.
  Status release_claim(const Session& session);

  // Leaves the participant (position nullopt) or one planned trial of their session out of the
  // analysis, with a reason (non-empty) and who decided; appended, never changed. include()
  // appends the decision that takes an exclusion back. not_found: unknown participant or
  // position; invalid_input: empty reason.
  Status exclude(const std::string& participant_id, std::optional<int> position, const std::string& reason,
                 const std::string& by);
  Status include(const std::string& participant_id, std::optional<int> position, const std::string& reason,
                 const std::string& by);

  // A free-text note about the study (participant ""), a participant, or one of their trials.
  Status add_note(const std::string& participant_id, std::optional<int> position, const std::string& author,
                  const std::string& text);

  struct Impl;  // opaque: the connection and the current study (detail/store_impl.h)

 private:
  explicit Store(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

}  // namespace dtlab::store

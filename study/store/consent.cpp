// Consent, withdrawal and the screen log (docs/store.md, "Schema v4" and
// invariants 13-14). A participant's answer on the consent page is stored in
// the transaction that enrolls them; a decline stores the refusal, a
// withdrawal and the release of the order row, and nothing else of theirs
// ever; a later withdrawal ends a running session and frees the row in the
// transaction that appends it. Each screen is one appended row. Never:
// deletes or changes a row of these tables, or lets a withdrawn participant
// run again (begin_session and enroll refuse them; a trigger refuses their
// session even to SQL written by hand).
#include <algorithm>
#include <chrono>
#include <string>

#include "study/store/detail/store_impl.h"
#include "study/store/detail/time.h"

namespace dtlab::store {

using detail::Stmt;

namespace {

constexpr const char* kDeclinedReason = "declined consent";
constexpr const char* kDeclinedBy = "participant";

std::string trimmed(const std::string& s) {
  const auto b = s.find_first_not_of(" \t\r\n");
  if (b == std::string::npos) return "";
  return s.substr(b, s.find_last_not_of(" \t\r\n") - b + 1);
}

bool lower_hex_64(const std::string& s) {
  return s.size() == 64 &&
         std::all_of(s.begin(), s.end(), [](char c) { return (c >= '0' && c <= '9') || (c >= 'a' && c <= 'f'); });
}

// The participant's stored consent answer: nullopt if none; first: agreed, second: when.
Result<std::optional<std::pair<bool, std::string>>> stored_consent(detail::Db& db, const std::string& participant_id) {
  const char* what = "reading the consent";
  auto st = Stmt::prepare(db,
                          "SELECT c.agreed AS agreed, c.answered_at AS answered_at FROM consents c "
                          "JOIN participants p ON p.id = c.participant_id "
                          "WHERE p.participant = :participant",
                          what);
  if (!st) return st.error();
  st->bind("participant", participant_id);
  auto row = st->step(what);
  if (!row) return row.error();
  if (!*row) return std::optional<std::pair<bool, std::string>>{};
  return std::optional<std::pair<bool, std::string>>{std::make_pair(st->int64("agreed") != 0, st->text("answered_at"))};
}

Status insert_consent(detail::Db& db, const std::string& participant_id, bool agreed, const std::string& sha,
                      const std::string& now) {
  auto ins = Stmt::prepare(db,
                           "INSERT INTO consents (participant_id, agreed, text_sha256, answered_at) "
                           "SELECT id, :agreed, :text_sha256, :answered_at FROM participants "
                           "WHERE participant = :participant",
                           "storing the consent");
  if (!ins) return ins.error();
  ins->bind("agreed", agreed ? 1 : 0).bind("text_sha256", sha).bind("answered_at", now);
  ins->bind("participant", participant_id);
  return ins->run("storing the consent");
}

const char* answer_word(bool agreed) { return agreed ? "agreed" : "declined"; }

}  // namespace

Status Store::Impl::withdraw_in(const std::string& participant_id, const std::string& reason, const std::string& by,
                                const std::string& now) {
  auto e = read_enrollment(db, participant_id);
  if (!e) return e.error();
  if (e->withdrawn) return {};  // the first withdrawal stays
  const char* what = "withdrawing the participant";
  auto q = Stmt::prepare(db,
                         "SELECT s.id AS id, s.status AS status FROM sessions s "
                         "JOIN participants p ON p.id = s.participant_id "
                         "WHERE p.participant = :participant",
                         what);
  if (!q) return q.error();
  q->bind("participant", participant_id);
  auto has = q->step(what);
  if (!has) return has.error();
  if (*has && q->text("status") == "running") {
    const std::int64_t session_id = q->int64("id");
    q->reset();
    // A session another live process runs is not ended under it (busy); a dead one's claim is taken.
    if (auto c = take_claim(session_id, participant_id, /*take_over=*/false, nullptr); !c) return c;
    if (auto c = drop_claim(session_id); !c) return c;
    auto up = Stmt::prepare(db, "UPDATE sessions SET status = 'abandoned', ended_at = :ended_at WHERE id = :id",
                            "ending the session");
    if (!up) return up.error();
    up->bind("ended_at", now).bind("id", session_id);
    if (auto s = up->run("ending the session"); !s) return s;
  }
  if (!e->released) {
    auto rel = Stmt::prepare(db, "UPDATE participants SET released_at = :released_at WHERE participant = :participant",
                            "freeing the order row");
    if (!rel) return rel.error();
    rel->bind("released_at", now).bind("participant", participant_id);
    if (auto s = rel->run("freeing the order row"); !s) return s;
  }
  auto id = detail::next_id(db, "withdrawals");
  if (!id) return id.error();
  auto ins = Stmt::prepare(db,
                           "INSERT INTO withdrawals (id, participant_id, withdrawn_at, reason, decided_by) "
                           "SELECT :id, id, :withdrawn_at, :reason, :decided_by FROM participants "
                           "WHERE participant = :participant",
                           "recording the withdrawal");
  if (!ins) return ins.error();
  ins->bind("id", *id).bind("withdrawn_at", now).bind("reason", reason).bind("decided_by", by);
  ins->bind("participant", participant_id);
  return ins->run("recording the withdrawal");
}

Result<Enrollment> Store::record_consent(const std::string& participant_id, const Demographics& demographics,
                                         bool agreed, const std::string& text_sha256) {
  Impl& m = *impl_;
  if (auto s = check_participant_id(participant_id); !s)
    return m.invalid("participant", s.error().message);
  if (!lower_hex_64(text_sha256))
    return m.invalid("consent.text_sha256", "\"" + text_sha256 + "\" is not 64 lowercase hex digits (the SHA-256 "
                                            "of the consent text shown)");
  // A participant who declines is enrolled with no demographics: only the refusal is stored.
  auto demo = agreed ? demographics_json(m.path, demographics) : Result<std::string>(std::string("{}"));
  if (!demo) return demo.error();
  Enrollment out;
  Status st = m.write("recording the consent of \"" + participant_id + "\"", [&]() -> Status {
    auto now = m.db.now_iso();
    if (!now) return now.error();
    auto existing = read_enrollment(m.db, participant_id);
    if (!existing && existing.error().kind != ErrorKind::not_found) return existing.error();
    if (existing) {
      auto first = stored_consent(m.db, participant_id);
      if (!first) return first.error();
      if (*first) {
        if ((*first)->first != agreed)
          return m.invalid("consent",
                           "participant \"" + participant_id + "\" " + answer_word((*first)->first) +
                               " at " + (*first)->second + "; the first answer stays (a later withdrawal of "
                               "consent is recorded by withdraw, `dtlab withdraw`)",
                           ErrorKind::conflict);
        if (agreed && existing->withdrawn) return withdrawn_error(m.db, participant_id);
        out = *existing;
        return {};
      }
      if (existing->withdrawn) return withdrawn_error(m.db, participant_id);
      if (existing->released)
        return m.invalid("participant", "participant \"" + participant_id +
                                            "\" was released (abandoned session); enroll them under a new id",
                         ErrorKind::conflict);
      out = *existing;  // enrolled before consent was asked: the enrollment stays as it is
    } else {
      auto e = m.insert_enrollment(participant_id, *demo, *now);
      if (!e) return e.error();
      out = *e;
    }
    if (auto s = insert_consent(m.db, participant_id, agreed, text_sha256, *now); !s) return s;
    if (agreed) return {};
    if (auto s = m.withdraw_in(participant_id, kDeclinedReason, kDeclinedBy, *now); !s) return s;
    out.released = out.withdrawn = true;
    return {};
  });
  if (!st) return st.error();
  return out;
}

Status Store::withdraw(const std::string& participant_id, const std::string& reason, const std::string& by) {
  Impl& m = *impl_;
  const std::string why = trimmed(reason);
  if (why.empty()) return m.invalid("reason", "a withdrawal needs a reason (e.g. \"withdrew consent\")");
  return m.write("withdrawing participant \"" + participant_id + "\"", [&]() -> Status {
    auto now = m.db.now_iso();
    if (!now) return now.error();
    return m.withdraw_in(participant_id, why, trimmed(by), *now);
  });
}

Status Store::record_screen(const Session& session, const ScreenRecord& r) {
  Impl& m = *impl_;
  if (trimmed(r.screen).empty()) return m.invalid("screen.screen", "the screen's name is empty");
  if (r.ended_at < r.shown_at) return m.invalid("screen.ended_at", "the screen \"" + r.screen + "\" ended before it was shown");
  const std::string who = "session " + std::to_string(session.id) + " (" + session.participant_id + ")";
  return m.write("recording a screen of " + who, [&]() -> Status {
    auto exists = m.db.query_int("SELECT count(*) AS n FROM sessions WHERE id = :id", "reading the session",
                                 {{"id", session.id}});
    if (!exists) return exists.error();
    if (exists->value_or(0) == 0)
      return m.invalid("session", who + " does not exist in this database", ErrorKind::not_found);
    auto ins = Stmt::prepare(m.db,
                             "INSERT INTO screens (session_id, seq, screen, shown, shown_at, ended_at, duration_s, "
                             "answer) SELECT :session_id, coalesce(max(seq), 0) + 1, :screen, :shown, :shown_at, "
                             ":ended_at, :duration_s, :answer FROM screens WHERE session_id = :session_id",
                             "recording the screen");
    if (!ins) return ins.error();
    const double seconds = std::chrono::duration<double>(r.ended_at - r.shown_at).count();
    ins->bind("session_id", session.id).bind("screen", r.screen).bind("shown", r.shown);
    ins->bind("shown_at", detail::iso8601_utc(r.shown_at)).bind("ended_at", detail::iso8601_utc(r.ended_at));
    ins->bind("duration_s", seconds).bind("answer", r.answer);
    return ins->run("recording the screen");
  });
}

}  // namespace dtlab::store

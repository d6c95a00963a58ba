// The lab's decisions about recorded data (docs/store.md, "Exclusions and
// notes"): excluding a participant or one trial from the analysis, taking
// that back, and free-text notes. Each is one appended row with who, why and
// when, in one transaction; nothing recorded is changed or deleted, so the
// history of every decision stays in the file and the analysis applies the
// latest one. Never: touches results, plans or sessions.
#include <string>

#include "study/store/detail/columns.h"
#include "study/store/detail/store_impl.h"
#include "study/store/detail/time.h"

namespace dtlab::store {

using detail::Stmt;

namespace {

std::string trimmed(const std::string& s) {
  const auto b = s.find_first_not_of(" \t\r\n");
  if (b == std::string::npos) return "";
  return s.substr(b, s.find_last_not_of(" \t\r\n") - b + 1);
}

// The participant's ledger row id; with a position, checks that their session plans it.
Result<std::int64_t> participant_row(Store::Impl& m, const std::string& participant, std::optional<int> position) {
  const char* what = "finding the participant";
  auto q = Stmt::prepare(m.db, "SELECT id AS id FROM participants WHERE participant = :participant", what);
  if (!q) return q.error();
  q->bind("participant", participant);
  auto row = q->step(what);
  if (!row) return row.error();
  if (!*row) return m.invalid("participant", "unknown participant \"" + participant + "\"", ErrorKind::not_found);
  const std::int64_t id = q->int64("id");
  if (!position) return id;
  auto t = Stmt::prepare(m.db,
                         "SELECT count(*) AS found, (SELECT count(*) FROM planned_trials p2 JOIN sessions s2 "
                         "ON s2.id = p2.session_id WHERE s2.participant_id = :id) AS planned "
                         "FROM planned_trials p JOIN sessions s ON s.id = p.session_id "
                         "WHERE s.participant_id = :id AND p.position = :position",
                         what);
  if (!t) return t.error();
  t->bind("id", id).bind("position", *position);
  if (auto r = t->step(what); !r) return r.error();
  if (t->int64("found") == 0)
    return m.invalid("trial", "participant \"" + participant + "\" has no planned trial " + std::to_string(*position) +
                                  " (their session plans " + std::to_string(t->int64("planned")) +
                                  " trials, numbered from 1 as in `dtlab plan` and the export's position column)",
                     ErrorKind::not_found);
  return id;
}

Status decide(Store::Impl& m, const char* action, const std::string& participant, std::optional<int> position,
              const std::string& reason, const std::string& by) {
  const std::string why = trimmed(reason);
  if (std::string(action) == "exclude" && why.empty())
    return m.invalid("reason", "an exclusion needs a reason (what happened, e.g. \"misunderstood the task\")");
  const std::string what = std::string(action) + " participant \"" + participant + "\"" +
                           (position ? " trial " + std::to_string(*position) : std::string());
  return m.write(what, [&]() -> Status {
    auto id = participant_row(m, participant, position);
    if (!id) return id.error();
    auto row = detail::next_id(m.db, "exclusions");
    if (!row) return row.error();
    auto now = m.db.now_iso();
    if (!now) return now.error();
    detail::RowInsert ins("exclusions");
    ins.set("id", *row).set("participant_id", *id).set("position", position).set("action", action);
    ins.set("reason", why).set("decided_by", trimmed(by)).set("decided_at", *now);
    return ins.run(m.db, what);
  });
}

}  // namespace

Status Store::exclude(const std::string& participant_id, std::optional<int> position, const std::string& reason,
                      const std::string& by) {
  return decide(*impl_, "exclude", participant_id, position, reason, by);
}

Status Store::include(const std::string& participant_id, std::optional<int> position, const std::string& reason,
                      const std::string& by) {
  return decide(*impl_, "include", participant_id, position, reason, by);
}

Status Store::add_note(const std::string& participant_id, std::optional<int> position, const std::string& author,
                       const std::string& text) {
  Impl& m = *impl_;
  const std::string body = trimmed(text);
  if (body.empty()) return m.invalid("note", "the note is empty");
  if (position && participant_id.empty()) return m.invalid("note", "a note about a trial needs its participant");
  return m.write("adding a note", [&]() -> Status {
    std::optional<std::int64_t> who;
    if (!participant_id.empty()) {
      auto id = participant_row(m, participant_id, position);
      if (!id) return id.error();
      who = *id;
    }
    auto row = detail::next_id(m.db, "notes");
    if (!row) return row.error();
    auto now = m.db.now_iso();
    if (!now) return now.error();
    detail::RowInsert ins("notes");
    ins.set("id", *row).set("participant_id", who).set("position", position).set("author", trimmed(author));
    ins.set("text", body).set("written_at", *now);
    return ins.run(m.db, "adding a note");
  });
}

}  // namespace dtlab::store

// The store's session and trial tables: Store's session and trial calls
// (docs/store.md, invariants 5-10 and the session state diagram). The plan
// is stored once with its session, each finished trial is one transaction
// holding its result, scores, events and poses, and the next trial is always
// derived from the database, never from memory, so resuming after a crash
// runs exactly the trials the session would have run. A result's row is set
// by column name (detail/columns.h), never by parameter number.
#include <cmath>

#include "study/store/detail/columns.h"
#include "study/store/detail/schema.h"
#include "study/store/detail/store_impl.h"
#include "study/store/detail/time.h"
#include "study/store/store.h"

namespace dtlab::store {
namespace {

using detail::Db;
using detail::RowInsert;
using detail::Stmt;
using detail::parse_seed;
using detail::parse_status;

std::string seed_text(std::uint64_t seed) { return std::to_string(seed); }

std::string describe(const Session& s) { return "session " + std::to_string(s.id) + " (" + s.participant_id + ")"; }

// The participant's session with its counts, or nullopt if it has none.
Result<std::optional<Session>> read_session(Db& db, const std::string& participant_id) {
  const char* what = "reading the session";
  auto st = Stmt::prepare(db,
                          "SELECT s.id AS id, s.status AS status, "
                          " (SELECT count(*) FROM planned_trials p WHERE p.session_id = s.id) AS planned, "
                          " (SELECT count(*) FROM planned_trials p JOIN trial_results r ON r.planned_trial_id = p.id "
                          "  WHERE p.session_id = s.id) AS recorded "
                          "FROM sessions s JOIN participants pa ON pa.id = s.participant_id "
                          "WHERE pa.participant = :participant",
                          what);
  if (!st) return st.error();
  st->bind("participant", participant_id);
  auto row = st->step(what);
  if (!row) return row.error();
  if (!*row) return std::optional<Session>{};
  Session s;
  s.id = st->int64("id");
  s.participant_id = participant_id;
  s.status = parse_status(st->text("status"));
  s.planned = static_cast<int>(st->int64("planned"));
  s.recorded = static_cast<int>(st->int64("recorded"));
  return std::optional<Session>{s};
}

// Status of the session with this id; Error if there is none.
Result<SessionStatus> read_status(Db& db, const Session& s) {
  auto st = Stmt::prepare(db, "SELECT status AS status FROM sessions WHERE id = :id", "reading the session");
  if (!st) return st.error();
  st->bind("id", s.id);
  auto row = st->step("reading the session");
  if (!row) return row.error();
  if (!*row)
    return Error{db.path(), 0, 0, "session", describe(s) + " does not exist in this database", ErrorKind::not_found};
  return parse_status(st->text("status"));
}

// Planned trials of a session in position order; `only_next` limits the
// answer to the first one without a result. Second member: its row id.
Result<std::vector<std::pair<std::int64_t, design::PlannedTrial>>> read_planned(Db& db, std::int64_t session_id,
                                                                                bool only_next) {
  const char* what = "reading the planned trials";
  std::string sql =
      "SELECT " + detail::select_list(*detail::find_table("planned_trials"), "p.", kSchemaVersion) +
      " FROM planned_trials p WHERE p.session_id = :session_id";
  if (only_next) sql += " AND NOT EXISTS (SELECT 1 FROM trial_results r WHERE r.planned_trial_id = p.id)";
  sql += " ORDER BY p.position";
  if (only_next) sql += " LIMIT 1";
  auto st = Stmt::prepare(db, sql, what);
  if (!st) return st.error();
  auto lv = Stmt::prepare(db, "SELECT factor AS factor, level AS level FROM planned_levels "
                          "WHERE planned_trial_id = :planned_trial_id ORDER BY factor_position",
                          what);
  if (!lv) return lv.error();
  st->bind("session_id", session_id);
  std::vector<std::pair<std::int64_t, design::PlannedTrial>> out;
  for (;;) {
    auto row = st->step(what);
    if (!row) return row.error();
    if (!*row) break;
    design::PlannedTrial t;
    t.position = static_cast<int>(st->int64("position"));
    t.block = static_cast<int>(st->int64("block"));
    t.task = st->text("task");
    t.trial = static_cast<int>(st->int64("trial"));
    t.seed = parse_seed(st->text("seed"));
    t.method = st->text("method");
    t.practice = st->int64("practice") != 0;
    lv->bind("planned_trial_id", st->int64("id"));
    for (;;) {
      auto l = lv->step(what);
      if (!l) return l.error();
      if (!*l) break;
      t.levels.emplace_back(lv->text("factor"), lv->text("level"));
    }
    lv->reset();
    out.emplace_back(st->int64("id"), std::move(t));
  }
  return out;
}

// First field in which two planned trials differ, or "" if none.
std::string first_difference(const design::PlannedTrial& a, const design::PlannedTrial& b) {
  if (a.position != b.position) return "position";
  if (a.block != b.block) return "block";
  if (a.levels != b.levels) return "levels";
  if (a.task != b.task) return "task";
  if (a.trial != b.trial) return "trial";
  if (a.seed != b.seed) return "seed";
  if (a.method != b.method) return "method";
  if (a.practice != b.practice) return "practice";
  return "";
}

Status validate_plan(const Store::Impl& m, const Enrollment& e, const design::Plan& plan) {
  if (plan.protocol_id != m.study.protocol_id)
    return m.invalid("plan.protocol_id", "the plan is for protocol \"" + plan.protocol_id + "\", the database for \"" +
                                             m.study.protocol_id + "\"");
  if (plan.index != e.index || plan.order_row != e.order_row)
    return m.invalid("plan.index", "the plan is for enrollment index " + std::to_string(plan.index) + ", order row " +
                                       std::to_string(plan.order_row) + "; participant \"" + e.participant_id +
                                       "\" has index " + std::to_string(e.index) + ", order row " +
                                       std::to_string(e.order_row));
  if (plan.trials.empty()) return m.invalid("plan.trials", "the plan has no trials");
  for (std::size_t i = 0; i < plan.trials.size(); ++i) {
    const auto& t = plan.trials[i];
    const std::string where = "plan.trials[" + std::to_string(i) + "]";
    if (t.position != static_cast<int>(i + 1))
      return m.invalid(where + ".position", "is " + std::to_string(t.position) + "; expected " + std::to_string(i + 1) +
                                                " (positions are 1, 2, 3, ...)");
    if (t.block < 1) return m.invalid(where + ".block", "must be >= 1");
    if (t.trial < 1) return m.invalid(where + ".trial", "must be >= 1");
    if (t.task.empty()) return m.invalid(where + ".task", "is empty");
    if (t.levels.size() != m.study.factors.size())
      return m.invalid(where + ".levels", std::to_string(t.levels.size()) + " levels for " +
                                              std::to_string(m.study.factors.size()) + " factors");
    for (std::size_t f = 0; f < t.levels.size(); ++f)
      if (t.levels[f].first != m.study.factors[f])
        return m.invalid(where + ".levels", "factor " + std::to_string(f + 1) + " is \"" + t.levels[f].first +
                                                "\"; expected \"" + m.study.factors[f] + "\" (protocol order)");
  }
  return {};
}

Status insert_plan(Db& db, std::int64_t session_id, const design::Plan& plan) {
  const char* what = "storing the planned trials";
  auto first = detail::next_id(db, "planned_trials");
  if (!first) return first.error();
  std::vector<RowInsert> trials, levels;
  std::int64_t id = *first;
  for (const auto& t : plan.trials) {
    RowInsert& row = trials.emplace_back("planned_trials");
    row.set("id", id).set("session_id", session_id).set("position", t.position).set("block", t.block);
    row.set("task", t.task).set("trial", t.trial).set("seed", seed_text(t.seed)).set("method", t.method);
    row.set("practice", t.practice ? 1 : 0);
    for (std::size_t f = 0; f < t.levels.size(); ++f)
      levels.emplace_back("planned_levels")
          .set("planned_trial_id", id)
          .set("factor_position", static_cast<int>(f + 1))
          .set("factor", t.levels[f].first)
          .set("level", t.levels[f].second);
    ++id;
  }
  if (auto s = detail::insert_all(db, trials, what); !s) return s;
  return detail::insert_all(db, levels, what);
}

bool finite(double v) { return std::isfinite(v); }

Status validate_record(const Store::Impl& m, const TrialRecord& r) {
  const std::string w = "trial " + std::to_string(r.position);
  auto bad = [&](const std::string& field, const std::string& msg) { return m.invalid(w + "." + field, msg); };
  if (r.scene_hash.size() != 64 || r.scene_hash.find_first_not_of("0123456789abcdef") != std::string::npos)
    return bad("scene_hash", "\"" + r.scene_hash + "\" is not 64 lowercase hex digits");
  if (r.answer && r.answer->index() != r.truth.index())
    return bad("answer", "the answer's kind (count, letter, position) differs from the truth's");
  for (const Answer* a : {r.answer ? &*r.answer : nullptr, &r.truth}) {
    if (!a) continue;
    if (const auto* c = std::get_if<Count>(a); c && c->n < 0) return bad("answer", "a count must be >= 0");
    if (const auto* l = std::get_if<Letter>(a); l && l->letter.empty()) return bad("answer", "a letter is empty");
    if (const auto* p = std::get_if<Position>(a); p && !(finite(p->x) && finite(p->z)))
      return bad("answer", "a position must be finite");
  }
  if (!finite(r.completion_s) || r.completion_s < 0) return bad("completion_s", "must be finite and >= 0");
  if (r.ended_at < r.started_at) return bad("ended_at", "is before started_at");
  const FrameStats& f = r.frames;
  if (f.frames != static_cast<std::int64_t>(r.poses.size()))
    return bad("frames", std::to_string(f.frames) + " frames but " + std::to_string(r.poses.size()) +
                             " camera poses; expected one pose per frame");
  const bool some = f.frames > 0;
  if (f.mean_ms.has_value() != some || f.p95_ms.has_value() != some || f.max_ms.has_value() != some ||
      f.sd_ms.has_value() != (f.frames > 1))
    return bad("frames", "frame statistics do not match the frame count; use frame_stats()");
  for (const auto& v : {f.mean_ms, f.sd_ms, f.p95_ms, f.max_ms, f.first_ms, f.steady_median_ms})
    if (v && (!finite(*v) || *v < 0)) return bad("frames", "frame statistics must be finite and >= 0");
  if (f.first_ms.has_value() != some || f.steady_median_ms.has_value() != (f.frames > 1) ||
      f.late.has_value() != (f.frames > 1) || (f.late && (*f.late < 0 || *f.late > f.frames - 1)))
    return bad("frames", "warm-up and late-frame statistics do not match the frame count; use frame_stats()");
  if (f.refresh_hz && !(finite(*f.refresh_hz) && *f.refresh_hz > 0))
    return bad("frames", "the refresh rate must be finite and > 0");
  for (std::size_t i = 0; i < r.events.size(); ++i) {
    const auto& e = r.events[i];
    if (!finite(e.t_s) || e.t_s < 0 || !finite(e.x) || !finite(e.y))
      return bad("events[" + std::to_string(i) + "]", "times must be finite and >= 0, positions finite");
  }
  for (std::size_t i = 0; i < r.poses.size(); ++i) {
    const auto& p = r.poses[i];
    if (!finite(p.t_s) || p.t_s < 0 || !finite(p.x) || !finite(p.y) || !finite(p.z) || !finite(p.yaw) ||
        !finite(p.pitch))
      return bad("poses[" + std::to_string(i) + "]", "must be finite, with t_s >= 0");
  }
  return {};
}

// The trial_results row of `r`, set by column name; the score columns are score()'s (the schema's
// CHECK holds them to it).
Status insert_result(Db& db, std::int64_t planned_id, const TrialRecord& r) {
  static const char* kinds[] = {"count", "letter", "position"};
  RowInsert row("trial_results");
  row.set("planned_trial_id", planned_id).set("scene_hash", r.scene_hash);
  row.set("answer_kind", kinds[r.truth.index()]).set("answered", r.answer ? 1 : 0);
  auto set_answer = [&](const std::string& prefix, const Answer* a) {
    if (!a) return;
    if (const auto* c = std::get_if<Count>(a)) row.set(prefix + "_count", c->n);
    if (const auto* l = std::get_if<Letter>(a)) row.set(prefix + "_letter", l->letter);
    if (const auto* p = std::get_if<Position>(a)) row.set(prefix + "_x", p->x).set(prefix + "_z", p->z);
  };
  set_answer("answer", r.answer ? &*r.answer : nullptr);
  set_answer("truth", &r.truth);
  const Scores s = score(r.answer, r.truth);
  row.set("rel_error", s.rel_error).set("signed_error", s.signed_error).set("distance", s.distance);
  if (s.correct) row.set("correct", *s.correct ? 1 : 0);
  row.set("completion_s", r.completion_s);
  row.set("started_at", detail::iso8601_utc(r.started_at)).set("ended_at", detail::iso8601_utc(r.ended_at));
  row.set("frame_count", r.frames.frames).set("frame_ms_mean", r.frames.mean_ms).set("frame_ms_sd", r.frames.sd_ms);
  row.set("frame_ms_p95", r.frames.p95_ms).set("frame_ms_max", r.frames.max_ms);
  row.set("event_count", static_cast<std::int64_t>(r.events.size()));
  auto now = db.now_iso();
  if (!now) return now.error();
  row.set("recorded_at", *now);
  row.set("frame_first_ms", r.frames.first_ms).set("frame_ms_median", r.frames.steady_median_ms);
  row.set("late_frames", r.frames.late).set("refresh_hz", r.frames.refresh_hz);
  if (auto x = row.run(db, "storing the trial result"); !x) return x;

  std::vector<RowInsert> events;
  events.reserve(r.events.size());
  for (std::size_t i = 0; i < r.events.size(); ++i) {
    const auto& e = r.events[i];
    RowInsert& row = events.emplace_back("input_events");
    row.set("trial_id", planned_id).set("seq", static_cast<std::int64_t>(i + 1)).set("t_s", e.t_s);
    row.set("kind", to_string(e.kind)).set("detail", e.detail).set("x", e.x).set("y", e.y);
  }
  if (auto x = detail::insert_all(db, events, "storing the input events"); !x) return x;
  std::vector<RowInsert> poses;
  poses.reserve(r.poses.size());
  for (std::size_t i = 0; i < r.poses.size(); ++i) {
    const auto& p = r.poses[i];
    RowInsert& row = poses.emplace_back("camera_poses");
    row.set("trial_id", planned_id).set("frame", static_cast<std::int64_t>(i + 1)).set("t_s", p.t_s);
    row.set("x", p.x).set("y", p.y).set("z", p.z).set("yaw", p.yaw).set("pitch", p.pitch);
  }
  return detail::insert_all(db, poses, "storing the camera poses");
}

}  // namespace

const char* to_string(InputEvent::Kind k) {
  switch (k) {
    case InputEvent::Kind::key_down: return "key_down";
    case InputEvent::Kind::key_up: return "key_up";
    case InputEvent::Kind::button_down: return "button_down";
    case InputEvent::Kind::button_up: return "button_up";
    case InputEvent::Kind::cursor: return "cursor";
    case InputEvent::Kind::scroll: return "scroll";
    case InputEvent::Kind::answer: return "answer";
  }
  return "?";
}

Result<Session> Store::begin_session(const std::string& participant_id, const design::Plan& plan,
                                     BeginOptions options) {
  Impl& m = *impl_;
  Session out;
  Status st = m.write("beginning the session of \"" + participant_id + "\"", [&]() -> Status {
    auto e = lookup(participant_id);
    if (!e) return e.error();
    if (e->withdrawn) return withdrawn_error(m.db, participant_id);
    if (e->released)
      return m.invalid("participant", "participant \"" + participant_id + "\" was released; their session is abandoned",
                       ErrorKind::conflict);
    if (auto v = validate_plan(m, *e, plan); !v) return v;
    auto existing = read_session(m.db, participant_id);
    if (!existing) return existing.error();
    if (!*existing) {
      auto next = detail::next_id(m.db, "sessions");
      if (!next) return next.error();
      const std::int64_t id = *next;
      auto now = m.db.now_iso();
      if (!now) return now.error();
      auto ins = Stmt::prepare(m.db,
                               "INSERT INTO sessions (id, participant_id, study_id, software_version, status, started_at) "
                               "SELECT :id, id, :study_id, :software_version, 'running', :started_at FROM participants "
                               "WHERE participant = :participant",
                               "creating the session");
      if (!ins) return ins.error();
      ins->bind("id", id).bind("study_id", m.study_id).bind("software_version", m.study.software_version);
      ins->bind("started_at", *now).bind("participant", participant_id);
      if (auto s = ins->run("creating the session"); !s) return s;
      if (auto s = insert_plan(m.db, id, plan); !s) return s;
      out = Session{id, participant_id, SessionStatus::running, static_cast<int>(plan.trials.size()), 0, false, false};
      return m.take_claim(id, participant_id, options.take_over, nullptr);
    }
    out = **existing;
    if (out.status != SessionStatus::running)
      return m.invalid("session", describe(out) + " is " + to_string(out.status) + "; only a running session resumes",
                       ErrorKind::conflict);
    if (auto c = m.take_claim(out.id, participant_id, options.take_over, &out.took_over); !c) return c;
    auto stored = read_planned(m.db, out.id, false);
    if (!stored) return stored.error();
    if (stored->size() != plan.trials.size())
      return m.invalid("plan.trials",
                       "the stored plan of " + describe(out) + " has " + std::to_string(stored->size()) +
                           " trials, this plan " + std::to_string(plan.trials.size()) +
                           "; the protocol or the design code changed since the session began",
                       ErrorKind::conflict);
    for (std::size_t i = 0; i < stored->size(); ++i)
      if (auto d = first_difference((*stored)[i].second, plan.trials[i]); !d.empty())
        return m.invalid("plan.trials[" + std::to_string(i) + "]." + d,
                         "differs from the stored plan of " + describe(out) +
                             "; the protocol or the design code changed since the session began",
                         ErrorKind::conflict);
    auto now = m.db.now_iso();
    if (!now) return now.error();
    RowInsert res("session_resumes");
    res.set("session_id", out.id).set("resumed_at", *now).set("software_version", m.study.software_version);
    if (out.recorded < out.planned) res.set("next_position", out.recorded + 1);
    if (auto s = res.run(m.db, "recording the resume"); !s) return s;
    out.resumed = true;
    return {};
  });
  if (!st) return st.error();
  return out;
}

Result<std::optional<design::PlannedTrial>> Store::next_trial(const Session& session) {
  Impl& m = *impl_;
  if (m.broken) return m.broken_error;
  if (auto s = read_status(m.db, session); !s) return s.error();
  auto next = read_planned(m.db, session.id, true);
  if (!next) return next.error();
  if (next->empty()) return std::optional<design::PlannedTrial>{};
  return std::optional<design::PlannedTrial>{std::move(next->front().second)};
}

// In a write transaction: the session is running, claimed by this Store (renewed), and
// `position` is its next trial. Returns the planned trial's row id.
Result<std::int64_t> check_next(Store::Impl& m, const Session& session, int position, const char* doing) {
  auto status = read_status(m.db, session);
  if (!status) return status.error();
  if (*status != SessionStatus::running)
    return m.invalid("session", describe(session) + " is " + to_string(*status) + "; only a running session " + doing,
                     ErrorKind::conflict);
  if (auto c = m.renew_claim(session.id, session.participant_id); !c) return c.error();
  auto next = read_planned(m.db, session.id, true);
  if (!next) return next.error();
  if (next->empty())
    return m.invalid("trial " + std::to_string(position) + ".position",
                     "every planned trial of " + describe(session) + " already has a result", ErrorKind::conflict);
  if (next->front().second.position != position)
    return m.invalid("trial " + std::to_string(position) + ".position",
                     "trial " + std::to_string(next->front().second.position) + " is next in " + describe(session) +
                         ", not trial " + std::to_string(position) + " (trials are recorded once, in plan order)",
                     ErrorKind::conflict);
  return next->front().first;
}

Status Store::begin_trial(const Session& session, int position) {
  Impl& m = *impl_;
  return m.write("starting trial " + std::to_string(position) + " of " + describe(session), [&]() -> Status {
    auto id = check_next(m, session, position, "runs trials");
    if (!id) return id.error();
    auto ins = Stmt::prepare(m.db,
                             "INSERT INTO trial_attempts (session_id, position, attempt, started_at, owner) "
                             "SELECT :session_id, :position, coalesce(max(attempt), 0) + 1, :started_at, :owner "
                             "FROM trial_attempts WHERE session_id = :session_id AND position = :position",
                             "recording the trial attempt");
    if (!ins) return ins.error();
    auto now = m.db.now_iso();
    if (!now) return now.error();
    ins->bind("session_id", session.id).bind("position", position).bind("started_at", *now).bind("owner", m.me.owner);
    return ins->run("recording the trial attempt");
  });
}

Status Store::record_trial(const Session& session, const TrialRecord& record) {
  Impl& m = *impl_;
  if (auto v = validate_record(m, record); !v) return v;
  return m.write("recording trial " + std::to_string(record.position) + " of " + describe(session), [&]() -> Status {
    auto id = check_next(m, session, record.position, "records trials");
    if (!id) return id.error();
    return insert_result(m.db, *id, record);
  });
}

Status Store::record_pause(const Session& session, std::optional<int> position,
                           std::chrono::system_clock::time_point paused_at,
                           std::chrono::system_clock::time_point resumed_at) {
  Impl& m = *impl_;
  if (resumed_at < paused_at) return m.invalid("pause", "resumed before it was paused");
  if (position && *position < 1) return m.invalid("pause.position", "must be >= 1");
  return m.write("recording a pause of " + describe(session), [&]() -> Status {
    auto status = read_status(m.db, session);
    if (!status) return status.error();
    if (*status != SessionStatus::running)
      return m.invalid("session", describe(session) + " is " + to_string(*status) + "; only a running session pauses",
                       ErrorKind::conflict);
    const double seconds = std::chrono::duration<double>(resumed_at - paused_at).count();
    RowInsert ins("session_pauses");
    ins.set("session_id", session.id).set("position", position).set("paused_at", detail::iso8601_utc(paused_at));
    ins.set("resumed_at", detail::iso8601_utc(resumed_at)).set("duration_s", seconds);
    return ins.run(m.db, "recording the pause");
  });
}

Status Store::record_display(const Session& session, const DisplayInfo& d) {
  Impl& m = *impl_;
  if (d.kind != "window" && d.kind != "headless") return m.invalid("display.kind", "expected \"window\" or \"headless\"");
  if (d.width < 1 || d.height < 1) return m.invalid("display.size", "width and height must be >= 1");
  if (d.refresh_hz && !(finite(*d.refresh_hz) && *d.refresh_hz > 0))
    return m.invalid("display.refresh_hz", "must be finite and > 0");
  return m.write("recording the display of " + describe(session), [&]() -> Status {
    if (auto s = read_status(m.db, session); !s) return s.error();
    auto now = m.db.now_iso();
    if (!now) return now.error();
    // Rows are read in recorded_at order (detail::kDisplayOrder): a display recorded in the same
    // millisecond as the session's last one is stamped a millisecond later, so the order read is
    // the order recorded on both engines.
    auto last = m.db.query_text("SELECT max(recorded_at) AS n FROM session_displays WHERE session_id = :session_id",
                                "reading the session's displays", {{"session_id", session.id}});
    if (!last) return last.error();
    if (last->has_value() && **last >= *now)
      if (const auto t = detail::parse_iso8601_utc(**last)) now = detail::iso8601_utc(*t + std::chrono::milliseconds(1));
    RowInsert ins("session_displays");
    ins.set("session_id", session.id).set("recorded_at", *now).set("kind", d.kind).set("width", d.width);
    ins.set("height", d.height).set("refresh_hz", d.refresh_hz).set("renderer", d.renderer).set("monitor", d.monitor);
    return ins.run(m.db, "recording the display");
  });
}

Status Store::finish_session(const Session& session) {
  Impl& m = *impl_;
  return m.write("finishing " + describe(session), [&]() -> Status {
    auto status = read_status(m.db, session);
    if (!status) return status.error();
    if (*status != SessionStatus::running)
      return m.invalid("session", describe(session) + " is " + to_string(*status) + "; only a running session finishes",
                       ErrorKind::conflict);
    auto left = Stmt::prepare(m.db,
                              "SELECT count(*) AS n FROM planned_trials p WHERE session_id = :session_id AND NOT EXISTS "
                              "(SELECT 1 FROM trial_results r WHERE r.planned_trial_id = p.id)",
                              "counting the remaining trials");
    if (!left) return left.error();
    left->bind("session_id", session.id);
    if (auto r = left->step("counting the remaining trials"); !r) return r.error();
    if (const auto n = left->int64("n"); n > 0)
      return m.invalid("session", describe(session) + " still has " + std::to_string(n) +
                                      " planned trials without a result; record them or release the participant",
                       ErrorKind::conflict);
    left->reset();
    auto up = Stmt::prepare(m.db, "UPDATE sessions SET status = 'finished', ended_at = :ended_at WHERE id = :id",
                            "finishing");
    if (!up) return up.error();
    auto now = m.db.now_iso();
    if (!now) return now.error();
    up->bind("ended_at", *now).bind("id", session.id);
    if (auto s = up->run("finishing"); !s) return s;
    auto del = Stmt::prepare(m.db, "DELETE FROM session_claims WHERE session_id = :session_id",
                             "releasing the claim");
    if (!del) return del.error();
    del->bind("session_id", session.id);
    if (auto s = del->run("releasing the claim"); !s) return s;
    m.claimed.erase(session.id);
    return {};
  });
}

Status Store::record_questionnaire(const Session& session, const std::vector<QuestionnaireAnswer>& answers) {
  Impl& m = *impl_;
  for (const auto& a : answers) {
    if (a.item.empty()) return m.invalid("questionnaire.item", "an item id is empty");
    if (const auto* d = std::get_if<double>(&a.value); d && !finite(*d))
      return m.invalid("questionnaire." + a.item, "the answer must be a finite number");
  }
  return m.write("recording the questionnaire of " + describe(session), [&]() -> Status {
    auto status = read_status(m.db, session);
    if (!status) return status.error();
    if (*status == SessionStatus::abandoned)
      return m.invalid("session", describe(session) + " is abandoned; it takes no questionnaire answers",
                       ErrorKind::conflict);
    auto seen = Stmt::prepare(m.db, "SELECT count(*) AS n FROM questionnaire_answers WHERE session_id = :session_id AND "
                              "item = :item AND scope = :scope",
                              "checking the questionnaire");
    if (!seen) return seen.error();
    auto clock = m.db.now_iso();
    if (!clock) return clock.error();
    const std::string now = *clock;
    for (const auto& a : answers) {
      seen->bind("session_id", session.id).bind("item", a.item).bind("scope", a.scope);
      if (auto r = seen->step("checking the questionnaire"); !r) return r.error();
      const auto n = seen->int64("n");
      seen->reset();
      if (n > 0)
        return m.invalid("questionnaire." + a.item,
                         "item \"" + a.item + "\"" + (a.scope.empty() ? std::string() : " (" + a.scope + ")") +
                             " was already answered in " + describe(session),
                         ErrorKind::conflict);
      RowInsert ins("questionnaire_answers");
      ins.set("session_id", session.id).set("item", a.item).set("scope", a.scope).set("answered_at", now);
      if (const auto* d = std::get_if<double>(&a.value)) ins.set("value_number", *d);
      else ins.set("value_text", std::get<std::string>(a.value));
      if (auto r = ins.run(m.db, "storing the questionnaire"); !r) return r;
    }
    return {};
  });
}

Result<Session> Store::session(const std::string& participant_id) {
  Impl& m = *impl_;
  if (m.broken) return m.broken_error;
  auto e = lookup(participant_id);
  if (!e) return e.error();
  auto s = read_session(m.db, participant_id);
  if (!s) return s.error();
  if (!*s) return m.invalid("participant", "participant \"" + participant_id + "\" has no session yet", ErrorKind::not_found);
  return **s;
}

}  // namespace dtlab::store

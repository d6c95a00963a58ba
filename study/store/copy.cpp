// `dtlab copy SRC DST` (copy.h): SRC is read in one snapshot; DST is written
// in one transaction holding its write lock. Into an empty DST every table is
// copied row for row with its ids (sessions enter as running and take their
// final status after their results, so every trigger holds); into a DST that
// holds the study already, merge.cpp decides what may be added. A new SQLite
// file that a failed copy created is removed again.
#include "study/store/copy.h"

#include <algorithm>
#include <charconv>
#include <filesystem>
#include <map>

#include "study/common/version.h"
#include "study/store/detail/copy_rows.h"
#include "study/store/detail/file_check.h"
#include "study/store/detail/schema.h"
#include "study/store/store.h"

namespace dtlab::store {
namespace detail {

const std::vector<TableSpec>& copied_tables() {
  static const std::vector<TableSpec> t = {
      {"studies", {"id", "protocol_id", "protocol_text", "protocol_sha256", "software_version", "order_rows", "created_at"},
       "id", 1},
      {"study_factors", {"study_id", "position", "name"}, "study_id, position", 1},
      {"study_designs", {"study_id", "design_sha256"}, "study_id", 2},
      {"participants",
       {"id", "participant", "enrollment_index", "order_row", "study_id", "demographics", "enrolled_at", "released_at"},
       "id", 1},
      {"sessions", {"id", "participant_id", "study_id", "software_version", "status", "started_at", "ended_at"}, "id", 1},
      {"session_resumes", {"session_id", "resumed_at", "software_version", "next_position"},
       "session_id, resumed_at, next_position IS NULL, next_position", 1},
      {"planned_trials", {"id", "session_id", "position", "block", "task", "trial", "seed", "method", "practice"}, "id", 1},
      {"planned_levels", {"planned_trial_id", "factor_position", "factor", "level"}, "planned_trial_id, factor_position", 1},
      {"trial_results",
       {"planned_trial_id", "scene_hash", "answer_kind", "answered", "answer_count", "answer_letter", "answer_x",
        "answer_z", "truth_count", "truth_letter", "truth_x", "truth_z", "rel_error", "signed_error", "correct",
        "distance", "completion_s", "started_at", "ended_at", "frame_count", "frame_ms_mean", "frame_ms_sd",
        "frame_ms_p95", "frame_ms_max", "event_count", "recorded_at", "frame_first_ms", "frame_ms_median",
        "late_frames", "refresh_hz"},
       // plan order within each session (trigger trial_results_in_plan_order)
       "(SELECT p.session_id FROM planned_trials p WHERE p.id = trial_results.planned_trial_id), "
       "(SELECT p.position FROM planned_trials p WHERE p.id = trial_results.planned_trial_id)",
       1,
       {{"frame_first_ms", 3}, {"frame_ms_median", 3}, {"late_frames", 3}, {"refresh_hz", 3}}},
      {"input_events", {"trial_id", "seq", "t_s", "kind", "detail", "x", "y"}, "trial_id, seq", 1},
      {"camera_poses", {"trial_id", "frame", "t_s", "x", "y", "z", "yaw", "pitch"}, "trial_id, frame", 1},
      {"questionnaire_answers", {"session_id", "item", "scope", "value_number", "value_text", "answered_at"},
       "session_id, item, scope", 1},
      {"exclusions", {"id", "participant_id", "position", "action", "reason", "decided_by", "decided_at"}, "id", 2},
      {"notes", {"id", "participant_id", "position", "author", "text", "written_at"}, "id", 2},
      {"session_pauses", {"session_id", "position", "paused_at", "resumed_at", "duration_s"},
       "session_id, paused_at, resumed_at", 2},
      {"trial_attempts", {"session_id", "position", "attempt", "started_at", "owner"}, "session_id, position, attempt", 2},
      {"session_displays", {"session_id", "recorded_at", "kind", "width", "height", "refresh_hz", "renderer", "monitor"},
       kDisplayOrder, 3},
      {"consents", {"participant_id", "agreed", "text_sha256", "answered_at"}, "participant_id", 4},
      {"screens", {"session_id", "seq", "screen", "shown", "shown_at", "ended_at", "duration_s", "answer"},
       "session_id, seq", 4},
      // after sessions: a withdrawal refuses the participant's session (trigger sessions_not_after_withdrawal)
      {"withdrawals", {"id", "participant_id", "withdrawn_at", "reason", "decided_by"}, "id", 4},
  };
  return t;
}

std::string TableSpec::select_list(int version, const std::string& alias) const {
  std::string s;
  for (const std::string& c : columns) {
    auto later = std::find_if(added_later.begin(), added_later.end(), [&](const auto& a) { return a.first == c; });
    s += s.empty() ? "" : ", ";
    s += later != added_later.end() && later->second > version ? "NULL" : (alias.empty() ? c : alias + "." + c);
  }
  return s;
}

Status each_row(Db& db, const std::string& sql, const Row& binds, const std::function<Status(Row&)>& row) {
  auto st = Stmt::prepare(db, sql, "reading the study");
  if (!st) return st.error();
  for (std::size_t i = 0; i < binds.size(); ++i) st->bind(static_cast<int>(i + 1), binds[i]);
  for (;;) {
    auto r = st->step("reading the study");
    if (!r) return r.error();
    if (!*r) return {};
    Row values;
    values.reserve(static_cast<std::size_t>(st->columns()));
    for (int c = 0; c < st->columns(); ++c) values.push_back(st->value(c));
    if (auto s = row(values); !s) return s;
  }
}

Status RowSink::add(Row row) {
  rows_.push_back(std::move(row));
  ++count_;
  return rows_.size() >= 5000 ? finish() : Status{};
}

Status RowSink::finish() {
  Status s = db_.conn().insert_rows(table_, columns_, rows_, "copying " + table_);
  rows_.clear();
  return s;
}

std::string canonical(const Value& v) {
  if (const auto* n = std::get_if<std::int64_t>(&v)) return std::to_string(*n);
  if (const auto* d = std::get_if<double>(&v)) {
    char buf[64];
    const double x = *d == 0 ? 0.0 : *d;  // -0 and 0 are one value (SQLite stores no signed zero)
    return "r" + std::string(buf, std::to_chars(buf, buf + sizeof buf, x).ptr);
  }
  if (const auto* t = std::get_if<std::string>(&v)) return "'" + std::to_string(t->size()) + ":" + *t;
  return "NULL";
}

std::string canonical(const Row& row) {
  std::string out;
  for (const Value& v : row) out += canonical(v) + "|";
  return out;
}

namespace {

// Copies one table verbatim; events and poses page by trial so memory stays bounded.
Status copy_table(Db& src, int src_version, Db& dst, const TableSpec& t, std::vector<Row>* finals,
                  std::int64_t& written) {
  RowSink sink(dst, t.name, t.columns);
  const bool sessions = std::string(t.name) == "sessions";
  auto add = [&](Row& r) -> Status {
    if (sessions && std::get_if<std::string>(&r[4]) && std::get<std::string>(r[4]) != "running") {
      finals->push_back({r[0], r[4], r[6]});  // id, status, ended_at: set once the results are in
      r[4] = std::string("running");
      r[6] = std::monostate{};
    }
    return sink.add(std::move(r));
  };
  const std::string select = "SELECT " + t.select_list(src_version) + " FROM " + t.name;
  const bool paged = std::string(t.name) == "input_events" || std::string(t.name) == "camera_poses";
  if (!paged) {
    if (auto s = each_row(src, select + " ORDER BY " + t.order_by, {}, add); !s) return s;
  } else {
    auto last = src.query_int(std::string("SELECT max(trial_id) FROM ") + t.name, "reading the study");
    if (!last) return last.error();
    constexpr std::int64_t kStep = 200;  // trials per page
    for (std::int64_t from = 0; from <= last->value_or(-1); from += kStep)
      if (auto s = each_row(src, select + " WHERE trial_id >= ? AND trial_id < ? ORDER BY " + t.order_by,
                            {from, from + kStep}, add);
          !s)
        return s;
  }
  if (auto s = sink.finish(); !s) return s;
  written = sink.count();
  return {};
}

Status full_copy(Db& src, int src_version, Db& dst, CopySummary& summary) {
  std::map<int, AppliedMigration> history;  // SRC's migration rows are DST's history
  Status st = each_row(src, "SELECT version, description, applied_at, software_version FROM schema_migrations", {},
                       [&](Row& r) -> Status {
                         history[static_cast<int>(std::get<std::int64_t>(r[0]))] =
                             AppliedMigration{std::get<std::string>(r[1]), std::get<std::string>(r[2]),
                                              std::get<std::string>(r[3])};
                         return {};
                       });
  if (!st) return st;
  if (auto s = migrate(dst, 0, std::string(version_string()), history); !s) return s;
  std::vector<Row> finals;
  for (const TableSpec& t : copied_tables()) {
    if (t.since_version > src_version) continue;
    std::int64_t n = 0;
    if (auto s = copy_table(src, src_version, dst, t, &finals, n); !s) return s;
    summary.rows.emplace_back(t.name, n);
    if (std::string(t.name) == "participants") summary.participants = static_cast<int>(n);
    if (std::string(t.name) == "sessions") summary.sessions = static_cast<int>(n);
    if (std::string(t.name) == "trial_results") summary.trials = static_cast<int>(n);
    if (std::string(t.name) == "studies") summary.revisions = static_cast<int>(n);
    if (std::string(t.name) == "exclusions") summary.decisions = static_cast<int>(n);
    if (std::string(t.name) == "notes") summary.notes = static_cast<int>(n);
    if (std::string(t.name) == "consents") summary.consents = static_cast<int>(n);
    if (std::string(t.name) == "withdrawals") summary.withdrawals = static_cast<int>(n);
    if (std::string(t.name) == "screens") summary.screens = static_cast<int>(n);
  }
  auto fin = Stmt::prepare(dst, "UPDATE sessions SET status = ?, ended_at = ? WHERE id = ?", "finishing the sessions");
  if (!fin) return fin.error();
  for (const Row& f : finals) {
    fin->bind(1, f[1]).bind(2, f[2]).bind(3, f[0]);
    if (auto s = fin->run("finishing the sessions"); !s) return s;
  }
  return create_trial_table_view(dst);
}

// A claim that has not expired: someone may be running that session now.
Status refuse_running_sessions(Db& src, int src_version) {
  if (src_version < 2) return {};
  auto now = src.now_iso();
  if (!now) return now.error();
  Status refused;
  Status st = each_row(src,
                       "SELECT p.participant, c.pid, c.host, c.expires_at FROM session_claims c "
                       "JOIN sessions s ON s.id = c.session_id JOIN participants p ON p.id = s.participant_id "
                       "WHERE c.expires_at > ? ORDER BY p.enrollment_index",
                       {*now}, [&](Row& r) -> Status {
                         if (refused)
                           refused = Error{src.path(), 0, 0, "session_claims",
                                           "the session of \"" + std::get<std::string>(r[0]) + "\" is being run now by process " +
                                               std::to_string(std::get<std::int64_t>(r[1])) + " on host " +
                                               std::get<std::string>(r[2]) + " (its claim expires at " +
                                               std::get<std::string>(r[3]) +
                                               "); finish or stop it, then copy (a crashed run's claim expires by itself)",
                                           ErrorKind::conflict};
                         return {};
                       });
  return st ? refused : st;
}

bool same_database(const std::string& src, const std::string& dst) {
  if (is_server_uri(src) != is_server_uri(dst)) return false;
  if (is_server_uri(src)) return display_name(src) == display_name(dst);
  std::error_code ec;
  return std::filesystem::equivalent(src, dst, ec);
}

}  // namespace
}  // namespace detail

Result<CopySummary> copy_study(const std::string& src, const std::string& dst, const CopyOptions& options) {
  using namespace detail;
  if (same_database(src, dst))
    return Error{display_name(dst), 0, 0, "", "SRC and DST are the same database; copy to another file or schema",
                 ErrorKind::invalid_input};
  auto in = open_connection(src, Access::read, options.busy_timeout_ms);
  if (!in) return in.error();
  Db from(std::move(*in));
  auto src_state = inspect(from);
  if (!src_state) return src_state.error();
  if (auto s = check_dtlab(from, *src_state, false); !s) return s.error();
  if (auto s = check_tables(from, std::max(src_state->user_version, src_state->migrations)); !s) return s.error();
  const int src_version = std::max(src_state->user_version, src_state->migrations);

  const bool new_file = !is_server_uri(dst) && !std::filesystem::exists(dst);
  auto remove_new_file = [&] {
    if (!new_file) return;
    std::error_code ec;
    for (const char* suffix : {"", "-wal", "-shm", "-journal"}) std::filesystem::remove(dst + suffix, ec);
  };
  auto out = open_connection(dst, Access::create, options.busy_timeout_ms);
  if (!out) return out.error();
  Db to(std::move(*out));
  CopySummary summary;
  Status st = [&]() -> Status {
    auto dst_state = inspect(to);
    if (!dst_state) return dst_state.error();
    if (auto s = check_dtlab(to, *dst_state, true); !s) return s;
    if (auto s = to.conn().configure_for_writing(options.busy_timeout_ms); !s) return s;
    if (auto s = from.conn().begin_read("reading the study"); !s) return s;  // one snapshot of SRC throughout
    if (auto s = refuse_running_sessions(from, src_version); !s) return s;
    Transaction tx(to);
    if (auto s = tx.begin("copying the study"); !s) return s;
    auto now_state = inspect(to, /*in_transaction=*/true);  // another process may have created it since
    if (!now_state) return now_state.error();
    if (auto s = check_dtlab(to, *now_state, true); !s) return s;
    if (now_state->empty) {
      if (auto s = full_copy(from, src_version, to, summary); !s) return s;
    } else {
      auto version = applied_schema_version(to);
      if (!version) return version.error();
      if (*version < kSchemaVersion)
        if (auto s = migrate(to, *version, std::string(version_string())); !s) return s;
      summary.merged = true;
      if (auto s = merge_study(from, src_version, to, options, summary); !s) return s;
    }
    return tx.commit("copying the study");
  }();
  from.conn().rollback();  // the read snapshot
  if (!st) {
    to = Db();  // close DST before removing a file it created
    remove_new_file();
    return st.error();
  }
  return summary;
}

}  // namespace dtlab::store

// `dtlab copy SRC DST` (copy.h): SRC is read in one snapshot; DST is written
// in one transaction holding its write lock. Into an empty DST every table is
// copied row for row with its ids (sessions enter as running and take their
// final status after their results, so every trigger holds); into a DST that
// holds the study already, merge.cpp decides what may be added. A new SQLite
// file that a failed copy created is removed again.
#include "study/store/copy.h"

#include <algorithm>
#include <cassert>
#include <charconv>
#include <filesystem>
#include <map>
#include <mutex>

#include "study/common/version.h"
#include "study/store/detail/columns.h"
#include "study/store/detail/copy_rows.h"
#include "study/store/detail/file_check.h"
#include "study/store/detail/schema.h"
#include "study/store/store.h"

namespace dtlab::store {
namespace detail {

const std::vector<TableSpec>& copied_tables() {
  static const std::vector<TableSpec> t = {
      {"studies", "id"},
      {"study_factors", "study_id, position"},
      {"study_designs", "study_id"},
      {"participants", "id"},
      {"sessions", "id"},
      {"session_resumes", "session_id, resumed_at, next_position IS NULL, next_position"},
      {"planned_trials", "id"},
      {"planned_levels", "planned_trial_id, factor_position"},
      // plan order within each session (trigger trial_results_in_plan_order)
      {"trial_results",
       "(SELECT p.session_id FROM planned_trials p WHERE p.id = trial_results.planned_trial_id), "
       "(SELECT p.position FROM planned_trials p WHERE p.id = trial_results.planned_trial_id)"},
      {"input_events", "trial_id, seq"},
      {"camera_poses", "trial_id, frame"},
      {"questionnaire_answers", "session_id, item, scope"},
      {"exclusions", "id"},
      {"notes", "id"},
      {"session_pauses", "session_id, paused_at, resumed_at"},
      {"trial_attempts", "session_id, position, attempt"},
      {"session_displays", kDisplayOrder},
      {"consents", "participant_id"},
      {"screens", "session_id, seq"},
      // after sessions: a withdrawal refuses the participant's session (trigger sessions_not_after_withdrawal)
      {"withdrawals", "id"},
  };
  return t;
}

const TableSpec& copied_table(std::string_view name) {
  for (const TableSpec& t : copied_tables())
    if (t.name == name) return t;
  assert(false && "not a copied table: add it to copied_tables()");
  return copied_tables().front();
}

const Table& TableSpec::table() const {
  const Table* t = find_table(name);
  assert(t && "a copied table must be described in schema_tables.cpp");
  return *t;
}

const std::vector<std::string>& TableSpec::columns() const {
  static std::map<std::string, std::vector<std::string>, std::less<>> cache;  // filled once, at the first copy
  static std::once_flag once;
  std::call_once(once, [] {
    for (const TableSpec& s : copied_tables())
      for (const Column& c : s.table().columns) cache[s.name].push_back(c.name);
  });
  return cache.find(name)->second;
}

std::string TableSpec::select_list(int version, const std::string& alias) const {
  return detail::select_list(table(), alias.empty() ? alias : alias + ".", version);
}

int Row::index(std::string_view column) const {
  if (!names_) return -1;
  for (std::size_t c = 0; c < names_->size(); ++c)
    if ((*names_)[c] == column) return static_cast<int>(c);
  return -1;
}

const Value& Row::operator[](std::string_view column) const {
  const int c = index(column);
  assert(c >= 0 && "the row has no such column: select it by that name");
  return c < 0 ? scratch_ : cells_[static_cast<std::size_t>(c)];
}

Value& Row::operator[](std::string_view column) {
  const int c = index(column);
  assert(c >= 0 && "the row has no such column: select it by that name");
  return c < 0 ? scratch_ : cells_[static_cast<std::size_t>(c)];
}

Row Row::without(std::string_view column) const {
  auto names = std::make_shared<std::vector<std::string>>();
  std::vector<Value> cells;
  for (std::size_t c = 0; c < cells_.size(); ++c)
    if ((*names_)[c] != column) {
      names->push_back((*names_)[c]);
      cells.push_back(cells_[c]);
    }
  return Row(std::move(names), std::move(cells));
}

const std::vector<std::string>& Row::names() const {
  static const std::vector<std::string> none;
  return names_ ? *names_ : none;
}

bool same_except(const Row& a, const Row& b, std::initializer_list<std::string_view> ignored) {
  if (a.names() != b.names()) return false;
  for (std::size_t c = 0; c < a.cells().size(); ++c)
    if (std::find(ignored.begin(), ignored.end(), a.names()[c]) == ignored.end() && a.cells()[c] != b.cells()[c])
      return false;
  return true;
}

Status each_row(Db& db, const std::string& sql, const Binds& binds, const std::function<Status(Row&)>& row) {
  auto st = Stmt::prepare(db, sql, "reading the study");
  if (!st) return st.error();
  for (const auto& [name, value] : binds) st->bind(name, value);
  std::shared_ptr<const std::vector<std::string>> names;
  for (;;) {
    auto r = st->step("reading the study");
    if (!r) return r.error();
    if (!*r) return {};
    if (!names) names = std::make_shared<const std::vector<std::string>>(st->column_names());
    Row values(names, st->cells());
    if (auto s = row(values); !s) return s;
  }
}

Status insert_named(Db& db, const std::string& table, const std::vector<Row>& rows, std::string_view what) {
  if (rows.empty()) return {};
  const Table* t = find_table(table);
  if (!t)
    return Error{db.path(), 0, 0, table, std::string(what) + ": the schema has no table " + table, ErrorKind::internal};
  std::vector<std::string> columns;
  for (const Column& c : t->columns) columns.push_back(c.name);
  std::vector<std::vector<Value>> cells;
  cells.reserve(rows.size());
  const std::vector<std::string>* names = nullptr;
  std::vector<int> at;  // the row's cell of each described column, found once per query's names
  for (const Row& r : rows) {
    if (&r.names() != names) {
      names = &r.names();
      at.clear();
      for (const std::string& c : columns) {
        const auto it = std::find(names->begin(), names->end(), c);
        at.push_back(it == names->end() ? -1 : static_cast<int>(it - names->begin()));
      }
      for (const std::string& n : *names)
        if (std::find(columns.begin(), columns.end(), n) == columns.end())
          return Error{db.path(), 0, 0, table + "." + n,
                       std::string(what) + ": the schema has no column " + n + " in " + table, ErrorKind::internal};
    }
    std::vector<Value> row;
    row.reserve(columns.size());
    for (int c : at) row.push_back(c < 0 ? Value{} : r.cells()[static_cast<std::size_t>(c)]);
    cells.push_back(std::move(row));
  }
  return db.conn().insert_rows(table, columns, cells, what);
}

Status RowSink::add(Row row) {
  rows_.push_back(std::move(row));
  ++count_;
  return rows_.size() >= 5000 ? finish() : Status{};
}

Status RowSink::finish() {
  Status s = insert_named(db_, table_, rows_, "copying " + table_);
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
  for (const Value& v : row.cells()) out += canonical(v) + "|";
  return out;
}

namespace {

// Copies one table verbatim; events and poses page by trial so memory stays bounded.
Status copy_table(Db& src, int src_version, Db& dst, const TableSpec& t, std::vector<Row>* finals,
                  std::int64_t& written) {
  RowSink sink(dst, t.name);
  const bool sessions = std::string(t.name) == "sessions";
  auto add = [&](Row& r) -> Status {
    if (sessions && std::get_if<std::string>(&r["status"]) && std::get<std::string>(r["status"]) != "running") {
      finals->push_back(r);  // its status and ended_at are set once the results are in
      r["status"] = std::string("running");
      r["ended_at"] = std::monostate{};
    }
    return sink.add(std::move(r));
  };
  const std::string select = "SELECT " + t.select_list(src_version) + " FROM " + t.name;
  const bool paged = std::string(t.name) == "input_events" || std::string(t.name) == "camera_poses";
  if (!paged) {
    if (auto s = each_row(src, select + " ORDER BY " + t.order_by, {}, add); !s) return s;
  } else {
    auto last = src.query_int(std::string("SELECT max(trial_id) AS n FROM ") + t.name, "reading the study");
    if (!last) return last.error();
    constexpr std::int64_t kStep = 200;  // trials per page
    for (std::int64_t from = 0; from <= last->value_or(-1); from += kStep)
      if (auto s = each_row(src, select + " WHERE trial_id >= :from AND trial_id < :to ORDER BY " + t.order_by,
                            {{"from", from}, {"to", from + kStep}}, add);
          !s)
        return s;
  }
  if (auto s = sink.finish(); !s) return s;
  written = sink.count();
  return {};
}

Status full_copy(Db& src, int src_version, Db& dst, CopySummary& summary) {
  std::map<int, AppliedMigration> history;  // SRC's migration rows are DST's history
  Status st = each_row(src,
                       "SELECT " + select_list(*find_table("schema_migrations"), "", src_version) +
                           " FROM schema_migrations",
                       {}, [&](Row& r) -> Status {
                         history[static_cast<int>(std::get<std::int64_t>(r["version"]))] =
                             AppliedMigration{std::get<std::string>(r["description"]),
                                              std::get<std::string>(r["applied_at"]),
                                              std::get<std::string>(r["software_version"])};
                         return {};
                       });
  if (!st) return st;
  if (auto s = migrate(dst, 0, std::string(version_string()), history); !s) return s;
  std::vector<Row> finals;
  for (const TableSpec& t : copied_tables()) {
    if (t.table().since > src_version) continue;
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
  auto fin = Stmt::prepare(dst, "UPDATE sessions SET status = :status, ended_at = :ended_at WHERE id = :id",
                           "finishing the sessions");
  if (!fin) return fin.error();
  for (const Row& f : finals) {
    fin->bind("status", f["status"]).bind("ended_at", f["ended_at"]).bind("id", f["id"]);
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
                       "SELECT p.participant AS participant, c.pid AS pid, c.host AS host, c.expires_at AS expires_at "
                       "FROM session_claims c JOIN sessions s ON s.id = c.session_id "
                       "JOIN participants p ON p.id = s.participant_id WHERE c.expires_at > :now "
                       "ORDER BY p.enrollment_index",
                       {{"now", *now}}, [&](Row& r) -> Status {
                         if (refused)
                           refused = Error{src.path(), 0, 0, "session_claims",
                                           "the session of \"" + std::get<std::string>(r["participant"]) +
                                               "\" is being run now by process " +
                                               std::to_string(std::get<std::int64_t>(r["pid"])) + " on host " +
                                               std::get<std::string>(r["host"]) + " (its claim expires at " +
                                               std::get<std::string>(r["expires_at"]) +
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

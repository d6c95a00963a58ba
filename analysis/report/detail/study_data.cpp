// Reading a study database for the report; see study_data.h. A small RAII
// layer over the SQLite C API of its own (analysis reads the store's schema
// through SQLite only, docs/store.md "Views"), read-only, one transaction.
#include "analysis/report/detail/study_data.h"

#include <sqlite3.h>

#include <nlohmann/json.hpp>

#include <memory>

namespace dtlab::report::detail {
namespace {

struct Conn {
  sqlite3* db = nullptr;
  std::string path;
  ~Conn() { sqlite3_close_v2(db); }
  Error error(const std::string& what) const {
    return Error{path, 0, 0, "sqlite", what + ": " + (db ? sqlite3_errmsg(db) : "out of memory")};
  }
};

struct Query {
  sqlite3_stmt* st = nullptr;
  ~Query() { sqlite3_finalize(st); }
  bool null(int c) const { return sqlite3_column_type(st, c) == SQLITE_NULL; }
  std::string text(int c) const {
    const unsigned char* t = sqlite3_column_text(st, c);
    return t ? std::string(reinterpret_cast<const char*>(t), static_cast<size_t>(sqlite3_column_bytes(st, c))) : "";
  }
  std::int64_t int64(int c) const { return sqlite3_column_int64(st, c); }
  double real(int c) const { return sqlite3_column_double(st, c); }
  std::optional<double> opt_real(int c) const { return null(c) ? std::nullopt : std::optional<double>(real(c)); }
  std::optional<std::int64_t> opt_int(int c) const {
    return null(c) ? std::nullopt : std::optional<std::int64_t>(int64(c));
  }
  std::optional<std::string> opt_text(int c) const {
    return null(c) ? std::nullopt : std::optional<std::string>(text(c));
  }
};

// Runs `sql`, calling row(q) per result row; an Error names what was read.
template <class F>
Status each_row(Conn& c, const std::string& sql, const std::string& what, F&& row) {
  Query q;
  if (sqlite3_prepare_v2(c.db, sql.c_str(), -1, &q.st, nullptr) != SQLITE_OK) return c.error(what);
  for (;;) {
    const int rc = sqlite3_step(q.st);
    if (rc == SQLITE_DONE) return {};
    if (rc != SQLITE_ROW) return c.error(what);
    row(q);
  }
}

std::string quote_identifier(const std::string& name) {
  std::string q = "\"";
  for (char ch : name) q += ch == '"' ? std::string("\"\"") : std::string(1, ch);
  return q + "\"";
}

std::map<std::string, std::string> parse_demographics(const std::string& text) {
  std::map<std::string, std::string> out;
  const auto j = nlohmann::json::parse(text, nullptr, false);
  if (!j.is_object()) return out;
  for (const auto& [k, v] : j.items()) out[k] = v.is_string() ? v.get<std::string>() : v.dump();
  return out;
}

}  // namespace

Result<StudyData> read_study(const std::string& path) {
  Conn c;
  c.path = path;
  // Read-write without CREATE, made read-only by query_only (as the store's read-only connections,
  // study/store/detail/readonly.cpp): a SQLITE_OPEN_READONLY connection cannot checkpoint, so as the
  // last one to close it would leave -wal and -shm behind. A write-protected file opens read-only.
  if (sqlite3_open_v2(path.c_str(), &c.db, SQLITE_OPEN_READWRITE, nullptr) != SQLITE_OK)
    return c.error("opening the database");
  if (sqlite3_exec(c.db, "PRAGMA query_only = ON", nullptr, nullptr, nullptr) != SQLITE_OK)
    return c.error("making the connection read-only");
  sqlite3_busy_timeout(c.db, 10000);
  if (sqlite3_exec(c.db, "BEGIN", nullptr, nullptr, nullptr) != SQLITE_OK) return c.error("starting a read transaction");

  StudyData d;
  d.path = path;
  std::int64_t study_id = -1;
  std::string protocol_text, sha;
  Status s = each_row(c, "SELECT id, protocol_text, protocol_sha256, software_version, "
                         "(SELECT count(*) FROM studies) FROM studies ORDER BY id DESC LIMIT 1",
                      "reading the protocol record", [&](const Query& q) {
                        study_id = q.int64(0);
                        protocol_text = q.text(1);
                        sha = q.text(2);
                        d.software_version = q.text(3);
                        d.studies = static_cast<int>(q.int64(4));
                      });
  if (!s) return s.error();
  if (study_id < 0) return Error{path, 0, 0, "studies", "the database records no protocol (no study was ever started)"};
  auto proto = protocol::load_protocol_text(protocol_text, path + " (recorded protocol)");
  if (!proto) {
    Error e = proto.error();
    e.message = "the protocol recorded in the database does not load: " + e.message;
    return e;
  }
  d.protocol = std::move(*proto);

  s = each_row(c,
               "SELECT pa.participant, pa.enrollment_index, pa.order_row, pa.released_at IS NOT NULL, pa.demographics, "
               "coalesce(s.status, ''), "
               "(SELECT count(*) FROM planned_trials p WHERE p.session_id = s.id), "
               "(SELECT count(*) FROM planned_trials p JOIN trial_results r ON r.planned_trial_id = p.id "
               " WHERE p.session_id = s.id), "
               "(SELECT count(*) FROM session_resumes x WHERE x.session_id = s.id), coalesce(s.software_version, '') "
               "FROM participants pa LEFT JOIN sessions s ON s.participant_id = pa.id "
               "WHERE coalesce(s.study_id, pa.study_id) = " + std::to_string(study_id) +
                   " ORDER BY pa.enrollment_index",
               "reading the participant ledger", [&](const Query& q) {
                 ParticipantRow p;
                 p.id = q.text(0);
                 p.index = static_cast<int>(q.int64(1));
                 p.order_row = static_cast<int>(q.int64(2));
                 p.released = q.int64(3) != 0;
                 p.demographics = parse_demographics(q.text(4));
                 p.session_status = q.text(5);
                 p.planned = static_cast<int>(q.int64(6));
                 p.recorded = static_cast<int>(q.int64(7));
                 p.resumes = static_cast<int>(q.int64(8));
                 p.software_version = q.text(9);
                 d.participants.push_back(std::move(p));
               });
  if (!s) return s.error();

  // The trial table: the view's columns by name, factor columns in protocol order.
  std::string sql = "SELECT participant, enrollment_index, order_row, session_status, position, block, ";
  for (const auto& f : d.protocol.factors) {
    // A factor missing from the view (cannot happen for the current protocol) reads as NULL.
    sql += quote_identifier(f.name) + ", ";
  }
  sql +=
      "task, trial, practice, method, answer_count, answer_letter, answer_x, answer_z, truth_count, "
      "truth_letter, truth_x, truth_z, rel_error, signed_error, correct, distance, completion_time_s, frame_count, "
      "frame_ms_mean, frame_ms_sd, frame_ms_p95, frame_ms_max, protocol_sha256 "
      "FROM trial_table ORDER BY enrollment_index, position";
  const int nf = static_cast<int>(d.protocol.factors.size());
  s = each_row(c, sql, "reading trial_table", [&](const Query& q) {
    TrialRow t;
    t.participant = q.text(0);
    t.enrollment_index = static_cast<int>(q.int64(1));
    t.order_row = static_cast<int>(q.int64(2));
    t.session_status = q.text(3);
    t.position = static_cast<int>(q.int64(4));
    t.block = static_cast<int>(q.int64(5));
    for (int f = 0; f < nf; ++f) {
      t.levels.push_back(q.text(6 + f));
      const auto& lv = d.protocol.factors[static_cast<size_t>(f)].levels;
      int idx = -1;
      for (size_t l = 0; l < lv.size(); ++l)
        if (lv[l] == t.levels.back()) idx = static_cast<int>(l);
      t.level_index.push_back(idx);
    }
    int k = 6 + nf;
    t.task = q.text(k++);
    t.trial = static_cast<int>(q.int64(k++));
    t.practice = q.int64(k++) != 0;
    t.method = q.text(k++);
    t.answer_count = q.opt_int(k++);
    t.answer_letter = q.opt_text(k++);
    t.answer_x = q.opt_real(k++);
    t.answer_z = q.opt_real(k++);
    t.truth_count = q.opt_int(k++);
    t.truth_letter = q.opt_text(k++);
    t.truth_x = q.opt_real(k++);
    t.truth_z = q.opt_real(k++);
    t.rel_error = q.opt_real(k++);
    t.signed_error = q.opt_int(k++);
    if (!q.null(k)) t.correct = q.int64(k) != 0;
    ++k;
    t.distance = q.opt_real(k++);
    t.time_s = q.real(k++);
    t.frame_count = q.int64(k++);
    t.frame_mean = q.opt_real(k++);
    t.frame_sd = q.opt_real(k++);
    t.frame_p95 = q.opt_real(k++);
    t.frame_max = q.opt_real(k++);
    t.protocol_sha256 = q.text(k++);
    if (t.protocol_sha256 != sha) {
      ++d.other_protocol_trials;
      return;
    }
    d.trials.push_back(std::move(t));
  });
  if (!s) return s.error();

  s = each_row(c,
               "SELECT pa.participant, q.item, q.scope, q.value_number, q.value_text FROM questionnaire_answers q "
               "JOIN sessions s ON s.id = q.session_id JOIN participants pa ON pa.id = s.participant_id "
               "WHERE s.study_id = " + std::to_string(study_id) + " ORDER BY pa.enrollment_index, q.item, q.scope",
               "reading questionnaire_answers", [&](const Query& q) {
                 d.answers.push_back({q.text(0), q.text(1), q.text(2), q.opt_real(3), q.opt_text(4)});
               });
  if (!s) return s.error();
  sqlite3_exec(c.db, "COMMIT", nullptr, nullptr, nullptr);
  return d;
}

}  // namespace dtlab::report::detail

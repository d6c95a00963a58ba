// StudyReader (read.h): opening a study database for reading and the typed
// reads. An owned reader holds one read transaction (its snapshot) from open
// until refresh() or destruction; the reader a Store lends (Store::read())
// borrows the Store's connection and wraps each call in its own short read
// transaction, so it never holds a snapshot across the Store's writes.
#include "study/store/read.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <map>
#include <set>

#include "study/store/detail/columns.h"
#include "study/store/detail/file_check.h"
#include "study/store/detail/reader_impl.h"
#include "study/store/detail/schema.h"

namespace dtlab::store {

using detail::Db;
using detail::NamedColumns;
using detail::by_name;
using detail::find_table;
using detail::select_list;
using detail::Stmt;
using detail::parse_seed;
using detail::parse_status;
using namespace detail::reading;

namespace {

InputEvent::Kind parse_kind(const std::string& s) {
  using K = InputEvent::Kind;
  for (K k : {K::key_down, K::key_up, K::button_down, K::button_up, K::cursor, K::scroll, K::answer})
    if (s == to_string(k)) return k;
  return K::key_down;
}

Demographics parse_demographics(const std::string& text) {
  Demographics out;
  const auto j = nlohmann::ordered_json::parse(text, nullptr, false);
  if (!j.is_object()) return out;
  for (const auto& [k, v] : j.items()) out.emplace_back(k, v.is_string() ? v.get<std::string>() : v.dump());
  return out;
}

// The answer of one kind from its four columns (PREFIX_count, _letter, _x, _z), by name.
std::optional<Answer> read_answer(const NamedColumns& col, const Stmt& q, const std::string& kind,
                                  const std::string& prefix) {
  if (kind == "count") {
    if (col.is_null(q, prefix + "_count")) return std::nullopt;
    return Answer{Count{col.int64(q, prefix + "_count")}};
  }
  if (kind == "letter") {
    if (col.is_null(q, prefix + "_letter")) return std::nullopt;
    return Answer{Letter{col.text(q, prefix + "_letter")}};
  }
  if (col.is_null(q, prefix + "_x") || col.is_null(q, prefix + "_z")) return std::nullopt;
  return Answer{Position{col.real(q, prefix + "_x"), col.real(q, prefix + "_z")}};
}

// A recorded trial as trials() selects it: the trial_results columns by their names, and the
// session, ledger and revision columns by the names the query gives them.
TrialRow read_trial_row(const NamedColumns& col, const Stmt& q) {
  TrialRow t;
  t.participant = col.text(q, "participant");
  t.enrollment_index = static_cast<int>(col.int64(q, "enrollment_index"));
  t.order_row = static_cast<int>(col.int64(q, "order_row"));
  t.session_id = col.int64(q, "session_id");
  t.session_status = parse_status(col.text(q, "session_status"));
  t.scene_hash = col.text(q, "scene_hash");
  const std::string kind = col.text(q, "answer_kind");
  t.answer = read_answer(col, q, kind, "answer");
  t.truth = read_answer(col, q, kind, "truth").value_or(Answer{Count{0}});
  t.scores.rel_error = col.opt_real(q, "rel_error");  // as stored (the schema's CHECK holds them to score())
  t.scores.signed_error = col.opt_int(q, "signed_error");
  if (auto c = col.opt_int(q, "correct")) t.scores.correct = *c != 0;
  t.scores.distance = col.opt_real(q, "distance");
  t.completion_s = col.real(q, "completion_s");
  t.started_at = col.text(q, "started_at");
  t.ended_at = col.text(q, "ended_at");
  t.frames.frames = col.int64(q, "frame_count");
  t.frames.mean_ms = col.opt_real(q, "frame_ms_mean");
  t.frames.sd_ms = col.opt_real(q, "frame_ms_sd");
  t.frames.p95_ms = col.opt_real(q, "frame_ms_p95");
  t.frames.max_ms = col.opt_real(q, "frame_ms_max");
  t.frames.first_ms = col.opt_real(q, "frame_first_ms");
  t.frames.steady_median_ms = col.opt_real(q, "frame_ms_median");
  t.frames.late = col.opt_int(q, "late_frames");
  t.frames.refresh_hz = col.opt_real(q, "refresh_hz");
  t.event_count = col.int64(q, "event_count");
  t.study_id = col.int64(q, "study_id");
  t.protocol_sha256 = col.text(q, "protocol_sha256");
  t.withdrawn = col.int64(q, "withdrawn") != 0;
  return t;
}

}  // namespace

bool LedgerEntry::simulated() const {
  for (const auto& [k, v] : demographics)
    if (k == "simulated") return v == "true" || v == "1" || v == "yes";
  return false;
}

double SessionRecord::paused_s() const {
  double s = 0;
  for (const Pause& p : pauses) s += p.duration_s;
  return s;
}

std::string TrialRow::level(const std::string& factor) const {
  for (const auto& [f, l] : planned.levels)
    if (f == factor) return l;
  return "";
}

// --- Impl -----------------------------------------------------------------------------

Status StudyReader::Impl::begin() {
  if (in_snapshot || !owned) return {};
  if (auto s = db->conn().begin_read("starting a read transaction"); !s) return s;
  in_snapshot = true;
  return {};
}

void StudyReader::Impl::end() {
  if (!in_snapshot) return;
  db->conn().commit("ending the read transaction");  // read only: nothing to lose if it fails
  in_snapshot = false;
}

StudyReader::StudyReader(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
StudyReader::StudyReader(StudyReader&&) noexcept = default;
StudyReader& StudyReader::operator=(StudyReader&&) noexcept = default;
StudyReader::~StudyReader() {
  if (impl_) impl_->end();
}

StudyReader StudyReader::borrow(detail::Db& db, ReadOptions options) {
  auto impl = std::make_unique<Impl>();
  impl->db = &db;
  impl->owned = false;
  impl->options = std::move(options);
  return StudyReader(std::move(impl));
}

Result<StudyReader> StudyReader::open(const std::string& path, ReadOptions options) {
  auto opened = detail::open_connection(path, detail::Access::read, options.busy_timeout_ms);
  if (!opened) return opened.error();
  Db db(std::move(*opened));
  auto state = detail::inspect(db);
  if (!state) return state.error();
  if (auto s = detail::check_dtlab(db, *state, false); !s) return s.error();
  if (auto s = detail::check_tables(db, std::max(state->user_version, state->migrations)); !s) return s.error();
  auto impl = std::make_unique<Impl>();
  impl->own = std::move(db);
  impl->db = &impl->own;
  impl->owned = true;
  impl->options = std::move(options);
  impl->schema_version = std::max(state->user_version, state->migrations);
  if (auto s = impl->begin(); !s) return s.error();
  return StudyReader(std::move(impl));
}

const std::string& StudyReader::path() const { return impl_->db->path(); }
int StudyReader::schema_version() const { return impl_->schema_version; }

Status StudyReader::refresh() {
  impl_->end();
  impl_->revisions.reset();
  return impl_->begin();
}

Result<std::vector<Revision>> StudyReader::Impl::read_revisions() {
  if (owned && revisions) return *revisions;
  std::vector<Revision> out;
  const bool v2 = schema_version >= 2;
  const std::string sql = "SELECT " + select_list(*find_table("studies"), "s.", schema_version) + ", " +
                          (v2 ? "d.design_sha256" : "NULL") + " AS design_sha256 FROM studies s " +
                          (v2 ? "LEFT JOIN study_designs d ON d.study_id = s.id " : "") + "ORDER BY s.id";
  Status st = each_row(*db, sql, "reading the protocol revisions", no_bind,
                       by_name([&](const NamedColumns& c, const Stmt& q) {
                         Revision r;
                         r.study_id = c.int64(q, "id");
                         r.protocol_id = c.text(q, "protocol_id");
                         r.protocol_text = c.text(q, "protocol_text");
                         r.protocol_sha256 = c.text(q, "protocol_sha256");
                         r.design_sha256 = c.opt_text(q, "design_sha256").value_or("");
                         r.software_version = c.text(q, "software_version");
                         r.order_rows = static_cast<int>(c.int64(q, "order_rows"));
                         r.created_at = c.text(q, "created_at");
                         out.push_back(std::move(r));
                       }));
  if (!st) return st.error();
  std::map<std::int64_t, std::vector<std::string>> factors;
  st = each_row(*db, "SELECT " + select_list(*find_table("study_factors"), "", schema_version) +
                         " FROM study_factors ORDER BY study_id, position",
                "reading the factors", no_bind, by_name([&](const NamedColumns& c, const Stmt& q) {
                  factors[c.int64(q, "study_id")].push_back(c.text(q, "name"));
                }));
  if (!st) return st.error();
  std::vector<std::string> designs;  // distinct design hashes in order of first appearance
  for (Revision& r : out) {
    r.factors = factors[r.study_id];
    if (r.design_sha256.empty() && options.design_hash_of)
      r.design_sha256 = options.design_hash_of(r.protocol_text).value_or("");
    if (r.design_sha256.empty()) continue;
    auto it = std::find(designs.begin(), designs.end(), r.design_sha256);
    if (it == designs.end()) it = designs.insert(designs.end(), r.design_sha256);
    r.design_revision = static_cast<int>(it - designs.begin()) + 1;
  }
  if (owned) revisions = out;
  return out;
}

Result<std::vector<Revision>> StudyReader::revisions() {
  return impl_->call([&] { return impl_->read_revisions(); });
}

Result<std::vector<LedgerEntry>> StudyReader::ledger() {
  return impl_->call([&]() -> Result<std::vector<LedgerEntry>> {
    std::vector<LedgerEntry> out;
    Status st = each_row(*impl_->db,
                         "SELECT " + select_list(*find_table("participants"), "", impl_->schema_version) + ", " +
                             withdrawn_sql(impl_->schema_version, "participants.id") +
                             " AS withdrawn FROM participants ORDER BY enrollment_index",
                         "reading the participant ledger", no_bind, by_name([&](const NamedColumns& c, const Stmt& q) {
                           LedgerEntry e;
                           e.participant = c.text(q, "participant");
                           e.index = static_cast<int>(c.int64(q, "enrollment_index"));
                           e.order_row = static_cast<int>(c.int64(q, "order_row"));
                           e.study_id = c.int64(q, "study_id");
                           e.demographics = parse_demographics(c.text(q, "demographics"));
                           e.enrolled_at = c.text(q, "enrolled_at");
                           e.released_at = c.opt_text(q, "released_at");
                           e.withdrawn = c.int64(q, "withdrawn") != 0;
                           out.push_back(std::move(e));
                         }));
    if (!st) return st.error();
    return out;
  });
}

namespace {

// The resumes, pauses, displays, claims and interrupted attempts of the sessions in `out` (`at`:
// a session's id to its index there), each read by column name.
Status read_session_details(Db& db, int version, std::vector<SessionRecord>& out,
                            const std::map<std::int64_t, std::size_t>& at) {
  Status st;
  // Resumes and pauses of a session in the order they happened (time, then the plan's progress).
  auto all_of = [&](const char* table) {
    return "SELECT " + select_list(*find_table(table), "", version) + " FROM " + table;
  };
  st = each_row(db, all_of("session_resumes") + " ORDER BY session_id, resumed_at, next_position IS NULL, next_position",
                "reading the resumes", no_bind, by_name([&](const NamedColumns& c, const Stmt& q) {
                  if (auto it = at.find(c.int64(q, "session_id")); it != at.end())
                    out[it->second].resumes.push_back(Resume{c.text(q, "resumed_at"), c.text(q, "software_version"),
                                                             c.opt_int32(q, "next_position")});
                }));
  if (!st) return st;
  if (version < 2) return {};
  st = each_row(db, all_of("session_pauses") + " ORDER BY session_id, paused_at, resumed_at", "reading the pauses",
                no_bind, by_name([&](const NamedColumns& c, const Stmt& q) {
                  if (auto it = at.find(c.int64(q, "session_id")); it != at.end())
                    out[it->second].pauses.push_back(Pause{c.opt_int32(q, "position"), c.text(q, "paused_at"),
                                                           c.text(q, "resumed_at"), c.real(q, "duration_s")});
                }));
  if (!st) return st;
  if (version >= 3) {
    st = each_row(db, all_of("session_displays") + " ORDER BY " + detail::kDisplayOrder, "reading the displays",
                  no_bind, by_name([&](const NamedColumns& c, const Stmt& q) {
                    if (auto it = at.find(c.int64(q, "session_id")); it != at.end()) {
                      DisplayInfo d{c.text(q, "kind"), static_cast<int>(c.int64(q, "width")),
                                    static_cast<int>(c.int64(q, "height")), c.opt_real(q, "refresh_hz"),
                                    c.text(q, "renderer"), c.text(q, "monitor")};
                      out[it->second].displays.push_back(Display{c.text(q, "recorded_at"), std::move(d)});
                    }
                  }));
    if (!st) return st;
  }
  st = each_row(db, all_of("session_claims"), "reading the session claims", no_bind,
                by_name([&](const NamedColumns& c, const Stmt& q) {
                  if (auto it = at.find(c.int64(q, "session_id")); it != at.end())
                    out[it->second].claim = Claim{c.text(q, "owner"),      c.text(q, "host"),
                                                  c.int64(q, "pid"),       c.text(q, "claimed_at"),
                                                  c.text(q, "heartbeat_at"), c.text(q, "expires_at")};
                }));
  if (!st) return st;
  // An attempt ended without a result when a later attempt of the same trial exists, or when it is
  // the last one, has no result, and nobody runs the session now (unclaimed or no longer running).
  st = each_row(db,
                "SELECT " + select_list(*find_table("trial_attempts"), "a.", version) + ", "
                " CASE WHEN EXISTS (SELECT 1 FROM trial_attempts b WHERE b.session_id = a.session_id "
                "         AND b.position = a.position AND b.attempt > a.attempt) THEN 1 ELSE 0 END AS later, "
                " CASE WHEN EXISTS (SELECT 1 FROM planned_trials p JOIN trial_results r ON r.planned_trial_id = p.id "
                "         WHERE p.session_id = a.session_id AND p.position = a.position) THEN 1 ELSE 0 END AS result "
                "FROM trial_attempts a ORDER BY a.session_id, a.position, a.attempt",
                "reading the trial attempts", no_bind, by_name([&](const NamedColumns& c, const Stmt& q) {
                  auto it = at.find(c.int64(q, "session_id"));
                  if (it == at.end()) return;
                  SessionRecord& s = out[it->second];
                  const bool later = c.int64(q, "later") != 0, result = c.int64(q, "result") != 0;
                  const bool in_progress = s.status == SessionStatus::running && s.claim.has_value();
                  if (later || (!result && !in_progress))
                    s.interruptions.push_back(Interruption{static_cast<int>(c.int64(q, "position")),
                                                           static_cast<int>(c.int64(q, "attempt")),
                                                           c.text(q, "started_at")});
                }));
  return st;
}

}  // namespace

Result<std::vector<SessionRecord>> StudyReader::sessions() {
  return impl_->call([&]() -> Result<std::vector<SessionRecord>> {
    Db& db = *impl_->db;
    std::vector<SessionRecord> out;
    std::map<std::int64_t, std::size_t> at;
    Status st = each_row(
        db,
        "SELECT " + select_list(*find_table("sessions"), "s.", impl_->schema_version) +
            ", pa.participant AS participant, "
            "(SELECT count(*) FROM planned_trials p WHERE p.session_id = s.id) AS planned, "
            "(SELECT count(*) FROM planned_trials p JOIN trial_results r ON r.planned_trial_id = p.id "
            " WHERE p.session_id = s.id) AS recorded, " + withdrawn_sql(impl_->schema_version, "pa.id") +
            " AS withdrawn FROM sessions s JOIN participants pa ON pa.id = s.participant_id ORDER BY pa.enrollment_index",
        "reading the sessions", no_bind, by_name([&](const NamedColumns& c, const Stmt& q) {
          SessionRecord r;
          r.id = c.int64(q, "id");
          r.participant = c.text(q, "participant");
          r.study_id = c.int64(q, "study_id");
          r.software_version = c.text(q, "software_version");
          r.status = parse_status(c.text(q, "status"));
          r.started_at = c.text(q, "started_at");
          r.ended_at = c.opt_text(q, "ended_at");
          r.planned = static_cast<int>(c.int64(q, "planned"));
          r.recorded = static_cast<int>(c.int64(q, "recorded"));
          r.withdrawn = c.int64(q, "withdrawn") != 0;
          at[r.id] = out.size();
          out.push_back(std::move(r));
        }));
    if (!st) return st.error();
    if (auto d = read_session_details(db, impl_->schema_version, out, at); !d) return d.error();
    return out;
  });
}

Result<std::vector<PlannedRow>> StudyReader::planned(const std::string& participant) {
  return impl_->call([&]() -> Result<std::vector<PlannedRow>> {
    Db& db = *impl_->db;
    std::map<std::int64_t, std::vector<std::pair<std::string, std::string>>> levels;
    const std::string filter = participant.empty() ? "" : " AND pa.participant = :participant";
    Status st = each_row(db,
                         "SELECT l.planned_trial_id AS planned_trial_id, l.factor AS factor, l.level AS level "
                         "FROM planned_levels l "
                         "JOIN planned_trials p ON p.id = l.planned_trial_id JOIN sessions s ON s.id = p.session_id "
                         "JOIN participants pa ON pa.id = s.participant_id WHERE TRUE" + filter +
                             " ORDER BY l.planned_trial_id, l.factor_position",
                         "reading the planned levels",
                         bind_participant(participant),
                         by_name([&](const NamedColumns& c, const Stmt& q) {
                           levels[c.int64(q, "planned_trial_id")].emplace_back(c.text(q, "factor"), c.text(q, "level"));
                         }));
    if (!st) return st.error();
    std::vector<PlannedRow> out;
    st = each_row(db,
                  "SELECT " + select_list(*find_table("planned_trials"), "p.", impl_->schema_version) +
                      ", pa.participant AS participant FROM planned_trials p JOIN sessions s ON s.id = p.session_id "
                      "JOIN participants pa ON pa.id = s.participant_id WHERE TRUE" + filter +
                      " ORDER BY pa.enrollment_index, p.position",
                  "reading the planned trials", bind_participant(participant),
                  by_name([&](const NamedColumns& c, const Stmt& q) {
                    PlannedRow r;
                    r.session_id = c.int64(q, "session_id");
                    r.participant = c.text(q, "participant");
                    r.trial.position = static_cast<int>(c.int64(q, "position"));
                    r.trial.block = static_cast<int>(c.int64(q, "block"));
                    r.trial.task = c.text(q, "task");
                    r.trial.trial = static_cast<int>(c.int64(q, "trial"));
                    r.trial.seed = parse_seed(c.text(q, "seed"));
                    r.trial.method = c.text(q, "method");
                    r.trial.practice = c.int64(q, "practice") != 0;
                    r.trial.levels = std::move(levels[c.int64(q, "id")]);
                    out.push_back(std::move(r));
                  }));
    if (!st) return st.error();
    return out;
  });
}

Result<std::vector<Exclusion>> StudyReader::Impl::read_exclusions() {
  std::vector<Exclusion> out;
  if (schema_version < 2) return out;
  Status st = each_row(*db,
                       "SELECT " + select_list(*find_table("exclusions"), "x.", schema_version) +
                           ", pa.participant AS participant "
                           "FROM exclusions x JOIN participants pa ON pa.id = x.participant_id ORDER BY x.id",
                       "reading the exclusions", no_bind, by_name([&](const NamedColumns& c, const Stmt& q) {
                         out.push_back(Exclusion{c.int64(q, "id"), c.text(q, "participant"), c.opt_int32(q, "position"),
                                                 c.text(q, "action") == "exclude", c.text(q, "reason"),
                                                 c.text(q, "decided_by"), c.text(q, "decided_at")});
                       }));
  if (!st) return st.error();
  return out;
}

Result<std::vector<Exclusion>> StudyReader::exclusions() {
  return impl_->call([&] { return impl_->read_exclusions(); });
}

Result<std::vector<TrialRow>> StudyReader::trials(const std::string& participant) {
  return impl_->call([&]() -> Result<std::vector<TrialRow>> {
    auto revs = impl_->read_revisions();
    if (!revs) return revs.error();
    auto excl = impl_->read_exclusions();
    if (!excl) return excl.error();
    auto plan = planned(participant);  // borrowed readers nest: a read inside a read transaction is fine
    if (!plan) return plan.error();
    std::map<std::pair<std::int64_t, int>, const design::PlannedTrial*> by_position;
    for (const PlannedRow& p : *plan) by_position[{p.session_id, p.trial.position}] = &p.trial;
    std::map<std::int64_t, const Revision*> rev;
    for (const Revision& r : *revs) rev[r.study_id] = &r;
    // The latest decision per (participant, position); position 0 = the participant as a whole.
    std::map<std::pair<std::string, int>, const Exclusion*> decision;
    for (const Exclusion& x : *excl) decision[{x.participant, x.position.value_or(0)}] = &x;
    auto excluded = [&](const std::string& who, int position) -> std::optional<std::string> {
      for (int p : {0, position})
        if (auto it = decision.find({who, p}); it != decision.end() && it->second->exclude) return it->second->reason;
      return std::nullopt;
    };

    std::vector<TrialRow> out;
    const std::string filter = participant.empty() ? "" : " WHERE pa.participant = :participant";
    Status st = each_row(
        *impl_->db,
        "SELECT pa.participant AS participant, pa.enrollment_index AS enrollment_index, pa.order_row AS order_row, "
        "s.id AS session_id, s.status AS session_status, p.position AS position, s.study_id AS study_id, "
        "st.protocol_sha256 AS protocol_sha256, " + withdrawn_sql(impl_->schema_version, "pa.id") + " AS withdrawn, " +
        select_list(*find_table("trial_results"), "r.", impl_->schema_version) +
        " FROM trial_results r JOIN planned_trials p ON p.id = r.planned_trial_id "
        "JOIN sessions s ON s.id = p.session_id JOIN participants pa ON pa.id = s.participant_id "
        "JOIN studies st ON st.id = s.study_id" + filter + " ORDER BY pa.enrollment_index, p.position",
        "reading the trial results", bind_participant(participant),
        by_name([&](const NamedColumns& col, const Stmt& q) {
          TrialRow t = read_trial_row(col, q);
          const int position = static_cast<int>(col.int64(q, "position"));
          if (auto it = by_position.find({t.session_id, position}); it != by_position.end()) t.planned = *it->second;
          if (auto it = rev.find(t.study_id); it != rev.end()) t.design_revision = it->second->design_revision;
          t.excluded = excluded(t.participant, position);
          out.push_back(std::move(t));
        }));
    if (!st) return st.error();
    return out;
  });
}

Result<std::vector<QuestionnaireRecord>> StudyReader::questionnaire(const std::string& participant) {
  return impl_->call([&]() -> Result<std::vector<QuestionnaireRecord>> {
    std::vector<QuestionnaireRecord> out;
    const std::string filter = participant.empty() ? "" : " WHERE pa.participant = :participant";
    Status st = each_row(*impl_->db,
                         "SELECT pa.participant AS participant, " +
                             select_list(*find_table("questionnaire_answers"), "q.", impl_->schema_version) +
                             " FROM questionnaire_answers q JOIN sessions s ON s.id = q.session_id "
                             "JOIN participants pa ON pa.id = s.participant_id" + filter +
                             " ORDER BY pa.enrollment_index, q.item, q.scope",
                         "reading the questionnaire answers",
                         bind_participant(participant),
                         by_name([&](const NamedColumns& c, const Stmt& q) {
                           QuestionnaireRecord r;
                           r.participant = c.text(q, "participant");
                           r.session_id = c.int64(q, "session_id");
                           r.item = c.text(q, "item");
                           r.scope = c.text(q, "scope");
                           if (c.is_null(q, "value_number")) r.value = c.text(q, "value_text");
                           else r.value = c.real(q, "value_number");
                           r.answered_at = c.text(q, "answered_at");
                           out.push_back(std::move(r));
                         }));
    if (!st) return st.error();
    return out;
  });
}

Result<std::vector<Note>> StudyReader::notes() {
  return impl_->call([&]() -> Result<std::vector<Note>> {
    std::vector<Note> out;
    if (impl_->schema_version < 2) return out;
    Status st = each_row(*impl_->db,
                         "SELECT " + select_list(*find_table("notes"), "n.", impl_->schema_version) +
                             ", coalesce(pa.participant, '') AS participant "
                             "FROM notes n LEFT JOIN participants pa ON pa.id = n.participant_id ORDER BY n.id",
                         "reading the notes", no_bind, by_name([&](const NamedColumns& c, const Stmt& q) {
                           out.push_back(Note{c.int64(q, "id"), c.text(q, "participant"), c.opt_int32(q, "position"),
                                              c.text(q, "author"), c.text(q, "text"), c.text(q, "written_at")});
                         }));
    if (!st) return st.error();
    return out;
  });
}

Result<std::int64_t> StudyReader::Impl::result_id(const std::string& participant, int position) {
  auto st = Stmt::prepare(*db,
                          "SELECT p.id AS id FROM planned_trials p JOIN trial_results r ON r.planned_trial_id = p.id "
                          "JOIN sessions s ON s.id = p.session_id JOIN participants pa ON pa.id = s.participant_id "
                          "WHERE pa.participant = :participant AND p.position = :position",
                          "finding the trial");
  if (!st) return st.error();
  st->bind("participant", participant).bind("position", position);
  auto row = st->step("finding the trial");
  if (!row) return row.error();
  if (!*row)
    return Error{db->path(), 0, 0, "trial",
                 "participant \"" + participant + "\" has no recorded trial at position " + std::to_string(position),
                 ErrorKind::not_found};
  return st->int64("id");
}

Result<std::vector<CameraPose>> StudyReader::poses(const std::string& participant, int position) {
  return impl_->call([&]() -> Result<std::vector<CameraPose>> {
    auto id = impl_->result_id(participant, position);
    if (!id) return id.error();
    std::vector<CameraPose> out;
    Status st = each_row(*impl_->db,
                         "SELECT " + select_list(*find_table("camera_poses"), "", impl_->schema_version) +
                             " FROM camera_poses WHERE trial_id = :trial_id ORDER BY frame",
                         "reading the camera poses", [&](Stmt& s) { s.bind("trial_id", *id); },
                         by_name([&](const NamedColumns& c, const Stmt& q) {
                           out.push_back(CameraPose{c.real(q, "t_s"), c.real(q, "x"), c.real(q, "y"), c.real(q, "z"),
                                                    c.real(q, "yaw"), c.real(q, "pitch")});
                         }));
    if (!st) return st.error();
    return out;
  });
}

Result<std::vector<InputEvent>> StudyReader::events(const std::string& participant, int position) {
  return impl_->call([&]() -> Result<std::vector<InputEvent>> {
    auto id = impl_->result_id(participant, position);
    if (!id) return id.error();
    std::vector<InputEvent> out;
    Status st = each_row(*impl_->db,
                         "SELECT " + select_list(*find_table("input_events"), "", impl_->schema_version) +
                             " FROM input_events WHERE trial_id = :trial_id ORDER BY seq",
                         "reading the input events", [&](Stmt& s) { s.bind("trial_id", *id); },
                         by_name([&](const NamedColumns& c, const Stmt& q) {
                           out.push_back(InputEvent{c.real(q, "t_s"), parse_kind(c.text(q, "kind")), c.text(q, "detail"),
                                                    c.real(q, "x"), c.real(q, "y")});
                         }));
    if (!st) return st.error();
    return out;
  });
}

Result<std::string> StudyReader::integrity_check() {
  return impl_->call([&]() { return impl_->db->conn().integrity_check(); });
}

}  // namespace dtlab::store

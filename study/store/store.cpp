// Opening a study database, its protocol revisions and the participant
// ledger (docs/store.md, invariants 1-4). open() inspects a database read-only
// (one snapshot) before touching it, so a foreign or newer one is never
// modified, and inspects it again inside its first write transaction, so
// processes creating one database together all see it whole; every write is
// one transaction holding the study's write lock (SQLite: BEGIN IMMEDIATE;
// PostgreSQL: an advisory lock), which makes enrollment atomic across
// processes and stations.
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cctype>

#include "study/common/version.h"
#include "study/store/detail/columns.h"
#include "study/store/detail/file_check.h"
#include "study/store/detail/schema.h"
#include "study/store/detail/store_impl.h"
#include "study/store/detail/time.h"
#include "study/store/read.h"
#include "study/store/store.h"

namespace dtlab::store {
namespace {

using detail::Db;
using detail::Stmt;

bool is_lower_hex(const std::string& s, std::size_t n) {
  return s.size() == n && std::all_of(s.begin(), s.end(), [](char c) {
           return (c >= '0' && c <= '9') || (c >= 'a' && c <= 'f');
         });
}

std::string lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

// StudyInfo is the caller's data: check it before it can reach the file.
Status validate_study(const std::string& path, const StudyInfo& s) {
  auto bad = [&](const char* field, std::string msg) { return Error{path, 0, 0, field, std::move(msg)}; };
  if (s.protocol_id.empty()) return bad("study.protocol_id", "is empty; expected the protocol's id");
  if (!is_lower_hex(s.protocol_sha256, 64))
    return bad("study.protocol_sha256", "\"" + s.protocol_sha256 + "\" is not 64 lowercase hex digits");
  if (!s.design_sha256.empty() && !is_lower_hex(s.design_sha256, 64))
    return bad("study.design_sha256", "\"" + s.design_sha256 + "\" is not 64 lowercase hex digits (or empty)");
  if (s.order_rows < 1) return bad("study.order_rows", std::to_string(s.order_rows) + " rows; expected >= 1");
  std::vector<std::string> seen;
  for (const std::string& f : s.factors) {
    if (f.empty()) return bad("study.factors", "a factor name is empty");
    const std::string lf = lower(f);
    for (const auto* fixed : {&detail::fixed_trial_columns_before_factors(), &detail::fixed_trial_columns_after_factors()})
      for (const std::string& c : *fixed)
        if (lf == c) return bad("study.factors", "factor \"" + f + "\" has the name of a fixed export column; rename it");
    if (lf.rfind(detail::kDemographicPrefix, 0) == 0)
      return bad("study.factors", "factor \"" + f + "\" starts with \"" + detail::kDemographicPrefix +
                                      "\", which names the export's demographic columns; rename it");
    if (std::find(seen.begin(), seen.end(), lf) != seen.end())
      return bad("study.factors", "factor \"" + f + "\" appears twice (names are case-insensitive)");
    seen.push_back(lf);
  }
  return {};
}

Status validate_participant_id(const std::string& path, const std::string& id) {
  auto bad = [&](std::string msg) { return Error{path, 0, 0, "participant", std::move(msg)}; };
  if (id.empty()) return bad("the participant ID is empty");
  if (id.size() > kMaxParticipantId)
    return bad("\"" + id + "\" is " + std::to_string(id.size()) + " bytes long; a participant ID has at most " +
               std::to_string(kMaxParticipantId) + " (bytes of UTF-8: characters, for plain ASCII)");
  for (unsigned char c : id)
    if (c < 0x20 || c == 0x7f) return bad("\"" + id + "\" contains a control character");
  if (id.front() == ' ' || id.back() == ' ') return bad("\"" + id + "\" starts or ends with a space");
  return {};
}

// Inserts the study row (and its factors) and makes it current.
Result<std::int64_t> insert_study(Db& db, const StudyInfo& s) {
  const char* what = "recording the protocol";
  auto id_or = detail::next_id(db, "studies");
  if (!id_or) return id_or.error();
  const std::int64_t id = *id_or;
  auto now = db.now_iso();
  if (!now) return now.error();
  detail::RowInsert study("studies");
  study.set("id", id).set("protocol_id", s.protocol_id).set("protocol_text", s.protocol_text);
  study.set("protocol_sha256", s.protocol_sha256).set("software_version", s.software_version);
  study.set("order_rows", s.order_rows).set("created_at", *now);
  if (auto r = study.run(db, what); !r) return r.error();
  for (std::size_t i = 0; i < s.factors.size(); ++i) {
    detail::RowInsert f("study_factors");
    f.set("study_id", id).set("position", static_cast<int>(i + 1)).set("name", s.factors[i]);
    if (auto r = f.run(db, what); !r) return r.error();
  }
  if (!s.design_sha256.empty()) {
    detail::RowInsert d("study_designs");
    d.set("study_id", id).set("design_sha256", s.design_sha256);
    if (auto r = d.run(db, what); !r) return r.error();
  }
  if (auto r = detail::create_trial_table_view(db); !r) return r.error();
  return id;
}

// Rows recorded before schema v2 get their design hash once a caller can compute it.
Status hash_legacy_designs(Db& db, const OpenOptions& options) {
  if (!options.design_hash_of) return {};
  const char* what = "recording design hashes";
  auto st = Stmt::prepare(db,
                          "SELECT s.id AS id, s.protocol_text AS protocol_text FROM studies s WHERE NOT EXISTS "
                          "(SELECT 1 FROM study_designs d WHERE d.study_id = s.id) ORDER BY s.id",
                          what);
  if (!st) return st.error();
  std::vector<std::pair<std::int64_t, std::string>> missing;
  for (;;) {
    auto row = st->step(what);
    if (!row) return row.error();
    if (!*row) break;
    if (auto h = options.design_hash_of(st->text("protocol_text")); h && is_lower_hex(*h, 64))
      missing.emplace_back(st->int64("id"), *h);
  }
  if (missing.empty()) return {};
  for (const auto& [id, hash] : missing) {
    detail::RowInsert d("study_designs");
    d.set("study_id", id).set("design_sha256", hash);
    if (auto r = d.run(db, what); !r) return r;
  }
  return detail::create_trial_table_view(db);
}

// Reads the current (latest) study and decides whether `s` may use the file:
// the same text uses its row; the same design with another text is a new
// revision, recorded without asking; another design needs allow_protocol_change.
Result<std::int64_t> check_study(Db& db, const StudyInfo& s, const OpenOptions& options) {
  const char* what = "reading the protocol record";
  auto st = Stmt::prepare(db,
                          "SELECT s.id AS id, s.protocol_id AS protocol_id, s.protocol_sha256 AS protocol_sha256, "
                          "s.order_rows AS order_rows, coalesce(d.design_sha256, '') AS design_sha256 FROM studies s "
                          "LEFT JOIN study_designs d ON d.study_id = s.id ORDER BY s.id DESC LIMIT 1",
                          what);
  if (!st) return st.error();
  auto row = st->step(what);
  if (!row) return row.error();
  if (!*row) return insert_study(db, s);
  const std::int64_t id = st->int64("id");
  const std::string old_id = st->text("protocol_id"), old_hash = st->text("protocol_sha256");
  const std::string old_design = st->text("design_sha256");
  const auto old_rows = st->int64("order_rows");
  const bool same_text = old_hash == s.protocol_sha256;
  const bool same_design = same_text || (!s.design_sha256.empty() && s.design_sha256 == old_design);
  if (same_design && old_rows != s.order_rows)
    return Error{db.path(), 0, 0, "study.order_rows",
                 "the database records " + std::to_string(old_rows) + " order rows for this design, the caller " +
                     std::to_string(s.order_rows) + "; the design code changed, the protocol did not",
                 ErrorKind::internal};
  if (same_text) return id;
  if (same_design) return insert_study(db, s);  // a revision of the wording: sessions continue, analyses pool
  if (!options.allow_protocol_change)
    return Error{db.path(), 0, 0, "studies.protocol_sha256",
                 "the database belongs to protocol \"" + old_id + "\" with SHA-256 " + old_hash +
                     (old_design.empty() ? std::string() : " (design " + old_design.substr(0, 12) + ")") +
                     ", and protocol \"" + s.protocol_id + "\" with SHA-256 " + s.protocol_sha256 +
                     (s.design_sha256.empty() ? std::string() : " (design " + s.design_sha256.substr(0, 12) + ")") +
                     " changes what runs (its design, not only its wording); use the protocol it was created with, a "
                     "new database, or allow a protocol change (--allow-protocol-change) to record it as a new design "
                     "revision, which the analysis reports separately",
                 ErrorKind::conflict};
  return insert_study(db, s);
}

// The current (latest) study row as a StudyInfo, for open_existing().
Result<std::pair<std::int64_t, StudyInfo>> current_study(Db& db) {
  const char* what = "reading the protocol record";
  auto st = Stmt::prepare(db,
                          "SELECT s.id AS id, s.protocol_id AS protocol_id, s.protocol_text AS protocol_text, "
                          "s.protocol_sha256 AS protocol_sha256, s.order_rows AS order_rows, "
                          "coalesce(d.design_sha256, '') AS design_sha256 FROM studies s "
                          "LEFT JOIN study_designs d ON d.study_id = s.id "
                          "ORDER BY s.id DESC LIMIT 1",
                          what);
  if (!st) return st.error();
  auto row = st->step(what);
  if (!row) return row.error();
  if (!*row)
    return Error{db.path(), 0, 0, "studies", "the database records no protocol (no study was ever started)",
                 ErrorKind::not_found};
  StudyInfo info;
  const std::int64_t id = st->int64("id");
  info.protocol_id = st->text("protocol_id");
  info.protocol_text = st->text("protocol_text");
  info.protocol_sha256 = st->text("protocol_sha256");
  info.order_rows = static_cast<int>(st->int64("order_rows"));
  info.design_sha256 = st->text("design_sha256");
  info.software_version = std::string(version_string());
  auto f = Stmt::prepare(db, "SELECT name AS name FROM study_factors WHERE study_id = :study_id ORDER BY position",
                         what);
  if (!f) return f.error();
  f->bind("study_id", id);
  for (;;) {
    auto r = f->step(what);
    if (!r) return r.error();
    if (!*r) break;
    info.factors.push_back(f->text("name"));
  }
  return std::make_pair(id, std::move(info));
}

}  // namespace

Result<Enrollment> read_enrollment(Db& db, const std::string& participant_id) {
  const char* what = "reading the participant ledger";
  auto st = Stmt::prepare(db,
                          "SELECT p.enrollment_index AS enrollment_index, p.order_row AS order_row, "
                          "CASE WHEN p.released_at IS NULL THEN 0 ELSE 1 END AS released, "
                          "CASE WHEN EXISTS (SELECT 1 FROM withdrawals w WHERE w.participant_id = p.id) THEN 1 ELSE 0 END "
                          "AS withdrawn FROM participants p WHERE p.participant = :participant",
                          what);
  if (!st) return st.error();
  st->bind("participant", participant_id);
  auto row = st->step(what);
  if (!row) return row.error();
  if (!*row)
    return Error{db.path(), 0, 0, "participant", "unknown participant \"" + participant_id + "\"", ErrorKind::not_found};
  Enrollment e;
  e.participant_id = participant_id;
  e.index = static_cast<int>(st->int64("enrollment_index"));
  e.order_row = static_cast<int>(st->int64("order_row"));
  e.released = st->int64("released") != 0;
  e.withdrawn = st->int64("withdrawn") != 0;
  return e;
}

Error withdrawn_error(Db& db, const std::string& participant_id) {
  std::string when;
  auto st = Stmt::prepare(db,
                          "SELECT w.withdrawn_at AS withdrawn_at, w.reason AS reason FROM withdrawals w "
                          "JOIN participants p ON p.id = w.participant_id WHERE p.participant = :participant",
                          "reading the withdrawal");
  if (st) {
    st->bind("participant", participant_id);
    if (auto row = st->step("reading the withdrawal"); row && *row)
      when = " at " + st->text("withdrawn_at") + " (" + st->text("reason") + ")";
  }
  return Error{db.path(), 0, 0, "participant",
               "participant \"" + participant_id + "\" withdrew their consent" + when +
                   "; they never run again and are not enrolled again (a new person gets a new id)",
               ErrorKind::conflict};
}

Result<std::string> demographics_json(const std::string& path, const Demographics& demographics) {
  nlohmann::ordered_json demo = nlohmann::ordered_json::object();  // kept in the order given (the protocol's)
  for (const auto& [k, v] : demographics) {
    if (k.empty()) return Error{path, 0, 0, "demographics", "a demographic field name is empty"};
    if (demo.contains(k)) return Error{path, 0, 0, "demographics." + k, "appears twice"};
    demo[k] = v;
  }
  // Invalid UTF-8 in a demographic value becomes U+FFFD instead of throwing.
  return demo.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
}

Status check_participant_id(const std::string& id) { return validate_participant_id("", id); }

const char* to_string(SessionStatus s) {
  switch (s) {
    case SessionStatus::running: return "running";
    case SessionStatus::finished: return "finished";
    case SessionStatus::abandoned: return "abandoned";
  }
  return "?";
}

Store::Store(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
Store::Store(Store&&) noexcept = default;
Store& Store::operator=(Store&&) noexcept = default;
Store::~Store() = default;
const std::string& Store::path() const { return impl_->path; }

// Opens the connection and makes it a study database connection: the database is looked at
// first (one read snapshot, nothing written), then configured for writing. `create`: a missing
// file (or PostgreSQL schema) becomes a new database; otherwise it must be a dtlab database.
Result<std::unique_ptr<Store::Impl>> connect(const std::string& where, const OpenOptions& options, bool create) {
  auto opened = detail::open_connection(where, create ? detail::Access::create : detail::Access::write,
                                        options.busy_timeout_ms);
  if (!opened) return opened.error();
  Db db(std::move(*opened));
  const std::string name = db.path();

  // 1. Look before touching: a foreign or newer database is refused unmodified.
  auto state = detail::inspect(db);
  if (!state) return state.error();
  if (auto s = detail::check_dtlab(db, *state, create); !s) return s.error();
  if (auto s = detail::check_tables(db, std::max(state->user_version, state->migrations)); !s) return s.error();

  // 2. Connection settings (docs/store.md, "Connection settings").
  if (auto s = db.conn().configure_for_writing(options.busy_timeout_ms); !s) return s.error();
  return std::make_unique<Store::Impl>(std::move(db), name, options);
}

// Inside the first write transaction: the file is looked at again (another process may have
// created it since step 1), then its schema is brought to kSchemaVersion.
Status prepare_schema(Store::Impl& m, const std::string& software_version, bool allow_empty) {
  auto state = detail::inspect(m.db, /*in_transaction=*/true);
  if (!state) return state.error();
  if (auto s = detail::check_dtlab(m.db, *state, allow_empty); !s) return s;
  auto version = detail::applied_schema_version(m.db);
  if (!version) return version.error();
  if (*version < kSchemaVersion)
    if (auto s = detail::migrate(m.db, *version, software_version); !s) return s;
  return hash_legacy_designs(m.db, m.options);
}

Result<Store> Store::open(const std::string& path, const StudyInfo& study, OpenOptions options) {
  if (auto s = validate_study(path, study); !s) return s.error();
  auto impl = connect(path, options, /*create=*/true);
  if (!impl) return impl.error();
  Impl& m = **impl;
  m.study = study;
  // 3. Create or check the schema and the protocol in one write transaction,
  //    so two processes creating the same file cannot both create it.
  Status st = m.write("opening the study database", [&]() -> Status {
    if (auto s = prepare_schema(m, study.software_version, /*allow_empty=*/true); !s) return s;
    auto id = check_study(m.db, study, m.options);
    if (!id) return id.error();
    m.study_id = *id;
    return {};
  });
  if (!st) return st.error();
  return Store(std::move(*impl));
}

Result<Store> Store::open_existing(const std::string& path, OpenOptions options) {
  auto impl = connect(path, options, /*create=*/false);
  if (!impl) return impl.error();
  Impl& m = **impl;
  Status st = m.write("opening the study database", [&]() -> Status {
    if (auto s = prepare_schema(m, std::string(version_string()), /*allow_empty=*/false); !s) return s;
    auto cur = current_study(m.db);
    if (!cur) return cur.error();
    m.study_id = cur->first;
    m.study = std::move(cur->second);
    return {};
  });
  if (!st) return st.error();
  return Store(std::move(*impl));
}

StudyReader& Store::read() { return impl_->reader; }

Result<Enrollment> Store::Impl::insert_enrollment(const std::string& participant_id, const std::string& demo_text,
                                                  const std::string& now) {
  const char* what = "assigning an order row";
  auto id = detail::next_id(db, "participants");
  if (!id) return id.error();
  auto next = db.query_int("SELECT coalesce(max(enrollment_index) + 1, 0) AS n FROM participants", what);
  if (!next) return next.error();
  // Rule (docs/store.md, invariant 4): fewest active participants, ties to the lowest row.
  std::vector<std::int64_t> fill(static_cast<std::size_t>(study.order_rows), 0);
  auto f = Stmt::prepare(db, "SELECT order_row AS order_row, count(*) AS n FROM participants WHERE released_at IS NULL "
                         "GROUP BY order_row",
                         what);
  if (!f) return f.error();
  for (;;) {
    auto row = f->step(what);
    if (!row) return row.error();
    if (!*row) break;
    const auto r = f->int64("order_row");
    if (r >= 0 && r < study.order_rows) fill[static_cast<std::size_t>(r)] = f->int64("n");
  }
  const auto row = std::min_element(fill.begin(), fill.end()) - fill.begin();
  // A demographic field nobody had before is a new column of trial_table (and of the export).
  bool new_field = false;
  if (const auto given = nlohmann::ordered_json::parse(demo_text, nullptr, false); given.is_object() && !given.empty()) {
    auto known = detail::demographic_fields(db);
    if (!known) return known.error();
    for (const auto& [k, v] : given.items())
      new_field = new_field || std::find(known->begin(), known->end(), k) == known->end();
  }
  detail::RowInsert ins("participants");
  ins.set("id", *id).set("participant", participant_id).set("enrollment_index", next->value_or(0));
  ins.set("order_row", static_cast<std::int64_t>(row)).set("study_id", study_id).set("demographics", demo_text);
  ins.set("enrolled_at", now);
  if (auto s = ins.run(db, "enrolling"); !s) return s.error();
  if (new_field)
    if (auto s = detail::create_trial_table_view(db); !s) return s.error();
  Enrollment e;
  e.participant_id = participant_id;
  e.index = static_cast<int>(next->value_or(0));
  e.order_row = static_cast<int>(row);
  e.newly_enrolled = true;
  return e;
}

Result<Enrollment> Store::enroll(const std::string& participant_id, const Demographics& demographics) {
  Impl& m = *impl_;
  if (auto s = validate_participant_id(m.path, participant_id); !s) return s.error();
  auto demo = demographics_json(m.path, demographics);
  if (!demo) return demo.error();
  Enrollment out;
  Status st = m.write("enrolling participant \"" + participant_id + "\"", [&]() -> Status {
    auto existing = read_enrollment(m.db, participant_id);
    if (existing) {
      if (existing->withdrawn) return withdrawn_error(m.db, participant_id);
      if (existing->released)
        return m.invalid("participant",
                         "participant \"" + participant_id + "\" was released (abandoned session); enroll them under a new id",
                         ErrorKind::conflict);
      out = *existing;
      return {};
    }
    if (existing.error().kind != ErrorKind::not_found) return existing.error();
    auto now = m.db.now_iso();
    if (!now) return now.error();
    auto e = m.insert_enrollment(participant_id, *demo, *now);
    if (!e) return e.error();
    out = *e;
    return {};
  });
  if (!st) return st.error();
  return out;
}

Result<Enrollment> Store::lookup(const std::string& participant_id) {
  if (impl_->broken) return impl_->broken_error;
  return read_enrollment(impl_->db, participant_id);
}

Status Store::release(const std::string& participant_id) {
  Impl& m = *impl_;
  return m.write("releasing participant \"" + participant_id + "\"", [&]() -> Status {
    auto e = read_enrollment(m.db, participant_id);
    if (!e) return e.error();
    if (e->released) return {};  // releasing twice is harmless
    auto q = Stmt::prepare(m.db,
                           "SELECT s.status AS status, s.id AS id FROM sessions s JOIN participants p "
                           "ON p.id = s.participant_id WHERE p.participant = :participant",
                           "reading the session");
    if (!q) return q.error();
    q->bind("participant", participant_id);
    auto has = q->step("reading the session");
    if (!has) return has.error();
    const std::string status = *has ? q->text("status") : std::string();
    const std::int64_t session_id = *has ? q->int64("id") : 0;
    if (status == "finished")
      return m.invalid("participant",
                       "participant \"" + participant_id + "\" finished their session; a finished session cannot be released",
                       ErrorKind::conflict);
    if (status == "running") {
      // A session another live process runs is not abandoned under it (busy); a dead one's claim is taken.
      if (auto c = m.take_claim(session_id, participant_id, /*take_over=*/false, nullptr); !c) return c;
      if (auto c = m.drop_claim(session_id); !c) return c;
    }
    auto clock = m.db.now_iso();
    if (!clock) return clock.error();
    const std::string now = *clock;
    auto up = Stmt::prepare(m.db,
                            "UPDATE sessions SET status = 'abandoned', ended_at = :ended_at WHERE status = 'running' "
                            "AND participant_id = (SELECT id FROM participants WHERE participant = :participant)",
                            "abandoning the session");
    if (!up) return up.error();
    up->bind("ended_at", now).bind("participant", participant_id);
    if (auto s = up->run("abandoning the session"); !s) return s;
    auto rel = Stmt::prepare(m.db, "UPDATE participants SET released_at = :released_at WHERE participant = :participant",
                             "releasing the order row");
    if (!rel) return rel.error();
    rel->bind("released_at", now).bind("participant", participant_id);
    return rel->run("releasing the order row");
  });
}

}  // namespace dtlab::store

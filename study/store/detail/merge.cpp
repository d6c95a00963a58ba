// Merging a study into a database that holds it already (copy.h; docs/store.md,
// "Copying and merging"): a station's offline file into the lab's server.
// What may change and what may not: a participant's enrollment index, order
// row and trial seeds are their plan (seeds derive from the index,
// design/seeds.h), so a participant with a stored session keeps their ledger
// slot, and the merge is refused if DST gave that slot to someone else; a
// participant enrolled but never started has no plan yet and takes DST's next
// free slot and the order row DST's rule gives. A participant in both must
// hold the same data in both (DST may lack the session, or have more);
// decisions are merged when one side's list continues the other's (consent,
// withdrawal and screens likewise: merge_answers.cpp). Every check runs
// before the first row is written; the caller's one transaction makes the
// merge whole or nothing. Never changes a row DST holds, except by the
// effects of a withdrawal SRC adds (the row released, a running session
// abandoned), as withdraw() would.
#include <algorithm>
#include <map>
#include <tuple>

#include "study/store/detail/columns.h"
#include "study/store/detail/merge.h"
#include "study/store/detail/schema.h"

namespace dtlab::store::detail {
namespace merging {

Error refuse(const Db& dst, const std::string& field, const std::string& why) {
  return Error{dst.path(), 0, 0, field, why + "; the merge is refused and nothing was written", ErrorKind::conflict};
}

namespace {

Result<std::vector<StudyRow>> read_studies(Db& db, bool v2, const CopyOptions& options) {
  std::vector<StudyRow> out;
  Status st = each_row(db, "SELECT " + columns_of("studies", "") + " FROM studies ORDER BY id", {},
                       [&](Row& r) -> Status {
                         out.push_back(StudyRow{std::move(r), {}, ""});
                         return {};
                       });
  if (!st) return st.error();
  for (StudyRow& s : out) {
    st = each_row(db, "SELECT name AS name FROM study_factors WHERE study_id = :study_id ORDER BY position",
                  {{"study_id", s.id()}}, [&](Row& r) -> Status {
                    s.factors.push_back(text(r["name"]));
                    return {};
                  });
    if (!st) return st.error();
    if (v2) {
      auto d = db.query_text("SELECT design_sha256 AS n FROM study_designs WHERE study_id = :study_id",
                             "reading the designs", {{"study_id", s.id()}});
      if (!d) return d.error();
      if (*d) s.design = **d;
    }
    if (s.design.empty() && options.design_hash_of)
      s.design = options.design_hash_of(text(s.row["protocol_text"])).value_or("");
  }
  return out;
}

Result<std::vector<Person>> read_ledger(Db& db) {
  std::vector<Person> out;
  Status st = each_row(db,
                       "SELECT " + columns_of("participants", "p") + ", s.id AS session_of_participant "
                       "FROM participants p LEFT JOIN sessions s ON s.participant_id = p.id "
                       "ORDER BY p.enrollment_index",
                       {}, [&](Row& r) -> Status {
                         Person p;
                         if (!std::holds_alternative<std::monostate>(r["session_of_participant"]))
                           p.session = num(r["session_of_participant"]);
                         p.row = r.without("session_of_participant");
                         out.push_back(std::move(p));
                         return {};
                       });
  if (!st) return st.error();
  return out;
}

}  // namespace

std::string columns_of(const char* table, const std::string& alias, int version) {
  return copied_table(table).select_list(version, alias);
}

namespace {

// The rows of a session's tables, keyed by the session's own ids: selects per table, reading a
// database of schema `version`.
struct SessionQueries {
  std::string session, planned, levels, results, events, poses, resumes, answers, pauses, attempts, displays, screens;
};
SessionQueries session_queries(int version) {
  return {
      "SELECT " + columns_of("sessions", "s") + " FROM sessions s WHERE s.id = :session",
      "SELECT " + columns_of("planned_trials", "p") +
          " FROM planned_trials p WHERE p.session_id = :session ORDER BY p.position",
      "SELECT " + columns_of("planned_levels", "l") +
          " FROM planned_levels l JOIN planned_trials p ON p.id = l.planned_trial_id WHERE p.session_id = :session "
          "ORDER BY p.position, l.factor_position",
      "SELECT " + columns_of("trial_results", "r", version) +
          " FROM trial_results r JOIN planned_trials p ON p.id = r.planned_trial_id WHERE p.session_id = :session "
          "ORDER BY p.position",
      "SELECT " + columns_of("input_events", "e") +
          " FROM input_events e JOIN planned_trials p ON p.id = e.trial_id WHERE p.session_id = :session "
          "ORDER BY p.position, e.seq",
      "SELECT " + columns_of("camera_poses", "c") +
          " FROM camera_poses c JOIN planned_trials p ON p.id = c.trial_id WHERE p.session_id = :session "
          "ORDER BY p.position, c.frame",
      "SELECT " + columns_of("session_resumes", "x") +
          " FROM session_resumes x WHERE x.session_id = :session "
          "ORDER BY x.resumed_at, x.next_position IS NULL, x.next_position",
      "SELECT " + columns_of("questionnaire_answers", "q") +
          " FROM questionnaire_answers q WHERE q.session_id = :session ORDER BY q.item, q.scope",
      "SELECT " + columns_of("session_pauses", "x") +
          " FROM session_pauses x WHERE x.session_id = :session ORDER BY x.paused_at, x.resumed_at",
      "SELECT " + columns_of("trial_attempts", "a") +
          " FROM trial_attempts a WHERE a.session_id = :session ORDER BY a.position, a.attempt",
      "SELECT " + columns_of("session_displays", "x") +
          " FROM session_displays x WHERE x.session_id = :session ORDER BY " +
          kDisplayOrder,
      "SELECT " + columns_of("screens", "x") + " FROM screens x WHERE x.session_id = :session ORDER BY x.seq",
  };
}

// Everything recorded in a session that schema `version` records, with its ids replaced (the
// session's and planned trials' by positions, the study's by its protocol hash): two databases
// hold the same session exactly when these are equal at SRC's version (what an older SRC could
// not record is not compared; the screen log is merged on its own). A session abandoned at
// `withdrawn_at` (by the participant's withdrawal) reads as running, so a session withdrawn on
// one side equals the same session still running on the other. Also counts the recorded trials.
Result<std::vector<std::string>> session_record(Db& db, std::int64_t session, int version,
                                                const std::map<std::int64_t, std::string>& sha,
                                                const std::string& withdrawn_at, int* recorded) {
  std::vector<std::string> out;
  std::map<std::int64_t, std::int64_t> position;  // planned trial id -> position
  const SessionQueries q = session_queries(version);
  // A row of a trial's table (`id_column` its planned trial) or of the session's (its session).
  auto add = [&](const std::string& sql, const char* tag, const char* id_column, bool by_trial) -> Status {
    return each_row(db, sql, {{"session", session}}, [&](Row& r) -> Status {
      if (by_trial) r[id_column] = position[num(r[id_column])];
      else r[id_column] = std::int64_t{0};
      out.push_back(tag + canonical(r));
      return {};
    });
  };
  Status st = each_row(db, q.session, {{"session", session}}, [&](Row& r) -> Status {
    r["id"] = r["participant_id"] = std::int64_t{0};
    if (!withdrawn_at.empty() && text(r["status"]) == "abandoned" && text(r["ended_at"]) == withdrawn_at) {
      r["status"] = std::string("running");
      r["ended_at"] = std::monostate{};
    }
    const std::int64_t study = num(r["study_id"]);
    r["study_id"] = sha.count(study) ? sha.at(study) : std::string("?");
    out.push_back("S" + canonical(r));
    return {};
  });
  if (!st) return st.error();
  st = each_row(db, q.planned, {{"session", session}}, [&](Row& r) -> Status {
    position[num(r["id"])] = num(r["position"]);
    r["id"] = r["session_id"] = std::int64_t{0};
    out.push_back("P" + canonical(r));
    return {};
  });
  if (!st) return st.error();
  const std::size_t before = out.size();
  for (const auto& [sql, tag, column, by_trial] :
       std::vector<std::tuple<std::string, const char*, const char*, bool>>{
           {q.levels, "L", "planned_trial_id", true},
           {q.results, "R", "planned_trial_id", true},
           {q.events, "E", "trial_id", true},
           {q.poses, "C", "trial_id", true},
           {q.resumes, "X", "session_id", false},
           {q.answers, "Q", "session_id", false}}) {
    if (auto s = add(sql, tag, column, by_trial); !s) return s.error();
  }
  if (version >= 2)
    for (const auto& [sql, tag] : std::vector<std::pair<std::string, const char*>>{{q.pauses, "U"}, {q.attempts, "A"}})
      if (auto s = add(sql, tag, "session_id", false); !s) return s.error();
  if (version >= 3)
    if (auto s = add(q.displays, "D", "session_id", false); !s) return s.error();
  *recorded = static_cast<int>(std::count_if(out.begin() + static_cast<std::ptrdiff_t>(before), out.end(),
                                             [](const std::string& s) { return s[0] == 'R'; }));
  return out;
}

// The decisions (or notes) about one participant (nullopt: about the study), without ids.
Result<std::vector<Row>> decisions_about(Db& db, const char* table, std::optional<std::int64_t> participant) {
  std::vector<Row> out;
  const std::string where = participant ? "participant_id = :participant_id" : "participant_id IS NULL";
  const std::string sql = "SELECT " + columns_of(table, std::string(table)) + " FROM " + table + " WHERE " + where +
                          " ORDER BY id";
  Status st = each_row(db, sql, participant ? Binds{{"participant_id", *participant}} : Binds{}, [&](Row& r) -> Status {
    out.push_back(std::move(r));
    return {};
  });
  if (!st) return st.error();
  return out;
}

}  // namespace

Status Merger::run() {
  if (auto s = map_studies(); !s) return s;
  if (auto s = plan_ledger(); !s) return s;
  if (auto s = write_participants(); !s) return s;
  return create_trial_table_view(dst_);
}

std::string Merger::src_name(std::optional<std::int64_t> pid) const {
  for (const Person& p : src_ledger_)
    if (pid && p.id() == *pid) return p.name();
  return "";
}

Result<std::int64_t> Merger::next(const char* table) {
  auto it = next_ids_.find(table);
  if (it == next_ids_.end()) {
    auto id = next_id(dst_, table);
    if (!id) return id.error();
    it = next_ids_.emplace(table, *id).first;
  }
  return it->second++;
}

Status Merger::map_studies() {
  auto s = read_studies(src_, v2_, options_);
  if (!s) return s.error();
  auto d = read_studies(dst_, true, options_);
  if (!d) return d.error();
  src_studies_ = std::move(*s);
  dst_studies_ = std::move(*d);
  if (dst_studies_.empty()) return refuse(dst_, "studies", "DST records no protocol");
  const StudyRow& current = dst_studies_.back();
  for (const StudyRow& r : dst_studies_) dst_sha_[r.id()] = r.sha();
  for (const StudyRow& r : src_studies_) {
    src_sha_[r.id()] = r.sha();
    auto same = std::find_if(dst_studies_.begin(), dst_studies_.end(), [&](const StudyRow& x) { return x.sha() == r.sha(); });
    if (same != dst_studies_.end()) {
      if (same->order_rows() != r.order_rows() || same->factors != r.factors)
        return refuse(dst_, "studies", "protocol " + r.sha() + " has other order rows or factors in SRC than in DST");
      study_[r.id()] = same->id();
      continue;
    }
    if (r.design.empty() || r.design != current.design)
      return refuse(dst_, "studies.design_sha256",
                    "SRC was recorded under protocol " + r.sha().substr(0, 12) + " (design " +
                        (r.design.empty() ? std::string("unknown") : r.design.substr(0, 12)) +
                        "), DST runs design " + (current.design.empty() ? std::string("unknown") : current.design.substr(0, 12)) +
                        ": a study of another design cannot be merged into it");
    append_.push_back(r);
  }
  return {};
}

Status Merger::plan_ledger() {
  auto s = read_ledger(src_);
  if (!s) return s.error();
  auto d = read_ledger(dst_);
  if (!d) return d.error();
  src_ledger_ = std::move(*s);
  dst_ledger_ = std::move(*d);
  std::map<std::string, const Person*> dst_by_name;
  Slots used;
  for (const Person& q : dst_ledger_) {
    dst_by_name[q.name()] = &q;
    used[q.index()] = &q;
  }
  std::vector<const Person*> renumber;
  for (const Person& p : src_ledger_) {
    if (auto it = dst_by_name.find(p.name()); it != dst_by_name.end()) {
      if (auto st = plan_present(p, *it->second); !st) return st;
      continue;
    }
    if (!p.session) {  // no plan yet: takes DST's next free slot below
      renumber.push_back(&p);
      continue;
    }
    if (auto it = used.find(p.index()); it != used.end())
      return refuse(dst_, "participants.enrollment_index",
                    "participant \"" + p.name() + "\" ran the plan of ledger slot " + std::to_string(p.index()) +
                        " (order row " + std::to_string(p.order_row()) + "), which DST gives to participant \"" +
                        it->second->name() + "\"; another slot would give other trial seeds (design/seeds.h)");
    used[p.index()] = &p;
    plans_.push_back(Plan{.person = &p, .existing = std::nullopt, .index = p.index(), .order_row = p.order_row(),
                          .import_session = true});
  }
  plan_free_slots(renumber, used);
  for (Plan& plan : plans_)  // new to DST: whatever SRC holds of their consent comes with them
    if (!plan.existing)
      if (auto s = plan_answers(plan, *plan.person, nullptr); !s) return s;
  return check_no_gaps(used);
}

// A participant DST holds already: the same enrollment (a never-started one may have been given
// another slot by an earlier merge), and the same session or none in DST.
Status Merger::plan_present(const Person& p, const Person& q) {
  const std::string who = "participant \"" + p.name() + "\"";
  Plan plan{.person = &p, .existing = q.id(), .index = q.index(), .order_row = q.order_row()};
  if (auto s = plan_answers(plan, p, &q); !s) return s;
  // A row released by the participant's withdrawal (at its instant) compares as not released, so a
  // withdrawal on one side only is a decision that side adds, not another enrollment.
  const std::string src_withdrawn = plan.src.withdrawn_at(), dst_withdrawn = plan.dst.withdrawn_at();
  Row a = p.row, b = q.row;
  if (!src_withdrawn.empty() && text(a["released_at"]) == src_withdrawn) a["released_at"] = std::monostate{};
  if (!dst_withdrawn.empty() && text(b["released_at"]) == dst_withdrawn) b["released_at"] = std::monostate{};
  a["id"] = b["id"] = std::int64_t{0};
  a["study_id"] = src_sha_[num(a["study_id"])];
  b["study_id"] = dst_sha_[num(b["study_id"])];
  if (!p.session) a["enrollment_index"] = b["enrollment_index"] = a["order_row"] = b["order_row"] = std::int64_t{0};
  if (a != b)
    return refuse(dst_, "participants",
                  who + " is in both with different enrollments (SRC: slot " + std::to_string(p.index()) + ", row " +
                      std::to_string(p.order_row()) + ", enrolled " + text(p.row["enrolled_at"]) +
                      (p.released() ? ", released" : "") + "; DST: slot " + std::to_string(q.index()) + ", row " +
                      std::to_string(q.order_row()) + ", enrolled " + text(q.row["enrolled_at"]) +
                      (q.released() ? ", released" : "") + ")");
  if (p.session && q.session) {
    int in_src = 0, in_dst = 0;
    auto rs = session_record(src_, *p.session, src_version_, src_sha_, src_withdrawn, &in_src);
    if (!rs) return rs.error();
    auto rd = session_record(dst_, *q.session, src_version_, dst_sha_, dst_withdrawn, &in_dst);  // what both record
    if (!rd) return rd.error();
    if (*rs != *rd)
      return refuse(dst_, "sessions",
                    who + " has a session in both that differs (SRC: " + std::to_string(in_src) +
                        " trials recorded, DST: " + std::to_string(in_dst) + "); sessions are not merged trial by trial");
    if (auto s = plan_screens(plan, *p.session, *q.session); !s) return s;
  }
  plan.import_session = p.session && !q.session;
  if (plan.import_session && plan.dst.withdrawal)
    return refuse(dst_, "withdrawals",
                  who + " withdrew their consent in DST (at " + dst_withdrawn +
                      "), and SRC holds a session of theirs that DST lacks; a participant who withdrew never runs "
                      "again");
  if (!plan.import_session && !plan.adds_answers()) ++sum_.unchanged;
  plans_.push_back(std::move(plan));
  return {};
}

// Enrolled, never started: the lowest free slot and the row DST's rule gives (invariant 4).
void Merger::plan_free_slots(const std::vector<const Person*>& renumber, Slots& used) {
  const std::int64_t rows = dst_studies_.back().order_rows();
  std::vector<std::int64_t> fill(static_cast<std::size_t>(rows), 0);
  auto count_active = [&](std::int64_t row, bool released) {
    if (!released && row >= 0 && row < rows) ++fill[static_cast<std::size_t>(row)];
  };
  for (const Person& q : dst_ledger_) count_active(q.order_row(), q.released());
  for (const Plan& p : plans_)
    if (!p.existing) count_active(p.order_row, p.person->released());
  std::int64_t free_slot = 0;
  for (const Person* p : renumber) {
    while (used.count(free_slot)) ++free_slot;
    const auto row = std::min_element(fill.begin(), fill.end()) - fill.begin();
    used[free_slot] = p;
    count_active(row, p->released());
    plans_.push_back(Plan{.person = p, .existing = std::nullopt, .index = free_slot, .order_row = row});
    if (free_slot != p->index() || row != p->order_row())
      sum_.changes.push_back("participant \"" + p->name() + "\" (enrolled, never started): ledger slot " +
                             std::to_string(p->index()) + " -> " + std::to_string(free_slot) + ", order row " +
                             std::to_string(p->order_row()) + " -> " + std::to_string(row));
    ++sum_.renumbered;
  }
}

Status Merger::check_no_gaps(const Slots& used) const {
  std::string gaps;
  std::int64_t expect = 0;
  for (const auto& [index, who] : used) {
    for (; expect < index; ++expect) gaps += (gaps.empty() ? "" : ", ") + std::to_string(expect);
    expect = index + 1;
  }
  if (gaps.empty()) return {};
  return refuse(dst_, "participants.enrollment_index",
                "the merge would leave ledger slot(s) " + gaps +
                    " empty: participants who ran a plan keep their slot, and slots are given without gaps "
                    "(docs/store.md, invariant 3)");
}

// SRC's texts of DST's design that DST lacks, recorded as revisions (as Store::open would).
Status Merger::append_revisions() {
  const std::int64_t was_current = dst_studies_.back().id();
  for (const StudyRow& r : append_) {
    auto id = next("studies");
    if (!id) return id.error();
    Row row = r.row;
    row["id"] = *id;
    if (auto s = insert_named(dst_, "studies", {row}, "adding a protocol revision"); !s) return s;
    std::vector<RowInsert> factors;
    for (std::size_t i = 0; i < r.factors.size(); ++i)
      factors.push_back(std::move(RowInsert("study_factors")
                                      .set("study_id", *id)
                                      .set("position", static_cast<std::int64_t>(i + 1))
                                      .set("name", r.factors[i])));
    if (auto s = insert_all(dst_, factors, "adding a protocol revision"); !s) return s;
    if (auto s = insert_all(dst_, {RowInsert("study_designs").set("study_id", *id).set("design_sha256", r.design)},
                            "adding a protocol revision");
        !s)
      return s;
    study_[r.id()] = *id;
    ++sum_.revisions;
    sum_.changes.push_back("protocol text " + r.sha().substr(0, 12) + " added as a revision of DST's design (DST's "
                           "current text was study " + std::to_string(was_current) + ")");
  }
  return {};
}

Status Merger::write_participants() {
  if (auto s = append_revisions(); !s) return s;
  for (Plan& p : plans_) {
    std::optional<std::int64_t> dst_pid = p.existing;
    if (!dst_pid) {
      auto id = next("participants");
      if (!id) return id.error();
      Row row = p.person->row;
      row["id"] = *id;
      row["enrollment_index"] = p.index;
      row["order_row"] = p.order_row;
      row["study_id"] = study_.at(num(row["study_id"]));
      if (auto s = insert_named(dst_, "participants", {row}, "adding a participant"); !s) return s;
      dst_pid = *id;
      ++sum_.participants;
    }
    if (p.import_session)
      if (auto s = import_session(*p.person->session, *dst_pid); !s) return s;
    if (auto s = write_answers(p, *dst_pid); !s) return s;  // after the session: a withdrawal refuses new ones
    if (v2_) {  // a participant new to DST has no decisions there: all of SRC's are added
      if (auto s = merge_decisions("exclusions", p.person->id(), *dst_pid); !s) return s;
      if (auto s = merge_decisions("notes", p.person->id(), *dst_pid); !s) return s;
    }
  }
  return v2_ ? merge_decisions("notes", std::nullopt, std::nullopt) : Status{};
}

Status Merger::import_session(std::int64_t src_session, std::int64_t dst_participant) {
  const SessionQueries q = session_queries(src_version_);
  auto session = next("sessions");
  if (!session) return session.error();
  std::optional<Row> final_state;  // the session's status and ended_at, set after its results
  std::map<std::int64_t, std::int64_t> trial;  // SRC planned trial id -> DST
  auto copy = [&](const std::string& sql, const char* table, auto&& map) -> Status {
    RowSink sink(dst_, table);
    Status st = each_row(src_, sql, {{"session", src_session}}, [&](Row& r) -> Status {
      if (auto s = map(r); !s) return s;
      return sink.add(std::move(r));
    });
    if (!st) return st;
    if (auto s = sink.finish(); !s) return s;
    if (std::string(table) == "trial_results") sum_.trials += static_cast<int>(sink.count());
    if (std::string(table) == "screens") sum_.screens += static_cast<int>(sink.count());
    return {};
  };
  auto by_session = [&](Row& r) -> Status {
    r["session_id"] = *session;
    return {};
  };
  auto by_trial = [&](const char* column) {
    return [&trial, column](Row& r) -> Status {
      r[column] = trial.at(num(r[column]));
      return {};
    };
  };
  Status st = copy(q.session, "sessions", [&](Row& r) -> Status {
    r["id"] = *session;
    r["participant_id"] = dst_participant;
    r["study_id"] = study_.at(num(r["study_id"]));
    if (text(r["status"]) != "running") {
      final_state = r;
      r["status"] = std::string("running");
      r["ended_at"] = std::monostate{};
    }
    return {};
  });
  if (!st) return st;
  st = copy(q.planned, "planned_trials", [&](Row& r) -> Status {
    auto id = next("planned_trials");
    if (!id) return id.error();
    trial[num(r["id"])] = *id;
    r["id"] = *id;
    r["session_id"] = *session;
    return {};
  });
  if (!st) return st;
  for (const auto& [sql, table, column] : std::vector<std::tuple<std::string, const char*, const char*>>{
           {q.levels, "planned_levels", "planned_trial_id"},
           {q.results, "trial_results", "planned_trial_id"},
           {q.events, "input_events", "trial_id"},
           {q.poses, "camera_poses", "trial_id"}})
    if (auto s = copy(sql, table, by_trial(column)); !s) return s;
  for (const auto& [sql, table] : std::vector<std::pair<std::string, const char*>>{
           {q.resumes, "session_resumes"}, {q.answers, "questionnaire_answers"}})
    if (auto s = copy(sql, table, by_session); !s) return s;
  if (v2_)
    for (const auto& [sql, table] :
         std::vector<std::pair<std::string, const char*>>{{q.pauses, "session_pauses"}, {q.attempts, "trial_attempts"}})
      if (auto s = copy(sql, table, by_session); !s) return s;
  if (src_version_ >= 3)
    if (auto s = copy(q.displays, "session_displays", by_session); !s) return s;
  if (src_version_ >= 4)
    if (auto s = copy(q.screens, "screens", by_session); !s) return s;
  ++sum_.sessions;
  if (!final_state) return {};
  auto fin = Stmt::prepare(dst_, "UPDATE sessions SET status = :status, ended_at = :ended_at WHERE id = :id",
                           "finishing the session");
  if (!fin) return fin.error();
  fin->bind("status", (*final_state)["status"]).bind("ended_at", (*final_state)["ended_at"]).bind("id", *session);
  return fin->run("finishing the session");
}

// Exclusions: the latest decision holds, so one side's list must continue the other's (the
// longer one wins; a fork is refused). Notes: SRC's notes DST lacks are added.
Status Merger::merge_decisions(const char* table, std::optional<std::int64_t> src_pid,
                               std::optional<std::int64_t> dst_pid) {
  const bool notes = std::string(table) == "notes";
  auto from = decisions_about(src_, table, src_pid);
  if (!from) return from.error();
  auto d = decisions_about(dst_, table, dst_pid);
  if (!d) return d.error();
  const std::vector<Row> have = std::move(*d);
  std::vector<Row> add;
  if (notes) {
    std::vector<bool> matched(have.size(), false);
    for (const Row& r : *from) {
      auto it = std::find_if(have.begin(), have.end(), [&](const Row& h) {
        return !matched[static_cast<std::size_t>(&h - have.data())] && same_except(h, r, {"id", "participant_id"});
      });
      if (it != have.end()) matched[static_cast<std::size_t>(it - have.begin())] = true;
      else add.push_back(r);
    }
  } else {
    const std::size_t common = std::min(from->size(), have.size());
    for (std::size_t i = 0; i < common; ++i)
      if (!same_except((*from)[i], have[i], {"id", "participant_id"}))
        return refuse(dst_, "exclusions",
                      "the exclusion decisions about participant \"" + src_name(src_pid) +
                          "\" differ in SRC and DST (each has decisions the other lacks), so which one holds would depend "
                          "on the merge");
    add.assign(from->begin() + static_cast<std::ptrdiff_t>(common), from->end());
  }
  std::vector<Row> rows;
  for (Row r : add) {
    auto id = next(table);
    if (!id) return id.error();
    r["id"] = *id;
    r["participant_id"] = dst_pid ? Value{*dst_pid} : Value{};
    rows.push_back(std::move(r));
  }
  (notes ? sum_.notes : sum_.decisions) += static_cast<int>(rows.size());
  return insert_named(dst_, table, rows, std::string("adding ") + table);
}

}  // namespace merging

Status merge_study(Db& src, int src_version, Db& dst, const CopyOptions& options, CopySummary& summary) {
  merging::Merger m(src, src_version, dst, options, summary);
  return m.run();
}

}  // namespace dtlab::store::detail

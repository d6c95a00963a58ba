// The merge of a study into a database that holds it already (copy.h;
// docs/store.md, "Copying and merging"): the Merger and the row helpers its
// two files share (merge.cpp: protocol revisions, the ledger, sessions and
// decisions; merge_answers.cpp: consent, withdrawal and the screen log of
// schema v4). Every check runs before the first row is written; the caller's
// one transaction makes the merge whole or nothing. Internal to study/store.
#pragma once
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "study/store/detail/copy_rows.h"
#include "study/store/store.h"

namespace dtlab::store::detail::merging {

inline std::string text(const Value& v) {
  if (const auto* s = std::get_if<std::string>(&v)) return *s;
  if (const auto* n = std::get_if<std::int64_t>(&v)) return std::to_string(*n);
  return "";
}
inline std::int64_t num(const Value& v) {
  if (const auto* n = std::get_if<std::int64_t>(&v)) return *n;
  if (const auto* d = std::get_if<double>(&v)) return static_cast<std::int64_t>(*d);
  return 0;
}

// A conflict: `why`, ending "the merge is refused and nothing was written".
Error refuse(const Db& dst, const std::string& field, const std::string& why);

struct StudyRow {
  Row row;  // the described columns of `studies`
  std::vector<std::string> factors;
  std::string design;
  std::int64_t id() const { return num(row["id"]); }
  std::string sha() const { return text(row["protocol_sha256"]); }
  std::int64_t order_rows() const { return num(row["order_rows"]); }
};

struct Person {
  Row row;  // the described columns of `participants`
  std::optional<std::int64_t> session;
  std::int64_t id() const { return num(row["id"]); }
  std::string name() const { return text(row["participant"]); }
  std::int64_t index() const { return num(row["enrollment_index"]); }
  std::int64_t order_row() const { return num(row["order_row"]); }
  bool released() const { return !std::holds_alternative<std::monostate>(row["released_at"]); }
};

// The select list of `table`'s described columns in a database of schema `version`, each
// prefixed with `alias` and named AS itself (a column that version lacks reads as NULL).
std::string columns_of(const char* table, const std::string& alias, int version = kSchemaVersion);

// A participant's schema v4 rows in one database (the described columns of each table).
struct Answers {
  std::optional<Row> consent;
  std::optional<Row> withdrawal;
  std::string withdrawn_at() const { return withdrawal ? text((*withdrawal)["withdrawn_at"]) : std::string(); }
};

// The merge itself: plan (every check, nothing written), then write. One object per merge.
class Merger {
 public:
  Merger(Db& src, int src_version, Db& dst, const CopyOptions& o, CopySummary& sum)
      : src_(src), dst_(dst), src_version_(src_version), v2_(src_version >= 2), options_(o), sum_(sum) {}

  Status run();

 private:
  using Slots = std::map<std::int64_t, const Person*>;  // DST ledger slots after the merge
  Status map_studies();
  Status plan_ledger();
  struct Plan;
  Status plan_present(const Person& p, const Person& q);
  // Schema v4 (merge_answers.cpp): a participant's consent and withdrawal in SRC and DST (DST's
  // row when `q`), refused where both hold one and they differ; the screens of a session both
  // hold, refused unless one log continues the other; then what SRC adds, with a withdrawal's
  // effects on DST's rows (released, a running session abandoned).
  Status plan_answers(Plan& plan, const Person& p, const Person* q);
  Status plan_screens(Plan& plan, std::int64_t src_session, std::int64_t dst_session);
  Status write_answers(const Plan& plan, std::int64_t dst_participant);
  Status apply_withdrawal(const Plan& plan, std::int64_t dst_participant);
  void plan_free_slots(const std::vector<const Person*>& renumber, Slots& used);
  Status check_no_gaps(const Slots& used) const;
  Status append_revisions();
  Status write_participants();
  Status import_session(std::int64_t src_session, std::int64_t dst_participant);
  Status merge_decisions(const char* table, std::optional<std::int64_t> src_pid, std::optional<std::int64_t> dst_pid);
  Result<std::int64_t> next(const char* table);
  std::string src_name(std::optional<std::int64_t> pid) const;

  Db& src_;
  Db& dst_;
  int src_version_;
  bool v2_;
  const CopyOptions& options_;
  CopySummary& sum_;
  std::vector<StudyRow> src_studies_, dst_studies_;
  std::map<std::int64_t, std::int64_t> study_;  // SRC study id -> DST study id
  std::map<std::int64_t, std::string> src_sha_, dst_sha_;
  std::vector<StudyRow> append_;               // SRC revisions DST lacks (same design)
  std::vector<Person> src_ledger_, dst_ledger_;
  struct Plan {
    const Person* person;
    std::optional<std::int64_t> existing;  // DST's participant row when DST has them already
    std::int64_t index = 0, order_row = 0;
    bool import_session = false;
    Answers src = {}, dst = {};            // consent and withdrawal in SRC and in DST (schema v4)
    std::optional<std::int64_t> dst_session = {};  // DST's session of a participant both hold
    std::vector<Row> screens = {};         // SRC's screens beyond DST's, of a session both hold
    bool adds_answers() const;             // SRC brings a consent, withdrawal or screens DST lacks
  };
  std::vector<Plan> plans_;
  std::map<std::string, std::int64_t> next_ids_;
};

}  // namespace dtlab::store::detail::merging

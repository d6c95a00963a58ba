// StudyReader's private state (read.cpp, read_consent.cpp): the connection it
// reads through -- its own, holding one snapshot, or a Store's, borrowed --
// what one snapshot caches (the revisions, which every trial row refers to),
// and the row helpers the reads share. Reads only; nothing here writes.
#pragma once
#include <optional>
#include <string>
#include <vector>

#include "study/store/detail/db.h"
#include "study/store/read.h"

namespace dtlab::store {
namespace detail::reading {

// Runs `sql` with `bind` applied, calling row(st) per result row (wrap it in detail::by_name,
// columns.h, to read the row by column name).
template <class Bind, class Row>
Status each_row(Db& db, const std::string& sql, const char* what, Bind&& bind, Row&& row) {
  auto st = Stmt::prepare(db, sql, what);
  if (!st) return st.error();
  bind(*st);
  for (;;) {
    auto r = st->step(what);
    if (!r) return r.error();
    if (!*r) return {};
    row(*st);
  }
}

inline constexpr auto no_bind = [](Stmt&) {};
// Binds :participant to `participant` where a query filters by one ("" = every participant: the
// query has no filter and nothing is bound).
inline auto bind_participant(const std::string& participant) {
  return [&participant](Stmt& s) {
    if (!participant.empty()) s.bind("participant", participant);
  };
}

// The SQL of a 0/1 column that says whether the participant with row id `participant_id` (an
// SQL expression) withdrew; a constant 0 below schema v4.
inline std::string withdrawn_sql(int schema_version, const std::string& participant_id) {
  if (schema_version < 4) return "0";
  return "CASE WHEN EXISTS (SELECT 1 FROM withdrawals w WHERE w.participant_id = " + participant_id +
         ") THEN 1 ELSE 0 END";
}

}  // namespace detail::reading

struct StudyReader::Impl {
  detail::Db own;           // the reader's own connection (owned readers only)
  detail::Db* db = nullptr; // the connection reads go through
  bool owned = true;
  bool in_snapshot = false; // an owned reader's read transaction is open
  int depth = 0;            // nesting of call(): only the outermost call of a borrowed reader opens a transaction
  int schema_version = kSchemaVersion;
  ReadOptions options;
  std::optional<std::vector<Revision>> revisions;  // cached for the snapshot (owned readers)

  Status begin();  // owned readers: open the snapshot
  void end();      // owned readers: close it
  template <class F>
  auto call(F&& f) -> decltype(f()) {
    // A borrowed connection reads each outermost call in a short transaction of its own (unless its
    // Store is inside one); an owned one reads in its snapshot.
    const bool own_tx = !owned && depth == 0 && !db->conn().in_transaction();
    if (own_tx)
      if (auto s = db->conn().begin_read("starting a read transaction"); !s) return s.error();
    ++depth;
    auto r = f();
    --depth;
    if (own_tx) db->conn().commit("ending the read transaction");
    return r;
  }
  Result<std::vector<Revision>> read_revisions();
  Result<std::vector<Exclusion>> read_exclusions();
  Result<std::int64_t> result_id(const std::string& participant, int position);
};

}  // namespace dtlab::store

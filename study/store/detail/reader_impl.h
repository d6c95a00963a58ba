// StudyReader's private state (read.cpp): the connection it reads through --
// its own, holding one snapshot, or a Store's, borrowed -- and what one
// snapshot caches (the revisions, which every trial row refers to).
#pragma once
#include <optional>
#include <vector>

#include "study/store/detail/db.h"
#include "study/store/read.h"

namespace dtlab::store {

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
  auto call(F&& f) -> decltype(f());
  Result<std::vector<Revision>> read_revisions();
  Result<std::vector<Exclusion>> read_exclusions();
  Result<std::int64_t> result_id(const std::string& participant, int position);
};

}  // namespace dtlab::store

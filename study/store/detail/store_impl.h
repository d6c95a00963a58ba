// Store's private state, shared by store.cpp (open, ledger) and session.cpp
// (sessions, trials). Holds the connection and the current study; nothing
// else, so the database is the only place where study state lives.
#pragma once
#include <string>
#include <utility>

#include "study/store/detail/sqlite.h"
#include "study/store/store.h"

namespace dtlab::store {

struct Store::Impl {
  detail::Db db;
  std::string path;
  StudyInfo study;           // the current protocol, as passed to open()
  std::int64_t study_id = 0; // its row in `studies`
  bool broken = false;       // ERROR state: a ROLLBACK failed; only reopening recovers
  Error broken_error;

  Error invalid(std::string field, std::string message) const {
    return Error{path, 0, 0, std::move(field), std::move(message)};
  }

  // Runs `body` inside BEGIN IMMEDIATE ... COMMIT; on any failure rolls back
  // so nothing of it is saved. A failed rollback moves the store to ERROR.
  template <class Body>
  Status write(std::string_view what, Body&& body) {
    if (broken) return broken_error;
    detail::Transaction tx(db);
    if (auto s = tx.begin(what); !s) return s;
    Status st = body();
    if (st) st = tx.commit(what);
    if (!st && !tx.rollback()) {
      broken = true;
      broken_error = Error{path, 0, 0, "sqlite",
                           "the store is in the ERROR state: a ROLLBACK failed after \"" + st.error().message +
                               "\"; committed trials are safe; close and reopen the database to recover"};
    }
    return st;
  }
};

}  // namespace dtlab::store

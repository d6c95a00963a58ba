// Store's private state, shared by store.cpp (open, ledger), store_sessions.cpp
// (sessions, trials), claim.cpp (who runs a session), consent.cpp (consent,
// withdrawal, the screen log) and annotate.cpp (the lab's decisions). Holds the connection, the current study, this Store's
// identity as a claimant and the sessions it claims; nothing of the study
// itself, so the database is the only place where study state lives.
#pragma once
#include <set>
#include <string>
#include <utility>

#include "study/store/detail/db.h"
#include "study/store/read.h"
#include "study/store/store.h"

namespace dtlab::store {

// Who claims a session: this process on this host, one Store of it (docs/store.md, "Claims").
struct Claimant {
  std::string host;
  std::int64_t pid = 0;
  std::string start_time;  // the process's start time (Linux: /proc/self/stat field 22); "" if unknown
  std::string machine;     // /etc/machine-id: tells apart stations cloned with one host name; "" if unknown
  std::string owner;       // host/pid/start_time/nonce/machine: unique per Store object
};
Claimant make_claimant();

// The participant's enrollment as stored now (with released and withdrawn); not_found if unknown.
Result<Enrollment> read_enrollment(detail::Db& db, const std::string& participant_id);

// Demographics as the ledger stores them: a JSON object's text in the order given (invalid UTF-8
// becomes U+FFFD); invalid_input for an empty or repeated field name.
Result<std::string> demographics_json(const std::string& path, const Demographics& demographics);

// The refusal of a participant who withdrew (conflict, field "participant", saying when and why),
// for enroll, record_consent and begin_session alike.
Error withdrawn_error(detail::Db& db, const std::string& participant_id);

struct Store::Impl {
  detail::Db db;
  std::string path;
  OpenOptions options;
  StudyInfo study;           // the current protocol, as passed to open() (or read by open_existing())
  std::int64_t study_id = 0; // its row in `studies`
  bool broken = false;       // ERROR state: a ROLLBACK failed; only reopening recovers
  Error broken_error;
  Claimant me = make_claimant();
  std::set<std::int64_t> claimed;  // sessions this Store holds a claim on (released by the destructor)
  StudyReader reader;

  Impl(detail::Db connection, std::string file, OpenOptions o)
      : db(std::move(connection)), path(std::move(file)), options(std::move(o)),
        reader(StudyReader::borrow(db, ReadOptions{options.design_hash_of, options.busy_timeout_ms})) {}
  ~Impl();

  Error invalid(std::string field, std::string message, ErrorKind kind = ErrorKind::invalid_input) const {
    return Error{path, 0, 0, std::move(field), std::move(message), kind};
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
      broken_error = Error{path, 0, 0, "database",
                           "the store is in the ERROR state: a ROLLBACK failed after \"" + st.error().message +
                               "\"; committed trials are safe; close and reopen the database to recover",
                           ErrorKind::environment};
    }
    return st;
  }

  // The ledger (store.cpp, consent.cpp); each runs inside the caller's write transaction.
  // A new enrollment with the next index and the row of invariant 4, `demographics_json` as
  // stored, enrolled at `now`; the trial_table view is recreated when it brings a demographic
  // field no one had.
  Result<Enrollment> insert_enrollment(const std::string& participant_id, const std::string& demographics_json,
                                       const std::string& now);
  // The effects of a withdrawal and its row (consent.cpp): a running session abandoned (claim
  // taken, busy if another live process holds it), the row released, the withdrawal appended,
  // all stamped `now`. No-op when the participant withdrew before.
  Status withdraw_in(const std::string& participant_id, const std::string& reason, const std::string& by,
                     const std::string& now);

  // Claims (claim.cpp); each runs inside the caller's write transaction.
  Status take_claim(std::int64_t session_id, const std::string& who, bool take_over, bool* took_over);
  Status renew_claim(std::int64_t session_id, const std::string& who);  // conflict unless ours
  Status drop_claim(std::int64_t session_id);                           // ours only; no-op otherwise
};

}  // namespace dtlab::store

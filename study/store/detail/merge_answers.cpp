// The merge of schema v4's consent, withdrawal and screen log (merge.h;
// docs/store.md, "Copying and merging"). A participant's consent and
// withdrawal are one row each: what SRC holds and DST lacks is added, the
// same row in both is left alone, two different rows are refused (which
// answer or decision holds would depend on the merge). A session's screens
// are a list: one side's must continue the other's, and SRC's rest is
// appended. A withdrawal SRC adds for a participant DST holds takes its
// effects in DST as withdraw() would (the row released, a running session
// abandoned at the withdrawal's instant), refused while someone runs that
// session in DST. Checks run in the plan, before anything is written.
#include "study/store/detail/merge.h"

#include <algorithm>
#include <utility>

namespace dtlab::store::detail::merging {
namespace {

Result<std::optional<Row>> one_row(Db& db, const std::string& sql, std::int64_t participant) {
  std::optional<Row> out;
  Status st = each_row(db, sql, {{"participant_id", participant}}, [&](Row& r) -> Status {
    out = std::move(r);
    return {};
  });
  if (!st) return st.error();
  return out;
}

// The consent and withdrawal of the participant with row id `participant` (schema v4).
Result<Answers> read_answers(Db& db, std::int64_t participant) {
  Answers a;
  auto c = one_row(db, "SELECT " + columns_of("consents", "") + " FROM consents WHERE participant_id = :participant_id",
                   participant);
  if (!c) return c.error();
  auto w = one_row(db,
                   "SELECT " + columns_of("withdrawals", "") +
                       " FROM withdrawals WHERE participant_id = :participant_id",
                   participant);
  if (!w) return w.error();
  a.consent = std::move(*c);
  a.withdrawal = std::move(*w);
  return a;
}

Result<std::vector<Row>> screens_of(Db& db, std::int64_t session) {
  std::vector<Row> out;
  Status st = each_row(db,
                       "SELECT " + columns_of("screens", "") +
                           " FROM screens WHERE session_id = :session_id ORDER BY seq",
                       {{"session_id", session}}, [&](Row& r) -> Status {
                         out.push_back(std::move(r));
                         return {};
                       });
  if (!st) return st.error();
  return out;
}

}  // namespace

bool Merger::Plan::adds_answers() const {
  return (src.consent && !dst.consent) || (src.withdrawal && !dst.withdrawal) || !screens.empty();
}

Status Merger::plan_answers(Plan& plan, const Person& p, const Person* q) {
  if (src_version_ >= 4) {
    auto a = read_answers(src_, p.id());
    if (!a) return a.error();
    plan.src = std::move(*a);
  }
  if (!q) return {};
  auto d = read_answers(dst_, q->id());
  if (!d) return d.error();
  plan.dst = std::move(*d);
  plan.dst_session = q->session;
  const std::string who = "participant \"" + p.name() + "\"";
  if (plan.src.consent && plan.dst.consent && !same_except(*plan.src.consent, *plan.dst.consent, {"participant_id"}))
    return refuse(dst_, "consents",
                  who + " answered the consent page differently in SRC and DST (the first answer stays, so which "
                        "one holds would depend on the merge)");
  if (plan.src.withdrawal && plan.dst.withdrawal &&
      !same_except(*plan.src.withdrawal, *plan.dst.withdrawal, {"id", "participant_id"}))
    return refuse(dst_, "withdrawals",
                  who + " withdrew in SRC (at " + plan.src.withdrawn_at() + ") and in DST (at " +
                      plan.dst.withdrawn_at() + "); one withdrawal per participant");
  if (!plan.src.withdrawal || plan.dst.withdrawal || !q->session) return {};
  // SRC's withdrawal will end DST's session if it runs: not while someone runs it there.
  auto now = dst_.now_iso();
  if (!now) return now.error();
  auto live = dst_.query_int("SELECT count(*) AS n FROM session_claims c JOIN sessions s ON s.id = c.session_id WHERE "
                             "s.status = 'running' AND c.session_id = :session_id AND c.expires_at > :now",
                             "reading the session claims", {{"session_id", *q->session}, {"now", *now}});
  if (!live) return live.error();
  if (live->value_or(0) > 0)
    return refuse(dst_, "session_claims",
                  who + " withdrew in SRC, and their session is being run in DST now; stop it there, then merge");
  return {};
}

Status Merger::plan_screens(Plan& plan, std::int64_t src_session, std::int64_t dst_session) {
  if (src_version_ < 4) return {};
  auto from = screens_of(src_, src_session);
  if (!from) return from.error();
  auto have = screens_of(dst_, dst_session);
  if (!have) return have.error();
  const std::size_t common = std::min(from->size(), have->size());
  for (std::size_t i = 0; i < common; ++i)
    if (!same_except((*from)[i], (*have)[i], {"session_id"}))
      return refuse(dst_, "screens",
                    "the screen logs of participant \"" + plan.person->name() + "\"'s session differ at screen " +
                        std::to_string(i + 1) + " (each has screens the other lacks)");
  plan.screens.assign(from->begin() + static_cast<std::ptrdiff_t>(common), from->end());
  return {};
}

Status Merger::apply_withdrawal(const Plan& plan, std::int64_t dst_participant) {
  const Value at = (*plan.src.withdrawal)["withdrawn_at"];
  auto rel = Stmt::prepare(dst_, "UPDATE participants SET released_at = :at WHERE id = :id AND released_at IS NULL",
                           "freeing the order row");
  if (!rel) return rel.error();
  rel->bind("at", at).bind("id", dst_participant);
  if (auto s = rel->run("freeing the order row"); !s) return s;
  if (!plan.dst_session) return {};
  auto del = Stmt::prepare(dst_, "DELETE FROM session_claims WHERE session_id = :session_id",
                           "dropping the session claim");
  if (!del) return del.error();
  del->bind("session_id", *plan.dst_session);
  if (auto s = del->run("dropping the session claim"); !s) return s;
  auto end = Stmt::prepare(dst_, "UPDATE sessions SET status = 'abandoned', ended_at = :at WHERE id = :id AND "
                                 "status = 'running'",
                           "ending the session");
  if (!end) return end.error();
  end->bind("at", at).bind("id", *plan.dst_session);
  return end->run("ending the session");
}

Status Merger::write_answers(const Plan& plan, std::int64_t dst_participant) {
  if (plan.src.consent && !plan.dst.consent) {
    Row row = *plan.src.consent;
    row["participant_id"] = dst_participant;
    if (auto s = insert_named(dst_, "consents", {row}, "adding a consent"); !s) return s;
    ++sum_.consents;
  }
  if (!plan.screens.empty()) {
    std::vector<Row> rows = plan.screens;
    for (Row& r : rows) r["session_id"] = *plan.dst_session;
    if (auto s = insert_named(dst_, "screens", rows, "adding screens"); !s) return s;
    sum_.screens += static_cast<int>(rows.size());
  }
  if (!plan.src.withdrawal || plan.dst.withdrawal) return {};
  if (plan.existing)  // a participant new to DST came with SRC's rows, released and ended already
    if (auto s = apply_withdrawal(plan, dst_participant); !s) return s;
  auto id = next("withdrawals");
  if (!id) return id.error();
  Row row = *plan.src.withdrawal;
  row["id"] = *id;
  row["participant_id"] = dst_participant;
  if (auto s = insert_named(dst_, "withdrawals", {row}, "adding a withdrawal"); !s) return s;
  ++sum_.withdrawals;
  return {};
}

}  // namespace dtlab::store::detail::merging

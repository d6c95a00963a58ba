// StudyReader's reads of schema v4 (read.h): consent answers, withdrawals and
// the screen log, each from the reader's snapshot. A database of an older
// schema, which the reader never migrates, has none of them: the lists are
// empty. Never writes.
#include "study/store/detail/reader_impl.h"
#include "study/store/read.h"

namespace dtlab::store {

using detail::Stmt;
using namespace detail::reading;

Result<std::vector<ConsentRecord>> StudyReader::consents() {
  return impl_->call([&]() -> Result<std::vector<ConsentRecord>> {
    std::vector<ConsentRecord> out;
    if (impl_->schema_version < 4) return out;
    Status st = each_row(*impl_->db,
                         "SELECT pa.participant, c.agreed, c.text_sha256, c.answered_at FROM consents c "
                         "JOIN participants pa ON pa.id = c.participant_id ORDER BY pa.enrollment_index",
                         "reading the consents", no_bind, [&](const Stmt& q) {
                           out.push_back(ConsentRecord{q.text(0), q.int64(1) != 0, q.text(2), q.text(3)});
                         });
    if (!st) return st.error();
    return out;
  });
}

Result<std::vector<WithdrawalRecord>> StudyReader::withdrawals() {
  return impl_->call([&]() -> Result<std::vector<WithdrawalRecord>> {
    std::vector<WithdrawalRecord> out;
    if (impl_->schema_version < 4) return out;
    Status st = each_row(*impl_->db,
                         "SELECT pa.participant, w.withdrawn_at, w.reason, w.decided_by FROM withdrawals w "
                         "JOIN participants pa ON pa.id = w.participant_id ORDER BY pa.enrollment_index",
                         "reading the withdrawals", no_bind, [&](const Stmt& q) {
                           out.push_back(WithdrawalRecord{q.text(0), q.text(1), q.text(2), q.text(3)});
                         });
    if (!st) return st.error();
    return out;
  });
}

Result<std::vector<ScreenRow>> StudyReader::screens(const std::string& participant) {
  return impl_->call([&]() -> Result<std::vector<ScreenRow>> {
    std::vector<ScreenRow> out;
    if (impl_->schema_version < 4) return out;
    const std::string filter = participant.empty() ? "" : " WHERE pa.participant = ?1";
    Status st = each_row(*impl_->db,
                         "SELECT pa.participant, x.seq, x.screen, x.shown, x.shown_at, x.ended_at, x.duration_s, "
                         "x.answer FROM screens x JOIN sessions s ON s.id = x.session_id "
                         "JOIN participants pa ON pa.id = s.participant_id" + filter +
                             " ORDER BY pa.enrollment_index, x.seq",
                         "reading the screens", [&](Stmt& s) { if (!participant.empty()) s.bind(1, participant); },
                         [&](const Stmt& q) {
                           out.push_back(ScreenRow{q.text(0), static_cast<int>(q.int64(1)), q.text(2), q.text(3),
                                                   q.text(4), q.text(5), q.real(6), opt_text(q, 7)});
                         });
    if (!st) return st.error();
    return out;
  });
}

}  // namespace dtlab::store

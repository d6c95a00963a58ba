// StudyReader's reads of schema v4 (read.h): consent answers, withdrawals and
// the screen log, each from the reader's snapshot. A database of an older
// schema, which the reader never migrates, has none of them: the lists are
// empty. Every cell is read by column name (detail/columns.h). Never writes.
#include "study/store/detail/columns.h"
#include "study/store/detail/reader_impl.h"
#include "study/store/read.h"

namespace dtlab::store {

using detail::NamedColumns;
using detail::Stmt;
using detail::by_name;
using detail::find_table;
using detail::select_list;
using namespace detail::reading;

Result<std::vector<ConsentRecord>> StudyReader::consents() {
  return impl_->call([&]() -> Result<std::vector<ConsentRecord>> {
    std::vector<ConsentRecord> out;
    if (impl_->schema_version < 4) return out;
    Status st = each_row(*impl_->db,
                         "SELECT pa.participant AS participant, " +
                             select_list(*find_table("consents"), "c.", impl_->schema_version) +
                             " FROM consents c JOIN participants pa ON pa.id = c.participant_id "
                             "ORDER BY pa.enrollment_index",
                         "reading the consents", no_bind, by_name([&](const NamedColumns& c, const Stmt& q) {
                           out.push_back(ConsentRecord{c.text(q, "participant"), c.int64(q, "agreed") != 0,
                                                       c.text(q, "text_sha256"), c.text(q, "answered_at")});
                         }));
    if (!st) return st.error();
    return out;
  });
}

Result<std::vector<WithdrawalRecord>> StudyReader::withdrawals() {
  return impl_->call([&]() -> Result<std::vector<WithdrawalRecord>> {
    std::vector<WithdrawalRecord> out;
    if (impl_->schema_version < 4) return out;
    Status st = each_row(*impl_->db,
                         "SELECT pa.participant AS participant, " +
                             select_list(*find_table("withdrawals"), "w.", impl_->schema_version) +
                             " FROM withdrawals w JOIN participants pa ON pa.id = w.participant_id "
                             "ORDER BY pa.enrollment_index",
                         "reading the withdrawals", no_bind, by_name([&](const NamedColumns& c, const Stmt& q) {
                           out.push_back(WithdrawalRecord{c.text(q, "participant"), c.text(q, "withdrawn_at"),
                                                          c.text(q, "reason"), c.text(q, "decided_by")});
                         }));
    if (!st) return st.error();
    return out;
  });
}

Result<std::vector<ScreenRow>> StudyReader::screens(const std::string& participant) {
  return impl_->call([&]() -> Result<std::vector<ScreenRow>> {
    std::vector<ScreenRow> out;
    if (impl_->schema_version < 4) return out;
    const std::string filter = participant.empty() ? "" : " WHERE pa.participant = :participant";
    Status st = each_row(*impl_->db,
                         "SELECT pa.participant AS participant, " +
                             select_list(*find_table("screens"), "x.", impl_->schema_version) +
                             " FROM screens x JOIN sessions s ON s.id = x.session_id "
                             "JOIN participants pa ON pa.id = s.participant_id" + filter +
                             " ORDER BY pa.enrollment_index, x.seq",
                         "reading the screens", bind_participant(participant),
                         by_name([&](const NamedColumns& c, const Stmt& q) {
                           out.push_back(ScreenRow{c.text(q, "participant"), static_cast<int>(c.int64(q, "seq")),
                                                   c.text(q, "screen"), c.text(q, "shown"), c.text(q, "shown_at"),
                                                   c.text(q, "ended_at"), c.real(q, "duration_s"),
                                                   c.opt_text(q, "answer")});
                         }));
    if (!st) return st.error();
    return out;
  });
}

}  // namespace dtlab::store

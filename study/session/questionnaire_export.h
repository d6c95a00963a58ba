// `dtlab export DB --questionnaires FILE`: a study's questionnaire answers
// as a tidy CSV (docs/questionnaires.md, "Export"): one row per participant
// x item x occasion x own scope, with the occasion's kind, block, task and
// the levels of the condition it followed (from the participant's plan),
// then each instrument's scores per participant and occasion as rows of
// type "score" (computed from the raw answers by the instrument's published
// scoring; never stored). Read through one StudyReader snapshot under the
// database's latest protocol text. Written as R's read.csv and pandas read
// it: a header, RFC 4180 quoting, NA for missing values, LF line ends.
// Never: modifies the database.
#pragma once
#include <ostream>
#include <string>
#include <vector>

#include "study/common/error.h"
#include "study/store/read.h"

namespace dtlab::session {

struct QuestionnaireExportSummary {
  std::vector<std::string> columns;
  long long rows = 0;     // data rows written
  long long answers = 0;  // of them, stored answers
  long long scores = 0;   // of them, instrument scores
};

// The columns: participant, enrollment_index, occasion, occasion_scope, block, task, one per factor
// of the protocol, item, instrument, type, scope, value, text, label, answered_at, excluded.
std::vector<std::string> questionnaire_export_columns(const std::vector<std::string>& factors);

// Writes the table to `out`; Errors name the database (a recorded protocol that does not load is
// invalid_input). On error `out` may hold part of the table (write to a temporary file).
Result<QuestionnaireExportSummary> export_questionnaire_csv(store::StudyReader& reader, std::ostream& out);

}  // namespace dtlab::session

// export_questionnaire_csv (questionnaire_export.h): the store's answers and
// plans through questionnaire::answer_table, written with the trial
// export's quoting (store::csv_field) and shortest round-trip numbers.
#include "study/session/questionnaire_export.h"

#include <charconv>
#include <map>

#include "study/protocol/protocol.h"
#include "study/questionnaire/table.h"
#include "study/store/export.h"

namespace dtlab::session {

namespace {

std::string number(double v) {
  char buf[64];
  auto r = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, r.ptr);
}

std::string text_or_na(const std::string& s) { return s.empty() ? "NA" : store::csv_field(s); }

// Participant -> the reason of the exclusion in force (the latest decision about the participant wins).
std::map<std::string, std::string> excluded_participants(const std::vector<store::Exclusion>& decisions) {
  std::map<std::string, std::string> out;
  for (const store::Exclusion& e : decisions) {
    if (e.position) continue;
    if (e.exclude) out[e.participant] = e.reason;
    else out.erase(e.participant);
  }
  return out;
}

}  // namespace

std::vector<std::string> questionnaire_export_columns(const std::vector<std::string>& factors) {
  std::vector<std::string> c = {"participant", "enrollment_index", "occasion", "occasion_scope", "block", "task"};
  c.insert(c.end(), factors.begin(), factors.end());
  for (const char* f : {"item", "instrument", "type", "scope", "value", "text", "label", "answered_at", "excluded"})
    c.emplace_back(f);
  return c;
}

Result<QuestionnaireExportSummary> export_questionnaire_csv(store::StudyReader& reader, std::ostream& out) {
  auto revisions = reader.revisions();
  if (!revisions) return revisions.error();
  if (revisions->empty()) return Error{reader.path(), 0, 0, "studies", "the database records no protocol"};
  auto protocol = protocol::load_protocol_text(revisions->back().protocol_text, "(recorded protocol)");
  if (!protocol)
    return Error{reader.path(), 0, 0, "studies.protocol_text",
                 "the recorded protocol does not load with this build: " + protocol.error().to_string()};
  const protocol::Protocol& p = protocol.value();
  auto ledger = reader.ledger();
  if (!ledger) return ledger.error();
  auto planned = reader.planned();
  if (!planned) return planned.error();
  auto records = reader.questionnaire();
  if (!records) return records.error();
  auto decisions = reader.exclusions();
  if (!decisions) return decisions.error();

  std::vector<questionnaire::ParticipantPlan> plans;
  std::map<std::string, std::size_t> plan_of;
  std::map<std::string, int> index_of;
  for (const store::LedgerEntry& e : ledger.value()) {
    if (e.withdrawn) continue;  // consent declined or withdrawn: none of their answers leaves the file
    plan_of[e.participant] = plans.size();
    index_of[e.participant] = e.index;
    plans.push_back({e.participant, {}});
  }
  for (const store::PlannedRow& r : planned.value())
    if (auto it = plan_of.find(r.participant); it != plan_of.end())
      plans[it->second].plan.push_back({r.trial.position, r.trial.block, r.trial.task, r.trial.levels});
  std::vector<questionnaire::StoredAnswer> answers;
  for (const store::QuestionnaireRecord& r : records.value())
    if (plan_of.count(r.participant)) answers.push_back({r.participant, r.item, r.scope, r.value, r.answered_at});
  std::vector<std::string> factors;
  for (const protocol::Factor& f : p.factors) factors.push_back(f.name);
  const questionnaire::Table table = questionnaire::answer_table(p.questionnaire, p.instruments, factors, plans, answers);
  const auto excluded = excluded_participants(decisions.value());

  QuestionnaireExportSummary sum;
  sum.columns = questionnaire_export_columns(factors);
  std::string line;
  for (std::size_t c = 0; c < sum.columns.size(); ++c) line += (c ? "," : "") + store::csv_field(sum.columns[c]);
  out << line << '\n';
  for (const questionnaire::TableRow& r : table.rows) {
    line = store::csv_field(r.participant) + "," + std::to_string(index_of[r.participant]) + "," + text_or_na(r.occasion) +
           "," + text_or_na(r.occasion_scope) + "," + (r.block > 0 ? std::to_string(r.block) : "NA") + "," +
           text_or_na(r.task);
    for (const std::string& level : r.levels) line += "," + text_or_na(level);
    const auto reason = excluded.find(r.participant);
    line += "," + store::csv_field(r.item) + "," + text_or_na(r.instrument) + "," + text_or_na(r.type) + "," +
            text_or_na(r.scope) + "," + (r.number ? number(*r.number) : "NA") + "," +
            (r.text ? store::csv_field(*r.text) : "NA") + "," + text_or_na(r.label) + "," + text_or_na(r.answered_at) +
            "," + (reason != excluded.end() ? store::csv_field(reason->second) : "NA");
    out << line << '\n';
    ++sum.rows;
    if (r.type == "score") ++sum.scores;
    else ++sum.answers;
  }
  if (!out) return Error{reader.path(), 0, 0, "questionnaires", "writing the table failed", ErrorKind::environment};
  return sum;
}

}  // namespace dtlab::session

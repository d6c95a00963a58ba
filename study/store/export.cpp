// CSV export of the recorded trials; see export.h. Numbers are written with
// std::to_chars (shortest form that reads back to the same double, never
// locale-dependent), so the file round-trips exactly through R and pandas.
#include "study/store/export.h"

#include <algorithm>
#include <charconv>
#include <map>

#include "study/store/detail/schema.h"

namespace dtlab::store {

std::string csv_field(const std::string& text) {
  if (text.find_first_of(",\"\r\n") == std::string::npos) return text;
  std::string q = "\"";
  for (char c : text) q += c == '"' ? std::string("\"\"") : std::string(1, c);
  return q + "\"";
}

namespace {

std::string number(double v) {
  char buf[64];
  auto r = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, r.ptr);
}

template <class T>
std::string opt(const std::optional<T>& v) {
  if (!v) return "NA";
  if constexpr (std::is_same_v<T, double>) return number(*v);
  else return std::to_string(*v);
}

// Demographic fields in order of first appearance over the ledger (detail::demographic_fields,
// which names the trial_table view's columns, follows the same rule).
std::vector<std::string> demographic_fields(const std::vector<LedgerEntry>& ledger) {
  std::vector<std::string> out;
  for (const LedgerEntry& e : ledger)
    for (const auto& [k, v] : e.demographics)
      if (std::find(out.begin(), out.end(), k) == out.end()) out.push_back(k);
  return out;
}

std::vector<std::string> factor_names(const std::vector<Revision>& revisions) {
  std::vector<std::string> out;
  for (const Revision& r : revisions)
    for (const std::string& f : r.factors)
      if (std::find(out.begin(), out.end(), f) == out.end()) out.push_back(f);
  return out;
}

// The answer columns (count, letter, x, z) of an answer; NA where it has none.
void answer_fields(const std::optional<Answer>& a, std::vector<std::string>& row) {
  const Count* c = a ? std::get_if<Count>(&*a) : nullptr;
  const Letter* l = a ? std::get_if<Letter>(&*a) : nullptr;
  const Position* p = a ? std::get_if<Position>(&*a) : nullptr;
  row.push_back(c ? std::to_string(c->n) : "NA");
  row.push_back(l ? csv_field(l->letter) : "NA");
  row.push_back(p ? number(p->x) : "NA");
  row.push_back(p ? number(p->z) : "NA");
}

// The fixed and factor columns of one trial's row (all but the demographic ones), into `row`.
void trial_fields(const TrialRow& t, const std::vector<std::string>& factors, std::vector<std::string>& row) {
  row.clear();
  row.push_back(csv_field(t.participant));
  row.push_back(std::to_string(t.enrollment_index));
  row.push_back(std::to_string(t.session_id));
  row.push_back(to_string(t.session_status));
  row.push_back(std::to_string(t.order_row));
  row.push_back(std::to_string(t.planned.position));
  row.push_back(std::to_string(t.planned.block));
  for (const std::string& f : factors) {
    const auto it = std::find_if(t.planned.levels.begin(), t.planned.levels.end(),
                                 [&](const auto& l) { return l.first == f; });
    row.push_back(it == t.planned.levels.end() ? "NA" : csv_field(it->second));
  }
  row.push_back(csv_field(t.planned.task));
  row.push_back(std::to_string(t.planned.trial));
  row.push_back(t.planned.practice ? "1" : "0");
  row.push_back(csv_field(t.planned.method));
  row.push_back(std::to_string(t.planned.seed));
  row.push_back(t.scene_hash);
  answer_fields(t.answer, row);
  answer_fields(t.truth, row);
  row.push_back(opt(t.scores.rel_error));
  row.push_back(opt(t.scores.signed_error));
  row.push_back(t.scores.correct ? (*t.scores.correct ? "1" : "0") : "NA");
  row.push_back(opt(t.scores.distance));
  row.push_back(number(t.completion_s));
  row.push_back(t.started_at);
  row.push_back(t.ended_at);
  row.push_back(std::to_string(t.frames.frames));
  row.push_back(opt(t.frames.mean_ms));
  row.push_back(opt(t.frames.sd_ms));
  row.push_back(opt(t.frames.p95_ms));
  row.push_back(opt(t.frames.max_ms));
  row.push_back(opt(t.frames.first_ms));
  row.push_back(opt(t.frames.steady_median_ms));
  row.push_back(opt(t.frames.late));
  row.push_back(opt(t.frames.refresh_hz));
  row.push_back(t.protocol_sha256);
  row.push_back(t.design_revision > 0 ? std::to_string(t.design_revision) : "NA");
  row.push_back(t.excluded ? csv_field(*t.excluded) : "NA");
}

}  // namespace

const std::vector<std::string>& measured_columns() {
  static const std::vector<std::string> c = {"session",        "started_at",    "ended_at",        "frame_ms_mean",
                                             "frame_ms_sd",    "frame_ms_p95",  "frame_ms_max",    "frame_first_ms",
                                             "frame_ms_median", "late_frames",  "refresh_hz"};
  return c;
}

std::string demographic_column(const std::string& field) { return detail::kDemographicPrefix + field; }

std::vector<std::string> export_columns(const std::vector<Revision>& revisions, const std::vector<LedgerEntry>& ledger) {
  std::vector<std::string> c = detail::fixed_trial_columns_before_factors();
  for (const std::string& f : factor_names(revisions)) c.push_back(f);
  for (const std::string& f : detail::fixed_trial_columns_after_factors()) c.push_back(f);
  for (const std::string& f : demographic_fields(ledger)) c.push_back(demographic_column(f));
  return c;
}

Result<ExportSummary> export_trials_csv(StudyReader& reader, std::ostream& out) {
  auto trials = reader.trials();
  if (!trials) return trials.error();
  return export_trials_csv(reader, *trials, out);
}

Result<ExportSummary> export_trials_csv(StudyReader& reader, const std::vector<TrialRow>& trials, std::ostream& out) {
  auto revisions = reader.revisions();
  if (!revisions) return revisions.error();
  auto ledger = reader.ledger();
  if (!ledger) return ledger.error();
  ExportSummary sum;
  sum.columns = export_columns(*revisions, *ledger);
  const std::vector<std::string> factors = factor_names(*revisions), fields = demographic_fields(*ledger);
  std::map<std::string, const Demographics*> demographics;
  for (const LedgerEntry& e : *ledger) {
    demographics[e.participant] = &e.demographics;
    if (e.withdrawn) ++sum.withdrawn;
  }
  std::string line;
  for (std::size_t c = 0; c < sum.columns.size(); ++c) line += (c ? "," : "") + csv_field(sum.columns[c]);
  out << line << '\n';
  std::vector<std::string> row;
  for (const TrialRow& t : trials) {
    if (t.withdrawn) {  // invariant 13: a participant who withdrew their consent is left out
      ++sum.withdrawn_rows;
      continue;
    }
    trial_fields(t, factors, row);
    static const Demographics none;
    const Demographics& demo = demographics.count(t.participant) ? *demographics[t.participant] : none;
    for (const std::string& f : fields) {
      const auto it = std::find_if(demo.begin(), demo.end(), [&](const auto& kv) { return kv.first == f; });
      row.push_back(it == demo.end() ? "NA" : csv_field(it->second));
    }
    if (t.excluded) ++sum.excluded;
    line.clear();
    for (std::size_t c = 0; c < row.size(); ++c) line += (c ? "," : "") + row[c];
    out << line << '\n';
    ++sum.rows;
  }
  if (!out) return Error{reader.path(), 0, 0, "", "writing the CSV failed", ErrorKind::environment};
  return sum;
}

Result<ExportSummary> export_trials_csv(const std::string& db_path, std::ostream& out, ReadOptions options) {
  auto reader = StudyReader::open(db_path, std::move(options));
  if (!reader) return reader.error();
  return export_trials_csv(*reader, out);
}

}  // namespace dtlab::store

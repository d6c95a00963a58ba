// The report's CSV files, laid out from the sections' results (render_data.h):
// one function per file, every field quoted as `dtlab export` quotes it
// (csv_line) and every number at full precision, NA for a missing one
// (csv_number), so R's read.csv reads back what the tables round.
#include <algorithm>

#include "analysis/report/detail/format.h"
#include "analysis/report/detail/render_data.h"

namespace dtlab::report::detail {
namespace {

// One line per pause-or-note participant and note (a participant without notes: one line, note empty).
// A long means file: the header, then each block's rows.
std::string means_csv(const std::vector<MeansBlock>& blocks, const Design& d) {
  std::string csv = matrix_csv_header(d);
  for (const MeansBlock& b : blocks) csv += matrix_csv_rows(*b.m, d, b.measure, b.scope);
  return csv;
}

// Every questionnaire answer as recorded (analysed participants), number or text.
std::string questionnaire_csv(const StudyData& data) {
  std::string csv = csv_line({"item", "participant", "scope", "value_number", "value_text"});
  for (const auto& a : data.answers)
    csv += csv_line({a.item, a.participant, a.scope, a.number ? csv_number(*a.number) : "NA", a.text ? *a.text : "NA"});
  return csv;
}

std::string sessions_notes_csv(const ParticipantsResult& r) {
  std::string csv = csv_line({"participant", "pauses", "paused_s", "note"});
  for (const auto& a : r.around) {
    if (a.notes.empty()) csv += csv_line({a.id, std::to_string(a.pauses), csv_number(a.paused_s), ""});
    for (const std::string& n : a.notes) csv += csv_line({a.id, std::to_string(a.pauses), csv_number(a.paused_s), n});
  }
  return csv;
}

std::string instrument_scores_csv(const QuestionnaireResults& res) {
  std::string csv =
      csv_line({"participant", "instrument", "scale", "occasion", "occasion_scope", "condition", "value"});
  for (const InstrumentScore& x : res.scores)
    csv += csv_line({x.participant, x.instrument, x.scale, x.occasion, x.occasion_scope, x.condition,
                     csv_number(x.value)});
  return csv;
}

// Free-text answers ordered by the condition they followed (stable: participant order within one).
std::string free_text_csv(const QuestionnaireResults& res) {
  std::string csv = csv_line({"participant", "item", "condition", "text"});
  std::vector<const FreeText*> sorted;
  for (const FreeText& f : res.texts) sorted.push_back(&f);
  std::stable_sort(sorted.begin(), sorted.end(),
                   [](const FreeText* a, const FreeText* b) { return a->condition < b->condition; });
  for (const FreeText* f : sorted) csv += csv_line({f->participant, f->item, f->condition, f->text});
  return csv;
}

std::string frames_csv(const FramesResult& fr) {
  std::string csv = csv_line({"condition", "method", "display", "trials", "trials_with_frames", "frames",
                              "display_hz", "median_fps", "late_frames", "late_share", "median_first_ms",
                              "median_p95_ms", "slow_trials", "slow_share"});
  for (const auto& c : fr.conditions)
    csv += csv_line({c.condition, c.method, c.display, std::to_string(c.trials), std::to_string(c.trials_with_frames),
                     std::to_string(c.frames), csv_number(c.display_hz), csv_number(c.median_fps),
                     std::to_string(c.late_frames), csv_number(c.late_share), csv_number(c.median_first_ms),
                     csv_number(c.median_p95_ms), std::to_string(c.slow_trials), csv_number(c.slow_share)});
  return csv;
}

}  // namespace

std::map<std::string, std::string> render_csv(const Context& ctx, const SectionResults& results) {
  std::map<std::string, std::string> files = ctx.csv;
  files["tests.csv"] = tests_csv(ctx);
  files["completion_time_means.csv"] = means_csv(results.time.means, ctx.design);
  if (!results.accuracy.rows.empty()) files["accuracy_means.csv"] = means_csv(results.accuracy.means, ctx.design);
  if (!results.sample.around.empty()) files["sessions_notes.csv"] = sessions_notes_csv(results.sample);
  if (results.questionnaire && !results.questionnaire->empty()) files["questionnaire.csv"] = questionnaire_csv(ctx.data);
  if (results.instruments) {
    files["instrument_scores.csv"] = instrument_scores_csv(*results.instruments);
    files["free_text.csv"] = free_text_csv(*results.instruments);
  }
  files["frames.csv"] = frames_csv(results.frames);
  return files;
}

}  // namespace dtlab::report::detail

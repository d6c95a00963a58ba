// The report's two data renderers: report.json (nlohmann::json) and the
// per-analysis CSV files, each laid out in one place from the sections'
// result structs (sections.h) and the study, as render_markdown, render_html
// and render_latex lay out the Document. Guarantees: the same results give
// the same bytes; numbers keep full precision (NaN as null in JSON, NA in
// CSV). Never computes a statistic, never reads the database, never writes
// a file (report.cpp writes what these return).
#pragma once
#include <nlohmann/json.hpp>

#include <map>
#include <optional>
#include <string>
#include <vector>

#include "analysis/report/detail/questionnaire_results.h"
#include "analysis/report/detail/sections.h"

namespace dtlab::report::detail {

// Every section's result, as report.cpp collects them in a paper's order.
struct SectionResults {
  OverviewResult overview;
  ParticipantsResult sample;
  TimeResult time;
  AccuracyResult accuracy;
  MixedResult mixed;
  SpeedAccuracyResult speed_accuracy;
  QuestionnaireResult questionnaire;
  std::optional<QuestionnaireResults> instruments;  // nullopt: no instruments section
  PositionResult position;
  FramesResult frames;
  PlanningResult planning;
  PathsResult paths;
  // Every section's tally, in the order above (the order of report.json's warnings).
  std::vector<const Tally*> tallies() const;
};

// report.json: the study as a whole (protocol, design, participants, exclusions, `summary`'s counts and
// warnings, the figures of `plots`) and every section's entry.
nlohmann::json render_json(const Context& ctx, const SectionResults& results, const ReportSummary& summary,
                           const std::vector<PlotSpec>& plots);

// Every CSV file of the report but trials.csv (the export's): file name -> text.
std::map<std::string, std::string> render_csv(const Context& ctx, const SectionResults& results);

}  // namespace dtlab::report::detail

// The sections of the report, as computations. Each section is a function
// that computes what the section found from the study (through the Context,
// which holds the inputs) into a plain result struct: numbers, the tests it
// reported, and its Tally (how many tests, which warnings). Its layout, the
// section's part of the Document, is a separate function (layout.h) that
// takes the result and computes nothing. A section that a later one builds
// on hands over a declared result (TimeResult, AccuracyResult) as an
// argument: no section reads another's output through the Context, so the
// order is written in the signatures. report.cpp computes every section
// first, in a paper's order (data and method, completion time, accuracy,
// mixed models, speed-accuracy, questionnaire, instruments, position
// effects, frame-time audit, planning the next study, walked paths), then
// lays them out in the same order; report.json and the CSV files are laid
// out from the results by one renderer each (render_data.h). Sections never
// build JSON, never write CSV or any file and never touch the database.
#pragma once
#include <deque>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "analysis/report/detail/cells.h"
#include "analysis/report/detail/report_design.h"
#include "analysis/report/detail/document.h"
#include "analysis/report/detail/plots.h"
#include "analysis/report/detail/study_data.h"
#include "analysis/report/detail/inference.h"
#include "analysis/report/detail/mixed_models.h"
#include "analysis/report/detail/rmcorr.h"
#include "analysis/report/planning.h"
#include "analysis/report/report.h"

namespace dtlab::report::detail {

// What every section hands back beside its findings: the statistical tests it reported (summed into
// report.json's summary.tests) and the data problems it found (report.json's warnings, in section order).
struct Tally {
  int tests = 0;
  std::vector<std::string> warnings;
};

// The inputs every section reads: the study, its design, the options, the analysed participants; and the
// storage its results point into.
struct Context {
  Context(const StudyData& d, const Design& g, const ReportOptions& o) : data(d), design(g), options(o) {}
  const StudyData& data;
  const Design& design;
  const ReportOptions& options;

  std::vector<std::string> subjects;     // participants with analysed trials, enrollment order
  std::vector<std::string> simulated;    // of those, the ones marked simulated
  long long analysed_trials = 0;

  // Storage, not output: the results point into it (their TestReport and CellMatrix pointers).
  std::deque<CellMatrix> matrices;         // stable storage: TestReport points into it
  std::deque<TestReport> reports;          // every test reported, in order (tests.csv)
  std::vector<std::string> report_section; // section id of reports[i]

  // True for a trial the report analyses: recorded, not practice, levels known.
  bool analysed(const TrialRow& t) const;
  const CellMatrix& keep(CellMatrix m) { matrices.push_back(std::move(m)); return matrices.back(); }
  // Aggregates per subject x cell of `factors` over the analysed trials passing `include`.
  const CellMatrix& cells(const std::vector<int>& factors, const TrialFilter& include, const Reducer& reduce);
  // Stores a test for tests.csv and adds the tests it reports to `tally`; returns the stored copy.
  const TestReport& add_test(const std::string& section, TestReport r, Tally& tally);
  std::string level_label(int f, int level) const { return design.level_label(f, level); }
};

// A block of a long means CSV: a participant x cell matrix with its measure's name and its scope
// (task id, "overall"), one row per participant and cell (matrix_csv_rows).
struct MeansBlock {
  const CellMatrix* m = nullptr;
  std::string measure, scope;
};
using TestRows = std::vector<std::pair<std::string, const TestReport*>>;  // a table's row label and its test

// What the completion-time section found, for the sections that build on it and the renderers (the tests
// live in ctx.reports).
struct TimeResult {
  std::map<std::string, const TestReport*> by_scope;  // the ANOVA of completion time by scope: task id, "overall"
  std::vector<const TestReport*> tests;               // every test the section stored, in order (planning reads it)
  TestRows rows;                                      // the ANOVAs per task, then "All tasks"
  std::vector<MeansBlock> means;                      // their matrices (completion_time_means.csv)
  std::vector<const TestReport*> rank_tests;          // the rank tests of each row's factors
  std::optional<TestRows> log_rows;                   // --log-time: the ANOVAs of log times, as `rows`
  Tally tally;
  // The ANOVA of `scope`, or nullptr.
  const TestReport* of(const std::string& scope) const;
};
// A row of the accuracy table: a task (or the counting tasks together) and one of its measures' test.
struct AccuracyRow {
  std::string label, measure, unit;
  const TestReport* r = nullptr;
  std::string published;  // the scope of its published row ([reference_results] accuracy), "" = none
  int decimals = 3;
};
// What the accuracy section found: per task, the test of its per-trial error measure.
struct AccuracyResult {
  std::map<std::string, const TestReport*> by_task;
  std::vector<const TestReport*> tests;  // every test the section stored, in order
  std::vector<AccuracyRow> rows;         // the table's rows, one test each (empty: no task is scored)
  std::vector<MeansBlock> means;         // the matrices of the rows and the signed errors (accuracy_means.csv)
  std::vector<std::string> notes;        // under the table: trials without an answer, true counts of 0
  Tally tally;
  // The test of task `id`'s per-trial error measure, or nullptr.
  const TestReport* of(const std::string& id) const;
};

// What the participants section found: consent, withdrawals, the demographics, pauses and notes.
struct ParticipantsResult {
  struct NumericField {
    std::string id, prompt;
    stats::Descriptives d;
  };
  struct ChoiceField {
    std::string id, prompt;
    std::vector<std::pair<std::string, int>> counts;  // per option in the protocol's order, then other answers
    int answered = 0;
  };
  struct TextField {
    std::string id, prompt;
    int answered = 0;
  };
  struct AroundSession {  // one participant with a pause or a note
    std::string id;
    int pauses = 0;
    double paused_s = 0;
    std::vector<std::string> notes;
  };
  int described = 0;  // participants the demographics describe (the analysed ones)
  bool consent_asked = false;
  int consented = 0, declined = 0;
  std::vector<std::string> withdrawn;  // left out of every analysis
  std::vector<NumericField> numeric;
  std::vector<ChoiceField> choices;
  std::vector<TextField> texts;
  std::vector<AroundSession> around;
  std::vector<std::string> study_notes;
  Tally tally;
};

struct FramesResult;

// What the data section found: sessions and trials as recorded (its warnings: incomplete sessions, unknown
// levels, excluded data, too few participants).
struct OverviewResult {
  int finished = 0, running = 0, abandoned = 0, never_started = 0;  // sessions by status
  long long planned = 0, recorded = 0, practice = 0;                // trials
  Tally tally;
};
OverviewResult section_overview(Context& ctx);  // sessions and trials, the data's warnings
ParticipantsResult section_participants(Context& ctx);  // demographics, pauses and notes per participant
TimeResult section_time(Context& ctx);      // completion time: ANOVAs, rank tests, --log-time
AccuracyResult section_errors(Context& ctx);  // accuracy: relative error, correctness, distance
// The tests of section_time and section_errors alone (no rank or log-time tests; the tests are still stored
// in ctx): what `dtlab power` plans. A TimeResult from time_tests holds the per-task and overall ANOVAs.
TimeResult time_tests(Context& ctx);
AccuracyResult accuracy_tests(Context& ctx);
// What the mixed models found: every model fitted (tests: one per term of each fit).
struct MixedResult {
  std::vector<MixedModelResult> models;
  Tally tally;
};
// Mixed models of the trials beside the ANOVAs of `time` and `accuracy` (section_mixed.cpp).
MixedResult section_mixed_models(Context& ctx, const TimeResult& time, const AccuracyResult& accuracy);
// What speed-accuracy found for a task with both a time and an error test.
struct SpeedAccuracyRow {
  struct Level {
    std::string level;
    double time_s = 0, error = 0;  // means over participants; error lower = better
  };
  struct Differences {  // second primary level minus first (error flipped for letters: lower = better)
    double time_s = 0, time_p = 0, error = 0, error_p = 0;
  };
  std::string task, error_measure;
  std::vector<Level> levels;               // per level of the primary factor
  std::optional<Differences> differences;  // a two-level primary factor with paired tests of both
  std::string reading;                     // "trade-off: ...", "—" without differences
  RmCorr rmcorr;                           // the trials' time against their error, within participants
};
// Time vs error per condition and participant, from the tests of `time` and `accuracy`; one row per task
// with both (none: no section body beyond a sentence).
struct SpeedAccuracyResult {
  std::vector<SpeedAccuracyRow> rows;
  Tally tally;  // one test per row (its repeated-measures correlation)
};
SpeedAccuracyResult section_speed_accuracy(Context& ctx, const TimeResult& time, const AccuracyResult& accuracy);
// What the questionnaire section found for one item asked at the end of the session.
struct QuestionnaireItemResult {
  enum class Kind { other, rating, numeric, choice };
  struct Share {
    int count = 0;
    double proportion = 0, sd = 0;  // of the participants who answered; NaN when none (sd: when < 2)
    std::string label;              // the option as the table names it (a factor level's label)
  };
  std::string id, type, prompt;
  std::size_t n = 0;                // participants who answered
  Kind kind = Kind::other;
  std::vector<const TestReport*> tests;       // rating: Friedman per combination of the other factors, overall
  stats::Descriptives descriptives;           // numeric: over the participants' values
  std::optional<double> proportion_correct;   // numeric depth test: mean pairs correct / pairs
  std::string scale;                          // numeric: "scale 1–7", "pairs correct of 10"
  int answered = 0;                           // choice: answers counted (the shares' denominator)
  std::map<std::string, Share> choices;       // choice: per option chosen
  std::optional<stats::SignTestResult> sign_test;  // choice between two options: second against first
  std::string first_option, second_option;    // those options, when sign_test is set
};
// What the questionnaire section found: `items` nullopt when the protocol asks nothing it reports; an empty
// list when no answer is recorded; else one result per item, in protocol order.
struct QuestionnaireResult {
  std::optional<std::vector<QuestionnaireItemResult>> items;
  Tally tally;
};
QuestionnaireResult section_questionnaire(Context& ctx);  // ratings, preference, self-reported depth, depth test
// A one-factor design over positions ("1", "2", ...) for the position tests (not movable: its design
// points into its protocol).
struct PositionDesign {
  protocol::Protocol protocol;
  Design design;
  PositionDesign(const std::string& name, int levels);
  PositionDesign(const PositionDesign&) = delete;
  PositionDesign& operator=(const PositionDesign&) = delete;
};
// What the position section found: the balance of conditions over block positions, the tests of
// relative time by block position and by repetition, and the order row's mixed ANOVA.
struct PositionResult {
  struct Level {
    int position = 0;                 // 1-based
    stats::Descriptives relative;     // relative time over the test's participants (the test's cell)
    stats::Descriptives time_s;       // the same participants' mean times in seconds
  };
  struct Split {
    std::string key;                              // "block" or "repetition"
    std::shared_ptr<const PositionDesign> design;  // the test's one-factor design
    const TestReport* test = nullptr;
    std::vector<Level> levels;
  };
  int blocks = 0;                                   // block positions (the largest seen)
  std::map<std::string, std::vector<int>> balance;  // condition -> participants per block position
  bool balanced = true;
  std::vector<Split> splits;                        // block position, repetition (those with >= 2 levels)
  const TestReport* order_row = nullptr;            // nullptr: not tested
  std::size_t order_rows_seen = 0, order_complete = 0;  // order rows among the complete participants, and they
  Tally tally;
};
// Position in the session, order rows of the counterbalancing; the overall completion time of `time`.
PositionResult section_position(Context& ctx, const TimeResult& time);
// What the frame-time audit found, per condition, and the warnings the top of the report repeats.
struct FramesResult {
  struct Condition {
    std::string condition, method, display;  // display: "headless 160 × 120"; "; "-joined when several
    long long trials = 0, trials_with_frames = 0, frames = 0;
    double display_hz = 0;                 // median over the trials with frames (NaN: none)
    bool display_hz_known = false;         // some analysed trial recorded its display's rate
    double median_fps = 0, median_steady_ms = 0;
    bool below_display = false;
    long long late_frames = 0, steady_frames = 0;  // late ones of the frames after each trial's first
    double late_share = 0;                 // NaN without steady frames
    double median_first_ms = 0, median_p95_ms = 0;
    long long slow_trials = 0, p95_trials = 0;  // trials whose p95 exceeds the threshold, of those with a p95
    double slow_share = 0;                 // NaN without a p95
  };
  double threshold_ms = 0, min_fps = 0, rate_spread = 0;
  double below_tolerance = 0;  // below the display: the median frame longer than (1 + this) x a refresh interval
  double assumed_hz = 0;       // the display rate late frames are counted against where it is unknown
  long long trials_with_frames = 0;
  std::vector<Condition> conditions;  // one per protocol condition, in order
  std::vector<std::string> warnings;  // why render cost may confound completion time; empty: no reason
  std::vector<std::string> below;     // conditions below the display's rate
  std::vector<std::string> renderers;        // every renderer the analysed trials recorded, sorted
  std::vector<std::string> simulated_sizes;  // "160 × 120": framebuffers of simulated participants' trials
  bool simulated_frames = false;             // a simulated participant's trial has frames
  bool software_renderer = false;            // some renderer is a software rasterizer (llvmpipe, ...)
  bool people = false;                       // some trial with frames is a person's
  Tally tally;                               // warnings: `warnings`, each prefixed "frame-time audit: "
};
FramesResult section_frames(Context& ctx);  // frame-time audit per condition
// What planning the next study found: the analytic power of each effect at `sizes` participants.
struct PlanningResult {
  std::vector<int> sizes;
  double alpha = 0.05;
  std::vector<PlannedEffect> effects;
  std::vector<std::string> not_planned;  // tests that could not be planned, with why
  Tally tally;
};
// Planning the next study: analytic power of every ANOVA effect of `time` and `accuracy`.
PlanningResult section_planning(Context& ctx, const TimeResult& time, const AccuracyResult& accuracy);

// A walked-path figure written beside the report (report.cpp draws them through ReportOptions::path_figure).
struct PathFigure {
  std::string participant, task;
  int trials = 0;    // analysed trials of the task the figure was asked for
  std::string file;  // relative to the report's directory, e.g. "paths/03-P03-T3.svg"
};
// The walked-path figures drawn and the trials left out of them ("participant trial N: why").
struct PathsResult {
  std::vector<PathFigure> figures;
  std::vector<std::string> left_out;
  bool shown = false;  // the section exists: some figure or some trial left out
  Tally tally;         // a warning when trials were left out
};
// The result of drawing `figures` and leaving out `left_out`.
PathsResult section_paths(std::vector<PathFigure> figures, std::vector<std::string> left_out);

// --- the tests beside the completion-time ANOVAs (section_time_checks.cpp) ------------------------
// Rank tests of each factor of each row on its marginal means (Wilcoxon for 2 levels, else Friedman);
// the tests go to result.rank_tests and result.tests, one per factor of each of result.rows.
void run_rank_tests(Context& ctx, TimeResult& result);

// --log-time: ANOVAs of log completion times per task and overall (stored in result.tests); returns the
// rows of their table (label, test).
TestRows run_log_time(Context& ctx, TimeResult& result);
// Mean over the condition's tasks of the per-task means of `field`; NaN unless every task of the
// condition's scenario has a trial (no silent re-weighting). (section_time.cpp)
Reducer overall_time(const Design& d, const std::function<std::optional<double>(const TrialRow&)>& field);

// --- (section_common.cpp) ----------------------------------------------------------------------
// Fills ctx.subjects (participants with analysed trials, enrollment order) and ctx.analysed_trials.
void collect_subjects(Context& ctx);

}  // namespace dtlab::report::detail

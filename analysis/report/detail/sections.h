// The sections of the report, each a function that reads the study through
// the Context, runs its tests and returns what it found as a plain result
// struct (numbers, tables, warnings) beside its part of the Document. A
// section that a later one builds on returns a declared result (TimeResult,
// AccuracyResult) and the later one takes it as an argument: no section reads
// another's output through the Context, so the call order is written in the
// signatures. The order in report.cpp is the order of a paper's results: data
// and method, completion time, accuracy, mixed models of the trials,
// speed-accuracy, questionnaire, instruments, position effects, frame-time
// audit, then planning the next study. report.json and the CSV files are laid
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

struct Context {
  Context(const StudyData& d, const Design& g, const ReportOptions& o) : data(d), design(g), options(o) {}
  const StudyData& data;
  const Design& design;
  const ReportOptions& options;

  std::vector<std::string> subjects;     // participants with analysed trials, enrollment order
  std::vector<std::string> simulated;    // of those, the ones marked simulated
  long long analysed_trials = 0;

  Document doc;
  std::vector<PlotSpec> plots;
  std::vector<std::string> warnings;       // data problems, shown at the top
  int tests = 0;                           // statistical tests reported

  std::deque<CellMatrix> matrices;         // stable storage: TestReport points into it
  std::deque<TestReport> reports;          // every test reported, in order (tests.csv)
  std::vector<std::string> report_section; // section id of reports[i]

  // True for a trial the report analyses: recorded, not practice, levels known.
  bool analysed(const TrialRow& t) const;
  const CellMatrix& keep(CellMatrix m) { matrices.push_back(std::move(m)); return matrices.back(); }
  // Aggregates per subject x cell of `factors` over the analysed trials passing `include`.
  const CellMatrix& cells(const std::vector<int>& factors, const TrialFilter& include, const Reducer& reduce);
  // Adds the figure to `s` and the plot to be drawn, or a note when the plot has nothing to draw.
  void add_figure(Section& s, PlotSpec p, const std::string& caption);
  // Stores a test for tests.csv and counts its tests; returns the stored copy.
  const TestReport& add_test(const std::string& section, TestReport r);
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
};

void section_overview(Context& ctx);        // title, data summary, warnings, methods
ParticipantsResult section_participants(Context& ctx);  // demographics, pauses and notes per participant
TimeResult section_time(Context& ctx);      // completion time: Table III layout, full ANOVAs, Fig. 9, participants
AccuracyResult section_errors(Context& ctx);  // accuracy: relative error, correctness, distance
// The tests of section_time and section_errors alone, without their layout (no document section, no
// report.json entry, no figure; the tests are still stored in ctx): what `dtlab power` plans. A TimeResult
// from time_tests holds the per-task and overall ANOVAs, not section_time's rank and log-time tests.
TimeResult time_tests(Context& ctx);
AccuracyResult accuracy_tests(Context& ctx);
// Mixed models of the trials beside the ANOVAs of `time` and `accuracy` (section_mixed.cpp); every model fitted.
std::vector<MixedModelResult> section_mixed_models(Context& ctx, const TimeResult& time, const AccuracyResult& accuracy);
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
std::vector<SpeedAccuracyRow> section_speed_accuracy(Context& ctx, const TimeResult& time, const AccuracyResult& accuracy);
// What the questionnaire section found for one item asked at the end of the session.
struct QuestionnaireItemResult {
  enum class Kind { other, rating, numeric, choice };
  struct Share {
    int count = 0;
    double proportion = 0, sd = 0;  // of the participants who answered; NaN when none (sd: when < 2)
  };
  std::string id, type, prompt;
  std::size_t n = 0;                // participants who answered
  Kind kind = Kind::other;
  std::vector<const TestReport*> tests;       // rating: Friedman per combination of the other factors, overall
  stats::Descriptives descriptives;           // numeric: over the participants' values
  std::optional<double> proportion_correct;   // numeric depth test: mean pairs correct / pairs
  std::map<std::string, Share> choices;       // choice: per option chosen
  std::optional<stats::SignTestResult> sign_test;  // choice between two options: second against first
  std::string first_option, second_option;    // those options, when sign_test is set
};
// What the questionnaire section found: nullopt when the protocol asks nothing it reports; an empty list
// when no answer is recorded; else one result per item, in protocol order.
using QuestionnaireResult = std::optional<std::vector<QuestionnaireItemResult>>;
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
  std::map<std::string, std::vector<int>> balance;  // condition -> participants per block position
  bool balanced = true;
  std::vector<Split> splits;                        // block position, repetition (those with >= 2 levels)
  const TestReport* order_row = nullptr;            // nullptr: not tested
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
  long long trials_with_frames = 0;
  std::vector<Condition> conditions;  // one per protocol condition, in order
  std::vector<std::string> warnings;  // why render cost may confound completion time; empty: no reason
  std::vector<std::string> below;     // conditions below the display's rate
};
FramesResult section_frames(Context& ctx);  // frame-time audit per condition
// The audit's warnings also at the top of the report, in the data section (section_overview's), where a
// reader starts; the report's assembly calls it once both sections exist.
void warn_at_top(Document& doc, const FramesResult& frames);
// What planning the next study found: the analytic power of each effect at `sizes` participants.
struct PlanningResult {
  std::vector<int> sizes;
  double alpha = 0.05;
  std::vector<PlannedEffect> effects;
  std::vector<std::string> not_planned;  // tests that could not be planned, with why
};
// Planning the next study: analytic power of every ANOVA effect of `time` and `accuracy`.
PlanningResult section_planning(Context& ctx, const TimeResult& time, const AccuracyResult& accuracy);
// What the report does not say; files written (`path_figures`: section_paths added its section).
void section_notes(Context& ctx, bool path_figures);

// A walked-path figure written beside the report (report.cpp draws them through ReportOptions::path_figure).
struct PathFigure {
  std::string participant, task;
  int trials = 0;    // analysed trials of the task the figure was asked for
  std::string file;  // relative to the report's directory, e.g. "paths/03-P03-T3.svg"
};
// The table linking them, and the trials left out of them ("participant trial N: why"; also a warning).
// Returns whether it added the section (false: no figure and nothing left out).
bool section_paths(Context& ctx, const std::vector<PathFigure>& figures, const std::vector<std::string>& left_out);

// --- plots shared by the sections (section_time.cpp) -------------------------------------------
// Bars per row (x groups) and primary level (series), SD error bars (the article's Figs. 9 and 10).
PlotSpec bar_plot(const Context& ctx, const std::vector<std::pair<std::string, const TestReport*>>& rows,
                  const std::string& id, const std::string& ylabel);
// One panel per row: each participant's marginal means per primary level (grey lines), the mean (black).
PlotSpec participant_lines(const Context& ctx, const std::vector<std::pair<std::string, const TestReport*>>& rows,
                           const std::string& id, const std::string& ylabel);

// --- checks beside the completion-time ANOVAs (section_time_checks.cpp) ---------------------------
// Rank tests of each factor of each row on its marginal means (Wilcoxon for 2 levels, else Friedman);
// the tests are appended to `out` and to `stored`.
void add_rank_tests(Context& ctx, Section& s, const std::vector<std::pair<std::string, const TestReport*>>& rows,
                    std::vector<const TestReport*>& out, std::vector<const TestReport*>& stored);
// Shapiro-Wilk of each row's ANOVA residuals (a table) and their normal Q-Q plots (one figure).
void add_normality(Context& ctx, Section& s, const std::vector<std::pair<std::string, const TestReport*>>& rows,
                   const std::string& measure, bool log_scale);

// --log-time: ANOVAs of log completion times per task and overall, a table beside the seconds'; the stored
// tests are appended to `stored`. Returns the rows of the table (label, test).
TestRows add_log_time(Context& ctx, Section& s, std::vector<const TestReport*>& stored);
// Mean over the condition's tasks of the per-task means of `field`; NaN unless every task of the
// condition's scenario has a trial (no silent re-weighting). (section_time.cpp)
Reducer overall_time(const Design& d, const std::function<std::optional<double>(const TrialRow&)>& field);

// --- helpers shared by the sections (section_common.cpp) ---------------------------------------
// Fills ctx.subjects (participants with analysed trials, enrollment order) and ctx.analysed_trials.
void collect_subjects(Context& ctx);
// An effect's df as a cell: "1, 15", or Greenhouse-Geisser corrected where ε < 1 ("2.39, 35.89").
std::string df_cell(const stats::Effect& e);
// F, df, p and ηp² of the effect as table cells (df and p as above); four dashes for nullptr.
std::vector<std::string> effect_cells(const stats::Effect* e);
// Paired comparisons (post-hoc or simple effects): n, mean difference, SE, 95% CI, t, df, p, Holm p, d_z.
Table comparison_table(const std::vector<stats::Comparison>& list, const std::string& id, const std::string& caption,
                       const std::string& unit);
// Notes for a test's table: n, excluded participants, warnings of the statistics library.
std::vector<std::string> test_notes(const TestReport& r);
// The full ANOVA table of a TestReport (df, GG-corrected where ε < 1, MSE, F, APA p, ηp² with
// its 90% CI, ηG², Mauchly's W and p, both epsilons), under it one APA sentence per effect, and
// for each followed-up interaction its simple effects and an interaction plot (within-subject CIs).
void add_anova(Context& ctx, Section& s, const TestReport& r, const std::string& id, const std::string& caption);
// "mean (SD)" per level of the design's primary factor, or "—" when it is not among the factors.
std::vector<std::string> primary_cells(const TestReport& r, const Design& d, int decimals);

}  // namespace dtlab::report::detail

// The report's layout: one function per section that turns the section's
// result (sections.h) into its part of the Document (paragraphs, tables,
// figures, call-outs) and the plots its figures draw. Each takes the Context
// const, so it cannot run or store a test, and computes no statistic: a
// number it prints is in a result; only a figure's geometry (bar heights,
// a Q-Q plot's normal quantiles, a participant's points) is worked out where
// the figure is drawn, from the matrices the results point to. report.cpp
// calls them in a paper's order after every section has computed. Never
// builds JSON, never writes a file.
#pragma once
#include <string>
#include <vector>

#include "analysis/report/detail/document.h"
#include "analysis/report/detail/plots.h"
#include "analysis/report/detail/questionnaire_results.h"
#include "analysis/report/detail/sections.h"

namespace dtlab::report::detail {

// What the lay_out_* functions build: the Document the text renderers print and the plots its figures
// draw, in order of appearance.
struct Layout {
  Document doc;
  std::vector<PlotSpec> plots;
  // Adds the figure to `s` and the plot to be drawn, or a note when the plot has nothing to draw.
  void add_figure(Section& s, PlotSpec p, const std::string& caption);
};

// --- one per section, in the report's order -------------------------------------------------------
// Title, data summary, warnings (with the frame-time audit's, where a reader starts), methods
// (layout_overview.cpp, as the next two).
void lay_out_overview(Layout& out, const Context& ctx, const OverviewResult& r, const FramesResult& frames);
// Consent, demographics, pauses and notes.
void lay_out_participants(Layout& out, const ParticipantsResult& r);
// Table III layout, full ANOVAs, Fig. 9, participants, rank tests, normality, log times (layout_time.cpp).
void lay_out_time(Layout& out, const Context& ctx, const TimeResult& r);
// The accuracy table, its notes and full ANOVAs (layout_accuracy.cpp, as the next).
void lay_out_accuracy(Layout& out, const Context& ctx, const AccuracyResult& r);
// The table, the correlations and the scatter (its points: the participant x cell means of `time` and
// `accuracy`).
void lay_out_speed_accuracy(Layout& out, const Context& ctx, const SpeedAccuracyResult& r, const TimeResult& time,
                            const AccuracyResult& accuracy);
// Per measure the models' table, their sentences, the R calls and where they disagree (layout_models.cpp).
void lay_out_mixed_models(Layout& out, const Context& ctx, const MixedResult& r);
// The ratings' tests and the other items (layout_questionnaire.cpp).
void lay_out_questionnaire(Layout& out, const Context& ctx, const QuestionnaireResult& r);
// Means per condition and their tests, the end-of-session measures, counts and free texts
// (layout_instruments.cpp).
void lay_out_instruments(Layout& out, const Context& ctx, const QuestionnaireResults& res);
// Balance, the tests by position, the order row's ANOVA and the figure (layout_position.cpp).
void lay_out_position(Layout& out, const Context& ctx, const PositionResult& r);
// The audit's table and what it says (layout_frames.cpp).
void lay_out_frames(Layout& out, const FramesResult& r);
// The power table (layout_models.cpp).
void lay_out_planning(Layout& out, const Context& ctx, const PlanningResult& r);
// The table linking the walked-path figures, and the trials left out of them; nothing unless r.shown
// (layout_overview.cpp, as the next).
void lay_out_paths(Layout& out, const PathsResult& r);
// What the report does not say; files written (`path_figures`: the walked-paths section exists).
void lay_out_notes(Layout& out, const Context& ctx, bool path_figures);

// --- parts of the completion-time section (layout_time.cpp) ----------------------------------------
// Bars per row (x groups) and primary level (series), SD error bars (the article's Figs. 9 and 10).
PlotSpec bar_plot(const Context& ctx, const TestRows& rows, const std::string& id, const std::string& ylabel);
// One panel per row: each participant's marginal means per primary level (grey lines), the mean (black).
PlotSpec participant_lines(const Context& ctx, const TestRows& rows, const std::string& id, const std::string& ylabel);
// The rank tests' table: one row per rank test, in the order run_rank_tests ran them.
void lay_out_rank_tests(Section& s, const Context& ctx, const TimeResult& r);
// Shapiro-Wilk of each row's ANOVA residuals (a table) and their normal Q-Q plots (one figure).
void lay_out_normality(Layout& out, Section& s, const TestRows& rows, const std::string& measure, bool log_scale);
// --log-time: the log ANOVAs' table beside the seconds', sentences, the overall ANOVA and its residuals.
void lay_out_log_time(Layout& out, Section& s, const Context& ctx, const TestRows& rows);

// --- helpers shared by the layouts (layout_common.cpp) ---------------------------------------------
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
void add_anova(Layout& out, Section& s, const Design& d, const TestReport& r, const std::string& id,
               const std::string& caption);
// "mean (SD)" per level of the design's primary factor, or "—" when it is not among the factors.
std::vector<std::string> primary_cells(const TestReport& r, const Design& d, int decimals);
// The paired difference of a two-level primary factor with its 95% CI, "0.31 [0.12, 0.50]", or "—".
std::string difference_text(const TestReport& r, int decimals);

}  // namespace dtlab::report::detail

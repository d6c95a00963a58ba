// The report's opening and closing: the data as recorded (participants,
// sessions, trials, who is simulated, what is incomplete and left out), the
// method paragraph that says how every number is computed, and the closing
// notes (the files written, what the report does not do). section_overview
// counts and collects the data's warnings; lay_out_overview and
// lay_out_notes only lay out (they compute no statistic).
#include <algorithm>
#include <cmath>
#include <set>

#include "analysis/report/detail/format.h"
#include "analysis/report/detail/sections.h"

namespace dtlab::report::detail {
namespace {

// The source of the published results the protocol compares with; "" when it declares none.
std::string published_source(const Context& ctx) {
  const auto& r = ctx.data.protocol.reference_results;
  return r ? r->source : "";
}

std::string join(const std::vector<std::string>& v, const std::string& sep) {
  std::string out;
  for (size_t i = 0; i < v.size(); ++i) out += (i ? sep : "") + v[i];
  return out;
}

// The design revision and protocol text notes at the top of the data section.
void revision_notes(const StudyData& data, Section& s) {
  if (data.design_revisions > 1)
    s.add(Callout{"warning",
                  "Design revision " + std::to_string(data.design_revision) + " of " +
                      std::to_string(data.design_revisions) + " of this database",
                  {"The protocol was changed during the study in a way that changes what runs (--allow-protocol-change). "
                   "This report analyses only the participants who ran under design revision " +
                       std::to_string(data.design_revision) + " (" + std::to_string(data.other_revision_trials) +
                       " trials of other revisions are not pooled with them; `dtlab analyze --revision N` chooses)."}});
  if (data.protocol_texts > 1)
    s.text("The protocol text was revised " + std::to_string(data.protocol_texts - 1) +
           (data.protocol_texts == 2 ? " time" : " times") +
           " without changing its design (comments, wording): all its participants are pooled, and the latest text "
           "is shown here.");
}

// The call-out naming the simulated participants, when there are any.
void simulated_callout(const Context& ctx, Section& s) {
  if (ctx.simulated.empty()) return;
  const bool all = ctx.simulated.size() == ctx.subjects.size();
  s.add(Callout{"warning",
                all ? "Simulated participants: every participant in this database is simulated."
                    : "Simulated participants: " + std::to_string(ctx.simulated.size()) + " of " +
                          dtlab::count(static_cast<long long>(ctx.subjects.size()), "participant") + " are simulated.",
                {"The database marks them as simulated in their enrollment record (demographics): " +
                     join(ctx.simulated, ", ") + ".",
                 "Their times, answers and ratings come from a model of a participant, not from people: the "
                 "statistics below describe that model. They test the pipeline; they are not evidence about "
                 "human performance" + (published_source(ctx).empty() ? std::string(".")
                                                  : " and not a replication of " + published_source(ctx) + ".")}});
}

// The sentence naming the factors, the order scheme and the tasks.
std::string design_sentence(const Design& d) {
  const auto& p = *d.protocol;
  std::string design = "Design: ";
  for (size_t f = 0; f < p.factors.size(); ++f)
    design += (f ? " x " : "") + p.factors[f].name + " {" + join(p.factors[f].levels, ", ") + "}";
  design += " within subjects; " + std::to_string(p.conditions.size()) + " conditions ordered by " +
            std::string(protocol::to_string(p.order.scheme)) + " (" + std::to_string(declared_order_rows(p)) +
            " order rows). Tasks: ";
  std::vector<std::string> tasks;
  for (const auto& t : d.tasks)
    tasks.push_back(d.task_label(t) + " in " + t.scenario + ", " + dtlab::count(t.trials, "trial") + " per condition");
  return design + join(tasks, "; ") + ". Primary factor of the tables: " + d.factor(d.primary).name + ".";
}

// Incomplete sessions, unknown levels, exclusions, too few participants: shown at the top, and report.json's warnings.
std::vector<std::string> data_warnings(const Context& ctx, long long unknown) {
  const StudyData& data = ctx.data;
  std::vector<std::string> warnings;
  for (const auto& pr : data.participants) {
    if (pr.session_status == store::SessionStatus::running || pr.session_status == store::SessionStatus::abandoned)
      warnings.push_back(pr.id + ": session " + store::to_string(*pr.session_status) + " with " + std::to_string(pr.recorded) + " of " +
                         dtlab::count(pr.planned, "trial") + " recorded; their recorded trials are analysed, and tests "
                         "needing a missing condition leave them out (named under each table).");
    if (!pr.session_status) warnings.push_back(pr.id + ": enrolled, no session started; not analysed.");
    else if (pr.recorded == 0) warnings.push_back(pr.id + ": no trial recorded; not analysed.");
  }
  if (unknown)
    warnings.push_back(dtlab::count(unknown, "trial") + " carry a factor level the protocol does not declare; left out.");
  if (!data.excluded_participants.empty() || data.excluded_trials > 0)
    warnings.push_back(data.with_excluded
                           ? "Excluded data are KEPT in this analysis (--with-excluded): " +
                                 std::to_string(data.excluded_trials) + " excluded trials are analysed; the "
                                 "exclusions are listed below."
                           : std::to_string(data.excluded_trials) + " recorded trial" +
                                 (data.excluded_trials == 1 ? " is" : "s are") + " excluded (" +
                                 std::to_string(data.excluded_participants.size()) + " excluded participant" +
                                 (data.excluded_participants.size() == 1 ? "" : "s") +
                                 ") and left out of every table and test; each exclusion and its reason is listed "
                                 "below.");
  if (ctx.subjects.size() < 2)
    warnings.push_back("Only " + std::to_string(ctx.subjects.size()) + " participant: no test across participants "
                       "is possible (F and p are undefined); the tables show descriptives only.");
  return warnings;
}

// Participants: enrollment, order row, session and trials.
Table participants_table(const Context& ctx) {
  Table pt;
  pt.id = "table-participants";
  pt.caption = "Participants: enrollment, order row of the counterbalancing, session and trials.";
  pt.header = {"Participant", "Index", "Order row", "Session", "Trials", "Resumes", "Simulated"};
  for (const auto& pr : ctx.data.participants) {
    const bool sim = std::find(ctx.simulated.begin(), ctx.simulated.end(), pr.id) != ctx.simulated.end();
    pt.rows.push_back({pr.id, std::to_string(pr.index), std::to_string(pr.order_row),
                       pr.session_status ? store::to_string(*pr.session_status) : "none",
                       std::to_string(pr.recorded) + " / " + std::to_string(pr.planned), std::to_string(pr.resumes),
                       sim ? "yes" : "no"});
  }
  pt.notes.push_back("Index: 0-based enrollment index. Trials: recorded / planned. Resumes: times the session was "
                     "resumed after an interruption.");
  return pt;
}

// Every exclusion decision, in order.
Table exclusions_table(const StudyData& data) {
  Table xt;
  xt.id = "table-exclusions";
  xt.caption = "Exclusions: every decision recorded about these participants (`dtlab exclude`, `dtlab include`, "
               "the experimenter console), in order; the latest decision about a participant or trial holds.";
  xt.header = {"Participant", "Trial", "Decision", "Reason", "By", "When (UTC)"};
  xt.text_columns = 6;
  for (const auto& x : data.exclusions)
    xt.rows.push_back({x.participant, x.position ? std::to_string(*x.position) : "all",
                       x.exclude ? "excluded" : "included again", x.reason.empty() ? "-" : x.reason,
                       x.by.empty() ? "-" : x.by, x.at});
  xt.notes.push_back(data.with_excluded ? "Excluded data are kept in this report (--with-excluded)."
                                        : "Excluded participants and trials are left out of every analysis; "
                                          "`dtlab analyze --with-excluded` keeps them.");
  return xt;
}

// The method of analysis: how trials are aggregated and what each test is (fixed text).
Section methods_section() {
  Section m{"methods", "Method of analysis", 2, {}};
  m.text("Aggregation. Every test compares conditions within participants. For each participant and condition the "
         "trials are first reduced to one number (the mean of the trials' completion times, of their relative "
         "errors, or the proportion of correct answers, ...); the tests then treat participants as the units (with "
         "n participants, a two-level factor's F has 1 and n − 1 degrees of freedom). Practice trials are excluded.");
  m.text("Repeated-measures ANOVA (analysis/stats, following R's afex::aov_car and car::Anova with type III sums of "
         "squares): F, its df, MSE, p, partial η² with its 90% confidence interval (noncentral F) and generalized "
         "η². For effects with more than 1 df, Mauchly's test and the Greenhouse-Geisser and Huynh-Feldt epsilons "
         "are given, and df and p are Greenhouse-Geisser corrected where ε < 1; effects with 1 df (two levels) "
         "satisfy sphericity trivially. A two-way interaction with p < .05 is followed up by simple effects (each "
         "factor at each level of the other, Holm-corrected) and an interaction plot with within-subject 95% CIs "
         "(Cousineau-Morey). The residuals of each completion-time ANOVA get the Shapiro-Wilk test and a Q-Q plot. For a factor of two levels the F test equals the paired t test (F = t²), "
         "and the tables add the mean paired difference with its 95% CI and Cohen's d_z. Factors with more than "
         "two levels get Holm-corrected pairwise paired t tests.");
  m.text("Friedman's test (R's friedman.test: mid-ranks for ties with the tie correction) for correctness "
         "proportions and ratings, with Kendall's W and, where it can be enumerated, the exact permutation p; "
         "pairwise Wilcoxon signed-rank tests with Holm correction for more than two levels. As a robustness check "
         "of the completion-time ANOVAs, each factor is tested by ranks on its own marginal means: the Wilcoxon "
         "signed-rank test for two levels, Friedman's test for more.");
  m.text("Missing data: a participant without a value in some cell of a test (no trial recorded, or no answer "
         "given) is left out of that test only (listwise deletion, as afex and friedman.test do); every table names "
         "the participants it left out and the cells they lacked. Descriptives in a test's table are over the "
         "participants the test kept.");
  m.text("p-values are exact tail probabilities from Boost.Math (the upper tail of F and χ², two-sided for t "
         "and Wilcoxon), printed in APA style (p = .002, p < .001); report.json and the CSV files keep them exact "
         "(never rounded to 0, with their log10). The statistics library is validated against NIST StRD certified "
         "values and R (README, \"Statistics\"); the repeated-measures correlation against R's rmcorr.");
  return m;
}

}  // namespace

OverviewResult section_overview(Context& ctx) {
  const StudyData& data = ctx.data;
  OverviewResult r;
  for (const auto& pr : data.participants) {
    r.finished += pr.session_status == store::SessionStatus::finished;
    r.running += pr.session_status == store::SessionStatus::running;
    r.abandoned += pr.session_status == store::SessionStatus::abandoned;
    r.never_started += !pr.session_status;
    r.planned += pr.planned;
    r.recorded += pr.recorded;
  }
  long long unknown = 0;
  for (const auto& t : data.trials) {
    r.practice += t.planned.practice ? 1 : 0;
    if (!t.planned.practice && !ctx.analysed(t)) ++unknown;
  }
  r.tally.warnings = data_warnings(ctx, unknown);
  return r;
}

void lay_out_overview(Layout& out, const Context& ctx, const OverviewResult& r, const FramesResult& frames) {
  const StudyData& data = ctx.data;
  const Design& d = ctx.design;
  const auto& p = *d.protocol;
  out.doc.title = "Results: " + p.title;
  out.doc.subtitle = "Protocol `" + p.id + "` (SHA-256 " + p.sha256.substr(0, 12) + "…), database `" + data.path +
                     "`, recorded with " + data.software_version + ".";

  Section s{"data", "Data", 2, {}};
  // The audit's warnings first, where a reader starts.
  if (!frames.warnings.empty()) {
    std::vector<std::string> items = frames.warnings;
    items.push_back("See the frame-time audit (#frames) before reading completion-time differences as the "
                    "conditions' effect on the participants.");
    s.add(Callout{"warning", "Render cost may confound completion time", items});
  }
  revision_notes(data, s);
  // Who and what is in the file.
  simulated_callout(ctx, s);
  s.text(dtlab::count(static_cast<long long>(data.participants.size()), "participant") + " enrolled under protocol `" + p.id + "`; sessions: " +
         std::to_string(r.finished) + " finished, " + std::to_string(r.running) + " still running (incomplete), " +
         std::to_string(r.abandoned) + " abandoned" +
         (r.never_started ? ", " + std::to_string(r.never_started) + " never started" : "") + ". " +
         std::to_string(r.recorded) + " of " + std::to_string(r.planned) + " planned trials are recorded; " +
         dtlab::count(ctx.analysed_trials, "trial") + " from " + dtlab::count(static_cast<long long>(ctx.subjects.size()), "participant") +
         " are analysed" + (r.practice ? " (" + dtlab::count(r.practice, "practice trial") + " excluded)" : "") +
         ".");
  s.text(design_sentence(d));

  if (!r.tally.warnings.empty()) s.add(Callout{"warning", "Incomplete or excluded data", r.tally.warnings});
  s.add(participants_table(ctx));
  if (!data.exclusions.empty()) s.add(exclusions_table(data));
  out.doc.sections.push_back(std::move(s));
  out.doc.sections.push_back(methods_section());
}

void lay_out_notes(Layout& out, const Context& ctx, bool path_figures) {
  Section s{"notes", "Notes and files", 2, {}};
  s.text("No correction for multiple testing is applied across tasks and measures: every task is its own family.");
  if (ctx.design.reference)
    s.text("The values of " + published_source(ctx) + ", where shown, are printed values the protocol declares "
           "([reference_results]) and quotes for comparison; they are labelled \"" +
           ctx.data.protocol.reference_results->label + "\" and never enter a computation.");
  s.text("Files beside this page: `report.md` (the same tables in Markdown), `report.tex` (the same in LaTeX: "
         "booktabs tables, `pdflatex report.tex`), `report.json` (every number of the "
         "tables, machine-readable), `trials.csv` (the tidy one-row-per-trial table, as `dtlab export` writes "
         "it), `completion_time_means.csv` and `accuracy_means.csv` (the participant x condition values every "
         "test used), `tests.csv` (one row per test), `questionnaire.csv`, `frames.csv`, and `figures/` (each "
         "figure's SVG, PNG and PDF, its data and the gnuplot script `report.gp` that draws them)" +
         std::string(path_figures ? ", and `paths/` (the walked-path figures)" : "") + ".");
  out.doc.sections.push_back(std::move(s));
}

}  // namespace dtlab::report::detail

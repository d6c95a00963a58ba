// The layout of the report's opening and closing (layout.h): the data as
// recorded (participants, sessions, trials, who is simulated, what is
// incomplete and left out, with the frame-time audit's warnings first), the
// method paragraphs that say how every number is computed, the participants
// (consent, demographics, pauses and notes), the walked-path figures and the
// closing notes (the files written, what the report does not do). Lays out
// the results of section_overview, section_participants and section_paths;
// computes nothing.
#include <algorithm>

#include "analysis/report/detail/format.h"
#include "analysis/report/detail/layout.h"

namespace dtlab::report::detail {
namespace {

using NumericField = ParticipantsResult::NumericField;
using ChoiceField = ParticipantsResult::ChoiceField;
using TextField = ParticipantsResult::TextField;
using AroundSession = ParticipantsResult::AroundSession;

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

Table demographics_table(const ParticipantsResult& r) {
  Table t;
  t.id = "table-demographics";
  t.caption = "Demographics of the " + std::to_string(r.described) + " analysed participants.";
  t.header = {"Field", "Question", "n", "Summary"};
  t.text_columns = 2;
  t.last_is_text = true;
  for (const NumericField& f : r.numeric)
    t.rows.push_back({f.id, f.prompt, std::to_string(f.d.n),
                      f.d.n == 0 ? kDash
                                 : "M = " + fixed(f.d.mean, 1) + ", SD = " + fixed(f.d.sd, 1) + ", range " +
                                       fixed(f.d.min, 0) + "–" + fixed(f.d.max, 0)});
  for (const ChoiceField& c : r.choices) {
    std::string counts;
    for (const auto& [option, n] : c.counts) counts += (counts.empty() ? "" : "; ") + option + " " + std::to_string(n);
    t.rows.push_back({c.id, c.prompt, std::to_string(c.answered), counts.empty() ? kDash : counts});
  }
  for (const TextField& f : r.texts)
    t.rows.push_back({f.id, f.prompt, std::to_string(f.answered), "free text (not summarised)"});
  t.notes.push_back("n: participants who answered the field; SD with n − 1.");
  return t;
}

// "Consent: 11 agreed, 1 declined. Withdrawn ...": what a method section says about consent.
std::string consent_text(const ParticipantsResult& r) {
  std::string t;
  if (r.consent_asked)
    t = "Consent: " + std::to_string(r.consented) + " agreed, " + std::to_string(r.declined) +
        " declined (of those who declined, only the refusal is stored).";
  if (!r.withdrawn.empty()) {
    std::string who;
    for (const std::string& w : r.withdrawn) who += (who.empty() ? "" : ", ") + w;
    t += std::string(t.empty() ? "" : " ") + std::to_string(r.withdrawn.size()) +
         (r.withdrawn.size() == 1 ? " participant" : " participants") +
         " withdrew consent (declined it, or withdrew later) and " + (r.withdrawn.size() == 1 ? "is" : "are") +
         " left out of every analysis: " + who + ".";
  }
  return t;
}

}  // namespace

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

void lay_out_participants(Layout& out, const ParticipantsResult& r) {
  Section s{"participants", "Participants", 2, {}};
  if (const std::string consent = consent_text(r); !consent.empty()) s.text(consent);
  if (!r.numeric.empty() || !r.choices.empty() || !r.texts.empty()) s.add(demographics_table(r));
  else s.text("The protocol asks no demographics (`[demographics.*]`).");
  if (!r.around.empty()) {
    Table t;
    t.id = "table-around-sessions";
    t.caption = "Pauses and the experimenter's notes, per participant.";
    t.header = {"Participant", "Pauses", "Paused (s)", "Notes"};
    t.text_columns = 1;
    t.last_is_text = true;
    for (const AroundSession& a : r.around) {
      std::string notes;
      for (const std::string& n : a.notes) notes += (notes.empty() ? "" : "; ") + n;
      t.rows.push_back({a.id, std::to_string(a.pauses), fixed(a.paused_s, 1), notes.empty() ? kDash : notes});
    }
    t.notes.push_back("Paused time is not completion time: a trial's clock stops while the session is paused.");
    s.add(t);
  }
  if (!r.study_notes.empty()) {
    std::string all;
    for (const std::string& n : r.study_notes) all += (all.empty() ? "" : " ") + n + ".";
    s.text("Notes about the study: " + all);
  }
  out.doc.sections.push_back(std::move(s));
}

void lay_out_paths(Layout& out, const PathsResult& r) {
  if (!r.shown) return;
  const std::vector<std::string>& left_out = r.left_out;
  Section s{"paths", "Walked paths", 2, {}};
  s.text("Where each participant walked in the WALKTHROUGH tasks: one figure per participant and task, a floor "
         "plan per trial (each trial has its own building) with the recorded eye positions as a line, the start "
         "cell, the target (circle, T3-like tasks), the position the participant marked (cross) and the distance "
         "walked. The figures are SVG files beside this page.");
  Table t;
  t.id = "table-paths";
  t.caption = "Walked-path figures per participant and task.";
  t.header = {"Participant", "Task", "Trials", "Figure"};
  t.text_columns = 2;
  t.last_is_text = true;
  for (const PathFigure& f : r.figures) {
    t.rows.push_back({f.participant, f.task, std::to_string(f.trials), f.file});
    t.links.push_back(f.file);
  }
  if (!left_out.empty())
    t.notes.push_back("Not drawn: " + std::to_string(left_out.size()) + " trial" + (left_out.size() == 1 ? "" : "s") +
                      ", e.g. " + left_out.front() + ".");
  if (!t.rows.empty()) s.add(std::move(t));
  else s.text(t.notes.front());
  out.doc.sections.push_back(std::move(s));
}

}  // namespace dtlab::report::detail

// The layout of the questionnaire section (layout.h) from its
// QuestionnaireResult: the ratings compared across the primary factor's
// levels (a row per Friedman test, its notes, published values beside, a
// bar chart), and the other items in a second table (a rating or depth test
// described, a choice item's shares with its sign test). Computes nothing.
#include <cmath>

#include "analysis/report/detail/format.h"
#include "analysis/report/detail/layout.h"

namespace dtlab::report::detail {
namespace {

// The section's two tables, filled item by item: the ratings compared across the primary factor's levels
// (summary) and the other items (others); fig_rows: the rating tests the bar chart draws.
struct QuestionnaireTables {
  Table summary, others;
  size_t width = 0;  // summary's columns (rows are padded to it)
  std::vector<std::pair<std::string, const TestReport*>> fig_rows;
};

QuestionnaireTables questionnaire_tables(const Design& d, const std::vector<std::string>& item_ids, size_t& ours) {
  const int pf = d.primary;
  QuestionnaireTables q;
  Table& summary = q.summary;
  summary.id = "table-questionnaire";
  summary.caption = "Questionnaire: ratings per level of " + d.factor(pf).name + " (mean (SD) over participants) "
                    "and Friedman's test.";
  summary.header = {"Item", "Scope"};
  summary.text_columns = 2;
  for (size_t l = 0; l < d.factor(pf).levels.size(); ++l) summary.header.push_back(d.level_label(pf, static_cast<int>(l)));
  summary.header.insert(summary.header.end(), {"n", "χ² (df)", "p", "Kendall's W"});
  ours = summary.header.size();
  for (const auto& h : d.published_header(/*with_f=*/false)) summary.header.push_back(h);
  q.width = summary.header.size();
  Table& others = q.others;
  others.id = "table-questionnaire-items";
  others.caption = "Questionnaire: the other items (self-reports, choices, depth test).";
  others.header = {"Item", "Question", "Summary", "n", "Test", "p"};
  others.text_columns = 3;
  if (d.reference) others.header.push_back(d.published_group(item_ids));
  return q;
}

// The summary table's rows of a rating item: one per test (its scope), with its notes and its bar.
void rating_rows(const Design& d, const QuestionnaireItemResult& item, QuestionnaireTables& q) {
  for (const TestReport* t : item.tests) {
    const TestReport& r = *t;
    const std::string& scope = r.scope;
    std::vector<std::string> row = {item.id, scope};
    for (const auto& c : primary_cells(r, d, 2)) row.push_back(c);
    row.push_back(std::to_string(r.kept.size()));
    row.push_back(r.friedman ? fixed(r.friedman->Q, 2) + " (" + df_text(r.friedman->df) + ")" : kDash);
    row.push_back(r.friedman ? p_text(r.friedman->p) + (std::isfinite(r.friedman->p_exact)
                                                           ? " (exact " + p_text(r.friedman->p_exact) + ")"
                                                           : "")
                             : kDash);
    row.push_back(r.friedman ? bounded(r.friedman->kendall_W) : kDash);
    const auto* a = d.published(item.id, scope);
    for (const auto& c : d.published_cells(item.id, scope, 2, /*with_f=*/false)) row.push_back(a ? c : "");
    row.resize(q.width, "");
    q.summary.rows.push_back(row);
    for (const auto& note : test_notes(r))
      if (note.rfind("n = ", 0) != 0 || !r.excluded.empty())
        q.summary.notes.push_back(item.id + " " + scope + ": " + note);
    q.fig_rows.push_back({scope, &r});
  }
}

// The other items' table row of a numeric item (a rating described, or a depth test).
void numeric_row(const Design& d, const QuestionnaireItemResult& item, QuestionnaireTables& q) {
  const stats::Descriptives& ds = item.descriptives;
  std::vector<std::string> row = {
      item.id, item.prompt + " (" + item.scale + ")",
      "mean (SD) " + mean_sd(ds.mean, ds.sd, 2) + ", median " + fixed(ds.median, 1) +
          (item.proportion_correct ? ", " + percent(*item.proportion_correct) + " of pairs" : ""),
      std::to_string(ds.n), kDash, kDash};
  if (d.reference) row.push_back(d.published_summary(item.id, "overall", 2));
  q.others.rows.push_back(row);
}

// The other items' table row of a choice item: each option's share, and the sign test between two options.
void choice_row(const Design& d, const QuestionnaireItemResult& item, QuestionnaireTables& q) {
  std::string text;
  for (const auto& [option, c] : item.choices)
    text += (text.empty() ? "" : "; ") + c.label + " " + std::to_string(c.count) + "/" + std::to_string(item.answered) +
            " = " + fixed(c.proportion, 2) + " (SD " + fixed(c.sd, 2) + ")";
  std::vector<std::string> row = {item.id, item.prompt, text, std::to_string(item.answered), kDash, kDash};
  if (const auto& st = item.sign_test) {
    row[4] = "sign test: " + std::to_string(st->positive) + " for " + item.second_option + ", " +
             std::to_string(st->negative) + " for " + item.first_option;
    row[5] = p_text(st->p);
  }
  if (d.reference) row.push_back(d.published_summary(item.id, "overall", 2));
  q.others.rows.push_back(row);
}

}  // namespace

void lay_out_questionnaire(Layout& out, const Context& ctx, const QuestionnaireResult& result) {
  const Design& d = ctx.design;
  Section s{"questionnaire", "Questionnaire", 2, {}};
  if (!result.items) {
    s.text(d.protocol->questionnaire.empty()
               ? "The protocol has no questionnaire."
               : "The protocol asks nothing at the end of the session apart from instruments and free text (see "
                 "below).");
    out.doc.sections.push_back(std::move(s));
    return;
  }
  if (ctx.data.answers.empty()) {
    s.text("No questionnaire answer is recorded in the database.");
    out.doc.sections.push_back(std::move(s));
    return;
  }
  s.text("Each item as the protocol declares it. Ratings of the levels of " + d.factor(d.primary).name +
         " are compared with Friedman's test (participants as blocks); the overall rating of a "
         "level is a participant's mean over the item's other factors. n counts the participants who rated every "
         "level compared.");
  const int pf = d.primary;
  std::vector<std::string> item_ids;
  for (const auto& item : *result.items) item_ids.push_back(item.id);
  size_t ours = 0;
  QuestionnaireTables q = questionnaire_tables(d, item_ids, ours);
  Table &summary = q.summary, &others = q.others;
  for (const auto& item : *result.items) {
    if (item.kind == QuestionnaireItemResult::Kind::rating) rating_rows(d, item, q);
    else if (item.kind == QuestionnaireItemResult::Kind::numeric) numeric_row(d, item, q);
    else if (item.kind == QuestionnaireItemResult::Kind::choice) choice_row(d, item, q);
  }
  if (d.reference)
    summary.groups = {{"this study", static_cast<int>(ours)},
                      {d.published_group(item_ids), static_cast<int>(summary.header.size() - ours)}};
  summary.notes.insert(summary.notes.begin(),
                       "χ², p: Friedman's test across the levels of " + d.factor(pf).name +
                           " (chi-square approximation; exact permutation p in parentheses). Kendall's W: agreement "
                           "of the participants' rankings (0..1).");
  if (d.reference) summary.notes.push_back(d.published_note(item_ids));
  if (!summary.rows.empty()) s.add(summary);
  if (!others.rows.empty()) {
    others.notes.push_back("Choice items: proportion of the participants choosing each option, with the SD of the "
                           "0/1 indicator; the sign test is exact (binomial, p = 1/2) among the participants who "
                           "chose one of two options. Depth test: pairs judged correctly per participant.");
    if (d.reference) others.notes.push_back(d.published_note(item_ids));
    s.add(others);
  }
  if (!q.fig_rows.empty()) {
    out.add_figure(s, bar_plot(ctx, q.fig_rows, "fig-ratings", "Rating"),
                   "Average subjective rating per " + d.factor(pf).name +
                       " level (error bars: standard deviation over participants" + d.published_cf() + ").");
  }
  out.doc.sections.push_back(std::move(s));
}

}  // namespace dtlab::report::detail

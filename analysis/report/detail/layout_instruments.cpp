// The layout of the section "Instruments and questions per condition"
// (layout.h), from questionnaire_results() (questionnaire_results.cpp): per
// measure (an instrument's scale, an item asked after a block, task set or
// level) the mean (SD) per condition and its test (RM-ANOVA effects, or
// Friedman's test), the measures asked only at the end as descriptives, the
// options chosen per condition, and every free-text answer with the
// condition it followed. report.json's "instruments" and the CSV files
// instrument_scores.csv and free_text.csv are laid out from the same result
// (render_data.h). Computes nothing.
#include <cmath>

#include "analysis/report/detail/format.h"
#include "analysis/report/detail/layout.h"

namespace dtlab::report::detail {

namespace {

// "Friedman χ²(1) = 6.25, p = .012, W = .78" or the ANOVA's effects, one cell per effect.
std::vector<std::vector<std::string>> test_rows(const ConditionMeasure& m, const Design& d) {
  std::vector<std::vector<std::string>> rows;
  const TestReport& r = *m.test;
  if (!r.not_tested.empty()) return {{m.id, kDash, r.not_tested, kDash, kDash, kDash}};
  if (r.anova)
    for (const stats::Effect& e : r.anova->effects) {
      const auto cells = effect_cells(&e);  // F, df, p, ηp²
      rows.push_back({m.id, e.name, "RM-ANOVA", cells[1], cells[0], cells[2], cells[3]});
    }
  if (r.friedman)
    rows.push_back({m.id, d.factor(r.m->factors.front()).name, "Friedman", df_text(r.friedman->df),
                    "χ² = " + fixed(r.friedman->Q, 2), p_text(r.friedman->p), "W = " + bounded(r.friedman->kendall_W)});
  return rows;
}

// One table of means per set of conditions (the cells of the measures' matrices).
void mean_tables(const Context& ctx, Section& s, const QuestionnaireResults& res) {
  const Design& d = ctx.design;
  std::map<std::vector<std::string>, Table> by_cells;
  for (const ConditionMeasure& m : res.measures) {
    if (!m.test) continue;
    const CellMatrix& cm = *m.test->m;
    Table& t = by_cells[cm.cell_names];
    if (t.header.empty()) {
      std::string factors;
      for (int f : cm.factors) factors += (factors.empty() ? "" : " x ") + d.factor(f).name;
      t.id = "table-instruments-" + std::to_string(by_cells.size());
      t.caption = "Questionnaire measures per " + factors + ": mean (SD) over the participants the test keeps.";
      t.header = {"Measure", "Asked"};
      t.text_columns = 2;
      for (const auto& c : cm.cell_names) t.header.push_back(c);
      t.header.push_back("n");
    }
    std::vector<std::string> row = {m.label, m.occasion};
    for (const auto& c : m.test->cells) row.push_back(mean_sd(c.mean, c.sd, 2));
    row.push_back(std::to_string(m.test->kept.size()));
    t.rows.push_back(row);
  }
  for (auto& [cells, t] : by_cells) s.add(std::move(t));
  Table tests;
  tests.id = "table-instrument-tests";
  tests.caption = "Tests per condition: RM-ANOVA for scores and numbers (df Greenhouse-Geisser corrected where ε < 1), "
                  "Friedman's test for points on a scale (participants as blocks).";
  tests.header = {"Measure", "Effect", "Test", "df", "F / χ²", "p", "Effect size"};
  tests.text_columns = 3;
  for (const ConditionMeasure& m : res.measures)
    if (m.test)
      for (auto& row : test_rows(m, d)) {
        row.resize(tests.header.size(), "");
        tests.rows.push_back(std::move(row));
      }
  for (const ConditionMeasure& m : res.measures)
    if (m.test)
      for (const auto& note : test_notes(*m.test)) tests.notes.push_back(m.id + ": " + note);
  if (!tests.rows.empty()) s.add(std::move(tests));
}

// A scale's end as people write it: "100", "200.34".
std::string scale_end(double v) { return v == std::round(v) ? integer(static_cast<long long>(v)) : fixed(v, 2); }

void end_table(Section& s, const QuestionnaireResults& res) {
  Table t;
  t.id = "table-instruments-end";
  t.caption = "Questionnaire measures asked once, at the end of the session: each participant's value.";
  t.header = {"Measure", "Scale", "Mean (SD)", "Median", "Min", "Max", "n"};
  t.text_columns = 2;
  for (const ConditionMeasure& m : res.measures) {
    if (m.test) continue;
    const auto& o = m.overall;
    t.rows.push_back({m.label, scale_end(m.min) + "–" + scale_end(m.max), mean_sd(o.mean, o.sd, 2), fixed(o.median, 2),
                      fixed(o.min, 2), fixed(o.max, 2), std::to_string(o.n)});
  }
  if (!t.rows.empty()) s.add(std::move(t));
}

void count_table(Section& s, const QuestionnaireResults& res) {
  Table t;
  t.id = "table-instrument-choices";
  t.caption = "Options chosen per condition (choice and multiple-choice items asked after a block, task set or level).";
  t.header = {"Item", "Condition", "Chosen", "Answers"};
  t.text_columns = 3;
  for (const ConditionCounts& c : res.counts) {
    std::string chosen;
    for (const auto& [option, n] : c.chosen) chosen += (chosen.empty() ? "" : "; ") + option + " " + std::to_string(n);
    t.rows.push_back({c.item, c.condition, chosen.empty() ? kDash : chosen, std::to_string(c.answers)});
  }
  if (!t.rows.empty()) s.add(std::move(t));
}

void text_table(Section& s, const QuestionnaireResults& res) {
  Table t;
  t.id = "table-free-text";
  t.caption = "Free-text answers, per condition they followed (\"end\": asked at the end of the session), as typed.";
  t.header = {"Condition", "Item", "Participant", "Answer"};
  t.text_columns = 4;
  std::vector<const FreeText*> sorted;
  for (const FreeText& f : res.texts) sorted.push_back(&f);
  std::stable_sort(sorted.begin(), sorted.end(), [](const FreeText* a, const FreeText* b) { return a->condition < b->condition; });
  for (const FreeText* f : sorted) {
    t.rows.push_back({f->condition.empty() ? "end" : f->condition, f->item, f->participant, f->text});
  }
  if (!t.rows.empty()) s.add(std::move(t));
}

}  // namespace

void lay_out_instruments(Layout& out, const Context& ctx, const QuestionnaireResults& res) {
  Section s{"instruments", "Instruments and questions per condition", 2, {}};
  s.text("Instruments are scored from the raw answers by their published scoring (NASA-TLX: the raw TLX, the mean "
         "of the six subscales, and with the pairwise comparisons the weighted score, sum of weight x rating / 15; "
         "SUS: 2.5 x the sum of the item contributions, 0..100; SSQ: the nausea, oculomotor and disorientation sums "
         "weighted 9.54, 7.58 and 13.92, the total 3.74 x their sum). A participant's value in a condition is the mean "
         "over the occasions it was asked there. Scores and numbers are compared with a repeated-measures ANOVA, "
         "points on a scale with Friedman's test, as the report compares ratings.");
  mean_tables(ctx, s, res);
  end_table(s, res);
  count_table(s, res);
  text_table(s, res);
  out.doc.sections.push_back(std::move(s));
}

}  // namespace dtlab::report::detail

// The report's CSV files, laid out from the sections' results (render_data.h):
// one function per file (tests.csv from every test the Context stored), every
// field quoted as `dtlab export` quotes it (csv_line) and every number at full
// precision, NA for a missing one (csv_number), so R's read.csv reads back
// what the tables round. Never computes a statistic.
#include <algorithm>

#include "analysis/report/detail/format.h"
#include "analysis/report/detail/render_data.h"
#include "analysis/stats/apa.h"
#include "study/store/export.h"

namespace dtlab::report::detail {
namespace {

// A CSV line from fields (quoted as the export quotes them).
std::string csv_line(const std::vector<std::string>& fields) {
  std::string line;
  for (size_t i = 0; i < fields.size(); ++i) line += (i ? "," : "") + store::csv_field(fields[i]);
  return line + "\n";
}

// The header of a long means file: measure, scope, participant, a column per factor, value, trials.
std::string matrix_csv_header(const Design& d) {
  std::vector<std::string> h = {"measure", "scope", "participant"};
  for (int f : d.all_factors) h.push_back(d.factor(f).name);
  h.push_back("value");
  h.push_back("trials");
  return csv_line(h);
}

// Participant x cell values of a matrix as long CSV rows (a factor the matrix averages over reads "all").
std::string matrix_csv_rows(const CellMatrix& m, const Design& d, const std::string& measure,
                            const std::string& scope) {
  std::string out;
  for (size_t s = 0; s < m.subjects.size(); ++s)
    for (size_t c = 0; c < m.cells(); ++c) {
      std::vector<std::string> row = {measure, scope, m.subjects[s]};
      for (int f : d.all_factors) {
        std::string level = "all";
        // A task runs in one scenario: name it rather than "all".
        if (f == d.scenario_factor)
          for (const auto& t : d.tasks)
            if (t.id == scope) level = t.scenario;
        for (size_t k = 0; k < m.factors.size(); ++k)
          if (m.factors[k] == f) level = d.factor(f).levels[static_cast<size_t>(m.level(c, k))];
        row.push_back(level);
      }
      row.push_back(csv_number(m.value[s][c]));
      row.push_back(std::to_string(m.trials[s][c]));
      out += csv_line(row);
    }
  return out;
}

// The tests.csv fields of one simple effect of a followed-up interaction, over the test's `base` fields.
std::map<std::string, std::string> simple_effect_fields(std::map<std::string, std::string> f,
                                                        const stats::SimpleEffect& se) {
  auto v = [](double x) { return csv_number(x); };
  f["n"] = std::to_string(se.n);
  f["test"] = "simple effect (" + se.test + ")";
  f["effect"] = se.factor + " at " + se.at_factor + " = " + se.at_level;
  f["p"] = v(se.p);
  f["p_holm"] = v(se.p_holm);
  if (se.test == "paired t") {
    const auto& c = se.contrast;
    f.insert({{"df1", v(c.df)}, {"statistic", v(c.statistic)}, {"estimate", v(c.estimate)}, {"se", v(c.se)},
              {"ci_low", v(c.ci_low)}, {"ci_high", v(c.ci_high)}, {"dz", v(c.dz)},
              {"apa", "t(" + stats::apa_df(c.df) + ") = " + stats::apa_number(c.statistic) + ", " +
                          stats::apa_p(se.p) + " (Holm " + stats::apa_p(se.p_holm) + "), d_z = " +
                          stats::apa_number(c.dz)}});
  } else {
    const auto& e = se.anova;
    f.insert({{"df1", v(e.df1)}, {"df2", v(e.df2)}, {"statistic", v(e.F)}, {"gg_epsilon", v(e.gg_epsilon)},
              {"p_gg", v(e.p_gg)}, {"eta_p2", v(e.eta_p2)}, {"apa", effect_sentence(e)}});
  }
  return f;
}

// tests.csv: one row per ANOVA effect, simple effect, normality, Friedman or Wilcoxon test of every stored
// TestReport, every number exact (never rounded).
std::string tests_csv(const Context& ctx) {
  const std::vector<std::string> columns = {
      "section", "measure", "unit", "scope", "test", "effect", "n", "df1", "df2", "statistic", "p", "log10_p",
      "p_exact", "gg_epsilon", "p_gg", "hf_epsilon", "p_hf", "eta_p2", "eta_g2", "kendall_W", "mse", "mauchly_W",
      "mauchly_p", "df1_gg", "df2_gg", "df1_hf", "df2_hf", "eta_p2_ci90_low", "eta_p2_ci90_high", "p_holm",
      "estimate", "se", "ci_low", "ci_high", "dz", "apa"};
  std::string out = csv_line(columns);
  // One line from column -> text; columns not given are NA.
  auto line = [&](const std::map<std::string, std::string>& fields) {
    std::vector<std::string> row;
    for (const auto& c : columns) {
      const auto it = fields.find(c);
      row.push_back(it == fields.end() ? "NA" : it->second);
    }
    return csv_line(row);
  };
  auto v = [](double x) { return csv_number(x); };
  for (size_t i = 0; i < ctx.reports.size(); ++i) {
    const TestReport& r = ctx.reports[i];
    std::map<std::string, std::string> base{{"section", ctx.report_section[i]}, {"measure", r.measure},
                                            {"unit", r.unit}, {"scope", r.scope},
                                            {"n", std::to_string(r.kept.size())}};
    std::string factors;
    for (int fi : r.m->factors) factors += (factors.empty() ? "" : ":") + ctx.design.factor(fi).name;
    if (r.anova)
      for (const auto& e : r.anova->effects) {
        auto f = base;
        f.insert({{"test", "rm-anova"}, {"effect", e.name}, {"df1", v(e.df1)}, {"df2", v(e.df2)},
                  {"statistic", v(e.F)}, {"p", v(e.p)}, {"log10_p", v(e.log10_p)},
                  {"gg_epsilon", v(e.gg_epsilon)}, {"p_gg", v(e.p_gg)}, {"hf_epsilon", v(e.hf_epsilon)},
                  {"p_hf", v(e.p_hf)}, {"eta_p2", v(e.eta_p2)}, {"eta_g2", v(e.eta_g2)}, {"mse", v(e.mse)},
                  {"mauchly_W", v(e.mauchly_W)}, {"mauchly_p", v(e.mauchly_p)}, {"df1_gg", v(e.df1_gg)},
                  {"df2_gg", v(e.df2_gg)}, {"df1_hf", v(e.df1_hf)}, {"df2_hf", v(e.df2_hf)},
                  {"eta_p2_ci90_low", v(e.eta_p2_ci_low)}, {"eta_p2_ci90_high", v(e.eta_p2_ci_high)},
                  {"apa", effect_sentence(e)}});
        out += line(f);
      }
    for (const auto& fu : r.followups)
      for (const auto& se : fu.simple.rows) out += line(simple_effect_fields(base, se));
    if (r.normality) {
      auto f = base;
      f.insert({{"test", "shapiro-wilk"}, {"effect", "residuals"}, {"statistic", v(r.normality->W)},
                {"p", v(r.normality->p)},
                {"apa", "W = " + stats::apa_bounded(r.normality->W, 3) + ", " + stats::apa_p(r.normality->p)}});
      out += line(f);
    }
    if (r.friedman) {
      const auto& x = *r.friedman;
      auto f = base;
      f.insert({{"test", "friedman"}, {"effect", factors}, {"df1", v(x.df)}, {"statistic", v(x.Q)}, {"p", v(x.p)},
                {"log10_p", v(x.log10_p)}, {"p_exact", v(x.p_exact)}, {"kendall_W", v(x.kendall_W)},
                {"apa", friedman_sentence(x)}});
      out += line(f);
    }
    if (r.wilcoxon) {
      const auto& w = *r.wilcoxon;
      auto f = base;
      f.insert({{"test", "wilcoxon"}, {"effect", factors}, {"statistic", v(w.V)}, {"p", v(w.p)},
                {"log10_p", v(w.log10_p)}, {"p_exact", v(w.p_exact)}, {"apa", wilcoxon_sentence(w)}});
      out += line(f);
    }
  }
  return out;
}


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
  std::map<std::string, std::string> files;
  files["tests.csv"] = tests_csv(ctx);
  files["completion_time_means.csv"] = means_csv(results.time.means, ctx.design);
  if (!results.accuracy.rows.empty()) files["accuracy_means.csv"] = means_csv(results.accuracy.means, ctx.design);
  if (!results.sample.around.empty()) files["sessions_notes.csv"] = sessions_notes_csv(results.sample);
  // Answers recorded: the section tested them.
  if (results.questionnaire.items && !results.questionnaire.items->empty())
    files["questionnaire.csv"] = questionnaire_csv(ctx.data);
  if (results.instruments) {
    files["instrument_scores.csv"] = instrument_scores_csv(*results.instruments);
    files["free_text.csv"] = free_text_csv(*results.instruments);
  }
  files["frames.csv"] = frames_csv(results.frames);
  return files;
}

}  // namespace dtlab::report::detail

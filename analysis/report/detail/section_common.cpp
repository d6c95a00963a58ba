// Helpers shared by the report sections: the Context's bookkeeping, the full
// ANOVA table, notes under a test's table, and the CSV rows every section
// writes. Formatting only; the numbers come from analysis/stats.
#include <cmath>

#include "analysis/report/detail/format.h"
#include "analysis/report/detail/sections.h"
#include "study/store/export.h"

namespace dtlab::report::detail {

bool Context::analysed(const TrialRow& t) const {
  if (t.practice) return false;
  for (int l : t.level_index)
    if (l < 0) return false;
  return true;
}

const CellMatrix& Context::cells(const std::vector<int>& factors, const TrialFilter& include, const Reducer& reduce) {
  return keep(aggregate(
      data, design, subjects, factors, [&](const TrialRow& t) { return analysed(t) && include(t); }, reduce));
}

void Context::add_figure(Section& s, PlotSpec p, const std::string& caption) {
  if (p.empty) {
    s.text("(Figure \"" + p.id + "\" is not drawn: there is no finite value to plot.)");
    return;
  }
  s.add(Figure{p.id, caption, p.width});
  plots.push_back(std::move(p));
}

const TestReport& Context::add_test(const std::string& section, TestReport r) {
  if (r.anova)
    tests += static_cast<int>(r.anova->effects.size());
  else if (r.friedman)
    ++tests;
  reports.push_back(std::move(r));
  report_section.push_back(section);
  return reports.back();
}

Table anova_table(const TestReport& r, const Design& d, const std::string& id, const std::string& caption) {
  (void)d;
  Table t;
  t.id = id;
  t.caption = caption;
  bool sphericity = false;
  if (r.anova)
    for (const auto& e : r.anova->effects) sphericity = sphericity || e.df1 > 1;
  t.header = {"Effect", "df1", "df2", "SS", "F", "p", "log10 p", "η²p", "η²G"};
  if (sphericity)
    for (const char* h : {"Mauchly W", "Mauchly p", "ε GG", "p GG", "ε HF", "p HF"}) t.header.push_back(h);
  if (r.anova)
    for (const auto& e : r.anova->effects) {
      std::vector<std::string> row = {e.name,  df_text(e.df1),           df_text(e.df2),
                                      fixed(e.ss, 3), f_text(e.F),       p_short(e.p, e.log10_p),
                                      fixed(e.log10_p, 2), fixed(e.eta_p2, 3), fixed(e.eta_g2, 3)};
      if (sphericity) {
        if (e.df1 > 1) {
          for (const auto& s : {fixed(e.mauchly_W, 3), p_short(e.mauchly_p, std::log10(e.mauchly_p)),
                                fixed(e.gg_epsilon, 3), p_short(e.p_gg, e.log10_p_gg), fixed(e.hf_epsilon, 3),
                                p_short(e.p_hf, e.log10_p_hf)})
            row.push_back(s);
        } else {
          for (const char* s : {"—", "—", "1", "= p", "1", "= p"}) row.push_back(s);
        }
      }
      t.rows.push_back(std::move(row));
    }
  t.notes = test_notes(r);
  if (r.anova) {
    if (sphericity)
      t.notes.push_back(
          "Sphericity: Mauchly's test with car's chi-square approximation; Greenhouse-Geisser and Huynh-Feldt "
          "epsilons correct the df of effects with more than 1 df (HF may exceed 1 and is used as min(1, HF)). "
          "Effects with 1 df (two levels) satisfy sphericity trivially (ε = 1).");
    else
      t.notes.push_back("Sphericity holds trivially: every effect has 1 df (two levels), so ε = 1 and no "
                        "correction applies.");
  }
  return t;
}

std::vector<std::string> test_notes(const TestReport& r) {
  std::vector<std::string> notes;
  std::string n = "n = " + counted(static_cast<long long>(r.kept.size()), "participant");
  if (!r.excluded.empty()) {
    n += "; excluded (listwise deletion, a cell without a value): ";
    for (size_t i = 0; i < r.excluded.size(); ++i) n += (i ? "; " : "") + r.excluded[i];
  }
  notes.push_back(n + ".");
  if (!r.not_tested.empty()) notes.push_back("Not tested: " + r.not_tested + ".");
  for (const auto& w : r.warnings) notes.push_back("Statistics: " + w);
  return notes;
}

std::vector<std::string> primary_cells(const TestReport& r, const Design& d, int decimals) {
  std::vector<std::string> out;
  const auto* m = r.marginal_of(d.primary);
  const size_t levels = d.factor(d.primary).levels.size();
  for (size_t l = 0; l < levels; ++l)
    out.push_back(m ? mean_sd((*m)[l].mean, (*m)[l].sd, decimals) : kDash);
  return out;
}

nlohmann::json published_json(const protocol::ReferenceResult& r, const Design& d) {
  const auto& rr = *d.protocol->reference_results;
  nlohmann::json j{{"source", rr.source}, {"label", rr.label}, {"location", r.location}, {"F", r.F}, {"p", r.p}};
  if (!r.per_level && !r.mean.empty()) {
    j["mean"] = r.mean[0];
    j["sd"] = r.sd[0];
  } else if (!r.mean.empty()) {
    for (size_t l = 0; l < r.mean.size(); ++l) {
      j["mean"][d.factor(d.primary).levels[l]] = r.mean[l];
      j["sd"][d.factor(d.primary).levels[l]] = r.sd[l];
    }
  }
  return j;
}

std::string csv_line(const std::vector<std::string>& fields) {
  std::string line;
  for (size_t i = 0; i < fields.size(); ++i) line += (i ? "," : "") + store::csv_field(fields[i]);
  return line + "\n";
}

std::string matrix_csv_header(const Design& d) {
  std::vector<std::string> h = {"measure", "scope", "participant"};
  for (int f : d.all_factors) h.push_back(d.factor(f).name);
  h.push_back("value");
  h.push_back("trials");
  return csv_line(h);
}

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

std::string tests_csv(const Context& ctx) {
  std::string out = csv_line({"section", "measure", "unit", "scope", "test", "effect", "n", "df1", "df2",
                              "statistic", "p", "log10_p", "p_exact", "gg_epsilon", "p_gg", "hf_epsilon", "p_hf",
                              "eta_p2", "eta_g2", "kendall_W"});
  auto v = [](double x) { return csv_number(x); };
  for (size_t i = 0; i < ctx.reports.size(); ++i) {
    const TestReport& r = ctx.reports[i];
    const std::string n = std::to_string(r.kept.size());
    if (r.anova)
      for (const auto& e : r.anova->effects)
        out += csv_line({ctx.report_section[i], r.measure, r.unit, r.scope, "rm-anova", e.name, n, v(e.df1), v(e.df2),
                         v(e.F), v(e.p), v(e.log10_p), "NA", v(e.gg_epsilon), v(e.p_gg), v(e.hf_epsilon), v(e.p_hf),
                         v(e.eta_p2), v(e.eta_g2), "NA"});
    if (r.friedman) {
      const auto& f = *r.friedman;
      std::string effect;
      for (int fi : r.m->factors) effect += (effect.empty() ? "" : ":") + ctx.design.factor(fi).name;
      out += csv_line({ctx.report_section[i], r.measure, r.unit, r.scope, "friedman", effect, n, v(f.df), "NA", v(f.Q),
                       v(f.p), v(f.log10_p), v(f.p_exact), "NA", "NA", "NA", "NA", "NA", "NA", v(f.kendall_W)});
    }
  }
  return out;
}

}  // namespace dtlab::report::detail

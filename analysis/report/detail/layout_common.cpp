// Helpers shared by the layout functions (layout.h): the Layout's figures,
// the full ANOVA table in APA style with its sentences, the follow-up of
// significant interactions (simple-effects table, interaction plot),
// paired-comparison tables, notes under a test's table and a test's cells.
// They lay out numbers the results hold and compute no statistic; the
// numbers come from analysis/stats through the sections (sections.h).
#include <algorithm>
#include <cmath>
#include <map>

#include "analysis/report/detail/format.h"
#include "analysis/report/detail/layout.h"
#include "analysis/stats/apa.h"

namespace dtlab::report::detail {
namespace {

// "transparency:scenario" as a paper writes it: "transparency × scenario".
std::string effect_label(const std::string& name) {
  std::string out;
  for (char c : name) out += c == ':' ? std::string(" × ") : std::string(1, c);
  return out;
}

Table anova_table(const TestReport& r, const std::string& id, const std::string& caption) {
  Table t;
  t.id = id;
  t.caption = caption;
  bool sphericity = false, corrected = false;
  if (r.anova)
    for (const auto& e : r.anova->effects) {
      sphericity = sphericity || std::isfinite(e.mauchly_W) || (e.within && e.df1 > 1 && e.gg_epsilon < 1);
      corrected = corrected || stats::applied_correction(e, stats::Correction::greenhouse_geisser) !=
                                   stats::Correction::none;
    }
  t.header = {"Effect", "df", "MSE", "F", "p", "ηp²", "ηp² 90% CI", "ηG²"};
  if (sphericity)
    for (const char* h : {"Mauchly's W", "p (Mauchly)", "ε GG", "ε HF"}) t.header.push_back(h);
  if (r.anova)
    for (const auto& e : r.anova->effects) {
      const bool gg = stats::applied_correction(e, stats::Correction::greenhouse_geisser) != stats::Correction::none;
      std::vector<std::string> row = {
          effect_label(e.name),
          df_cell(e) + (gg ? " (GG)" : ""),
          stats::apa_number(e.mse, std::fabs(e.mse) < 1 ? 4 : 2),
          f_text(e.F),
          p_text(reported_p(e)),
          bounded(e.eta_p2),
          std::isnan(e.eta_p2_ci_low) ? kDash : stats::apa_interval(e.eta_p2_ci_low, e.eta_p2_ci_high, true),
          bounded(e.eta_g2)};
      if (sphericity)
        for (const auto& c : {bounded(e.mauchly_W, 3), p_text(e.mauchly_p), bounded(e.gg_epsilon, 3),
                              bounded(e.hf_epsilon, 3)})
          row.push_back(c);
      t.rows.push_back(std::move(row));
    }
  t.notes = test_notes(r);
  if (!r.anova) return t;
  t.notes.push_back("df: numerator, denominator; MSE: mean square of the effect's error term; p in APA style "
                    "(exact values in report.json and tests.csv). ηp²: partial eta squared, with its 90% "
                    "confidence interval from the noncentral F (Steiger 2004); ηG²: generalized eta squared "
                    "(Olejnik & Algina 2003).");
  if (sphericity)
    t.notes.push_back(std::string("Sphericity: Mauchly's test (W, p) and the Greenhouse-Geisser (GG) and Huynh-Feldt "
                                  "(HF, may exceed 1) epsilons of each within effect with more than 1 df. ") +
                      (corrected ? "Where ε GG < 1, df and p are Greenhouse-Geisser corrected (df × ε, marked GG). "
                                 : "") +
                      "Effects with 1 df (two levels) satisfy sphericity trivially (ε = 1).");
  else
    t.notes.push_back("Sphericity holds trivially: every within effect has 1 df (two levels), so ε = 1 and no "
                      "correction applies.");
  return t;
}

// Simple effects of one interaction: paired t rows (difference first − second level) or one-way RM ANOVA rows.
Table simple_effects_table(const InteractionFollowUp& f, const std::string& id, const std::string& what,
                           const std::string& unit) {
  Table t;
  t.id = id;
  t.caption = "Simple effects of the " + f.a + " × " + f.b + " interaction on " + what +
              ": each factor at each level of the other, Holm-corrected within each factor.";
  const std::string u = unit.empty() ? "" : " (" + unit + ")";
  t.header = {"Effect of", "At", "Difference", "n", "M diff" + u, "SE", "95% CI", "Statistic", "df", "p",
              "p (Holm)", "Effect size"};
  t.text_columns = 3;
  for (const auto& se : f.simple.rows) {
    std::vector<std::string> row = {se.factor, se.at_factor + " = " + se.at_level};
    if (se.test == "paired t") {
      const auto& c = se.contrast;
      for (const auto& x : {c.a + " − " + c.b, std::to_string(se.n), fixed(c.estimate, 2), fixed(c.se, 2),
                            stats::apa_interval(c.ci_low, c.ci_high, false), "t = " + fixed(c.statistic, 2),
                            df_text(c.df), p_text(se.p), p_text(se.p_holm), "d_z = " + fixed(c.dz, 2)})
        row.push_back(x);
    } else {
      const auto& e = se.anova;
      const bool gg = stats::applied_correction(e, stats::Correction::greenhouse_geisser) != stats::Correction::none;
      for (const auto& x : {std::string("all levels"), std::to_string(se.n), std::string(kDash), std::string(kDash),
                            std::string(kDash), "F = " + f_text(e.F), df_cell(e) + (gg ? " (GG)" : ""),
                            p_text(se.p), p_text(se.p_holm), "ηp² = " + bounded(e.eta_p2)})
        row.push_back(x);
    }
    t.rows.push_back(std::move(row));
  }
  t.notes.push_back("Each participant's values are first averaged over the other within factors. Two levels: "
                    "paired t test (M diff: mean of the paired differences, first level minus second, with its SE "
                    "and 95% CI; d_z = M diff / SD of the differences). More levels: one-way repeated-measures ANOVA "
                    "of the subset (df and p Greenhouse-Geisser corrected where ε < 1). p (Holm): Holm-corrected "
                    "within the tests of one factor.");
  for (const auto& w : f.simple.warnings) t.notes.push_back("Statistics: " + w);
  return t;
}

// Cell means of a x b with Cousineau-Morey 95% CIs: x = levels of the factor `x`, one line per level of the other.
PlotSpec interaction_plot(const Design& d, const InteractionFollowUp& f, const std::string& id,
                          const std::string& ylabel) {
  const bool primary_is_b = d.factor(d.primary).name == f.b;
  const std::string x = primary_is_b ? f.b : f.a, line = primary_is_b ? f.a : f.b;
  std::vector<std::string> xl, ll;  // level names in order of appearance
  auto add = [](std::vector<std::string>& v, const std::string& s) {
    if (std::find(v.begin(), v.end(), s) == v.end()) v.push_back(s);
  };
  auto level_of = [](const stats::CellInterval& c, const std::string& factor) {
    for (const auto& [name, level] : c.levels)
      if (name == factor) return level;
    return std::string();
  };
  for (const auto& c : f.intervals) {
    add(xl, level_of(c, x));
    add(ll, level_of(c, line));
  }
  std::string dat = "# x index, mean, CI low, CI high (Cousineau-Morey 95%); one block per level of " + line + "\n";
  bool any = false;
  for (size_t j = 0; j < ll.size(); ++j) {
    dat += "# " + line + " = " + ll[j] + "\n";
    for (size_t i = 0; i < xl.size(); ++i)
      for (const auto& c : f.intervals)
        if (level_of(c, x) == xl[i] && level_of(c, line) == ll[j]) {
          const double dodge = (static_cast<double>(j) - (static_cast<double>(ll.size()) - 1) / 2) * 0.04;
          dat += gp_value(static_cast<double>(i) + dodge) + " " + gp_value(c.mean) + " " + gp_value(c.ci_low) + " " +
                 gp_value(c.ci_high) + "\n";
          any = any || std::isfinite(c.mean);
        }
    dat += "\n\n";
  }
  PlotSpec p;
  p.id = id;
  p.empty = !any;
  p.width = 560;
  p.height = 400;
  p.data[id + ".dat"] = dat;
  std::string c = "set xtics (";
  for (size_t i = 0; i < xl.size(); ++i) c += (i ? ", " : "") + gp_quote(xl[i]) + " " + std::to_string(i);
  c += ")\nset xrange [-0.4:" + std::to_string(xl.size() - 1) + ".4]\nset xlabel " + gp_quote(x) +
       "\nset ylabel " + gp_quote(ylabel) + "\nset key above center horizontal title " + gp_quote(line) + "\nplot ";
  for (size_t j = 0; j < ll.size(); ++j)
    c += std::string(j ? ", " : "") + gp_quote(id + ".dat") + " index " + std::to_string(j) +
         " using 1:2:3:4 with yerrorlines lw 2 pt 7 ps 1 lc rgb '" + series_color(j) + "' title " + gp_quote(ll[j]);
  p.commands = c + "\n";
  return p;
}

}  // namespace

void Layout::add_figure(Section& s, PlotSpec p, const std::string& caption) {
  if (p.empty) {
    s.text("(Figure \"" + p.id + "\" is not drawn: there is no finite value to plot.)");
    return;
  }
  s.add(Figure{p.id, caption, p.width});
  plots.push_back(std::move(p));
}

void add_anova(Layout& out, Section& s, const Design& d, const TestReport& r, const std::string& id,
               const std::string& caption) {
  s.add(anova_table(r, id, caption));
  if (!r.anova || r.anova->effects.empty()) return;
  Callout c{"note", "In the text (APA style; Greenhouse-Geisser corrected where ε < 1)", {}};
  for (const auto& e : r.anova->effects)
    if (std::isfinite(e.F)) c.items.push_back(effect_label(e.name) + ": " + effect_sentence(e) + ".");
  if (!c.items.empty()) s.add(c);
  const std::string what = r.measure + (r.scope.empty() ? "" : ", " + r.scope);
  const std::string ylabel = r.measure + (r.unit.empty() ? "" : " (" + r.unit + ")");
  for (const auto& f : r.followups) {
    const std::string stem = id + "-" + f.a + "-" + f.b;
    s.text("The " + f.a + " × " + f.b + " interaction is significant (p < " + stats::apa_bounded(kFollowUpAlpha) +
           "), so each factor's effect is tested at each "
           "level of the other (simple effects).");
    s.add(simple_effects_table(f, "table-simple-" + stem.substr(stem.find('-') + 1), what, r.unit));
    out.add_figure(s, interaction_plot(d, f, "fig-interaction-" + stem.substr(stem.find('-') + 1), ylabel),
                   "The " + f.a + " × " + f.b + " interaction, " + what + ": cell means with within-subject 95% "
                   "confidence intervals (Cousineau 2005 with Morey's 2008 correction; they show the precision of "
                   "comparisons within participants, not of the means themselves).");
  }
}

std::string df_cell(const stats::Effect& e) {
  if (stats::applied_correction(e, stats::Correction::greenhouse_geisser) == stats::Correction::none)
    return df_text(e.df1) + ", " + df_text(e.df2);
  return df_text(e.df1_gg) + ", " + df_text(e.df2_gg);
}

std::vector<std::string> effect_cells(const stats::Effect* e) {
  if (!e) return {kDash, kDash, kDash, kDash};
  return {f_text(e->F), df_cell(*e), p_text(reported_p(*e)), bounded(e->eta_p2)};
}

Table comparison_table(const std::vector<stats::Comparison>& list, const std::string& id, const std::string& caption,
                       const std::string& unit) {
  Table t;
  t.id = id;
  t.caption = caption;
  const std::string u = unit.empty() ? "" : " (" + unit + ")";
  t.header = {"Comparison", "n", "M diff" + u, "SE", "95% CI", "t", "df", "p", "p (Holm)", "d_z"};
  for (const auto& c : list)
    t.rows.push_back({c.a + " − " + c.b, std::to_string(c.n), fixed(c.estimate, 2), fixed(c.se, 2),
                      stats::apa_interval(c.ci_low, c.ci_high, false), (c.test == "wilcoxon" ? "V = " : "") +
                      fixed(c.statistic, 2), df_text(c.df), p_text(c.p), p_text(c.p_holm), fixed(c.dz, 2)});
  t.notes.push_back("M diff: mean of the paired differences (first level minus second) with its SE and 95% CI; d_z: "
                    "M diff / SD of the differences. p (Holm): Holm-corrected over the comparisons of the table.");
  return t;
}

std::vector<std::string> test_notes(const TestReport& r) {
  std::vector<std::string> notes;
  std::string n = "n = " + dtlab::count(static_cast<long long>(r.kept.size()), "participant");
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

std::string difference_text(const TestReport& r, int decimals) {
  if (!r.paired) return kDash;
  const auto& t = r.paired->t;
  return fixed(t.mean_difference, decimals) + " [" + fixed(t.ci_low, decimals) + ", " + fixed(t.ci_high, decimals) +
         "]";
}

}  // namespace dtlab::report::detail

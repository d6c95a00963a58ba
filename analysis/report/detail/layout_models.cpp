// The layout of the two model sections (layout.h). "Mixed models on
// trial-level data": section_mixed_models()'s results beside the ANOVAs of
// the completion-time and accuracy sections, per measure a table (the
// primary factor's test, its ratio or difference with a 95% CI, the ANOVA's
// p beside and whether both decide alike at alpha = .05), one APA sentence
// per model, the lme4 call of each model a reader can paste into R, and a
// note listing every effect on which the two analyses disagree. "Planning
// the next study": the power of each ANOVA effect at the planned numbers of
// participants (section_planning). Computes no statistic; report.json gets
// every fit in full from the results (render_data.h, through lmm_json.h).
#include <cmath>

#include "analysis/report/detail/format.h"
#include "analysis/report/detail/layout.h"
#include "analysis/report/detail/mixed_models.h"
#include "analysis/stats/apa.h"

namespace dtlab::report::detail {
namespace {

const char* kAlphaText = "α = .05";

std::string n_text(double n) { return std::isfinite(n) ? integer(static_cast<long long>(n)) : std::string("> 10⁷"); }

std::string model_name(const stats::LmmFit& f) {
  if (f.family == stats::Family::binomial) return "GLMM (logit)";
  return f.transform == stats::Transform::log ? "LMM (log)" : "LMM";
}

// The primary factor's second level against its first (levels[1] vs levels[0], as the ANOVA's Δ).
std::optional<stats::EmmContrast> primary_contrast(const MixedModelResult& m) {
  if (!m.primary || m.primary->contrasts.size() != 1) return std::nullopt;
  return stats::reversed(m.primary->contrasts.front());
}

std::string test_text(const MixedModelResult& m, const std::string& primary, double* p) {
  *p = NAN;
  if (!m.fit) return kDash;
  if (m.fit->family == stats::Family::binomial) {
    for (const auto& l : m.fit->lrt)
      if (l.term == primary) {
        *p = l.p;
        return "χ²(" + df_text(l.df) + ") = " + fixed(l.chisq, 2);
      }
    return kDash;
  }
  for (const auto& a : m.fit->anova)
    if (a.term == primary) {
      *p = a.p;
      return "F(" + df_text(a.num_df) + ", " + df_text(a.den_df) + ") = " + f_text(a.F);
    }
  return kDash;
}

std::string contrast_cell(const MixedModelResult& m, int decimals) {
  const auto c = primary_contrast(m);
  if (!c) return kDash;
  if (m.primary->scale == stats::EmmScale::identity)
    return fixed(c->estimate, decimals) + " [" + fixed(c->ci_low, decimals) + ", " + fixed(c->ci_high, decimals) + "]";
  return fixed(c->ratio, 2) + " [" + fixed(c->ratio_ci_low, 2) + ", " + fixed(c->ratio_ci_high, 2) + "]";
}

double beside_p(const MixedModelResult& m, const std::string& primary) {
  if (!m.beside) return NAN;
  if (const stats::Effect* e = m.beside->effect(primary)) return reported_p(*e);
  if (m.beside->friedman) return m.beside->friedman->p;
  return NAN;
}

// "T1: on trials took 0.58 times as long as off trials, 95% CI [...], t(...) = ..., p < .001."
std::string sentence(const MixedModelResult& m, const std::string& primary) {
  if (!m.fit) return m.label + ": no mixed model (" + m.not_fitted + ").";
  if (const auto c = primary_contrast(m)) {
    const bool time = m.section == "time";
    std::string s = stats::apa_contrast_sentence(*m.primary, *c, time,
                                                 m.fit->family == stats::Family::binomial ? "the odds of a correct answer"
                                                                                          : m.measure);
    return m.label + ": " + s;
  }
  double p = NAN;
  const std::string t = test_text(m, primary, &p);
  return m.label + ": " + primary + " " + t + ", " + stats::apa_p(p) + ".";
}

void lay_out_group(const Context& ctx, Section& s, const std::vector<MixedModelResult>& models,
                   const std::string& section, const std::string& title) {
  const Design& d = ctx.design;
  const auto& primary = d.factor(d.primary);
  std::vector<const MixedModelResult*> group;
  for (const auto& m : models)
    if (m.section == section) group.push_back(&m);
  if (group.empty()) return;
  const bool two = primary.levels.size() == 2;
  Table t;
  t.id = "table-lmm-" + section;
  t.caption = title + ": mixed models on the trials, the test of " + primary.name + ", and the report's test beside.";
  t.header = {"Task", "Measure", "Model", "Trials", "Test of " + primary.name, "p"};
  if (two) t.header.push_back(primary.levels[1] + " vs " + primary.levels[0] + " [95% CI]");
  t.header.insert(t.header.end(), {"Report's test p", "Same decision (" + std::string(kAlphaText) + ")"});
  t.text_columns = 3;
  t.last_is_text = true;
  for (const auto* m : group) {
    double p = NAN;
    std::vector<std::string> row{m->label, m->measure, m->fit ? model_name(*m->fit) : kDash,
                                 m->fit ? integer(m->trials) : kDash, test_text(*m, primary.name, &p), p_text(p)};
    if (two) row.push_back(contrast_cell(*m, 3));
    row.push_back(p_text(beside_p(*m, primary.name)));
    bool differ = false;
    for (const auto& x : m->decisions) differ = differ || x.disagree;
    row.push_back(!m->fit || m->decisions.empty() ? kDash : differ ? "no (see below)" : "yes");
    t.rows.push_back(std::move(row));
  }
  t.notes.push_back("Trials: analysed trials with a value (practice trials and excluded data left out). Fixed "
                    "effects: the full factorial of the factors of the report's test, in sum-to-zero coding; random "
                    "intercepts per participant. LMM: t and F tests with Satterthwaite's df (lmerTest); LMM (log): "
                    "of the logarithm of the time, so its contrast is a ratio of geometric means. GLMM: binomial, "
                    "Laplace approximation (lme4's glmer), likelihood-ratio χ² test of each term.");
  if (two)
    t.notes.push_back(primary.levels[1] + " vs " + primary.levels[0] + ": the ratio (log model), odds ratio (GLMM) "
                      "or difference (LMM) of the estimated marginal means, with its 95% CI (emmeans).");
  t.notes.push_back("Report's test p: the repeated-measures ANOVA (Greenhouse-Geisser corrected where ε < 1) or "
                    "Friedman test of the same scope, on participant x condition means" +
                    std::string(section == "time" ? " of the times in seconds" : "") + ".");
  s.add(t);
  for (const auto* m : group) s.text(sentence(*m, primary.name));
  std::vector<std::string> differences, problems;
  for (const auto* m : group) {
    for (const auto& x : m->decisions)
      if (x.disagree)
        differences.push_back(m->label + ", " + m->measure + ", " + x.effect + ": report's test " +
                              stats::apa_p(x.p_anova) + ", mixed model " + stats::apa_p(x.p_model) + ".");
    if (m->fit)
      for (const auto& w : m->fit->messages) problems.push_back(m->label + ", " + m->measure + ": " + w);
    if (m->fit)
      for (const auto& w : m->fit->warnings) problems.push_back(m->label + ", " + m->measure + ": " + w);
  }
  if (!differences.empty())
    s.add(Callout{"note", "Where the ANOVA and the mixed model disagree at " + std::string(kAlphaText), differences});
  else
    s.text("For every effect both test, the report's test and the mixed model reach the same decision at " +
           std::string(kAlphaText) + ".");
  if (!problems.empty()) s.add(Callout{"warning", "Mixed-model messages (lme4's wording)", problems});
}

}  // namespace

void lay_out_mixed_models(Layout& out, const Context& ctx, const MixedResult& r) {
  const std::vector<MixedModelResult>& models = r.models;
  Section s{"mixed-models", "Mixed models on trial-level data", 2, {}};
  s.text("The ANOVAs above average each participant's trials per condition first. A mixed model uses the trials "
         "themselves: participants enter as random effects, so an unbalanced participant, a missing or excluded "
         "trial weighs as much as it should. Completion time is modelled on the log scale (times are "
         "right-skewed; effects become ratios), correctness of letter tasks as a binomial outcome instead of "
         "proportions.");
  lay_out_group(ctx, s, models, "time", "Completion time");
  lay_out_group(ctx, s, models, "accuracy", "Accuracy");
  bool binomial = false;
  std::string calls;
  for (const auto& m : models)
    if (m.fit) {
      binomial = binomial || m.fit->family == stats::Family::binomial;
      calls += (calls.empty() ? "" : "; ") + std::string("`") + r_call(m) + "`";
    }
  if (!calls.empty()) {
    std::string setup = "`library(lmerTest); options(contrasts = c(\"contr.sum\", \"contr.poly\")); d <- "
                        "subset(read.csv(\"trials.csv\"), practice == 0" +
                        std::string(ctx.data.with_excluded ? "" : " & is.na(excluded)") + ")`";
    if (binomial)
      setup += " and `ctl <- glmerControl(tolPwrss = 1e-13, optimizer = \"nloptwrap\", optCtrl = list(xtol_abs = "
               "1e-14, ftol_abs = 1e-15, xtol_rel = 1e-14))` (glmer's defaults stop short of the optimum)";
    s.text("The same models in R (lme4 1.1, lmerTest 3.1; `trials.csv` is beside this report): " + setup +
           ", then " + calls + "; `summary()`, `anova()` and `emmeans::emmeans()` print what the tables show. "
           "report.json holds every fit in full, with the R code naming each factor's levels.");
  }
  out.doc.sections.push_back(std::move(s));
}

void lay_out_planning(Layout& out, const Context& ctx, const PlanningResult& result) {
  const std::vector<PlannedEffect>& effects = result.effects;
  const std::vector<int>& planned_sizes = result.sizes;
  Section s{"planning", "Planning the next study", 2, {}};
  std::string sizes;
  for (std::size_t k = 0; k < planned_sizes.size(); ++k)
    sizes += (k ? (k + 1 == planned_sizes.size() ? " and " : ", ") : "") + std::to_string(planned_sizes[k]);
  s.text("How many participants would a study of this design need to detect the effects seen here? For every effect "
         "of the repeated-measures ANOVAs above (completion time and accuracy, per task and over all tasks), the "
         "table gives the power of the same test at " + sizes + " participants (α = .05), computed from the effect "
         "observed in these data. An effect with one degree of freedom is a paired comparison: its power is that of "
         "the paired t test with the observed standardized difference d_z = √(F / N) (noncentral t). An effect with "
         "more degrees of freedom uses the noncentral F distribution with noncentrality λ = F · df1 · n / N, the "
         "observed Greenhouse-Geisser ε applied to λ and both df (as G*Power does). The last columns give the "
         "smallest number of participants that reaches 80% and 90% power.");
  s.text("These numbers take the observed effect as the true one. An effect estimated from few participants is "
         "uncertain, and effects noticed because they were significant tend to be overestimated, so treat the "
         "powers as optimistic for small effects. `dtlab power " + ctx.data.path +
         " --participants 8,12,16,24,32` adds the power found by resampling these participants with replacement "
         "and rerunning the same tests, with a Monte Carlo 95% interval.");
  Table t;
  t.id = "table-planning";
  t.caption = "Power of each ANOVA effect at the planned numbers of participants, from the observed effect "
              "(analytic), and the smallest n for 80% and 90% power.";
  t.header = {"Test", "Effect", "N", "η²p", "ε"};
  for (int n : planned_sizes) t.header.push_back("n = " + std::to_string(n));
  t.header.insert(t.header.end(), {"n for 80%", "n for 90%"});
  t.text_columns = 2;
  for (const auto& e : effects) {
    std::vector<std::string> row = {(e.scope == "overall" ? std::string("All tasks") : e.scope) + ", " + e.measure,
                                    e.effect, std::to_string(e.pilot_n), fixed(e.eta_p2, 3),
                                    e.df1 > 1 ? fixed(e.epsilon, 3) : kDash};
    for (const auto& a : e.at) row.push_back(fixed(a.analytic, 3));
    const bool finite = std::isfinite(e.F);
    row.push_back(finite ? n_text(e.n80) : kDash);
    row.push_back(finite ? n_text(e.n90) : kDash);
    t.rows.push_back(std::move(row));
  }
  t.notes.push_back("N: participants in the test. Power: probability that the test (two-sided, α = .05; "
                    "Greenhouse-Geisser corrected for effects with more than one df) rejects the null hypothesis when "
                    "the true effect equals the observed one. —: no finite F (e.g. no error variance).");
  if (effects.empty()) s.text("No ANOVA effect could be planned.");
  else s.add(t);
  for (const auto& why : result.not_planned) s.text("Not planned: " + why + ".");
  out.doc.sections.push_back(std::move(s));
}

}  // namespace dtlab::report::detail

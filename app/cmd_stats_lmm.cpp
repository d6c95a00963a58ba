// `dtlab stats lmm`: linear and binomial mixed models on trial-level data
// (analysis/stats/lmm.h, emmeans.h) from any long-format CSV, one row per
// trial. Rows are selected as for the other tests (stats_input.h). Prints
// lme4's summary, lmerTest's type III table, variance components, the
// estimated marginal means with Holm-corrected pairwise contrasts, APA
// sentences and the R code of the same model; --json prints one object
// (analysis/stats/lmm_json.h). lme4's messages and warnings go to stderr and
// into the JSON. Exit codes: 1 bad CSV or data, 2 bad command line, 3
// unreadable file. Never writes any file.
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "analysis/stats/apa.h"
#include "analysis/stats/emmeans.h"
#include "analysis/stats/lmm.h"
#include "analysis/stats/lmm_json.h"
#include "analysis/stats/lmm_power.h"
#include "app/commands.h"
#include "app/stats_input.h"

namespace dtlab::app {
namespace {

using json = nlohmann::ordered_json;
namespace st = dtlab::stats;

struct LmmCliOptions : StatsInput {
  std::string item, random = "intercepts", transform = "none", family = "gaussian", ddf = "satterthwaite";
  std::vector<std::string> emmeans;
  bool ml = false, reml = false, lrt = false, json = false;
  std::vector<std::size_t> power_subjects;  // --power-subjects: simulated power at these sizes
  std::string power_term;
  std::size_t replications = 200;
  std::uint64_t seed = 1;
  double alpha = 0.05;
};

// --power-subjects: simr-style simulated power of one term (lmm_power.h), progress on stderr.
std::vector<st::LmmPowerRow> simulated_power(const LmmCliOptions& o, const st::LmmData& data,
                                             const st::LmmOptions& options, const st::LmmFit& fit,
                                             std::string& term) {
  if (o.power_subjects.empty()) return {};
  term = o.power_term.empty() ? (fit.anova.empty() ? (fit.lrt.empty() ? "" : fit.lrt.front().term) : fit.anova.front().term)
                              : o.power_term;
  st::LmmOptions sim = options;
  if (sim.family == st::Family::binomial) sim.lrt = true;
  std::cerr << "dtlab stats: simulating " << o.replications << " studies per size for the power of " << term << "\n";
  auto rows = st::lmm_power(data, sim, fit, {o.power_subjects, o.replications, o.alpha, o.seed, term});
  if (!rows) stats_fail(kExitUsage, "--power-subjects: " + rows.error().to_string());
  return *rows;
}

std::string lmm_fmt(double v, const char* f = "%.6g") {
  if (std::isnan(v)) return "NA";
  if (std::isinf(v)) return v > 0 ? "Inf" : "-Inf";
  char b[64];
  std::snprintf(b, sizeof b, f, v);
  return b;
}

std::string lmm_fmt_p(double p, double log10_p) {
  if (std::isnan(p)) return "NA";
  if (p < 1e-300 && std::isfinite(log10_p)) {
    const double e = std::floor(log10_p);
    char b[64];
    std::snprintf(b, sizeof b, "%.3ge%.0f", std::pow(10.0, log10_p - e), e);
    return b;
  }
  return lmm_fmt(p, "%.4g");
}

st::LmmOptions parse_options(const LmmCliOptions& o) {
  st::LmmOptions l;
  if (o.random == "intercepts") l.random = st::RandomEffects::intercepts;
  else if (o.random == "slopes") l.random = st::RandomEffects::slopes;
  else if (o.random == "max") l.random = st::RandomEffects::maximal;
  else stats_fail(kExitUsage, "--random must be intercepts, slopes or max, got " + st::quote_text(o.random));
  if (o.transform == "log") l.transform = st::Transform::log;
  else if (o.transform != "none") stats_fail(kExitUsage, "--transform must be log or none, got " + st::quote_text(o.transform));
  if (o.family == "binomial") l.family = st::Family::binomial;
  else if (o.family != "gaussian") stats_fail(kExitUsage, "--family must be gaussian or binomial, got " + st::quote_text(o.family));
  if (o.ddf == "kenward-roger") l.ddf = st::DenominatorDf::kenward_roger;
  else if (o.ddf != "satterthwaite")
    stats_fail(kExitUsage, "--ddf must be satterthwaite or kenward-roger, got " + st::quote_text(o.ddf));
  if (o.ml && o.reml) stats_fail(kExitUsage, "--reml and --ml exclude each other");
  l.reml = !o.ml;
  l.lrt = o.lrt;
  if (l.family == st::Family::binomial && l.transform == st::Transform::log)
    stats_fail(kExitUsage, "--transform log is for the gaussian family; the binomial family models 0/1 outcomes");
  if (l.family == st::Family::binomial && l.ddf == st::DenominatorDf::kenward_roger)
    stats_fail(kExitUsage, "--ddf applies to linear mixed models; a binomial GLMM uses Wald z tests");
  return l;
}

// The tables of marginal means: --emmeans A,B:C means A, then B x C; default each factor.
std::vector<std::vector<std::string>> emm_requests(const LmmCliOptions& o, const st::LmmFit& fit) {
  std::vector<std::vector<std::string>> out;
  if (o.emmeans.empty()) {
    for (const auto& f : fit.factor_names) out.push_back({f});
    return out;
  }
  for (const auto& spec : o.emmeans) {
    if (spec == "none") return {};
    std::vector<std::string> factors;
    size_t start = 0;
    while (true) {
      const size_t colon = spec.find(':', start);
      factors.push_back(spec.substr(start, colon == std::string::npos ? std::string::npos : colon - start));
      if (colon == std::string::npos) break;
      start = colon + 1;
    }
    out.push_back(factors);
  }
  return out;
}

void print_fit(const st::LmmFit& f) {
  const bool glmm = f.family == st::Family::binomial;
  if (glmm)
    std::cout << "Generalized linear mixed model fit by maximum likelihood (Laplace Approximation) [glmerMod]\n"
                 " Family: binomial  ( logit )\n";
  else
    std::cout << "Linear mixed model fit by " << (f.reml ? "REML" : "maximum likelihood") << ". t-tests use "
              << (f.kenward_roger ? "Kenward-Roger's" : "Satterthwaite's") << " method [lmerModLmerTest]\n";
  std::cout << "Formula: " << f.formula << "\n";
  for (const auto& s : f.fallback) std::cout << "  random-effects structure: " << s << "\n";
  if (f.reml && !glmm) std::cout << "\nREML criterion at convergence: " << lmm_fmt(f.reml_criterion, "%.4f") << "\n";
  std::cout << "\n     AIC      BIC   logLik deviance\n"
            << lmm_fmt(f.aic, "%8.4f") << " " << lmm_fmt(f.bic, "%8.4f") << " " << lmm_fmt(f.loglik, "%8.4f") << " "
            << lmm_fmt(-2 * f.loglik, "%8.4f") << "  (df = " << f.df << ")\n";
  std::cout << "\nRandom effects:\n Groups       Name                  Variance     Std.Dev.\n";
  for (const auto& v : f.variances) {
    char b[256];
    std::snprintf(b, sizeof b, " %-12s %-20s %12s %12s\n", v.group.c_str(), v.name.c_str(), lmm_fmt(v.variance).c_str(),
                  lmm_fmt(v.sd).c_str());
    std::cout << b;
  }
  for (const auto& c : f.correlations)
    std::cout << " correlation (" << c.group << ") " << c.a << ", " << c.b << ": " << lmm_fmt(c.r, "%.3f") << "\n";
  std::cout << "Number of obs: " << f.n;
  for (const auto& [g, n] : f.groups) std::cout << ", groups: " << g << ", " << n;
  std::cout << "\n\nFixed effects:\n                       Estimate   Std. Error" << (glmm ? "" : "         df")
            << (glmm ? "    z value" : "    t value") << (glmm ? "   Pr(>|z|)\n" : "   Pr(>|t|)\n");
  for (const auto& c : f.coefficients) {
    char b[256];
    std::snprintf(b, sizeof b, "%-20s %12s %12s %10s %10s %10s\n", c.name.c_str(), lmm_fmt(c.estimate).c_str(),
                  lmm_fmt(c.se).c_str(), glmm ? "" : lmm_fmt(c.df, "%.2f").c_str(), lmm_fmt(c.statistic, "%.3f").c_str(),
                  lmm_fmt_p(c.p, c.log10_p).c_str());
    std::cout << b;
  }
  if (!f.anova.empty()) {
    std::cout << "\nType III Analysis of Variance Table with " << (f.kenward_roger ? "Kenward-Roger's" : "Satterthwaite's")
              << " method\n                       Sum Sq      Mean Sq NumDF      DenDF    F value     Pr(>F)\n";
    for (const auto& a : f.anova) {
      char b[256];
      std::snprintf(b, sizeof b, "%-16s %12s %12s %5s %10s %10s %10s\n", a.term.c_str(), lmm_fmt(a.sum_sq).c_str(),
                    lmm_fmt(a.mean_sq).c_str(), lmm_fmt(a.num_df, "%.0f").c_str(), lmm_fmt(a.den_df, "%.3f").c_str(),
                    lmm_fmt(a.F, "%.4f").c_str(), lmm_fmt_p(a.p, a.log10_p).c_str());
      std::cout << b;
    }
  }
  if (!f.lrt.empty()) {
    std::cout << "\nLikelihood-ratio tests (each term's columns removed, ML fits)\n"
                 "term                 Df        Chisq   Pr(>Chisq)\n";
    for (const auto& l : f.lrt) {
      char b[256];
      std::snprintf(b, sizeof b, "%-16s %6s %12s %12s\n", l.term.c_str(), lmm_fmt(l.df, "%.0f").c_str(),
                    lmm_fmt(l.chisq, "%.4f").c_str(), lmm_fmt_p(l.p, l.log10_p).c_str());
      std::cout << b;
    }
  }
}

void print_emm(const st::EmmTable& t) {
  std::string name;
  for (const auto& f : t.factors) name += (name.empty() ? "" : " x ") + f;
  const bool back = t.scale != st::EmmScale::identity;
  std::cout << "\nEstimated marginal means of " << name
            << (t.scale == st::EmmScale::log ? " (model scale: log; response: exp)"
                : t.scale == st::EmmScale::logit ? " (model scale: logit; response: probability)"
                                                 : "")
            << "\n  cell                       emmean         SE        df   95% CI" << (back ? "                     response [95% CI]" : "") << "\n";
  for (const auto& m : t.means) {
    std::string cell;
    for (const auto& l : m.levels) cell += (cell.empty() ? "" : " ") + l;
    char b[512];
    std::snprintf(b, sizeof b, "  %-24s %10s %10s %9s   [%s, %s]", cell.c_str(), lmm_fmt(m.estimate).c_str(),
                  lmm_fmt(m.se).c_str(), lmm_fmt(m.df, "%.2f").c_str(), lmm_fmt(m.ci_low).c_str(), lmm_fmt(m.ci_high).c_str());
    std::cout << b;
    if (back) std::cout << "   " << lmm_fmt(m.response) << " [" << lmm_fmt(m.response_ci_low) << ", " << lmm_fmt(m.response_ci_high) << "]";
    std::cout << "\n";
  }
  if (t.contrasts.empty()) return;
  std::cout << "  pairwise contrasts (Holm over " << t.contrasts.size() << "; CIs unadjusted)"
            << (t.scale == st::EmmScale::log ? ": ratio = exp(estimate)" : t.scale == st::EmmScale::logit ? ": odds ratio = exp(estimate)" : "")
            << "\n";
  for (const auto& c : t.contrasts) {
    std::cout << "  " << c.a << " - " << c.b << ": estimate " << lmm_fmt(c.estimate) << ", SE " << lmm_fmt(c.se) << ", df "
              << lmm_fmt(c.df, "%.2f") << ", " << (std::isinf(c.df) ? "z" : "t") << " " << lmm_fmt(c.statistic, "%.3f") << ", p "
              << lmm_fmt_p(c.p, c.log10_p) << ", p_holm " << lmm_fmt(c.p_holm, "%.4g");
    if (back) std::cout << ", ratio " << lmm_fmt(c.ratio) << " [" << lmm_fmt(c.ratio_ci_low) << ", " << lmm_fmt(c.ratio_ci_high) << "]";
    std::cout << "\n";
  }
}

void run_lmm(const LmmCliOptions& o) {
  if (o.wide) stats_fail(kExitUsage, "lmm reads trial-level long data: one row per trial (no --wide)");
  if (o.dv.empty() || o.subject.empty()) stats_fail(kExitUsage, "lmm needs --dv COL and --subject COL");
  const st::LmmOptions options = parse_options(o);
  const SelectedTable in = load_selected_table(o);
  auto data = st::lmm_data_from_csv(in.table, {o.dv, o.subject, o.within, o.between}, o.item);
  if (!data) stats_fail(kExitInvalid, data.error().to_string());
  auto fit = st::fit_lmm(*data, options);
  if (!fit) stats_fail(kExitInvalid, fit.error().to_string());
  std::vector<st::EmmTable> emms;
  for (const auto& factors : emm_requests(o, *fit)) {
    auto t = st::marginal_means(*fit, factors);
    if (!t) stats_fail(kExitUsage, "--emmeans: " + t.error().to_string());
    emms.push_back(*t);
  }
  std::string power_term;
  const auto power = simulated_power(o, *data, options, *fit, power_term);
  for (const auto& m : fit->messages) std::cerr << "dtlab stats: " << m << "\n";
  for (const auto& w : fit->warnings) std::cerr << "dtlab stats: warning: " << w << "\n";
  const bool time = o.transform == "log";
  if (o.json) {
    json j{{"test", "lmm"}, {"data", o.data}, {"dv", o.dv}, {"subject", o.subject}, {"within", o.within},
           {"between", o.between}, {"item", o.item},
           {"rows", {{"read", in.selection.read}, {"used", in.selection.kept}, {"notes", in.selection.notes}}}};
    j.update(st::lmm_fit_json(*fit));
    json e = json::array();
    for (const auto& t : emms) {
      json tj = st::emm_table_json(t);
      json sentences = json::array();
      for (const auto& c : t.contrasts) sentences.push_back(st::apa_contrast_sentence(t, c, time, o.dv));
      tj["apa"] = sentences;
      e.push_back(tj);
    }
    j["emmeans"] = e;
    if (!power.empty()) {
      json pj = json::array();
      for (const auto& r : power)
        pj.push_back({{"n", r.n}, {"power", st::json_number(r.power.power)}, {"ci_low", st::json_number(r.power.ci_low)},
                      {"ci_high", st::json_number(r.power.ci_high)}, {"replications", r.power.replications},
                      {"rejections", r.power.rejections}, {"failed", r.power.undefined}});
      j["power"] = {{"term", power_term}, {"alpha", o.alpha}, {"seed", o.seed}, {"sizes", pj}};
    }
    std::cout << j.dump(2) << "\n";
    return;
  }
  if (!in.selection.notes.empty()) {
    std::cout << "Rows: " << in.selection.read << " read, " << in.selection.kept << " used";
    for (const auto& n : in.selection.notes) std::cout << "; " << n;
    std::cout << "\n\n";
  }
  print_fit(*fit);
  for (const auto& t : emms) print_emm(t);
  bool any = false;
  for (const auto& t : emms)
    for (const auto& c : t.contrasts) {
      if (!any) std::cout << "\nAPA\n";
      any = true;
      std::cout << "  " << st::apa_contrast_sentence(t, c, time, o.dv) << "\n";
    }
  if (!power.empty()) {
    std::cout << "\nSimulated power of " << power_term << " at alpha " << lmm_fmt(o.alpha) << " (" << o.replications
              << " studies per size simulated from the fit, as simr; seed " << o.seed << ")\n";
    for (const auto& r : power)
      std::cout << "  n = " << r.n << ": " << lmm_fmt(r.power.power, "%.3f") << " [" << lmm_fmt(r.power.ci_low, "%.3f") << ", "
                << lmm_fmt(r.power.ci_high, "%.3f") << "]" << (r.power.undefined ? ", " + std::to_string(r.power.undefined) + " fits failed" : "")
                << "\n";
  }
  std::cout << "\nThe same model in R:\n" << fit->r_code;
}

}  // namespace

void add_stats_lmm_command(CLI::App& stats) {
  auto o = std::make_shared<LmmCliOptions>();
  auto* cmd = stats.add_subcommand("lmm", "Linear or binomial mixed model on trial-level data (lme4 / lmerTest)");
  cmd->add_option("--data", o->data, "CSV file, one row per trial")->required();
  cmd->add_option("--dv", o->dv, "Column of the dependent variable (numbers; empty or NA = missing)")->required();
  cmd->add_option("--subject", o->subject, "Column of the subject id (random intercepts)")->required();
  cmd->add_option("--within", o->within, "Within-subject factor column(s), comma separated")->delimiter(',');
  cmd->add_option("--between", o->between, "Between-subject factor column(s), comma separated")->delimiter(',');
  cmd->add_option("--item", o->item, "Column of the item (e.g. the scene): crossed random intercepts");
  cmd->add_option("--random", o->random,
                  "intercepts|slopes|max: random intercepts; plus by-subject slopes of the within factors; or the "
                  "maximal structure, simplified when singular or not converged")
      ->capture_default_str();
  cmd->add_option("--transform", o->transform, "none|log: model log(dv) (means and contrasts back-transformed to ratios)")
      ->capture_default_str();
  cmd->add_option("--family", o->family, "gaussian|binomial: binomial for 0/1 outcomes (GLMM, Laplace)")
      ->capture_default_str();
  cmd->add_flag("--reml", o->reml, "Fit by REML (the default for the gaussian family)");
  cmd->add_flag("--ml", o->ml, "Fit by maximum likelihood");
  cmd->add_option("--ddf", o->ddf, "satterthwaite|kenward-roger: denominator df of the t and F tests")
      ->capture_default_str();
  cmd->add_flag("--lrt", o->lrt, "Likelihood-ratio test of each term (ML fits; always with the binomial family)");
  cmd->add_option("--emmeans", o->emmeans,
                  "Marginal means to print: factors joined by ':' for a table of cells, comma between tables, "
                  "'none' for none (default: each factor)")
      ->delimiter(',');
  cmd->add_option("--power-subjects", o->power_subjects,
                  "Simulated power (as simr) of --power-term at these numbers of subjects, e.g. 8,16,24")
      ->delimiter(',');
  cmd->add_option("--power-term", o->power_term, "The fixed term whose power is simulated (default: the first)");
  cmd->add_option("--replications", o->replications, "Simulated studies per size")->capture_default_str();
  cmd->add_option("--seed", o->seed, "Seed of the simulation")->capture_default_str();
  cmd->add_option("--alpha", o->alpha, "Significance level of the simulated tests")->capture_default_str();
  cmd->add_option("--where", o->where, "Keep rows where COL=VALUE (or COL!=VALUE); repeatable, all must hold");
  cmd->add_flag("--exclude-practice", o->exclude_practice,
                "Leave out rows whose practice column is 1/true/yes (the default for a dtlab export)");
  cmd->add_flag("--include-practice", o->include_practice, "Keep the practice rows of a dtlab export");
  cmd->add_flag("--with-excluded", o->with_excluded, "Keep rows with a non-empty 'excluded' column (left out by default)");
  cmd->add_flag("--json", o->json, "Print one JSON object (see docs/stats.md)");
  cmd->callback([o] { run_lmm(*o); });
}

}  // namespace dtlab::app

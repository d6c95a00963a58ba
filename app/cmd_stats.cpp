// `dtlab stats anova|rm-anova|friedman|wilcoxon`: the statistics library
// (analysis/stats) on any long-format CSV (or --wide, one column per
// condition). Rows are selected first (--where, practice trials, rows marked
// excluded: analysis/stats/select.h) and what was left out is stated. Prints
// a readable table, or with --json one JSON object whose numbers round-trip
// (analysis/stats/json.h: NaN as null, infinities as "Infinity"/"-Infinity").
// Warnings (listwise deletion naming the subjects, degenerate data) go to
// stderr and into the JSON "warnings" array; Monte Carlo progress to stderr.
// Mixed designs' follow-ups are emmeans' on the afex fit (posthoc.h, followup.h).
// Exit codes: 1 bad CSV or data, 3 unreadable file, 2 bad command line.
// Never writes any file.
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "analysis/stats/anova.h"
#include "analysis/stats/apa.h"
#include "analysis/stats/assumptions.h"
#include "analysis/stats/csv.h"
#include "analysis/stats/effect_size.h"
#include "analysis/stats/followup.h"
#include "analysis/stats/friedman.h"
#include "analysis/stats/json.h"
#include "analysis/stats/long_data.h"
#include "analysis/stats/paired.h"
#include "analysis/stats/posthoc.h"
#include "analysis/stats/rm_anova.h"
#include "analysis/stats/select.h"
#include "app/commands.h"
#include "app/stats_input.h"

namespace dtlab::app {
namespace {

using json = nlohmann::ordered_json;
namespace st = dtlab::stats;

// Every option of the four tests; the table-reading ones are StatsInput's (stats_input.h).
struct StatsOptions : StatsInput {
  std::string exact = "auto", alternative = "two-sided", factor;
  std::vector<std::string> observed;
  std::uint64_t seed = 1;
  bool json = false, posthoc = false, no_correct = false;
  bool simple_effects = false, within_ci = false, normality = false;
};

// The optional follow-ups of rm-anova (--simple-effects, --within-ci, --normality).
struct Followups {
  std::vector<std::string> between;  // the design's between factors (their contrasts' effect size is d, not d_z)
  std::vector<st::SimpleEffects> simple;
  std::vector<st::CellInterval> intervals;
  std::optional<st::ShapiroWilkResult> normality;
};

[[noreturn]] void fail(int code, const std::string& message) { stats_fail(code, message); }

std::string fmt(double v) {
  if (std::isnan(v)) return "NA";
  if (std::isinf(v)) return v > 0 ? "Infinity" : "-Infinity";
  char b[64];
  std::snprintf(b, sizeof b, "%.6g", v);
  return b;
}

// p for a table: 6 significant digits; below the double range from its log10 ("5.89e-346"); 0 only when exact.
std::string fmt_p(double p, double log10_p) {
  if (std::isnan(p)) return "NA";
  if (p == 0 && std::isinf(log10_p)) return "0";
  if (p < 1e-300 && std::isfinite(log10_p)) {
    const double e = std::floor(log10_p);
    char b[64];
    std::snprintf(b, sizeof b, "%.3ge%.0f", std::pow(10.0, log10_p - e), e);
    return b;
  }
  return fmt(p);
}

std::string count(std::size_t n, const char* one, const char* many) {
  return std::to_string(n) + " " + (n == 1 ? one : many);
}

st::ExactOptions parse_exact(const StatsOptions& o) {
  st::ExactOptions e;
  e.seed = o.seed;
  if (o.exact == "auto") {
    e.mode = st::ExactMode::automatic;
  } else if (o.exact == "always") {
    e.mode = st::ExactMode::always;
  } else if (o.exact == "never") {
    e.mode = st::ExactMode::never;
  } else if (o.exact.rfind("monte-carlo=", 0) == 0) {
    e.mode = st::ExactMode::monte_carlo;
    const std::string n = o.exact.substr(12);
    char* end = nullptr;
    const unsigned long long v = std::strtoull(n.c_str(), &end, 10);
    if (n.empty() || *end != '\0' || v == 0 || v > 100000000ULL)
      fail(kExitUsage, "--exact monte-carlo=N needs N between 1 and 100000000, got " + st::quote_text(n));
    e.monte_carlo_samples = static_cast<std::size_t>(v);
    e.progress = [last = -1](std::size_t done, std::size_t total) mutable {
      const int tenth = static_cast<int>(10 * done / total);
      if (tenth == last) return;
      last = tenth;
      std::cerr << "dtlab stats: Monte Carlo " << done << " of " << total << " resamples\n";
    };
  } else {
    fail(kExitUsage, "--exact must be auto, always, never or monte-carlo=N, got " + st::quote_text(o.exact));
  }
  return e;
}

Loaded load(const StatsOptions& o, bool groups_design) { return load_stats_input(o, groups_design); }

void warn(const std::vector<std::string>& warnings) {
  for (const auto& w : warnings) std::cerr << "dtlab stats: warning: " << w << "\n";
}

json header_json(const char* test, const StatsOptions& o, const st::SelectionReport& s) {
  json where = json::array();
  for (const auto& w : o.where) where.push_back(w);
  return json{{"test", test},
              {"data", o.data},
              {"dv", o.dv},
              {"subject", o.subject},
              {"within", o.within},
              {"between", o.between},
              {"aggregate", o.aggregate},
              {"rows", {{"read", s.read},
                        {"used", s.kept},
                        {"practice_left_out", s.practice_left_out},
                        {"excluded_left_out", s.excluded_left_out},
                        {"where_left_out", s.where_left_out},
                        {"where", where},
                        {"notes", s.notes}}}};
}

void print_selection(const st::SelectionReport& s) {
  if (s.notes.empty()) return;
  std::cout << "Rows: " << s.read << " read, " << s.kept << " used";
  for (const auto& n : s.notes) std::cout << "; " << n;
  std::cout << "\n\n";
}

void print_comparisons(const std::string& factor, const std::vector<st::Comparison>& cs) {
  std::cout << "\nPairwise comparisons of " << factor << " (Holm-corrected; differences a - b)\n"
            << "  a - b                    test        n   estimate         SE   95% CI                    statistic"
               "       df          p     p_holm        dz\n";
  for (const auto& c : cs) {
    char b[512];
    std::snprintf(b, sizeof b, "  %-24s %-9s %4zu %10s %10s   [%10s, %10s] %10s %8s %10s %10s %9s\n",
                  (c.a + " - " + c.b).c_str(), c.test.c_str(), c.n, fmt(c.estimate).c_str(), fmt(c.se).c_str(),
                  fmt(c.ci_low).c_str(), fmt(c.ci_high).c_str(), fmt(c.statistic).c_str(), fmt(c.df).c_str(),
                  fmt(c.p).c_str(), fmt(c.p_holm).c_str(), fmt(c.dz).c_str());
    std::cout << b;
  }
}

void print_effects(const std::vector<st::Effect>& effects) {
  std::cout << "effect                    df1      df2          SS    SS_error         MSE           F          p"
               "   eta_p2  90% CI of eta_p2     eta_g2\n";
  for (const auto& e : effects) {
    char b[512];
    std::snprintf(b, sizeof b, "%-20s %8s %8s %11s %11s %11s %11s %10s %8s  [%6s, %6s] %10s\n", e.name.c_str(),
                  fmt(e.df1).c_str(), fmt(e.df2).c_str(), fmt(e.ss).c_str(), fmt(e.ss_error).c_str(), fmt(e.mse).c_str(),
                  fmt(e.F).c_str(), fmt_p(e.p, e.log10_p).c_str(), fmt(e.eta_p2).c_str(),
                  st::apa_bounded(e.eta_p2_ci_low, 3).c_str(), st::apa_bounded(e.eta_p2_ci_high, 3).c_str(),
                  fmt(e.eta_g2).c_str());
    std::cout << b;
  }
  std::cout << "(df, MSE and p uncorrected; 90% CI of eta_p2: noncentral F, lambda / (lambda + df1 + df2 + 1) as "
               "MBESS / apaTables, not effectsize's lambda / (lambda + df2))\n";
  bool any = false;
  for (const auto& e : effects) any = any || (e.within && !std::isnan(e.mauchly_W));
  if (any) {
    std::cout << "\nsphericity            Mauchly W     p(W)     GG eps            df (GG)    MSE (GG)      p[GG]"
                 "     HF eps            df (HF)      p[HF]\n";
    for (const auto& e : effects) {
      if (!e.within || std::isnan(e.mauchly_W)) continue;
      char b[512];
      std::snprintf(b, sizeof b, "%-20s %11s %8s %10s %18s %11s %10s %10s %18s %10s\n", e.name.c_str(),
                    fmt(e.mauchly_W).c_str(), fmt(e.mauchly_p).c_str(), fmt(e.gg_epsilon).c_str(),
                    (fmt(e.df1_gg) + ", " + fmt(e.df2_gg)).c_str(), fmt(e.mse_gg).c_str(),
                    fmt_p(e.p_gg, e.log10_p_gg).c_str(), fmt(e.hf_epsilon).c_str(),
                    (fmt(e.df1_hf) + ", " + fmt(e.df2_hf)).c_str(), fmt_p(e.p_hf, e.log10_p_hf).c_str());
      std::cout << b;
    }
    std::cout << "(MSE (GG) = SS_error / df2 (GG), as afex prints it beside corrected df)\n";
  }
  std::cout << "\nAPA (Greenhouse-Geisser df and p for within effects with more than one df)\n";
  for (const auto& e : effects) std::cout << "  " << e.name << ": " << st::apa_effect(e) << "\n";
}

void print_descriptives(const std::string& label, const st::Descriptives& d) {
  std::cout << "  " << label << ": n " << d.n << ", mean " << fmt(d.mean) << ", sd " << fmt(d.sd) << ", se " << fmt(d.se)
            << ", CI [" << fmt(d.ci_low) << ", " << fmt(d.ci_high) << "], median " << fmt(d.median) << ", IQR "
            << fmt(d.iqr) << "\n";
}

void run_anova(const StatsOptions& o) {
  if (o.between.size() != 1 && !o.wide) fail(kExitUsage, "anova needs --between COL (one factor)");
  if (!o.within.empty()) fail(kExitUsage, "anova takes no --within; use rm-anova");
  const Loaded in = load(o, true);
  auto r = st::one_way_anova(in.data);
  if (!r) fail(kExitInvalid, r.error().to_string());
  std::vector<st::Comparison> post;
  if (o.posthoc) {
    auto pc = st::pairwise_between(in.data);
    if (!pc) fail(kExitInvalid, pc.error().to_string());
    post = *pc;
  }
  warn(r->warnings);
  if (o.json) {
    json j = header_json("anova", o, in.selection);
    j["n"] = r->n;
    j["eta_p2_ci90_method"] = st::kEtaP2IntervalMethod;
    j["effects"] = json::array({st::effect_json(r->effect)});
    json groups = json::array();
    for (const auto& g : r->groups) {
      json d = st::descriptives_json(g.d);
      d["group"] = g.level;
      groups.push_back(d);
    }
    j["descriptives"] = groups;
    if (o.posthoc) j["posthoc"] = st::comparisons_json(post);
    j["warnings"] = r->warnings;
    std::cout << j.dump(2) << "\n";
    return;
  }
  print_selection(in.selection);
  std::cout << "One-way ANOVA of " << in.data.dv_name << " by " << r->factor << " ("
            << count(r->n, "observation", "observations") << ")\n\n";
  print_effects({r->effect});
  std::cout << "\ngroups\n";
  for (const auto& g : r->groups) print_descriptives(g.level, g.d);
  if (o.posthoc) print_comparisons(r->factor, post);
}

void require_subject_design(const StatsOptions& o, const char* test) {
  if (o.wide) return;
  if (o.subject.empty() || o.within.empty())
    fail(kExitUsage, std::string(test) + " needs --subject COL and --within COL[,COL] (or --wide)");
}

Followups followups(const StatsOptions& o, const st::LongData& data, const st::RmAnovaResult& r) {
  Followups f;
  f.between = r.between;
  // Every pair of within factors; with between factors every pair of factors (emmeans on the afex fit).
  std::vector<std::string> factors = r.between;
  factors.insert(factors.end(), r.within.begin(), r.within.end());
  if (o.simple_effects && factors.size() < 2) fail(kExitUsage, "--simple-effects needs two factors or more");
  if (o.simple_effects)
    for (std::size_t i = 0; i < factors.size(); ++i)
      for (std::size_t j = i + 1; j < factors.size(); ++j) {
        auto se = st::simple_effects(data, factors[i], factors[j]);
        if (!se) fail(kExitInvalid, se.error().to_string());
        f.simple.push_back(*se);
      }
  if (o.within_ci) {
    auto ci = st::within_subject_intervals(data);
    if (!ci) fail(kExitInvalid, ci.error().to_string());
    f.intervals = *ci;
  }
  if (o.normality) {
    auto res = st::anova_residuals(data);
    if (!res) fail(kExitInvalid, res.error().to_string());
    std::vector<double> e;
    for (const auto& x : res->residuals) e.push_back(x.value);
    f.normality = st::shapiro_wilk(e);
    warn(f.normality->warnings);
  }
  return f;
}

json levels_json(const std::vector<std::pair<std::string, std::string>>& levels) {
  json lv = json::object();
  for (const auto& [f, l] : levels) lv[f] = l;
  return lv;
}

void followups_json(json& j, const Followups& f) {
  if (!f.simple.empty()) {
    json rows = json::array();
    for (const auto& se : f.simple)
      for (const auto& row : se.rows) {
        json r{{"factor", row.factor}, {"at", {{row.at_factor, row.at_level}}}, {"test", row.test}, {"n", row.n},
               {"p", st::json_number(row.p)}, {"p_holm", st::json_number(row.p_holm)}};
        if (row.test == "paired t" || row.test == "emmeans t") r["contrast"] = st::comparison_json(row.contrast);
        else if (row.test == "emmeans F") r["joint_test"] = st::joint_test_json(row.anova);
        else r["anova"] = st::effect_json(row.anova);
        rows.push_back(r);
      }
    j["simple_effects"] = rows;
  }
  if (!f.intervals.empty()) {
    json cells = json::array();
    for (const auto& c : f.intervals)
      cells.push_back({{"cell", levels_json(c.levels)}, {"n", c.n}, {"mean", st::json_number(c.mean)},
                       {"se", st::json_number(c.se)}, {"ci_low", st::json_number(c.ci_low)},
                       {"ci_high", st::json_number(c.ci_high)}});
    j["within_subject_ci"] = cells;
  }
  if (f.normality)
    j["normality"] = {{"test", "shapiro-wilk on the ANOVA residuals"}, {"n", f.normality->n},
                      {"W", st::json_number(f.normality->W)}, {"p", st::json_number(f.normality->p)}};
}

void print_followups(const Followups& f) {
  for (const auto& se : f.simple) {
    const bool emmeans = !se.rows.empty() && se.rows[0].test.rfind("emmeans", 0) == 0;
    std::cout << "\nSimple effects (Holm within each family"
              << (emmeans ? "; emmeans on the multivariate afex fit: groups weighted equally, pooled error)" : ")") << "\n";
    for (const auto& row : se.rows) {
      std::cout << "  " << row.factor << " at " << row.at_factor << "=" << row.at_level << ": ";
      if (row.test == "emmeans F")
        std::cout << "F(" << fmt(row.anova.df1) << ", " << fmt(row.anova.df2) << ") = " << fmt(row.anova.F)
                  << ", p = " << fmt_p(row.p, row.anova.log10_p) << ", p_holm = " << fmt(row.p_holm) << " (emmeans joint test)\n";
      else if (row.test == "paired t" || row.test == "emmeans t")
        std::cout << row.contrast.a << " - " << row.contrast.b << " = " << fmt(row.contrast.estimate) << " [" << fmt(row.contrast.ci_low)
                  << ", " << fmt(row.contrast.ci_high) << "], t(" << fmt(row.contrast.df) << ") = " << fmt(row.contrast.statistic)
                  << ", p = " << fmt(row.p) << ", p_holm = " << fmt(row.p_holm) << ", "
                  << (std::find(f.between.begin(), f.between.end(), row.factor) != f.between.end() ? "d" : "d_z")
                  << " = " << fmt(row.contrast.dz) << "\n";
      else
        std::cout << st::apa_effect(row.anova, st::Correction::none) << " (p = " << fmt(row.p) << ", p_holm = " << fmt(row.p_holm) << ")\n";
    }
  }
  if (!f.intervals.empty()) {
    std::cout << "\nWithin-subject 95% CIs of the cell means (Cousineau-Morey)\n";
    for (const auto& c : f.intervals) {
      std::string label;
      for (const auto& [name, level] : c.levels) label += (label.empty() ? "" : ", ") + name + "=" + level;
      std::cout << "  " << label << ": mean " << fmt(c.mean) << ", se " << fmt(c.se) << ", CI [" << fmt(c.ci_low) << ", "
                << fmt(c.ci_high) << "]\n";
    }
  }
  if (f.normality)
    std::cout << "\nShapiro-Wilk on the ANOVA residuals: W = " << fmt(f.normality->W) << ", p = " << fmt(f.normality->p)
              << " (" << count(f.normality->n, "residual", "residuals") << ")\n";
}

void run_rm_anova(const StatsOptions& o) {
  require_subject_design(o, "rm-anova");
  const Loaded in = load(o, false);
  st::RmAnovaOptions ro;
  ro.observed = o.observed;
  auto r = st::rm_anova(in.data, ro);
  if (!r) fail(kExitInvalid, r.error().to_string());
  std::vector<std::pair<std::string, std::vector<st::Comparison>>> post;
  if (o.posthoc)
    for (const auto& f : r->within) {
      auto pc = st::pairwise_within(in.data, f, st::PairwiseTest::paired_t);
      if (!pc) fail(kExitInvalid, pc.error().to_string());
      post.emplace_back(f, *pc);
    }
  warn(r->warnings);
  const Followups more = followups(o, in.data, *r);
  if (o.json) {
    json j = header_json("rm-anova", o, in.selection);
    j["within"] = r->within;
    j["n_subjects"] = r->n_subjects;
    j["dropped_subjects"] = r->dropped_subjects;
    j["eta_p2_ci90_method"] = st::kEtaP2IntervalMethod;
    j["effects"] = json::array();
    for (const auto& e : r->effects) {
      json ej = st::effect_json(e);
      ej["apa"] = st::apa_effect(e);
      j["effects"].push_back(ej);
    }
    json cells = json::array();
    for (const auto& c : r->cells) {
      json d = st::descriptives_json(c.d);
      json lv = json::object();
      for (const auto& [f, l] : c.levels) lv[f] = l;
      d["cell"] = lv;
      cells.push_back(d);
    }
    j["descriptives"] = cells;
    if (o.posthoc) {
      json p = json::object();
      for (const auto& [f, cs] : post) p[f] = st::comparisons_json(cs);
      j["posthoc"] = p;
    }
    followups_json(j, more);
    j["warnings"] = r->warnings;
    std::cout << j.dump(2) << "\n";
    return;
  }
  print_selection(in.selection);
  std::cout << "Repeated-measures ANOVA of " << in.data.dv_name << " (" << count(r->n_subjects, "subject", "subjects");
  if (!r->dropped_subjects.empty()) std::cout << ", " << r->dropped_subjects.size() << " removed";
  std::cout << "; type III, car/afex conventions)\n\n";
  print_effects(r->effects);
  std::cout << "\ncell means (over subjects)\n";
  for (const auto& c : r->cells) {
    std::string label;
    for (const auto& [f, l] : c.levels) label += (label.empty() ? "" : ", ") + f + "=" + l;
    print_descriptives(label, c.d);
  }
  for (const auto& [f, cs] : post) print_comparisons(f, cs);
  print_followups(more);
}

void run_friedman(const StatsOptions& o) {
  require_subject_design(o, "friedman");
  const st::ExactOptions exact = parse_exact(o);
  const Loaded in = load(o, false);
  auto r = st::friedman(in.data, exact);
  if (!r) fail(kExitInvalid, r.error().to_string());
  std::vector<st::Comparison> post;
  if (o.posthoc) {
    if (in.data.within.size() != 1) fail(kExitUsage, "--posthoc for friedman needs exactly one within factor");
    auto pc = st::pairwise_within(in.data, in.data.within.front().name, st::PairwiseTest::wilcoxon);
    if (!pc) fail(kExitInvalid, pc.error().to_string());
    post = *pc;
  }
  warn(r->warnings);
  if (o.json) {
    json j = header_json("friedman", o, in.selection);
    j.update(st::friedman_json(*r));
    j["dropped_subjects"] = r->dropped_blocks;
    if (o.posthoc) j["posthoc"] = st::comparisons_json(post);
    j["warnings"] = r->warnings;
    std::cout << j.dump(2) << "\n";
    return;
  }
  print_selection(in.selection);
  std::cout << "Friedman rank sum test (" << count(r->n, "block", "blocks") << ", " << count(r->k, "treatment", "treatments")
            << (r->ties ? ", ties" : "") << ")\n  Q = " << fmt(r->Q) << ", df = " << fmt(r->df)
            << ", p = " << fmt_p(r->p, r->log10_p) << " (chi-square)\n  p_exact = " << fmt(r->p_exact) << " ("
            << r->exact_method;
  if (r->exact_method == "monte-carlo") std::cout << ", " << r->monte_carlo_samples << " resamples, seed " << r->seed;
  if (!r->exact_note.empty()) std::cout << ": " << r->exact_note;
  std::cout << ")\n  Kendall's W = " << fmt(r->kendall_W) << "\n  Iman-Davenport F(" << fmt(r->id_df1) << ", "
            << fmt(r->id_df2) << ") = " << fmt(r->iman_davenport_F)
            << ", p = " << fmt_p(r->p_iman_davenport, r->log10_p_iman_davenport) << "\n";
  for (std::size_t j = 0; j < r->treatments.size() && j < r->mean_ranks.size(); ++j)
    std::cout << "  mean rank " << r->treatments[j] << ": " << fmt(r->mean_ranks[j]) << "\n";
  if (o.posthoc) print_comparisons(in.data.within.front().name, post);
}

void run_wilcoxon(const StatsOptions& o) {
  require_subject_design(o, "wilcoxon");
  st::WilcoxonOptions wo;
  wo.exact = parse_exact(o);
  wo.correct = !o.no_correct;
  if (o.alternative == "two-sided") wo.alternative = st::Alternative::two_sided;
  else if (o.alternative == "less") wo.alternative = st::Alternative::less;
  else if (o.alternative == "greater") wo.alternative = st::Alternative::greater;
  else fail(kExitUsage, "--alternative must be two-sided, less or greater");
  const Loaded in = load(o, false);
  if (o.factor.empty() && in.data.within.size() > 1)
    fail(kExitUsage, "with several --within factors, name the two-level one to test with --factor");
  auto r = st::paired_tests(in.data, wo, o.factor);
  if (!r) fail(kExitInvalid, r.error().to_string());
  warn(r->warnings);
  const auto& w = r->wilcoxon;
  if (o.json) {
    json j = header_json("wilcoxon", o, in.selection);
    j["x"] = r->x_level;
    j["y"] = r->y_level;
    j["alternative"] = o.alternative;
    j.update(st::wilcoxon_json(w));
    j["sign_test"] = st::sign_test_json(r->sign);
    j["paired_t"] = st::paired_t_json(r->t);
    j["dropped_subjects"] = r->dropped_subjects;
    j["warnings"] = r->warnings;
    std::cout << j.dump(2) << "\n";
    return;
  }
  print_selection(in.selection);
  const char* ci = o.alternative == "two-sided" ? "95% CI" : "one-sided 95% CI";
  std::cout << "Paired tests of " << in.data.dv_name << ": " << r->x_level << " - " << r->y_level << " ("
            << count(w.pairs, "pair", "pairs") << ", alternative " << o.alternative << ")\n  Wilcoxon signed-rank: V = "
            << fmt(w.V) << ", p = " << fmt_p(w.p, w.log10_p) << " (" << w.method << "), z = " << fmt(w.z)
            << ", p_exact = " << fmt(w.p_exact);
  if (!w.exact_note.empty()) std::cout << " (" << w.exact_note << ")";
  std::cout << "\n  sign test: " << r->sign.positive << " positive, " << r->sign.negative
            << " negative, p = " << fmt_p(r->sign.p, r->sign.log10_p) << "\n  paired t: t(" << fmt(r->t.df)
            << ") = " << fmt(r->t.t) << ", p = " << fmt_p(r->t.p, r->t.log10_p) << ", mean difference "
            << fmt(r->t.mean_difference) << ", " << ci << " [" << fmt(r->t.ci_low) << ", " << fmt(r->t.ci_high)
            << "], d_z = " << fmt(r->t.dz) << "\n";
}

void add_common(CLI::App* cmd, StatsOptions& o) {
  cmd->add_option("--data", o.data, "CSV file (long format: one row per observation)")->required();
  cmd->add_option("--dv", o.dv, "Column of the dependent variable (numbers; empty or NA = missing)");
  cmd->add_option("--subject", o.subject, "Column of the subject id");
  cmd->add_option("--within", o.within, "Within-subject factor column(s), comma separated")->delimiter(',');
  cmd->add_option("--between", o.between, "Between-subject factor column(s), comma separated")->delimiter(',');
  cmd->add_flag("--wide", o.wide, "One row per subject, one column per condition (empty cell = missing)");
  cmd->add_option("--where", o.where, "Keep rows where COL=VALUE (or COL!=VALUE); repeatable, all must hold");
  cmd->add_flag("--exclude-practice", o.exclude_practice,
                "Leave out rows whose practice column is 1/true/yes. This is the default for a dtlab export (a CSV "
                "with the columns practice, trial_seed and protocol_sha256); the output's Rows line says which rule "
                "applied");
  cmd->add_flag("--include-practice", o.include_practice, "Keep the practice rows of a dtlab export");
  cmd->add_flag("--with-excluded", o.with_excluded,
                "Keep rows with a non-empty 'excluded' column (left out by default)");
  cmd->add_option("--aggregate", o.aggregate,
                  "none|mean|median: several rows per subject and cell (e.g. the trials of a dtlab export) are an "
                  "error naming both lines (none), or reduced to their mean or median")
      ->capture_default_str();
  cmd->add_flag("--json", o.json, "Print one JSON object (see README, Statistics)");
}

void add_exact(CLI::App* cmd, StatsOptions& o) {
  cmd->add_option("--exact", o.exact,
                  "auto|always|never|monte-carlo=N: how p_exact is computed (auto: exact when it is cheap, else none)")
      ->capture_default_str();
  cmd->add_option("--seed", o.seed, "Monte Carlo seed")->capture_default_str();
}

}  // namespace

void add_stats_command(CLI::App& root) {
  auto* stats = root.add_subcommand("stats", "Statistics on a CSV: ANOVA, repeated-measures ANOVA, Friedman, Wilcoxon, mixed models");
  stats->require_subcommand(1);
  auto o = std::make_shared<StatsOptions>();

  auto* anova = stats->add_subcommand("anova", "One-way between-subjects ANOVA (--between COL)");
  add_common(anova, *o);
  anova->add_flag("--posthoc", o->posthoc, "Holm-corrected pairwise t tests with pooled SD");
  anova->callback([o] { run_anova(*o); });

  auto* rm = stats->add_subcommand("rm-anova", "Repeated-measures (and mixed) ANOVA with sphericity corrections");
  add_common(rm, *o);
  rm->add_option("--observed", o->observed, "Measured (not manipulated) factors, for generalized eta squared")->delimiter(',');
  rm->add_flag("--posthoc", o->posthoc,
               "Holm-corrected pairwise comparisons of each within factor: paired t; with a between factor, emmeans "
               "contrasts on the afex fit (groups weighted equally, pooled error, N - g df)");
  rm->add_flag("--simple-effects", o->simple_effects,
               "Simple effects of every pair of within factors (paired t or one-way ANOVA); with a between factor, of "
               "every pair of factors as emmeans joint_tests / pairs(emmeans(fit, ~ A | B)) give them (Holm per family)");
  rm->add_flag("--within-ci", o->within_ci, "Within-subject 95% CIs of the cell means (Cousineau-Morey)");
  rm->add_flag("--normality", o->normality, "Shapiro-Wilk test of the ANOVA residuals");
  rm->callback([o] { run_rm_anova(*o); });

  auto* fr = stats->add_subcommand("friedman", "Friedman rank sum test with exact / Monte Carlo p and Kendall's W");
  add_common(fr, *o);
  add_exact(fr, *o);
  fr->add_flag("--posthoc", o->posthoc, "Holm-corrected pairwise Wilcoxon signed-rank tests");
  fr->callback([o] { run_friedman(*o); });

  auto* wx = stats->add_subcommand("wilcoxon", "Wilcoxon signed-rank, sign and paired t tests (two conditions)");
  add_common(wx, *o);
  add_exact(wx, *o);
  wx->add_flag("--no-correct", o->no_correct, "No continuity correction in the normal approximation");
  wx->add_option("--factor", o->factor,
                 "With several --within factors: the two-level factor to test (each subject's values averaged over the others)");
  wx->add_option("--alternative", o->alternative, "two-sided|less|greater (for first level - second level)")
      ->capture_default_str();
  wx->callback([o] { run_wilcoxon(*o); });

  add_stats_lmm_command(*stats);  // mixed models: app/cmd_stats_lmm.cpp
}

}  // namespace dtlab::app

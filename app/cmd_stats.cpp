// `dtlab stats anova|rm-anova|friedman|wilcoxon`: the statistics library
// (analysis/stats) on any long-format CSV (or --wide, one column per
// condition). Prints a readable table, or with --json one JSON object whose
// numbers round-trip (shortest representation that reads back to the same
// double; NaN as null, infinities as the strings "Infinity"/"-Infinity").
// Warnings (listwise deletion naming the subjects, degenerate data) go to
// stderr and into the JSON "warnings" array. Exit codes: 1 bad CSV or data,
// 3 unreadable file, 2 bad command line. Never writes any file.
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "analysis/stats/anova.h"
#include "analysis/stats/csv.h"
#include "analysis/stats/friedman.h"
#include "analysis/stats/long_data.h"
#include "analysis/stats/paired.h"
#include "analysis/stats/posthoc.h"
#include "analysis/stats/rm_anova.h"
#include "app/commands.h"

namespace dtlab::app {
namespace {

using json = nlohmann::ordered_json;
namespace st = dtlab::stats;

struct StatsOptions {
  std::string data, dv, subject, exact = "auto", alternative = "two-sided";
  std::vector<std::string> within, between, observed;
  std::uint64_t seed = 1;
  bool wide = false, json = false, posthoc = false, no_correct = false;
};

json num(double v) {
  if (std::isnan(v)) return nullptr;
  if (std::isinf(v)) return v > 0 ? "Infinity" : "-Infinity";
  return v;
}

[[noreturn]] void fail(int code, const std::string& message) {
  std::cerr << "dtlab stats: " << message << "\n";
  throw CLI::RuntimeError(code);
}

std::string fmt(double v) {
  if (std::isnan(v)) return "NA";
  if (std::isinf(v)) return v > 0 ? "Inf" : "-Inf";
  char b[64];
  std::snprintf(b, sizeof b, "%.6g", v);
  return b;
}

std::string fmt_p(double p, double log10_p) {
  if (std::isnan(p)) return "NA";
  if (p < 1e-300 || p == 0) return "1e" + fmt(log10_p);
  return fmt(p);
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
      fail(kExitUsage, "--exact monte-carlo=N needs N between 1 and 100000000, got '" + n + "'");
    e.monte_carlo_samples = static_cast<std::size_t>(v);
  } else {
    fail(kExitUsage, "--exact must be auto, always, never or monte-carlo=N, got '" + o.exact + "'");
  }
  return e;
}

// Reads the CSV and assigns the roles; on failure prints file:line:column and throws.
st::LongData load(const StatsOptions& o, bool groups_design) {
  auto table = st::read_csv_file(o.data);
  if (!table) fail(table.error().line == 0 && table.error().message.rfind("cannot open", 0) == 0 ? kExitFailure : kExitInvalid,
                   table.error().to_string());
  Result<st::LongData> data = Error{};
  if (o.wide) {
    st::WideRoles w;
    w.subject = o.subject;
    w.dv = o.dv.empty() ? "value" : o.dv;
    if (groups_design) {
      w.conditions_are_groups = true;
      w.factor = o.between.empty() ? "group" : o.between.front();
    } else {
      w.between = o.between;
      if (o.within.size() > 1) fail(kExitUsage, "--wide takes one within factor name (its columns are the conditions)");
      w.factor = o.within.empty() ? "condition" : o.within.front();
    }
    data = st::long_data_from_wide_csv(*table, w);
  } else {
    if (o.dv.empty()) fail(kExitUsage, "--dv COL is required (or --wide)");
    st::ColumnRoles roles{o.dv, groups_design ? std::string() : o.subject, groups_design ? std::vector<std::string>{} : o.within,
                          o.between};
    data = st::long_data_from_csv(*table, roles);
  }
  if (!data) fail(kExitInvalid, data.error().to_string());
  return std::move(data).value();
}

void warn(const std::vector<std::string>& warnings) {
  for (const auto& w : warnings) std::cerr << "dtlab stats: warning: " << w << "\n";
}

json effect_json(const st::Effect& e) {
  return json{{"effect", e.name},        {"df1", num(e.df1)},          {"df2", num(e.df2)},
              {"ss", num(e.ss)},         {"ss_error", num(e.ss_error)}, {"F", num(e.F)},
              {"p", num(e.p)},           {"log10_p", num(e.log10_p)},  {"eta_p2", num(e.eta_p2)},
              {"eta_g2", num(e.eta_g2)}, {"mauchly_W", num(e.mauchly_W)}, {"mauchly_p", num(e.mauchly_p)},
              {"gg_epsilon", num(e.gg_epsilon)}, {"hf_epsilon", num(e.hf_epsilon)},
              {"p_gg", num(e.p_gg)},     {"p_hf", num(e.p_hf)}};
}

json descriptives_json(const st::Descriptives& d) {
  return json{{"n", d.n},           {"mean", num(d.mean)},     {"sd", num(d.sd)},         {"se", num(d.se)},
              {"ci_low", num(d.ci_low)}, {"ci_high", num(d.ci_high)}, {"median", num(d.median)},
              {"q1", num(d.q1)},    {"q3", num(d.q3)},         {"iqr", num(d.iqr)}};
}

json comparisons_json(const std::vector<st::Comparison>& cs) {
  json a = json::array();
  for (const auto& c : cs)
    a.push_back({{"a", c.a}, {"b", c.b}, {"test", c.test}, {"estimate", num(c.estimate)},
                 {"statistic", num(c.statistic)}, {"df", num(c.df)}, {"p", num(c.p)}, {"p_holm", num(c.p_holm)}});
  return a;
}

void print_comparisons(const std::string& factor, const std::vector<st::Comparison>& cs) {
  std::cout << "\nPairwise comparisons of " << factor << " (Holm-corrected)\n";
  for (const auto& c : cs)
    std::cout << "  " << c.a << " - " << c.b << ": " << c.test << " statistic " << fmt(c.statistic)
              << (std::isnan(c.df) ? "" : ", df " + fmt(c.df)) << ", p " << fmt(c.p) << ", p_holm " << fmt(c.p_holm) << "\n";
}

void print_effects(const std::vector<st::Effect>& effects) {
  std::cout << "effect                   df1      df2          SS    SS_error           F          p   eta_p2   eta_g2\n";
  for (const auto& e : effects) {
    char b[512];
    std::snprintf(b, sizeof b, "%-20s %8s %8s %11s %11s %11s %10s %8s %8s\n", e.name.c_str(), fmt(e.df1).c_str(),
                  fmt(e.df2).c_str(), fmt(e.ss).c_str(), fmt(e.ss_error).c_str(), fmt(e.F).c_str(),
                  fmt_p(e.p, e.log10_p).c_str(), fmt(e.eta_p2).c_str(), fmt(e.eta_g2).c_str());
    std::cout << b;
  }
  bool any = false;
  for (const auto& e : effects)
    if (e.within && e.df1 > 1 && !std::isnan(e.gg_epsilon)) any = true;
  if (!any) return;
  std::cout << "\nsphericity               Mauchly W   p(W)     GG eps    HF eps     p[GG]      p[HF]\n";
  for (const auto& e : effects) {
    if (!e.within || std::isnan(e.mauchly_W)) continue;
    char b[512];
    std::snprintf(b, sizeof b, "%-20s %11s %8s %10s %9s %10s %10s\n", e.name.c_str(), fmt(e.mauchly_W).c_str(),
                  fmt(e.mauchly_p).c_str(), fmt(e.gg_epsilon).c_str(), fmt(e.hf_epsilon).c_str(),
                  fmt_p(e.p_gg, e.log10_p_gg).c_str(), fmt_p(e.p_hf, e.log10_p_hf).c_str());
    std::cout << b;
  }
}

json header_json(const char* test, const StatsOptions& o) {
  return json{{"test", test}, {"data", o.data}, {"dv", o.dv}, {"subject", o.subject}, {"within", o.within},
              {"between", o.between}};
}

void run_anova(const StatsOptions& o) {
  if (o.between.size() != 1 && !o.wide) fail(kExitUsage, "anova needs --between COL (one factor)");
  if (!o.within.empty()) fail(kExitUsage, "anova takes no --within; use rm-anova");
  const st::LongData data = load(o, true);
  auto r = st::one_way_anova(data);
  if (!r) fail(kExitInvalid, r.error().to_string());
  std::vector<st::Comparison> post;
  if (o.posthoc) {
    auto pc = st::pairwise_between(data);
    if (!pc) fail(kExitInvalid, pc.error().to_string());
    post = *pc;
  }
  warn(r->warnings);
  if (o.json) {
    json j = header_json("anova", o);
    j["n"] = r->n;
    j["effects"] = json::array({effect_json(r->effect)});
    json groups = json::array();
    for (const auto& g : r->groups) {
      json d = descriptives_json(g.d);
      d["group"] = g.level;
      groups.push_back(d);
    }
    j["descriptives"] = groups;
    if (o.posthoc) j["posthoc"] = comparisons_json(post);
    j["warnings"] = r->warnings;
    std::cout << j.dump(2) << "\n";
    return;
  }
  std::cout << "One-way ANOVA of " << data.dv_name << " by " << r->factor << " (" << r->n << " observations)\n\n";
  print_effects({r->effect});
  std::cout << "\ngroups\n";
  for (const auto& g : r->groups)
    std::cout << "  " << g.level << ": n " << g.d.n << ", mean " << fmt(g.d.mean) << ", sd " << fmt(g.d.sd) << ", CI ["
              << fmt(g.d.ci_low) << ", " << fmt(g.d.ci_high) << "], median " << fmt(g.d.median) << ", IQR " << fmt(g.d.iqr) << "\n";
  if (o.posthoc) print_comparisons(r->factor, post);
}

void require_subject_design(const StatsOptions& o, const char* test) {
  if (o.wide) return;
  if (o.subject.empty() || o.within.empty())
    fail(kExitUsage, std::string(test) + " needs --subject COL and --within COL[,COL] (or --wide)");
}

void run_rm_anova(const StatsOptions& o) {
  require_subject_design(o, "rm-anova");
  const st::LongData data = load(o, false);
  st::RmAnovaOptions ro;
  ro.observed = o.observed;
  auto r = st::rm_anova(data, ro);
  if (!r) fail(kExitInvalid, r.error().to_string());
  std::vector<std::pair<std::string, std::vector<st::Comparison>>> post;
  if (o.posthoc)
    for (const auto& f : r->within) {
      auto pc = st::pairwise_within(data, f, st::PairwiseTest::paired_t);
      if (!pc) fail(kExitInvalid, pc.error().to_string());
      post.emplace_back(f, *pc);
    }
  warn(r->warnings);
  if (o.json) {
    json j = header_json("rm-anova", o);
    j["within"] = r->within;
    j["n_subjects"] = r->n_subjects;
    j["dropped_subjects"] = r->dropped_subjects;
    j["effects"] = json::array();
    for (const auto& e : r->effects) j["effects"].push_back(effect_json(e));
    json cells = json::array();
    for (const auto& c : r->cells) {
      json d = descriptives_json(c.d);
      json lv = json::object();
      for (const auto& [f, l] : c.levels) lv[f] = l;
      d["cell"] = lv;
      cells.push_back(d);
    }
    j["descriptives"] = cells;
    if (o.posthoc) {
      json p = json::object();
      for (const auto& [f, cs] : post) p[f] = comparisons_json(cs);
      j["posthoc"] = p;
    }
    j["warnings"] = r->warnings;
    std::cout << j.dump(2) << "\n";
    return;
  }
  std::cout << "Repeated-measures ANOVA of " << data.dv_name << " (" << r->n_subjects << " subjects";
  if (!r->dropped_subjects.empty()) std::cout << ", " << r->dropped_subjects.size() << " removed";
  std::cout << "; type III, car/afex conventions)\n\n";
  print_effects(r->effects);
  std::cout << "\ncell means (over subjects)\n";
  for (const auto& c : r->cells) {
    std::string label;
    for (const auto& [f, l] : c.levels) label += (label.empty() ? "" : ", ") + f + "=" + l;
    std::cout << "  " << label << ": mean " << fmt(c.d.mean) << ", sd " << fmt(c.d.sd) << ", se " << fmt(c.d.se)
              << ", CI [" << fmt(c.d.ci_low) << ", " << fmt(c.d.ci_high) << "], median " << fmt(c.d.median) << ", IQR "
              << fmt(c.d.iqr) << "\n";
  }
  for (const auto& [f, cs] : post) print_comparisons(f, cs);
}

void run_friedman(const StatsOptions& o) {
  require_subject_design(o, "friedman");
  const st::ExactOptions exact = parse_exact(o);
  const st::LongData data = load(o, false);
  auto r = st::friedman(data, exact);
  if (!r) fail(kExitInvalid, r.error().to_string());
  std::vector<st::Comparison> post;
  if (o.posthoc) {
    if (data.within.size() != 1) fail(kExitUsage, "--posthoc for friedman needs exactly one within factor");
    auto pc = st::pairwise_within(data, data.within.front().name, st::PairwiseTest::wilcoxon);
    if (!pc) fail(kExitInvalid, pc.error().to_string());
    post = *pc;
  }
  warn(r->warnings);
  if (o.json) {
    json j = header_json("friedman", o);
    j["n"] = r->n;
    j["k"] = r->k;
    j["treatments"] = r->treatments;
    j["mean_ranks"] = r->mean_ranks;
    j["Q"] = num(r->Q);
    j["df"] = num(r->df);
    j["p"] = num(r->p);
    j["log10_p"] = num(r->log10_p);
    j["p_exact"] = num(r->p_exact);
    j["exact_method"] = r->exact_method;
    if (r->exact_method == "monte-carlo") {
      j["monte_carlo_samples"] = r->monte_carlo_samples;
      j["seed"] = r->seed;
    }
    j["kendall_W"] = num(r->kendall_W);
    j["iman_davenport_F"] = num(r->iman_davenport_F);
    j["iman_davenport_df1"] = num(r->id_df1);
    j["iman_davenport_df2"] = num(r->id_df2);
    j["p_iman_davenport"] = num(r->p_iman_davenport);
    j["ties"] = r->ties;
    j["dropped_subjects"] = r->dropped_blocks;
    if (o.posthoc) j["posthoc"] = comparisons_json(post);
    j["warnings"] = r->warnings;
    std::cout << j.dump(2) << "\n";
    return;
  }
  std::cout << "Friedman rank sum test (" << r->n << " blocks, " << r->k << " treatments" << (r->ties ? ", ties" : "")
            << ")\n  Q = " << fmt(r->Q) << ", df = " << fmt(r->df) << ", p = " << fmt_p(r->p, r->log10_p)
            << " (chi-square)\n  p_exact = " << fmt(r->p_exact) << " (" << r->exact_method << ")\n  Kendall's W = "
            << fmt(r->kendall_W) << "\n  Iman-Davenport F(" << fmt(r->id_df1) << ", " << fmt(r->id_df2)
            << ") = " << fmt(r->iman_davenport_F) << ", p = " << fmt_p(r->p_iman_davenport, r->log10_p_iman_davenport) << "\n";
  for (std::size_t j = 0; j < r->treatments.size(); ++j)
    std::cout << "  mean rank " << r->treatments[j] << ": " << fmt(r->mean_ranks[j]) << "\n";
  if (o.posthoc) print_comparisons(data.within.front().name, post);
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
  const st::LongData data = load(o, false);
  auto r = st::paired_tests(data, wo);
  if (!r) fail(kExitInvalid, r.error().to_string());
  warn(r->warnings);
  const auto& w = r->wilcoxon;
  if (o.json) {
    json j = header_json("wilcoxon", o);
    j["x"] = r->x_level;
    j["y"] = r->y_level;
    j["V"] = num(w.V);
    j["p"] = num(w.p);
    j["log10_p"] = num(w.log10_p);
    j["p_exact"] = num(w.p_exact);
    j["z"] = num(w.z);
    j["method"] = w.method;
    j["exact_method"] = w.exact_method;
    j["p_normal"] = num(w.p_normal);
    j["n"] = w.n;
    j["pairs"] = w.pairs;
    j["zeros"] = w.zeros;
    j["ties"] = w.ties;
    j["alternative"] = o.alternative;
    j["sign_test"] = {{"positive", r->sign.positive}, {"negative", r->sign.negative}, {"p", num(r->sign.p)},
                      {"log10_p", num(r->sign.log10_p)}};
    j["paired_t"] = {{"t", num(r->t.t)},   {"df", num(r->t.df)}, {"p", num(r->t.p)}, {"log10_p", num(r->t.log10_p)},
                     {"mean_difference", num(r->t.mean_difference)}, {"ci_low", num(r->t.ci_low)}, {"ci_high", num(r->t.ci_high)}};
    j["dropped_subjects"] = r->dropped_subjects;
    j["warnings"] = r->warnings;
    std::cout << j.dump(2) << "\n";
    return;
  }
  std::cout << "Paired tests of " << data.dv_name << ": " << r->x_level << " - " << r->y_level << " (" << w.pairs
            << " pairs)\n  Wilcoxon signed-rank: V = " << fmt(w.V) << ", p = " << fmt_p(w.p, w.log10_p) << " ("
            << w.method << "), z = " << fmt(w.z) << ", p_exact = " << fmt(w.p_exact) << "\n  sign test: "
            << r->sign.positive << " positive, " << r->sign.negative << " negative, p = " << fmt_p(r->sign.p, r->sign.log10_p)
            << "\n  paired t: t(" << fmt(r->t.df) << ") = " << fmt(r->t.t) << ", p = " << fmt_p(r->t.p, r->t.log10_p)
            << ", mean difference " << fmt(r->t.mean_difference) << " [" << fmt(r->t.ci_low) << ", " << fmt(r->t.ci_high) << "]\n";
}

void add_common(CLI::App* cmd, StatsOptions& o) {
  cmd->add_option("--data", o.data, "CSV file (long format: one row per observation)")->required();
  cmd->add_option("--dv", o.dv, "Column of the dependent variable (numbers; empty or NA = missing)");
  cmd->add_option("--subject", o.subject, "Column of the subject id");
  cmd->add_option("--within", o.within, "Within-subject factor column(s), comma separated")->delimiter(',');
  cmd->add_option("--between", o.between, "Between-subject factor column(s), comma separated")->delimiter(',');
  cmd->add_flag("--wide", o.wide, "One row per subject, one column per condition (empty cell = missing)");
  cmd->add_flag("--json", o.json, "Print one JSON object (see README, Statistics)");
}

void add_exact(CLI::App* cmd, StatsOptions& o) {
  cmd->add_option("--exact", o.exact, "auto|always|never|monte-carlo=N: how p_exact is computed")->capture_default_str();
  cmd->add_option("--seed", o.seed, "Monte Carlo seed")->capture_default_str();
}

}  // namespace

void add_stats_command(CLI::App& root) {
  auto* stats = root.add_subcommand("stats", "Statistics on a CSV: ANOVA, repeated-measures ANOVA, Friedman, Wilcoxon");
  stats->require_subcommand(1);
  auto o = std::make_shared<StatsOptions>();

  auto* anova = stats->add_subcommand("anova", "One-way between-subjects ANOVA (--between COL)");
  add_common(anova, *o);
  anova->add_flag("--posthoc", o->posthoc, "Holm-corrected pairwise t tests with pooled SD");
  anova->callback([o] { run_anova(*o); });

  auto* rm = stats->add_subcommand("rm-anova", "Repeated-measures (and mixed) ANOVA with sphericity corrections");
  add_common(rm, *o);
  rm->add_option("--observed", o->observed, "Measured (not manipulated) factors, for generalized eta squared")->delimiter(',');
  rm->add_flag("--posthoc", o->posthoc, "Holm-corrected pairwise paired t tests for each within factor");
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
  wx->add_option("--alternative", o->alternative, "two-sided|less|greater (for first level - second level)")
      ->capture_default_str();
  wx->callback([o] { run_wilcoxon(*o); });
}

}  // namespace dtlab::app

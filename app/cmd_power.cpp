// `dtlab power DB [--participants 8,12,16,24,32] [--replications R] [--alpha A]
// [--seed S] [--jobs J] [--revision latest|N] [--with-excluded] [--mixed
// [--mixed-replications R]] [--json]`:
// how many participants the next study needs, from a pilot database (real or
// simulated; analysis/report/planning.h, docs/stats.md "Power"). For every
// effect of the report's completion-time and accuracy ANOVAs: power at each
// size by resampling participants (with a Monte Carlo 95% CI) beside the
// analytic power of the observed effect, and the smallest n for 80% and 90%
// with the next n that keeps the counterbalancing's order rows balanced. The
// pilot's F is printed with the df of its p (Greenhouse-Geisser where corrected).
// With --mixed also the primary factor of each of the report's mixed models,
// by simulating studies from the fitted model (as simr).
// Progress on stderr. Never modifies the database. Exit 1: not a study
// database or nothing to plan; 2: bad command line; 3: I/O or database failure.
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "analysis/report/planning.h"
#include "app/commands.h"
#include "app/database_arg.h"
#include "study/protocol/protocol.h"
#include "study/store/read.h"

namespace dtlab::app {
namespace {

struct PowerArgs {
  std::string db;
  report::PlanningOptions options;
  bool json = false, quiet = false;
};

std::string num_text(double v, int decimals = 3) {
  if (!std::isfinite(v)) return "-";
  char b[64];
  std::snprintf(b, sizeof b, "%.*f", decimals, v);
  return b;
}

// p with 3 significant digits ("0.00171", "2.5e-09").
std::string p_text(double p) {
  if (!std::isfinite(p)) return "-";
  char b[64];
  std::snprintf(b, sizeof b, "%.3g", p);
  return b;
}

std::string n_text(double n) { return std::isfinite(n) ? std::to_string(static_cast<long long>(n)) : "more than 10^7"; }

// A df as APA writes it: an integer, or two decimals when corrected.
std::string df_text(double df) { return num_text(df, df == std::floor(df) ? 0 : 2); }

// "13 (analytic; 16 keeps the 4 order rows of the latin-square balanced)" when n is not a multiple of them.
std::string n_with_balance(double n, double balanced, const report::PowerPlan& plan) {
  std::string t = n_text(n) + " (analytic";
  if (std::isfinite(n) && balanced != n)
    t += "; " + n_text(balanced) + " keeps the " + std::to_string(plan.order_rows) + " order rows of the " +
         plan.order_scheme + " balanced";
  return t + ")";
}

void print_effect(const report::PlannedEffect& e, const report::PowerPlan& plan, bool resampled) {
  // The df printed are those of the p: Greenhouse-Geisser corrected where p is.
  const bool corrected = e.p_df1 != e.df1;
  std::cout << "\n" << (e.scope == "overall" ? std::string("all tasks") : e.scope) << ", " << e.measure << ": "
            << e.effect << "\n  pilot: N = " << e.pilot_n << ", F(" << df_text(e.p_df1) << ", " << df_text(e.p_df2)
            << ") = " << num_text(e.F, 2) << ", p = " << p_text(e.p) << (corrected ? " (Greenhouse-Geisser)" : "")
            << ", eta_p2 = " << num_text(e.eta_p2);
  if (e.df1 == 1) std::cout << ", d_z = " << num_text(e.dz);
  else std::cout << ", GG epsilon = " << num_text(e.epsilon);
  std::cout << "\n      n   " << (resampled ? "resampled [95% CI]        " : "") << "analytic\n";
  for (const auto& a : e.at) {
    char b[160];
    if (resampled)
      std::snprintf(b, sizeof b, "  %5d   %5s [%5s, %5s]     %8s\n", a.n, num_text(a.resampled.power).c_str(),
                    num_text(a.resampled.ci_low).c_str(), num_text(a.resampled.ci_high).c_str(), num_text(a.analytic).c_str());
    else
      std::snprintf(b, sizeof b, "  %5d   %8s\n", a.n, num_text(a.analytic).c_str());
    std::cout << b;
  }
  const auto tried = [](int n) { return n ? std::to_string(n) : std::string("none of the sizes tried"); };
  const bool finite = std::isfinite(e.F);
  std::cout << "  smallest n for 80% power: " << (finite ? n_with_balance(e.n80, e.n80_balanced, plan) : "- (analytic)");
  if (resampled) std::cout << ", " << tried(e.resampled_n80) << " (resampled)";
  std::cout << "\n  smallest n for 90% power: " << (finite ? n_with_balance(e.n90, e.n90_balanced, plan) : "- (analytic)");
  if (resampled) std::cout << ", " << tried(e.resampled_n90) << " (resampled)";
  std::cout << "\n";
}

void run_power(PowerArgs& a) {
  if (!a.quiet)
    a.options.progress = [last = -1](std::size_t done, std::size_t total) mutable {
      const int tenth = static_cast<int>(10 * done / total);
      if (tenth == last) return;
      last = tenth;
      std::cerr << "dtlab power: resampled " << done << " of " << total << " (test, size) pairs\n";
    };
  store::ReadOptions ro;
  ro.design_hash_of = &protocol::design_sha256_of_text;
  auto reader = store::StudyReader::open(a.db, ro);
  if (!reader) {
    std::cerr << "dtlab power: " << reader.error().to_string() << "\n";
    throw CLI::RuntimeError(exit_code(reader.error()));
  }
  auto plan = report::plan_power(*reader, a.options);
  if (!plan) {
    std::cerr << "dtlab power: " << plan.error().to_string() << "\n";
    throw CLI::RuntimeError(exit_code(plan.error()));
  }
  if (a.json) {
    nlohmann::json j = report::to_json(*plan);
    j["database"] = store::display_name(a.db);
    std::cout << j.dump(2) << "\n";
    return;
  }
  const bool resampled = a.options.replications > 0;
  std::cout << "Power planning from " << store::display_name(a.db) << " (design revision " << plan->design_revision
            << "): " << plan->participants << " participants analysed, alpha " << a.options.alpha;
  if (resampled) std::cout << ", " << a.options.replications << " resamples per size, seed " << a.options.seed;
  std::cout << "\nResampled: participants drawn with replacement, the report's test rerun; analytic: from the "
               "observed effect (noncentral t for 1-df effects, noncentral F with the observed GG epsilon otherwise)\n";
  std::vector<int> unbalanced;
  for (int n : a.options.sizes)
    if (plan->order_rows > 1 && n % plan->order_rows != 0) unbalanced.push_back(n);
  if (!unbalanced.empty()) {
    std::cout << "Note: the " << plan->order_scheme << " has " << plan->order_rows << " order rows; ";
    for (std::size_t i = 0; i < unbalanced.size(); ++i) {
      const long long up = (unbalanced[i] / plan->order_rows + 1) * plan->order_rows;
      std::cout << (i ? ", " : "") << unbalanced[i] << " (next balanced: " << up << ")";
    }
    std::cout << (unbalanced.size() == 1 ? " is not a multiple" : " are not multiples")
              << ", so some orders would be used more often than others\n";
  }
  for (const auto& e : plan->effects) print_effect(e, *plan, resampled);
  for (const auto& m : plan->mixed) {
    std::cout << "\nMixed model, " << m.section << " " << m.scope << " (" << m.measure << "): " << m.term;
    if (m.at.empty()) {
      std::cout << ": not planned (" << m.not_planned << ")\n";
      continue;
    }
    std::cout << ", pilot p = " << m.pilot_p << "; " << m.formula << "\n";
    for (const auto& r : m.at)
      std::cout << "  n = " << r.n << ": simulated power " << r.power.power << " [" << r.power.ci_low << ", "
                << r.power.ci_high << "]" << (r.power.undefined ? " (" + std::to_string(r.power.undefined) + " fits failed)" : "")
                << "\n";
  }
  for (const auto& why : plan->not_planned) std::cout << "\nnot planned: " << why << "\n";
}

}  // namespace

void add_power_command(CLI::App& root) {
  auto a = std::make_shared<PowerArgs>();
  auto* cmd = root.add_subcommand(
      "power",
      "How many participants the next study needs, from a pilot study database (real or simulated): for every "
      "effect of the report's completion-time and accuracy ANOVAs, the power at each planned size by resampling the "
      "pilot's participants (Monte Carlo 95% CI) and analytically from the observed effect, and the smallest n for "
      "80% and 90% power. Progress on stderr. Exit 1: not a study database or nothing to plan; 3: I/O or database "
      "failure");
  cmd->add_option("database", a->db, std::string(kDatabaseHelp) + ", the pilot (dtlab run, simulate or demo)")
      ->required()
      ->check(existing_database());
  cmd->add_option("--participants", a->options.sizes, "Numbers of participants to plan for, comma separated")
      ->delimiter(',')
      ->check(CLI::Range(2, 100000))
      ->capture_default_str();
  cmd->add_option("--replications", a->options.replications,
                  "Resamples per test and size (0: analytic power only)")
      ->check(CLI::Range(0, 1000000))
      ->capture_default_str();
  cmd->add_option("--alpha", a->options.alpha, "Significance level")
      ->check(CLI::Range(1e-12, 0.999999))
      ->capture_default_str();
  cmd->add_option("--seed", a->options.seed, "Seed of the resampling (the same seed gives the same numbers)")
      ->capture_default_str();
  cmd->add_option("--jobs", a->options.threads, "Threads (default: one per processor; the result does not depend on it)")
      ->check(CLI::Range(1, 256));
  cmd->add_option("--revision", a->options.revision,
                  "Design revision to plan from when the protocol's design was changed mid-study: latest or N")
      ->capture_default_str();
  cmd->add_flag("--mixed", a->options.mixed,
                "Also plan the primary factor of each of the report's mixed models by simulating studies from the "
                "fitted model (as R's simr): slower, see --mixed-replications");
  cmd->add_option("--mixed-replications", a->options.mixed_replications,
                  "Simulated studies per size for each mixed model")
      ->capture_default_str();
  cmd->add_flag("--with-excluded", a->options.with_excluded,
                "Keep excluded participants and trials (dtlab exclude); by default they are left out");
  cmd->add_flag("--json", a->json,
                "Print {database, design_revision, participants, sizes, replications, alpha, seed, effects, "
                "not_planned}");
  cmd->add_flag("--quiet", a->quiet, "No progress lines on stderr");
  cmd->callback([a] { run_power(*a); });
}

}  // namespace dtlab::app

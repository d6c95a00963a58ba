// Power planning from a pilot study (`dtlab power DB`; formulas in
// docs/stats.md "Power"): for every effect of the report's completion-time and
// accuracy RM ANOVAs, the power at each planned number of participants by
// resampling the pilot's participants and rerunning the report's own test
// (95% Wilson interval), and analytically from the observed effect, with the
// smallest n for 80% and 90%. The report's "Planning the next study" section
// is this code without resampling. Guarantees: reads the database only;
// deterministic for a seed whatever the number of threads; errors as the report's.
#pragma once
#include <nlohmann/json_fwd.hpp>

#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "analysis/stats/lmm_power.h"
#include "analysis/stats/power.h"
#include "study/common/error.h"
#include "study/store/read.h"

namespace dtlab::report {

struct PlanningOptions {
  std::vector<int> sizes = {8, 12, 16, 24, 32};  // participants of the next study, each >= 2
  std::size_t replications = 1000;               // resamples per size; 0 = analytic power only
  double alpha = 0.05;
  std::uint64_t seed = 1;
  unsigned threads = 0;                          // 0 = one per processor
  std::string revision = "latest";               // design revision: "latest" or "N"
  bool with_excluded = false;                    // keep excluded participants and trials
  bool mixed = false;                            // also the report's mixed models, by simulation (as simr)
  std::size_t mixed_replications = 200;          // simulated studies per size for each mixed model
  // Called after each (effect test, size) is resampled: done and total of those steps.
  std::function<void(std::size_t done, std::size_t total)> progress;
};

struct PowerAt {
  int n = 0;
  stats::ResampledPower resampled;  // NaN power when not resampled (replications 0)
  double analytic = 0;              // NaN when the effect has no finite F
};

// One effect of one of the report's ANOVAs.
struct PlannedEffect {
  std::string section;   // "time" or "accuracy"
  std::string measure;   // "completion time", "relative error (per trial)", ...
  std::string scope;     // task id, "overall", ...
  std::string effect;    // "transparency", "transparency:scenario"
  std::size_t pilot_n = 0;
  double df1 = 0, df2 = 0, F = 0, p = 0;  // the pilot's test (p: GG-corrected when df1 > 1)
  double p_df1 = 0, p_df2 = 0;            // the df that go with p: df1, df2 times GG epsilon where p is GG-corrected
  double eta_p2 = 0, epsilon = 1;         // observed partial eta squared; GG epsilon (1 for 1-df effects)
  double dz = 0;                          // 1-df effects: sqrt(F / N), the standardized paired difference
  std::vector<PowerAt> at;                // one per planned size
  double n80 = 0, n90 = 0;                // analytic smallest n reaching 80% / 90% (NaN: none up to 10^7)
  double n80_balanced = 0, n90_balanced = 0;  // the same rounded up to a multiple of the order rows (balanced counterbalancing)
  int resampled_n80 = 0, resampled_n90 = 0;  // smallest planned size whose resampled power reaches it; 0: none
};

// --mixed: the primary factor's test in one of the report's mixed models, its power by
// simulating studies from the fitted model (stats::lmm_power).
struct PlannedMixedModel {
  std::string section, measure, scope, formula, term;
  double pilot_p = 0;                      // the pilot's test of the term
  std::vector<stats::LmmPowerRow> at;      // one per planned size
  std::string not_planned;                 // why not, when `at` is empty
};

struct PowerPlan {
  std::string database;
  int design_revision = 1;
  long long order_rows = 1;      // rows of the protocol's counterbalancing (e.g. a Latin square's): each is used
                                 // equally often only when n is a multiple of them
  std::string order_scheme;      // "latin-square", "williams", ...
  std::size_t participants = 0;  // participants with analysed trials
  PlanningOptions options;       // as used (progress dropped)
  std::vector<PlannedEffect> effects;
  std::vector<PlannedMixedModel> mixed;  // with options.mixed
  std::vector<std::string> not_planned;  // tests that could not be planned, with the reason
};

// The plan as JSON (NaN as null): {database, design_revision, participants, order_rows, order_scheme,
// sizes, replications, alpha, seed, effects: [...], not_planned}.
nlohmann::json to_json(const PowerPlan& plan);

// Plans from the study `reader` reads (its design revision options.revision).
// Bad options (a size below 2, alpha outside (0, 1)) are input Errors.
Result<PowerPlan> plan_power(store::StudyReader& reader, const PlanningOptions& options);

}  // namespace dtlab::report

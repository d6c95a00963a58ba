// Mixed models beside the report's ANOVAs, on the trials themselves rather
// than on participant x condition means: for completion time a linear mixed
// model of log time per task and over all tasks (task as a factor), for
// counting tasks the relative error and for find-unique tasks the distance
// (linear, untransformed, as the ANOVA), for letter tasks a binomial GLMM of
// the trial's correctness (beside the Friedman test of the proportions).
// Fixed effects: the full factorial of the factors the ANOVA has, random
// intercepts per participant (analysis/stats/lmm.h). Each model is a plain
// result computed before any layout; a model that cannot be fitted keeps its
// reason. The comparison with the ANOVA is by decision at alpha = .05 for
// every effect both test (the ANOVA's Greenhouse-Geisser p where it reports one).
// Pure computation on the Context's trials; no I/O.
#pragma once
#include <optional>
#include <string>
#include <vector>

#include "analysis/report/detail/inference.h"
#include "analysis/stats/emmeans.h"
#include "analysis/stats/lmm.h"

namespace dtlab::report::detail {

struct Context;
struct TimeResult;
struct AccuracyResult;

// One effect both the ANOVA (or Friedman) and the mixed model test.
struct ModelDecision {
  std::string effect;      // "transparency", "transparency:scenario"
  double p_anova = 0;      // the report's p (GG-corrected where ε < 1; Friedman's p)
  double p_model = 0;      // the mixed model's p (Satterthwaite F, or the LRT for a GLMM)
  bool disagree = false;   // one is below .05 and the other is not
};

struct MixedModelResult {
  std::string section;     // "time" or "accuracy"
  std::string scope;       // task id, "overall"
  std::string label;       // "T1", "All tasks"
  std::string measure;     // "log completion time", "correct (0/1)", "relative error", "distance"
  std::string column;      // the trials.csv column of the dv
  std::string subset;      // the R condition selecting its trials: task == "T1"
  const TestReport* beside = nullptr;  // the ANOVA (or Friedman) of the same scope, if any
  stats::LmmData data;     // the trials the model was fitted to
  stats::LmmOptions options;
  std::optional<stats::LmmFit> fit;
  std::string not_fitted;  // why, when fit is empty
  std::optional<stats::EmmTable> primary;  // marginal means and contrasts of the primary factor
  std::vector<ModelDecision> decisions;
  long long trials = 0;    // trials with a value that entered the model
};

// The lme4 call of a fitted model, on the data frame `d` of the report's trials.csv.
std::string r_call(const MixedModelResult& m);

// Every mixed model the report shows, in section order (time, then accuracy); each beside the test of
// the same scope in `time` or `accuracy`.
std::vector<MixedModelResult> compute_mixed_models(const Context& ctx, const TimeResult& time,
                                                   const AccuracyResult& accuracy);

}  // namespace dtlab::report::detail

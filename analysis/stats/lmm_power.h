// Power of a mixed-model test by simulation from a fitted model, as R's simr
// (Green & MacLeod 2016, powerSim on extend(fit, along = subject, n)): n new
// subjects each take the trial design (factor levels, items, trials) of a
// pilot subject drawn with replacement; their random effects are drawn from
// the fitted covariance (sigma^2 Lambda Lambda' for an LMM, Lambda Lambda' for
// a GLMM), the items' once per replication; responses are X beta + Z b +
// sigma e (on the log scale for a log model) or Bernoulli(logit^-1(X beta +
// Z b)); the same model is refitted and the term tested (Satterthwaite F, or
// the likelihood-ratio test of a GLMM). Power: the share of replications
// with p < alpha and its 95% Wilson interval; a replication whose fit fails
// or whose p is undefined is counted apart. Replication b at size n draws
// from its own SplitMix64 stream (seed, n, b): the result depends on the
// seed only. The fitted effects are taken as the truth, so a pilot's
// overestimated effect overstates the power (as with every post-hoc power).
// Example: auto rows = lmm_power(data, options, *fit, {{8, 16, 24}, 200, 0.05, 1, "technique"});
#pragma once
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "analysis/stats/lmm.h"
#include "analysis/stats/power.h"
#include "study/common/error.h"

namespace dtlab::stats {

struct LmmPowerOptions {
  std::vector<std::size_t> subjects;  // sizes of the next study, each >= 2
  std::size_t replications = 200;
  double alpha = 0.05;
  std::uint64_t seed = 1;
  std::string term;                   // the fixed term tested ("A", "A:B")
};

struct LmmPowerRow {
  std::size_t n = 0;
  ResampledPower power;  // replications, rejections, undefined (failed fits), share, Wilson CI
};

// The simulated power of `options.term` at each size; `fit` is fit_lmm(pilot, options).
// --random max is refused (each replication would rerun its fallback).
Result<std::vector<LmmPowerRow>> lmm_power(const LmmData& pilot, const LmmOptions& options, const LmmFit& fit,
                                           const LmmPowerOptions& power);

}  // namespace dtlab::stats

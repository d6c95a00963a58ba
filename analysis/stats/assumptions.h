// Checks of the repeated-measures ANOVA's assumptions: the residuals of the
// within-subject model and the Shapiro-Wilk test of their normality.
//
// Shapiro-Wilk W (Shapiro & Wilk 1965) with Royston's approximations
// (Royston 1992, Statistics and Computing 2:117-119; algorithm AS R94,
// Applied Statistics 44:547-551, 1995), as R's shapiro.test:
//   m_i = Phi^-1((i - 3/8) / (n + 1/4)), u = 1/sqrt(n), c = m / ||m||;
//   a_n = c_n + 0.221157 u - 0.147981 u^2 - 2.071190 u^3 + 4.434685 u^4 - 2.706056 u^5,
//   a_{n-1} = c_{n-1} + 0.042981 u - 0.293762 u^2 - 1.752461 u^3 + 5.682633 u^4 - 3.582633 u^5 (n > 5),
//   the other a_i = m_i / sqrt(eps), eps = (||m||^2 - 2 m_n^2 [- 2 m_{n-1}^2]) / (1 - 2 a_n^2 [- 2 a_{n-1}^2]),
//   antisymmetric (a_1 = -a_n, ...); n = 3: a = (-sqrt(1/2), 0, sqrt(1/2)).
//   W = (sum a_i x_(i))^2 / sum (x_i - mean)^2, taken as the squared correlation of a and x
//   (1 - W formed without cancellation).
//   p: n = 3 exact, p = 6/pi (asin(sqrt W) - asin(sqrt(3/4)));
//      4 <= n <= 11: gamma = -2.273 + 0.459 n, z = (-log(gamma - log(1 - W)) - mu) / sigma,
//        mu = 0.5440 - 0.39978 n + 0.025054 n^2 - 0.0006714 n^3,
//        sigma = exp(1.3822 - 0.77857 n + 0.062767 n^2 - 0.0020322 n^3);
//        log(1 - W) >= gamma gives p = 1e-99 (as R);
//      12 <= n <= 5000: z = (log(1 - W) - mu) / sigma, with x = log n,
//        mu = -1.5861 - 0.31082 x - 0.083751 x^2 + 0.0038915 x^3, sigma = exp(-0.4803 - 0.082676 x + 0.0030302 x^2);
//      p = P(Z > z).
// Missing data: NaN values are dropped (R's complete.cases). Defined results,
// each with a warning and W = p = NaN: fewer than 3 or more than 5000 values
// (R stops: "sample size must be between 3 and 5000"), all values identical
// (R stops: "all 'x' values are identical").
// Validated against: R 4.2.2 shapiro.test on its documentation example data,
// on published textbook data and on generated samples (tests, R calls written there).
//
// Residuals of a within-subject (or mixed) ANOVA, per subject and within cell:
//   e_sc = y_sc - mean_s - mean_{g(s), c} + mean_{g(s)}
// (subject mean, cell mean and grand mean within the subject's between group;
// without between factors: value - subject mean - cell mean + grand mean),
// the residuals of the full model whose error terms the ANOVA's F tests use.
// Missing data: the subject x cell rules of rm_anova (listwise deletion).
#pragma once
#include <string>
#include <vector>

#include "analysis/stats/long_data.h"
#include "study/common/error.h"

namespace dtlab::stats {

struct ShapiroWilkResult {
  std::size_t n = 0;  // values used
  double W = 0, p = 0;
  std::vector<std::string> warnings;
};

// Shapiro-Wilk test of x (any order; NaN dropped).
ShapiroWilkResult shapiro_wilk(const std::vector<double>& x);

struct Residual {
  std::string subject;
  std::string cell;  // "angle=0, noise=absent"
  double value = 0;
};

struct AnovaResiduals {
  std::vector<Residual> residuals;  // subject-major, cells in design order
  std::vector<std::string> dropped_subjects;
  std::vector<std::string> warnings;
};

// The residuals of the within-subject model (see above); data as for rm_anova().
Result<AnovaResiduals> anova_residuals(const LongData& data);

}  // namespace dtlab::stats

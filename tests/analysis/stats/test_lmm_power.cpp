// Simulated power of a mixed-model test (lmm_power.h) against a closed form:
// with one trial per subject and level of a two-level within factor and
// random intercepts, the LMM's Satterthwaite F test of the factor is the
// paired t test (F = t^2, df = n - 1) whenever the subject variance is
// estimated inside its bound, so the simulated power must converge to R's
//   power.t.test(n = n, delta = |a1 - a2|, sd = sqrt(2) * sigma, type = "paired")
// (stats::power_paired_t, validated against R in test_followup_power.cpp)
// with the fitted effect and sigma as the truth. Also: the same seed gives
// the same power, and bad requests are errors.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "analysis/stats/lmm.h"
#include "analysis/stats/lmm_power.h"
#include "analysis/stats/power.h"

namespace dtlab::stats {
namespace {

// 12 subjects far apart (subject SD >> residual SD), a2 about 0.8 above a1, fixed noise.
LmmData pilot() {
  LmmData d;
  d.subject_name = "s";
  d.data.dv_name = "y";
  d.data.within = {{"A", {}}};
  const double noise[] = {0.3, -0.5, 0.1, 0.6, -0.2, -0.4, 0.5, -0.1, 0.2, -0.6, 0.4, 0.0,
                          -0.3, 0.2, 0.5, -0.4, 0.1, 0.3, -0.5, 0.6, -0.2, 0.1, -0.1, 0.4};
  std::vector<double> y;
  for (int s = 0; s < 12; ++s)
    for (int a = 0; a < 2; ++a) {
      d.data.subject.push_back("s" + std::to_string(s));
      d.data.within[0].level.push_back(a ? "a2" : "a1");
      y.push_back(10.0 * s + 0.8 * a + noise[2 * s + a]);
    }
  d.data.dv = Measurements::from_doubles(y);
  return d;
}

TEST(LmmPower, ConvergesToThePairedTPowerOfTheFittedEffect) {
  const LmmData d = pilot();
  const LmmOptions o;
  auto fit = fit_lmm(d, o);
  ASSERT_TRUE(fit.ok()) << fit.error().to_string();
  const double delta = 2 * std::fabs(fit->beta(1)), sd = std::sqrt(2.0) * fit->sigma;
  const std::size_t R = 1000;
  auto rows = lmm_power(d, o, *fit, {{6, 10}, R, 0.05, 7, "A"});
  ASSERT_TRUE(rows.ok()) << rows.error().to_string();
  ASSERT_EQ(rows->size(), 2u);
  for (const auto& r : *rows) {
    const double analytic = power_paired_t(static_cast<double>(r.n), delta, sd, 0.05);
    const double se = std::sqrt(analytic * (1 - analytic) / R);
    EXPECT_NEAR(r.power.power, analytic, 4 * se) << "n = " << r.n;
    EXPECT_LE(r.power.ci_low, r.power.power);
    EXPECT_GE(r.power.ci_high, r.power.power);
    EXPECT_EQ(r.power.undefined, 0u);
  }
  EXPECT_LT((*rows)[0].power.power, (*rows)[1].power.power);  // more subjects, more power
}

TEST(LmmPower, SameSeedSameResultAndBadRequestsAreErrors) {
  const LmmData d = pilot();
  LmmOptions o;
  auto fit = fit_lmm(d, o);
  ASSERT_TRUE(fit.ok());
  auto a = lmm_power(d, o, *fit, {{5}, 50, 0.05, 3, "A"});
  auto b = lmm_power(d, o, *fit, {{5}, 50, 0.05, 3, "A"});
  ASSERT_TRUE(a.ok() && b.ok());
  EXPECT_EQ((*a)[0].power.rejections, (*b)[0].power.rejections);
  EXPECT_FALSE(lmm_power(d, o, *fit, {{5}, 10, 0.05, 3, "B"}).ok());  // no such term
  EXPECT_FALSE(lmm_power(d, o, *fit, {{1}, 10, 0.05, 3, "A"}).ok());  // one subject
  o.random = RandomEffects::maximal;
  EXPECT_FALSE(lmm_power(d, o, *fit, {{5}, 10, 0.05, 3, "A"}).ok());
}

}  // namespace
}  // namespace dtlab::stats

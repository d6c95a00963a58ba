// Tail probabilities: moderate values against mpmath 1.3.0 (50 digits), far
// tails against closed forms whose log is exact, and the documented results
// for degenerate inputs (never an exception).
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "analysis/stats/distributions.h"
#include "test_util.h"

namespace dtlab::stats {
namespace {

using test::near_rel;
constexpr double kInf = std::numeric_limits<double>::infinity();

struct TailCase {
  const char* what;
  Tail (*fn)(double, double, double);
  double x, a, b;
  double expected_p;       // NaN: do not check p
  double expected_log10;   // always checked
  double rel_p, rel_log;
};

Tail f3(double x, double a, double b) { return f_upper(x, a, b); }
Tail chi3(double x, double df, double) { return chi_squared_upper(x, df); }
Tail norm3(double z, double, double) { return normal_upper(z); }
Tail norm2s(double z, double, double) { return normal_two_sided(z); }
Tail t2s(double t, double df, double) { return t_two_sided(t, df); }

const double kNaN = std::numeric_limits<double>::quiet_NaN();

// Each expected value: mpmath (mp.dps = 50) or a closed form, as written.
const TailCase kCases[] = {
    // mpmath: betainc(d2/2, d1/2, 0, d2/(d2+d1 f), regularized=True)
    {"F(3,12) at 5", f3, 5.0, 3, 12, 0.01776699763955282773, std::log10(0.01776699763955282773), 1e-13, 1e-13},
    {"F(1.7,15.3) at 4.2 (GG-corrected df)", f3, 4.2, 1.7, 15.3, 0.040399504081453642802, std::log10(0.040399504081453642802), 1e-12, 1e-12},
    {"F(3,40) at 1e20 (analytic log)", f3, 1e20, 3, 40, kNaN, -376.7902454032730719, 0, 1e-12},
    {"F(3.5,100.25) at 1e5 (analytic log)", f3, 1e5, 3.5, 100.25, kNaN, -176.28104708631947594, 0, 1e-12},
    // mpmath: x = 7/(7+5e300); log10(x^3.5 (1-x)^2.5 / (3.5 beta(2.5, 3.5)) * hyp2f1(6, 1, 4.5, x))
    {"F(5,7) at 1e300 (analytic log)", f3, 1e300, 5, 7, 0.0, -1048.5986510815783893, 0, 1e-14},
    // closed form: P(F(2, d) >= f) = (1 + 2f/d)^(-d/2)
    {"F(2,30) at 7 closed form", f3, 7.0, 2, 30, std::pow(1.0 + 14.0 / 30.0, -15.0), -15.0 * std::log10(1.0 + 14.0 / 30.0), 1e-13, 1e-13},
    {"F(2,400) at 1e6 closed form", f3, 1e6, 2, 400, kNaN, -200.0 * std::log10(1.0 + 2e6 / 400.0), 0, 1e-12},
    {"F(2,700) at 2430 closed form, subnormal p", f3, 2430, 2, 700, std::pow(1.0 + 4860.0 / 700.0, -350.0), -350.0 * std::log10(1.0 + 4860.0 / 700.0), 1e-6, 1e-12},
    // closed form: P(X2(2) >= x) = exp(-x/2)
    {"chi2(2) at 30 closed form", chi3, 30, 2, 0, std::exp(-15.0), -15.0 / std::log(10.0), 1e-13, 1e-13},
    {"chi2(2) at 1480 closed form, subnormal p", chi3, 1480, 2, 0, std::exp(-740.0), -740.0 / std::log(10.0), 1e-6, 1e-12},
    {"chi2(2) at 4000 closed form", chi3, 4000, 2, 0, 0.0, -2000.0 / std::log(10.0), 0, 1e-12},
    // mpmath: gammainc(df/2, x/2, inf, regularized=True)
    {"chi2(7) at 20", chi3, 20, 7, 0, 0.0055696830729455713361, std::log10(0.0055696830729455713361), 1e-13, 1e-13},
    {"chi2(3) at 1500 (analytic log)", chi3, 1500, 3, 0, 0.0, -324.23058649574523321, 0, 1e-12},
    {"chi2(1e5) at 3e5 (analytic log)", chi3, 3e5, 1e5, 0, 0.0, -19576.435066512134, 0, 1e-13},
    // mpmath: erfc(z/sqrt(2))/2
    {"normal upper at 5", norm3, 5, 0, 0, 2.8665157187919391167e-7, std::log10(2.8665157187919391167e-7), 1e-13, 1e-13},
    {"normal upper at 38 (subnormal)", norm3, 38, 0, 0, 2.8854283600687843084e-316, -315.53978970396250789, 1e-6, 1e-12},
    {"normal upper at 40", norm3, 40, 0, 0, 0.0, -349.43700645934584209, 0, 1e-12},
    {"normal two-sided at -60", norm2s, -60, 0, 0, 0.0, -783.60639916844672871, 0, 1e-12},
    // mpmath: betainc(df/2, 1/2, 0, df/(df+t^2), regularized=True)
    {"t(10) two-sided at 2.5", t2s, 2.5, 10, 0, 0.031446844236608804249, std::log10(0.031446844236608804249), 1e-13, 1e-13},
    {"t(10) two-sided at 1e40", t2s, 1e40, 10, 0, 0.0, -395.60889941585826786, 0, 1e-12},
    // closed form: t(1) two-sided p = (2/pi) atan(1/|t|) ~ 2/(pi t)
    {"t(1) two-sided at 1e300", t2s, 1e300, 1, 0, kNaN, std::log10(2.0 / M_PI) - 300.0, 0, 1e-12},
    // closed form: t(2) two-sided p = 1 - t/sqrt(2+t^2) ~ 1/t^2
    {"t(2) two-sided at 1e160 (subnormal)", t2s, 1e160, 2, 0, 1e-320, -320.0, 1e-3, 1e-12},
};

TEST(Distributions, TailsMatchMpmathAndClosedForms) {
  for (const auto& c : kCases) {
    SCOPED_TRACE(c.what);
    const Tail t = c.fn(c.x, c.a, c.b);
    EXPECT_TRUE(near_rel(t.log10_p, c.expected_log10, c.rel_log));
    if (std::isnan(c.expected_p)) continue;
    if (c.expected_p == 0.0) {
      EXPECT_EQ(t.p, 0.0) << "p below the smallest double must be 0 while log10_p stays finite";
    } else {
      EXPECT_TRUE(near_rel(t.p, c.expected_p, c.rel_p));
    }
    EXPECT_TRUE(std::isfinite(t.log10_p));
  }
}

TEST(Distributions, PNeverCollapsesToZeroAboveTheSmallestDouble) {
  // P(F(2, d) >= f) = (1 + 2f/d)^(-d/2): walk it down through 1e-290 .. 1e-322.
  for (double target = -280; target >= -322; target -= 3) {
    const double d = 100.0;
    const double f = (std::pow(10.0, -target / 50.0) - 1.0) * d / 2.0;
    const double expected_log = -50.0 * std::log10(1.0 + 2.0 * f / d);
    const Tail t = f_upper(f, 2, d);
    SCOPED_TRACE(target);
    EXPECT_GT(t.p, 0.0);
    EXPECT_TRUE(near_rel(t.log10_p, expected_log, 1e-12));
  }
}

TEST(Distributions, DegenerateInputsGiveDocumentedValues) {
  EXPECT_TRUE(std::isnan(f_upper(kNaN, 1, 2).p));
  EXPECT_TRUE(std::isnan(f_upper(3, 0, 2).p)) << "df1 = 0 (one level)";
  EXPECT_TRUE(std::isnan(f_upper(3, 2, 0).p)) << "df2 = 0 (one subject)";
  EXPECT_TRUE(std::isnan(f_upper(3, -1, 5).p));
  EXPECT_EQ(f_upper(kInf, 2, 5).p, 0.0);
  EXPECT_EQ(f_upper(kInf, 2, 5).log10_p, -kInf);
  EXPECT_EQ(f_upper(0, 2, 5).p, 1.0);
  EXPECT_EQ(f_upper(-1, 2, 5).p, 1.0);
  EXPECT_TRUE(std::isnan(chi_squared_upper(3, 0).p));
  EXPECT_EQ(chi_squared_upper(kInf, 3).p, 0.0);
  EXPECT_EQ(normal_two_sided(0).p, 1.0);
  EXPECT_EQ(normal_upper(-kInf).p, 1.0);
  EXPECT_EQ(t_two_sided(kInf, 4).p, 0.0);
  EXPECT_EQ(t_two_sided(-kInf, 4).log10_p, -kInf);
  EXPECT_TRUE(std::isnan(t_two_sided(2, 0).p));
  EXPECT_TRUE(std::isnan(t_quantile(0.975, 0)));
}

TEST(Distributions, OneSidedTailsAddUp) {
  // P(T >= t) + P(T <= t) = 1 and P(|T| >= t) = 2 P(T >= t) for t > 0.
  for (double t : {-3.0, -0.5, 0.7, 2.2}) {
    EXPECT_NEAR(t_upper(t, 7).p + t_lower(t, 7).p, 1.0, 1e-14);
    EXPECT_NEAR(normal_upper(t).p + normal_lower(t).p, 1.0, 1e-14);
  }
  EXPECT_NEAR(t_two_sided(2.2, 7).p, 2 * t_upper(2.2, 7).p, 1e-15);
  // R: qt(0.975, 9) = 2.262157; mpmath: findroot(betainc(9/2, 1/2, 0, 9/(9+q^2), regularized=True) - 0.05)
  EXPECT_TRUE(near_rel(t_quantile(0.975, 9), 2.2621571627982055, 1e-12));
}

}  // namespace
}  // namespace dtlab::stats

// Tail probabilities with an analytic log below the double range; see
// distributions.h for the formulas and guarantees.
#include "analysis/stats/distributions.h"

#include <boost/math/distributions/chi_squared.hpp>
#include <boost/math/distributions/fisher_f.hpp>
#include <boost/math/distributions/normal.hpp>
#include <boost/math/distributions/students_t.hpp>
#include <boost/math/special_functions/gamma.hpp>

#include <cmath>
#include <limits>

#include "analysis/stats/detail/numbers.h"
#include "analysis/stats/detail/policy.h"

namespace dtlab::stats {
namespace {

namespace bm = boost::math;
using detail::Policy;  // errors become NaN/inf values, never exceptions
using FisherF = bm::fisher_f_distribution<double, Policy>;
using ChiSquared = bm::chi_squared_distribution<double, Policy>;
using Normal = bm::normal_distribution<double, Policy>;
using StudentsT = bm::students_t_distribution<double, Policy>;

constexpr double kLn10 = 2.302585092994045684;
// Below this Boost's result is replaced by exp(analytic log): subnormal
// doubles carry too few bits, and the true value may lie below them.
constexpr double kSwitch = 1e-290;

Tail from_log(double ln_p) { return {std::exp(ln_p), ln_p / kLn10}; }
Tail from_p(double p) { return {p, p > 0 ? std::log10(p) : -kInf}; }

double lgam(double a) { return bm::lgamma(a, Policy()); }

// log I_x(a, b) for x below the mean of Beta(a, b) (where the continued
// fraction converges); ln_x and ln_1mx are passed separately so callers can
// form them without cancellation.
double log_ibeta_small_x(double a, double b, double x, double ln_x, double ln_1mx) {
  const double tiny = 1e-300, eps = 1e-16;
  double c = 1.0, d = 1.0 - (a + b) * x / (a + 1.0);
  if (std::fabs(d) < tiny) d = tiny;
  d = 1.0 / d;
  double h = d;
  for (int m = 1; m <= 1000000; ++m) {
    const double m2 = 2.0 * m;
    double aa = m * (b - m) * x / ((a - 1.0 + m2) * (a + m2));
    d = 1.0 + aa * d;
    if (std::fabs(d) < tiny) d = tiny;
    c = 1.0 + aa / c;
    if (std::fabs(c) < tiny) c = tiny;
    d = 1.0 / d;
    h *= d * c;
    aa = -(a + m) * (a + b + m) * x / ((a + m2) * (a + 1.0 + m2));
    d = 1.0 + aa * d;
    if (std::fabs(d) < tiny) d = tiny;
    c = 1.0 + aa / c;
    if (std::fabs(c) < tiny) c = tiny;
    d = 1.0 / d;
    const double del = d * c;
    h *= del;
    if (std::fabs(del - 1.0) < eps) break;
  }
  const double ln_beta = lgam(a) + lgam(b) - lgam(a + b);
  return a * ln_x + b * ln_1mx - std::log(a) - ln_beta + std::log(h);
}

// log Q(a, y), the regularized upper incomplete gamma, for y > a + 1.
double log_gamma_q_large_y(double a, double y) {
  const double tiny = 1e-300, eps = 1e-16;
  double b = y + 1.0 - a, c = 1.0 / tiny, d = 1.0 / b, h = d;
  for (int i = 1; i <= 1000000; ++i) {
    const double an = -i * (i - a);
    b += 2.0;
    d = an * d + b;
    if (std::fabs(d) < tiny) d = tiny;
    c = b + an / c;
    if (std::fabs(c) < tiny) c = tiny;
    d = 1.0 / d;
    const double del = d * c;
    h *= del;
    if (std::fabs(del - 1.0) < eps) break;
  }
  return -y + a * std::log(y) - lgam(a) + std::log(h);
}

// P(|T(df)| >= |t|) = I_{df/(df+t^2)}(df/2, 1/2), finite t != 0.
Tail t_two_sided_finite(double t, double df) {
  const double at = std::fabs(t);
  const double p = 2.0 * bm::cdf(bm::complement(StudentsT(df), at));
  if (p >= kSwitch) return from_p(std::min(1.0, p));
  const double ln_t2 = 2.0 * std::log(at);
  const double ln_sum = ln_t2 + std::log1p(df / (at * at));  // log(df + t^2) without overflow
  const double x = std::exp(std::log(df) - ln_sum);
  return from_log(log_ibeta_small_x(df / 2.0, 0.5, x, std::log(df) - ln_sum, ln_t2 - ln_sum));
}

}  // namespace

Tail f_upper(double f, double df1, double df2) {
  if (std::isnan(f) || !(df1 > 0) || !(df2 > 0) || std::isinf(df1) || std::isinf(df2)) return {kNaN, kNaN};
  if (f == kInf) return {0.0, -kInf};
  if (f <= 0) return {1.0, 0.0};
  const double p = bm::cdf(bm::complement(FisherF(df1, df2), f));
  if (p >= kSwitch) return from_p(p);
  // P(F >= f) = I_x(df2/2, df1/2) with x = df2 / (df2 + df1 f).
  const double ln_df1f = std::log(df1) + std::log(f);
  const double ln_sum = ln_df1f + std::log1p(df2 / (df1 * f));  // log(df2 + df1 f)
  const double ln_x = std::log(df2) - ln_sum;
  return from_log(log_ibeta_small_x(df2 / 2.0, df1 / 2.0, std::exp(ln_x), ln_x, ln_df1f - ln_sum));
}

Tail chi_squared_upper(double x, double df) {
  if (std::isnan(x) || !(df > 0) || std::isinf(df)) return {kNaN, kNaN};
  if (x == kInf) return {0.0, -kInf};
  if (x <= 0) return {1.0, 0.0};
  const double p = bm::cdf(bm::complement(ChiSquared(df), x));
  if (p >= kSwitch) return from_p(p);
  return from_log(log_gamma_q_large_y(df / 2.0, x / 2.0));
}

Tail normal_upper(double z) {
  if (std::isnan(z)) return {kNaN, kNaN};
  if (z == kInf) return {0.0, -kInf};
  if (z == -kInf) return {1.0, 0.0};
  const double p = bm::cdf(bm::complement(Normal(), z));
  if (p >= kSwitch) return from_p(p);
  // z > 37 here: P(Z >= z) = Q(1/2, z^2/2) / 2.
  const double y = z * z / 2.0;
  if (std::isinf(y)) return {0.0, -kInf};
  return from_log(log_gamma_q_large_y(0.5, y) - std::log(2.0));
}

Tail normal_lower(double z) { return normal_upper(-z); }

Tail normal_two_sided(double z) {
  if (std::isnan(z)) return {kNaN, kNaN};
  const Tail one = normal_upper(std::fabs(z));
  if (one.p >= 0.5) return {1.0, 0.0};
  return {2.0 * one.p, one.log10_p + std::log10(2.0)};
}

Tail t_two_sided(double t, double df) {
  if (std::isnan(t) || !(df > 0) || std::isinf(df)) return {kNaN, kNaN};
  if (std::isinf(t)) return {0.0, -kInf};
  if (t == 0) return {1.0, 0.0};
  return t_two_sided_finite(t, df);
}

Tail t_upper(double t, double df) {
  if (std::isnan(t) || !(df > 0) || std::isinf(df)) return {kNaN, kNaN};
  if (t == kInf) return {0.0, -kInf};
  if (t == -kInf) return {1.0, 0.0};
  if (t > 0) {
    const Tail two = t_two_sided_finite(t, df);
    return {two.p / 2.0, two.log10_p - std::log10(2.0)};
  }
  return from_p(bm::cdf(bm::complement(StudentsT(df), t)));
}

Tail t_lower(double t, double df) { return t_upper(-t, df); }

double t_quantile(double prob, double df) {
  if (!(df > 0) || !(prob > 0 && prob < 1)) return kNaN;
  return bm::quantile(StudentsT(df), prob);
}

double normal_quantile(double prob) {
  if (!(prob > 0 && prob < 1)) return kNaN;
  return bm::quantile(Normal(), prob);
}

}  // namespace dtlab::stats

// Descriptives; see descriptives.h.
#include "analysis/stats/descriptives.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "analysis/stats/detail/sum.h"
#include "analysis/stats/distributions.h"

namespace dtlab::stats {
namespace {

// R's quantile type 7 on sorted data.
double quantile7(const std::vector<double>& s, double p) {
  const double h = (static_cast<double>(s.size()) - 1.0) * p;
  const size_t lo = static_cast<size_t>(std::floor(h));
  const size_t hi = std::min(lo + 1, s.size() - 1);
  return s[lo] + (h - static_cast<double>(lo)) * (s[hi] - s[lo]);
}

}  // namespace

Descriptives describe(const std::vector<double>& deltas, double offset) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  std::vector<double> x;
  for (double d : deltas)
    if (!std::isnan(d)) x.push_back(d);
  Descriptives r;
  r.n = x.size();
  if (x.empty()) {
    r.mean = r.sd = r.se = r.ci_low = r.ci_high = r.median = r.q1 = r.q3 = r.iqr = r.min = r.max = nan;
    return r;
  }
  // Scaled by a power of two (exact) so that sums of squares neither overflow nor underflow.
  double largest = 0;
  for (double v : x) largest = std::max(largest, std::fabs(v));
  int e = 0;
  if (std::isfinite(largest) && largest > 0) std::frexp(largest, &e);
  std::vector<double> z(x.size());
  for (size_t i = 0; i < x.size(); ++i) z[i] = std::ldexp(x[i], -e);
  detail::Sum s;
  for (double v : z) s.add(v);
  double m = s.value() / static_cast<double>(z.size());
  detail::Sum corr;  // second pass: corrects the mean for the rounding of the first
  for (double v : z) corr.add(v - m);
  m += corr.value() / static_cast<double>(z.size());
  r.mean = offset + std::ldexp(m, e);
  if (z.size() > 1) {
    detail::Sum ss;
    for (double v : z) ss.add((v - m) * (v - m));
    r.sd = std::ldexp(std::sqrt(ss.value() / static_cast<double>(z.size() - 1)), e);
    r.se = r.sd / std::sqrt(static_cast<double>(z.size()));
    const double q = t_quantile(0.975, static_cast<double>(z.size() - 1));
    r.ci_low = r.mean - q * r.se;
    r.ci_high = r.mean + q * r.se;
  } else {
    r.sd = r.se = r.ci_low = r.ci_high = nan;
  }
  std::sort(x.begin(), x.end());
  r.median = offset + quantile7(x, 0.5);
  r.q1 = offset + quantile7(x, 0.25);
  r.q3 = offset + quantile7(x, 0.75);
  r.iqr = quantile7(x, 0.75) - quantile7(x, 0.25);
  r.min = offset + x.front();
  r.max = offset + x.back();
  return r;
}

}  // namespace dtlab::stats

// Repeated-measures correlation; see rmcorr.h. Two passes (group means, then
// centred sums) so large offsets in completion times cost no precision.
#include "analysis/report/detail/rmcorr.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

#include "analysis/stats/distributions.h"

namespace dtlab::report::detail {

RmCorr rm_corr(const std::vector<std::string>& group, const std::vector<double>& x, const std::vector<double>& y) {
  constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  std::map<std::string, std::pair<double, double>> sum;
  std::map<std::string, int> count;
  RmCorr out;
  for (size_t i = 0; i < x.size(); ++i) {
    if (std::isnan(x[i]) || std::isnan(y[i])) continue;
    sum[group[i]].first += x[i];
    sum[group[i]].second += y[i];
    ++count[group[i]];
    ++out.n;
  }
  out.groups = count.size();
  double sxx = 0, syy = 0, sxy = 0;
  for (size_t i = 0; i < x.size(); ++i) {
    if (std::isnan(x[i]) || std::isnan(y[i])) continue;
    const double n = count[group[i]];
    const double dx = x[i] - sum[group[i]].first / n, dy = y[i] - sum[group[i]].second / n;
    sxx += dx * dx;
    syy += dy * dy;
    sxy += dx * dy;
  }
  out.df = static_cast<double>(out.n) - static_cast<double>(out.groups) - 1;
  if (sxx <= 0 || syy <= 0 || out.df < 1) {
    out.r = out.t = out.p = out.log10_p = out.ci_low = out.ci_high = kNaN;
    out.slope = sxx > 0 ? sxy / sxx : kNaN;
    return out;
  }
  out.r = std::clamp(sxy / std::sqrt(sxx * syy), -1.0, 1.0);
  out.slope = sxy / sxx;
  if (std::fabs(out.r) >= 1) {
    out.t = out.r > 0 ? INFINITY : -INFINITY;
    out.p = 0;
    out.log10_p = -INFINITY;
  } else {
    out.t = out.r * std::sqrt(out.df / (1 - out.r * out.r));
    const auto tail = stats::t_two_sided(out.t, out.df);
    out.p = tail.p;
    out.log10_p = tail.log10_p;
  }
  if (out.df > 1 && std::fabs(out.r) < 1) {
    const double z = std::atanh(out.r), half = stats::normal_quantile(0.975) / std::sqrt(out.df - 1);
    out.ci_low = std::tanh(z - half);
    out.ci_high = std::tanh(z + half);
  } else {
    out.ci_low = out.ci_high = kNaN;
  }
  return out;
}

}  // namespace dtlab::report::detail

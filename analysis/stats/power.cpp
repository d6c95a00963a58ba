// Analytic and resampling power; see power.h.
#include "analysis/stats/power.h"

#include <boost/math/distributions/non_central_f.hpp>
#include <boost/math/distributions/non_central_t.hpp>
#include <boost/math/distributions/students_t.hpp>
#include <boost/math/special_functions/beta.hpp>
#include <boost/math/tools/toms748_solve.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <thread>
#include <utility>

#include "analysis/stats/detail/numbers.h"

#include "analysis/stats/detail/policy.h"
#include "study/common/random.h"

namespace dtlab::stats {
namespace {

namespace bm = boost::math;
using detail::Policy;  // errors become NaN/inf values, never exceptions

// The share of rejections among the defined replications and its 95% Wilson interval.
void wilson(ResampledPower& r) {
  const double m = static_cast<double>(r.replications - r.undefined);
  if (m == 0) {
    r.power = r.ci_low = r.ci_high = kNaN;
    return;
  }
  const double ph = static_cast<double>(r.rejections) / m, z = 1.959963984540054;
  r.power = ph;
  const double centre = (ph + z * z / (2 * m)) / (1 + z * z / m);
  const double half = z / (1 + z * z / m) * std::sqrt(ph * (1 - ph) / m + z * z / (4 * m * m));
  // At 0 or R rejections the bound is exactly 0 or 1 (centre -+ half rounds a few ulps inside).
  r.ci_low = r.rejections == 0 ? 0.0 : std::max(0.0, centre - half);
  r.ci_high = ph == 1 ? 1.0 : std::min(1.0, centre + half);
}

// F(1 - alpha; df1, df2) from P(F > f) = I_y(df2/2, df1/2), y = df2 / (df2 + df1 f).
double f_critical(double alpha, double df1, double df2) {
  const double y = bm::ibeta_inv(df2 / 2.0, df1 / 2.0, alpha, Policy());
  return df2 * (1.0 - y) / (df1 * y);
}

}  // namespace

double power_paired_t(double n, double delta, double sd, double alpha, Alternative alternative, bool strict) {
  if (!(n >= 2) || !(sd > 0) || !(alpha > 0 && alpha < 1) || std::isnan(delta)) return kNaN;
  const double df = n - 1.0, sides = alternative == Alternative::two_sided ? 2.0 : 1.0;
  double ncp = std::sqrt(n) * delta / sd;
  if (alternative == Alternative::less) ncp = -ncp;  // P(T < -q) with ncp = P(T > q) with -ncp
  const double q = bm::quantile(bm::complement(bm::students_t_distribution<double, Policy>(df), alpha / sides));
  const bm::non_central_t_distribution<double, Policy> t(df, ncp);
  double power = bm::cdf(bm::complement(t, q));
  if (strict && alternative == Alternative::two_sided) power += bm::cdf(t, -q);
  return power;
}

double n_for_power_paired_t(double delta, double sd, double power, double alpha, Alternative alternative) {
  if (!(power > 0 && power < 1)) return kNaN;
  auto f = [&](double n) { return power_paired_t(n, delta, sd, alpha, alternative) - power; };
  double lo = 2.0, hi = 4.0;
  if (f(lo) >= 0) return lo;
  while (f(hi) < 0) {
    lo = hi;
    hi *= 2.0;
    if (hi > 1e7) return kNaN;
  }
  std::uintmax_t iterations = 200;
  const auto r = bm::tools::toms748_solve(f, lo, hi, bm::tools::eps_tolerance<double>(48), iterations);
  return (r.first + r.second) / 2.0;
}


double power_noncentral_f(double lambda, double df1, double df2, double alpha) {
  if (!(df1 > 0) || !(df2 > 0) || !(lambda >= 0) || !(alpha > 0 && alpha < 1)) return kNaN;
  const double q = f_critical(alpha, df1, df2);
  if (lambda == 0) return alpha;
  return bm::cdf(bm::complement(bm::non_central_f_distribution<double, Policy>(df1, df2, lambda), q));
}

double power_rm_within(double f, double n, double m, double rho, double epsilon, double alpha) {
  if (!(m >= 2) || !(n >= 2) || !(rho < 1) || !(epsilon > 0)) return kNaN;
  const double lambda = f * f * n * m * epsilon / (1.0 - rho);
  const double df1 = (m - 1.0) * epsilon;
  return power_noncentral_f(lambda, df1, (n - 1.0) * df1, alpha);
}

double power_of_effect(const Effect& e, double n_pilot, double n, double alpha, double between_cells) {
  if (!std::isfinite(e.F) || !(e.df1 > 0) || !(n_pilot > 0) || !(n > between_cells)) return kNaN;
  const double eps = e.within && std::isfinite(e.gg_epsilon) ? e.gg_epsilon : 1.0;
  // p contrasts per between df: df2 = (N - q) p in the pilot.
  const double p = e.df2 / (n_pilot - between_cells);
  const double lambda = e.F * e.df1 * n / n_pilot * eps;
  return power_noncentral_f(lambda, e.df1 * eps, (n - between_cells) * p * eps, alpha);
}

double smallest_n(const std::function<double(double)>& power_at, double target) {
  double lo = 2.0;
  if (power_at(lo) >= target) return lo;
  double hi = 4.0;
  while (!(power_at(hi) >= target)) {
    lo = hi;
    hi *= 2.0;
    if (hi > 1e7) return kNaN;
  }
  while (hi - lo > 1.0) {  // power(lo) < target <= power(hi)
    const double mid = std::floor((lo + hi) / 2.0);
    (power_at(mid) >= target ? hi : lo) = mid;
  }
  return hi;
}

std::vector<ResampledPower> power_by_resampling(std::size_t participants, std::size_t n, std::size_t hypotheses,
                                                const ResampleTest& test, std::size_t replications,
                                                std::uint64_t seed, double alpha, unsigned threads) {
  std::vector<ResampledPower> out(hypotheses);
  for (auto& r : out) r.replications = replications;
  if (participants == 0 || n == 0 || replications == 0) {
    for (auto& r : out) r.power = r.ci_low = r.ci_high = kNaN;
    return out;
  }
  if (threads == 0) threads = std::max(1u, std::thread::hardware_concurrency());
  threads = static_cast<unsigned>(std::min<std::size_t>(threads, replications));
  // counts[t][h]: {rejections, undefined} of thread t; summed in thread order (integers: order-free anyway).
  std::vector<std::vector<std::pair<std::size_t, std::size_t>>> counts(threads, std::vector<std::pair<std::size_t, std::size_t>>(hypotheses));
  auto work = [&](unsigned t) {
    std::vector<std::size_t> draw(n);
    for (std::size_t b = t; b < replications; b += threads) {
      Random<SplitMix64> rng(mix64(seed, b));
      for (auto& i : draw) i = static_cast<std::size_t>(rng.below(participants));
      const std::vector<double> p = test(draw);
      for (std::size_t h = 0; h < hypotheses; ++h) {
        const double ph = h < p.size() ? p[h] : kNaN;
        if (std::isnan(ph)) ++counts[t][h].second;
        else if (ph < alpha) ++counts[t][h].first;
      }
    }
  };
  std::vector<std::thread> pool;
  for (unsigned t = 1; t < threads; ++t) pool.emplace_back(work, t);
  work(0);
  for (auto& th : pool) th.join();
  for (std::size_t h = 0; h < hypotheses; ++h) {
    for (unsigned t = 0; t < threads; ++t) {
      out[h].rejections += counts[t][h].first;
      out[h].undefined += counts[t][h].second;
    }
    wilson(out[h]);
  }
  return out;
}

void share_with_wilson_interval(ResampledPower& r) { wilson(r); }

ResampledPower power_by_resampling(const std::vector<std::vector<double>>& rows, std::size_t n,
                                   const std::function<double(const std::vector<std::vector<double>>&)>& test,
                                   std::size_t replications, std::uint64_t seed, double alpha) {
  const ResampleTest one = [&](const std::vector<std::size_t>& draw) {
    std::vector<std::vector<double>> sample;
    sample.reserve(draw.size());
    for (std::size_t i : draw) sample.push_back(rows[i]);
    return std::vector<double>{test(sample)};
  };
  return power_by_resampling(rows.size(), n, 1, one, replications, seed, alpha, 1).front();
}

}  // namespace dtlab::stats

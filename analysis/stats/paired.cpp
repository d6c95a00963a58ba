// Paired two-sample tests; see paired.h.
#include "analysis/stats/paired.h"

#include <boost/math/distributions/binomial.hpp>
#include <boost/math/special_functions/gamma.hpp>

#include <algorithm>
#include <cstdio>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "analysis/stats/detail/design.h"
#include "analysis/stats/detail/friedman_exact.h"
#include "analysis/stats/detail/numbers.h"
#include "analysis/stats/detail/ranks.h"
#include "analysis/stats/detail/sum.h"
#include "analysis/stats/distributions.h"
#include "study/common/random.h"

namespace dtlab::stats {
namespace {

constexpr double kLn10 = 2.302585092994045684;
constexpr double kSignedRankBudget = 2e8;  // ranks x sums in the signed-rank DP

std::vector<double> differences(const std::vector<double>& x, const std::vector<double>& y) {
  if (x.size() != y.size()) throw std::invalid_argument("paired test: x and y differ in length");
  std::vector<double> d;
  for (std::size_t i = 0; i < x.size(); ++i)
    if (!std::isnan(x[i]) && !std::isnan(y[i])) d.push_back(x[i] - y[i]);
  return d;
}

Tail from_p(double p) { return {p, p > 0 ? std::log10(p) : -kInf}; }

std::string g6(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%.6g", v);
  return b;
}

// P(Binomial(n, 1/2) <= m), with an analytic log when it underflows.
Tail binomial_half_lower(std::size_t n, std::size_t m) {
  if (m >= n) return {1.0, 0.0};
  const double p = boost::math::cdf(boost::math::binomial_distribution<double>(static_cast<double>(n), 0.5),
                                    static_cast<double>(m));
  if (p >= 1e-290) return from_p(p);
  double best = -kInf;
  std::vector<double> logs;
  for (std::size_t i = 0; i <= m; ++i) {
    const double l = boost::math::lgamma(static_cast<double>(n) + 1) - boost::math::lgamma(static_cast<double>(i) + 1) -
                     boost::math::lgamma(static_cast<double>(n - i) + 1) - static_cast<double>(n) * std::log(2.0);
    logs.push_back(l);
    best = std::max(best, l);
  }
  double s = 0;
  for (double l : logs) s += std::exp(l - best);
  const double ln_p = best + std::log(s);
  return {std::exp(ln_p), ln_p / kLn10};
}

Tail two_sided_from(Tail lower, Tail upper) {
  const Tail& t = lower.p < upper.p ? lower : upper;
  if (2.0 * t.p >= 1.0) return {1.0, 0.0};
  return {2.0 * t.p, t.log10_p + std::log10(2.0)};
}

// Exact distribution of T = sum of the doubled ranks given a + sign: P(T >= t) and P(T <= t).
bool signed_rank_exact(const std::vector<int>& w, long t, double budget, double& upper, double& lower) {
  long total = 0;
  for (int v : w) total += v;
  if (static_cast<double>(total) * static_cast<double>(w.size()) > budget) return false;
  std::vector<double> prob(static_cast<std::size_t>(total) + 1, 0.0);
  prob[0] = 1.0;
  long reach = 0;
  for (int v : w) {
    for (long s = reach; s >= 0; --s) {
      const double q = prob[static_cast<std::size_t>(s)] * 0.5;
      prob[static_cast<std::size_t>(s)] = q;
      prob[static_cast<std::size_t>(s + v)] += q;
    }
    reach += v;
  }
  detail::Sum up, lo;
  for (long s = 0; s <= total; ++s) {
    if (s >= t) up.add(prob[static_cast<std::size_t>(s)]);
    if (s <= t) lo.add(prob[static_cast<std::size_t>(s)]);
  }
  upper = std::min(1.0, up.value());
  lower = std::min(1.0, lo.value());
  return true;
}

double pick(Alternative alt, bool above_mean, double upper, double lower) {
  switch (alt) {
    case Alternative::greater: return upper;
    case Alternative::less: return lower;
    case Alternative::two_sided: break;
  }
  return std::min(1.0, 2.0 * (above_mean ? upper : lower));
}

}  // namespace

WilcoxonResult wilcoxon_signed_rank(const std::vector<double>& x, const std::vector<double>& y,
                                    const WilcoxonOptions& o) {
  WilcoxonResult r;
  const std::vector<double> all = differences(x, y);
  r.pairs = all.size();
  std::vector<double> d;
  for (double v : all)
    if (v != 0) d.push_back(v);
  r.zeros = r.pairs - d.size();
  r.n = d.size();
  r.p_exact = kNaN;
  const double n = static_cast<double>(r.n);
  std::vector<double> absd(d.size());
  for (std::size_t i = 0; i < d.size(); ++i) absd[i] = std::fabs(d[i]);
  const std::vector<double> rk = detail::average_ranks(absd);
  const double tie_term = detail::tie_sum(absd);
  r.ties = tie_term > 0;
  long v2 = 0;  // 2 V
  std::vector<int> w(d.size());
  for (std::size_t i = 0; i < d.size(); ++i) {
    w[i] = static_cast<int>(std::lround(2.0 * rk[i]));
    if (d[i] > 0) v2 += w[i];
  }
  r.V = static_cast<double>(v2) / 2.0;
  const double mean = n * (n + 1.0) / 4.0;
  const bool above_mean = r.V > mean;

  // Normal approximation (always computed; it is p when R would use it).
  const double sigma = std::sqrt(n * (n + 1.0) * (2.0 * n + 1.0) / 24.0 - tie_term / 48.0);
  double z0 = r.V - mean;
  double correction = 0.0;
  if (o.correct) {
    switch (o.alternative) {
      case Alternative::two_sided: correction = z0 > 0 ? 0.5 : (z0 < 0 ? -0.5 : 0.0); break;
      case Alternative::greater: correction = 0.5; break;
      case Alternative::less: correction = -0.5; break;
    }
  }
  r.z = sigma > 0 ? (z0 - correction) / sigma : kNaN;
  Tail normal{kNaN, kNaN};
  if (r.n > 0) {
    switch (o.alternative) {
      case Alternative::two_sided: normal = normal_two_sided(r.z); break;
      case Alternative::greater: normal = normal_upper(r.z); break;
      case Alternative::less: normal = normal_lower(r.z); break;
    }
  }
  r.p_normal = normal.p;

  // Exact or resampled permutation p.
  if (r.n > 0 && o.exact.mode != ExactMode::never) {
    if (o.exact.mode == ExactMode::monte_carlo) {
      Random<SplitMix64> rng(o.exact.seed);
      std::size_t hi = 0, lo = 0;
      const std::size_t total = o.exact.monte_carlo_samples, every = std::max<std::size_t>(1, total / 100);
      for (std::size_t b = 0; b < total; ++b) {
        if (o.exact.progress && b % every == 0) o.exact.progress(b, total);
        long t = 0;
        for (std::size_t i = 0; i < w.size(); ++i)
          if (rng.next() >> 63) t += w[i];
        if (t >= v2) ++hi;
        if (t <= v2) ++lo;
      }
      if (o.exact.progress) o.exact.progress(total, total);
      const double N = static_cast<double>(o.exact.monte_carlo_samples);
      r.p_exact = pick(o.alternative, above_mean, (static_cast<double>(hi) + 1) / (N + 1), (static_cast<double>(lo) + 1) / (N + 1));
      r.exact_method = "monte-carlo";
    } else {
      double up = 0, lo = 0;
      const double budget = o.exact.mode == ExactMode::always ? 50 * kSignedRankBudget : kSignedRankBudget;
      if (signed_rank_exact(w, v2, budget, up, lo)) {
        r.p_exact = pick(o.alternative, above_mean, up, lo);
        r.exact_method = "exact";
      } else {
        r.exact_note = "the exact signed-rank distribution is too large to enumerate for n = " + std::to_string(r.n) +
                       "; the normal approximation applies (a Monte Carlo estimate on request)";
        if (o.exact.mode == ExactMode::always) r.warnings.push_back("p_exact not computed: " + r.exact_note);
      }
    }
  }

  // Which p is "the" p (R's rules in automatic mode).
  bool use_exact = false;
  switch (o.exact.mode) {
    case ExactMode::automatic: use_exact = r.n < 50 && !r.ties && r.zeros == 0 && r.exact_method == "exact"; break;
    case ExactMode::always:
    case ExactMode::monte_carlo: use_exact = !std::isnan(r.p_exact); break;
    case ExactMode::never: break;
  }
  if (use_exact) {
    r.p = r.p_exact;
    r.log10_p = r.p > 0 ? std::log10(r.p) : -kInf;
    r.method = r.exact_method;
  } else {
    r.p = normal.p;
    r.log10_p = normal.log10_p;
    r.method = "normal";
    if (o.exact.mode == ExactMode::automatic && r.n < 50 && r.n > 0 && (r.ties || r.zeros > 0))
      r.warnings.push_back(std::string("cannot use the exact p-value with ") + (r.ties ? "ties" : "zeroes") +
                           ": p is the normal approximation (as R); p_exact is the exact conditional p");
  }
  if (r.n == 0) r.warnings.push_back("every difference is zero: the signed-rank test is undefined (p = NaN)");
  return r;
}

SignTestResult sign_test(const std::vector<double>& x, const std::vector<double>& y, Alternative alternative) {
  SignTestResult r;
  for (double v : differences(x, y)) {
    if (v > 0) ++r.positive;
    if (v < 0) ++r.negative;
  }
  r.n = r.positive + r.negative;
  if (r.n == 0) {
    r.p = r.log10_p = kNaN;
    return r;
  }
  const Tail lower = binomial_half_lower(r.n, r.positive);  // P(X <= n+)
  const Tail upper = binomial_half_lower(r.n, r.negative);  // P(X >= n+) = P(X <= n-) by symmetry
  Tail t{};
  switch (alternative) {
    case Alternative::greater: t = upper; break;
    case Alternative::less: t = lower; break;
    case Alternative::two_sided: t = two_sided_from(lower, upper); break;
  }
  r.p = t.p;
  r.log10_p = t.log10_p;
  return r;
}

PairedTResult paired_t(const std::vector<double>& x, const std::vector<double>& y, Alternative alternative) {
  if (x.size() != y.size()) throw std::invalid_argument("paired test: x and y differ in length");
  PairedTResult r;
  // x and y scaled by a power of two (exact) so that x - y cannot overflow.
  double largest = 0;
  for (std::size_t i = 0; i < x.size(); ++i)
    if (!std::isnan(x[i]) && !std::isnan(y[i])) largest = std::max({largest, std::fabs(x[i]), std::fabs(y[i])});
  int e = 0;
  if (std::isfinite(largest) && largest > 0) std::frexp(largest, &e);
  std::vector<double> d;
  for (std::size_t i = 0; i < x.size(); ++i)
    if (!std::isnan(x[i]) && !std::isnan(y[i])) d.push_back(std::ldexp(x[i], -e) - std::ldexp(y[i], -e));
  r.n = d.size();
  if (r.n < 2) {
    r.mean_difference = r.n == 1 ? std::ldexp(d.front(), e) : kNaN;
    r.sd = r.se = r.t = r.df = r.p = r.log10_p = r.ci_low = r.ci_high = r.dz = kNaN;
    r.warnings.push_back(r.n == 1 ? "one pair: the paired t test needs two (t and p undefined)"
                                  : "no complete pair: the paired t test is undefined");
    return r;
  }
  detail::Sum s;
  for (double v : d) s.add(v);
  double m = s.value() / static_cast<double>(r.n);
  detail::Sum c;
  for (double v : d) c.add(v - m);
  m += c.value() / static_cast<double>(r.n);
  detail::Sum ss;
  for (double v : d) ss.add((v - m) * (v - m));
  r.df = static_cast<double>(r.n - 1);
  const double sd = std::sqrt(ss.value() / r.df), se = sd / std::sqrt(static_cast<double>(r.n));
  r.t = se > 0 ? m / se : (m == 0 ? kNaN : (m > 0 ? kInf : -kInf));
  r.dz = sd > 0 ? m / sd : r.t;
  r.mean_difference = std::ldexp(m, e);
  r.sd = std::ldexp(sd, e);
  r.se = std::ldexp(se, e);
  const double q = t_quantile(alternative == Alternative::two_sided ? 0.975 : 0.95, r.df);
  r.ci_low = alternative == Alternative::less ? -kInf : r.mean_difference - q * r.se;
  r.ci_high = alternative == Alternative::greater ? kInf : r.mean_difference + q * r.se;
  if (m == 0 && se == 0)
    r.warnings.push_back("every difference is zero: the paired t statistic is 0/0 (t and p undefined)");
  else if (se < 10 * std::numeric_limits<double>::epsilon() * std::fabs(m))
    r.warnings.push_back("the differences are essentially constant (mean " + g6(r.mean_difference) + ", SD " +
                         g6(r.sd) + "): t = " + (std::isinf(r.t) ? "Infinity" : g6(r.t)) +
                         " is not a meaningful test (R's t.test stops here: \"data are essentially constant\")");
  if (!std::isfinite(r.mean_difference) || !std::isfinite(r.sd))
    r.warnings.push_back("overflow: the mean or SD of the differences exceeds the largest double (about 1.8e308); "
                         "t and p are computed on rescaled differences and stay valid");
  Tail t{};
  switch (alternative) {
    case Alternative::two_sided: t = t_two_sided(r.t, r.df); break;
    case Alternative::greater: t = t_upper(r.t, r.df); break;
    case Alternative::less: t = t_lower(r.t, r.df); break;
  }
  r.p = t.p;
  r.log10_p = t.log10_p;
  return r;
}

Result<PairedResult> paired_tests(const LongData& data, const WilcoxonOptions& options, const std::string& factor) {
  if (!data.between.empty())
    return Error{data.source, 0, 0, data.between.front().name, "the paired tests take no between-subject factor"};
  if (factor.empty() && data.within.size() != 1)
    return Error{data.source, 0, 0, "", "the paired tests need exactly one within-subject factor with two levels "
                                        "(or the name of one two-level factor of the design)"};
  auto built = detail::build_cell_design(data);
  if (!built) return built.error();
  const detail::CellDesign& d = *built;
  const auto it = std::find(d.within_names.begin(), d.within_names.end(), factor.empty() ? d.within_names[0] : factor);
  if (it == d.within_names.end()) return Error{data.source, 0, 0, factor, "not a within-subject factor of the design"};
  const std::size_t f = static_cast<std::size_t>(it - d.within_names.begin());
  if (d.within_levels[f].size() != 2)
    return Error{data.source, 0, 0, d.within_names[f],
                 "the paired tests need exactly two levels; this factor has " +
                     std::to_string(d.within_levels[f].size()) + " (use friedman or rm-anova for more)"};
  if (d.subjects.empty())
    return Error{data.source, 0, 0, "", "no subject has every cell: nothing left after listwise deletion"};
  PairedResult r;
  r.x_level = d.within_levels[f][0];
  r.y_level = d.within_levels[f][1];
  const detail::FactorMarginals m = detail::factor_marginals(d, f);  // the cells themselves for a lone factor
  const std::vector<double>&x = m.value[0], &y = m.value[1], &dx = m.delta[0], &dy = m.delta[1];
  r.wilcoxon = wilcoxon_signed_rank(x, y, options);
  r.sign = sign_test(x, y, options.alternative);
  r.t = paired_t(dx, dy, options.alternative);  // deltas: the offset cancels exactly
  r.dropped_subjects = d.dropped;
  r.warnings = d.warnings;
  r.warnings.insert(r.warnings.end(), r.wilcoxon.warnings.begin(), r.wilcoxon.warnings.end());
  for (const auto& w : r.t.warnings) r.warnings.push_back("paired t: " + w);
  return r;
}

}  // namespace dtlab::stats

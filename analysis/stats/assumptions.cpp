// Shapiro-Wilk (Royston's AS R94 approximations) and ANOVA residuals; see assumptions.h.
#include "analysis/stats/assumptions.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

#include "analysis/stats/detail/design.h"
#include "analysis/stats/detail/numbers.h"
#include "analysis/stats/detail/sum.h"
#include "analysis/stats/distributions.h"

namespace dtlab::stats {
namespace {

constexpr double kPi = 3.14159265358979323846;

// c[0] + c[1] x + c[2] x^2 + ...
double polynomial(std::initializer_list<double> c, double x) {
  double r = 0.0, power = 1.0;
  for (double v : c) {
    r += v * power;
    power *= x;
  }
  return r;
}

// The upper half of the coefficients: half[i] = a_{n-i} (positive), i = 0 .. n/2 - 1.
std::vector<double> upper_coefficients(std::size_t n) {
  const std::size_t half = n / 2;
  if (n == 3) return {std::sqrt(0.5)};
  const double an = static_cast<double>(n);
  std::vector<double> m(half);
  double mm = 0.0;
  for (std::size_t i = 0; i < half; ++i) {
    // m for rank n - i (upper tail): -Phi^-1((i + 1 - 3/8) / (n + 1/4))
    m[i] = -normal_quantile((static_cast<double>(i + 1) - 0.375) / (an + 0.25));
    mm += m[i] * m[i];
  }
  mm *= 2.0;  // both tails
  const double u = 1.0 / std::sqrt(an), root = std::sqrt(mm);
  std::vector<double> a(half);
  a[0] = m[0] / root + polynomial({0.0, 0.221157, -0.147981, -2.07119, 4.434685, -2.706056}, u);
  std::size_t first_scaled = 1;
  double eps;
  if (n > 5) {
    a[1] = m[1] / root + polynomial({0.0, 0.042981, -0.293762, -1.752461, 5.682633, -3.582633}, u);
    eps = (mm - 2.0 * m[0] * m[0] - 2.0 * m[1] * m[1]) / (1.0 - 2.0 * a[0] * a[0] - 2.0 * a[1] * a[1]);
    first_scaled = 2;
  } else {
    eps = (mm - 2.0 * m[0] * m[0]) / (1.0 - 2.0 * a[0] * a[0]);
  }
  for (std::size_t i = first_scaled; i < half; ++i) a[i] = m[i] / std::sqrt(eps);
  return a;
}

double shapiro_p(double w, std::size_t n) {
  const double an = static_cast<double>(n);
  if (n == 3) return std::max(0.0, 6.0 / kPi * (std::asin(std::sqrt(w)) - std::asin(std::sqrt(0.75))));
  double y = std::log1p(-w), mu, sigma;
  if (n <= 11) {
    const double gamma = polynomial({-2.273, 0.459}, an);
    if (y >= gamma) return 1e-99;  // beyond the approximation's range (R's value)
    y = -std::log(gamma - y);
    mu = polynomial({0.5440, -0.39978, 0.025054, -6.714e-4}, an);
    sigma = std::exp(polynomial({1.3822, -0.77857, 0.062767, -0.0020322}, an));
  } else {
    const double x = std::log(an);
    mu = polynomial({-1.5861, -0.31082, -0.083751, 0.0038915}, x);
    sigma = std::exp(polynomial({-0.4803, -0.082676, 0.0030302}, x));
  }
  return normal_upper((y - mu) / sigma).p;
}

}  // namespace

ShapiroWilkResult shapiro_wilk(const std::vector<double>& values) {
  ShapiroWilkResult r;
  std::vector<double> x;
  for (double v : values)
    if (!std::isnan(v)) x.push_back(v);
  std::sort(x.begin(), x.end());
  r.n = x.size();
  r.W = r.p = kNaN;
  if (r.n < 3 || r.n > 5000) {
    r.warnings.push_back("Shapiro-Wilk needs between 3 and 5000 values, got " + std::to_string(r.n) +
                         " (W and p undefined; R's shapiro.test stops here)");
    return r;
  }
  const double range = x.back() - x.front();
  if (!(range > 0)) {
    r.warnings.push_back("all values are identical: Shapiro-Wilk W is undefined (R's shapiro.test stops here)");
    return r;
  }
  const std::vector<double> half = upper_coefficients(r.n);
  std::vector<double> a(r.n, 0.0);
  for (std::size_t i = 0; i < half.size(); ++i) {
    a[r.n - 1 - i] = half[i];
    a[i] = -half[i];
  }
  // W as the squared correlation of a and x / range, with 1 - W formed without cancellation.
  detail::Sum sa, sx;
  for (std::size_t i = 0; i < r.n; ++i) {
    sa.add(a[i]);
    sx.add(x[i] / range);
  }
  const double ma = sa.value() / static_cast<double>(r.n), mx = sx.value() / static_cast<double>(r.n);
  detail::Sum ssa, ssx, sax;
  for (std::size_t i = 0; i < r.n; ++i) {
    const double da = a[i] - ma, dx = x[i] / range - mx;
    ssa.add(da * da);
    ssx.add(dx * dx);
    sax.add(da * dx);
  }
  const double root = std::sqrt(ssa.value() * ssx.value());
  const double w1 = (root - sax.value()) * (root + sax.value()) / (ssa.value() * ssx.value());
  r.W = 1.0 - w1;
  r.p = shapiro_p(r.W, r.n);
  return r;
}

Result<AnovaResiduals> anova_residuals(const LongData& data) {
  auto built = detail::build_cell_design(data);
  if (!built) return built.error();
  const detail::CellDesign& d = *built;
  AnovaResiduals out;
  out.dropped_subjects = d.dropped;
  out.warnings = d.warnings;
  const std::size_t N = d.subjects.size(), C = d.cells;
  std::map<std::vector<std::size_t>, std::vector<std::size_t>> groups;
  for (std::size_t s = 0; s < N; ++s) groups[d.group[s]].push_back(s);
  std::vector<double> subject_mean(N);
  for (std::size_t s = 0; s < N; ++s) {
    detail::Sum m;
    for (std::size_t c = 0; c < C; ++c) m.add(d.delta[s][c]);
    subject_mean[s] = m.value() / static_cast<double>(C);
  }
  std::vector<std::vector<double>> residual(N, std::vector<double>(C));
  for (const auto& [key, members] : groups) {
    const double k = static_cast<double>(members.size());
    std::vector<double> cell_mean(C);
    detail::Sum grand;
    for (std::size_t c = 0; c < C; ++c) {
      detail::Sum m;
      for (std::size_t s : members) m.add(d.delta[s][c]);
      cell_mean[c] = m.value() / k;
      grand.add(m.value());
    }
    const double g = grand.value() / (k * static_cast<double>(C));
    for (std::size_t s : members)
      for (std::size_t c = 0; c < C; ++c) residual[s][c] = d.delta[s][c] - subject_mean[s] - cell_mean[c] + g;
  }
  for (std::size_t s = 0; s < N; ++s)
    for (std::size_t c = 0; c < C; ++c) out.residuals.push_back({d.subjects[s], d.cell_label(c), residual[s][c]});
  return out;
}

}  // namespace dtlab::stats

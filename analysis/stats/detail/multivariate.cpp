// emmeans' contrasts and joint tests on the multivariate model; see multivariate.h.
#include "analysis/stats/detail/multivariate.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstdint>
#include <limits>

#include "analysis/stats/detail/linalg.h"
#include "analysis/stats/detail/numbers.h"
#include "analysis/stats/distributions.h"
#include "analysis/stats/detail/sum.h"

namespace dtlab::stats::detail {
namespace {

// Weight of the cell with level indices `lv` of the factors [first, first + lv.size()).
double product_weight(const FactorWeights& w, size_t first, const std::vector<size_t>& lv) {
  double p = 1;
  for (size_t f = 0; f < lv.size(); ++f) p *= w[first + f][lv[f]];
  return p;
}

}  // namespace

Result<MultivariateModel> MultivariateModel::fit(const CellDesign& d, const std::string& source) {
  MultivariateModel m;
  m.d_ = &d;
  const size_t nb = d.between_names.size();
  std::vector<std::vector<size_t>> renumber(nb);  // original level -> surviving level (or none)
  m.between_labels_.resize(nb);
  for (size_t f = 0; f < nb; ++f) {
    renumber[f].assign(d.between_levels[f].size(), SIZE_MAX);
    for (const auto& g : d.group)
      if (renumber[f][g[f]] == SIZE_MAX) {
        renumber[f][g[f]] = m.between_labels_[f].size();
        m.between_labels_[f].push_back(d.between_levels[f][g[f]]);
      }
    m.between_levels_.push_back(m.between_labels_[f].size());
  }
  for (const auto& lv : d.within_levels) m.within_levels_.push_back(lv.size());
  size_t q = 1;
  for (size_t L : m.between_levels_) q *= L;
  m.n_.assign(q, 0.0);
  for (const auto& g : d.group) {
    size_t cell = 0;
    for (size_t f = 0; f < nb; ++f) cell = cell * m.between_levels_[f] + renumber[f][g[f]];
    m.cell_of_.push_back(cell);
    m.n_[cell] += 1;
  }
  for (double n : m.n_)
    if (n == 0)
      return Error{source, 0, 0, "", "some combination of the between-subject factors has no subject (after listwise "
                                     "deletion): the marginal means of the full-factorial design cannot be estimated"};
  m.dfe_ = static_cast<double>(d.subjects.size()) - static_cast<double>(q);
  if (m.dfe_ < 1)
    return Error{source, 0, 0, "", "as many subjects as between-subject cells: no error degrees of freedom"};
  double largest = 0;
  for (const auto& row : d.delta)
    for (double v : row) largest = std::max(largest, std::fabs(v));
  if (largest > 0 && std::isfinite(largest)) std::frexp(largest, &m.exponent_);
  return m;
}

size_t MultivariateModel::levels(size_t factor) const {
  return factor < between_levels_.size() ? between_levels_[factor] : within_levels_[factor - between_levels_.size()];
}

const std::string& MultivariateModel::label(size_t factor, size_t level) const {
  const size_t nb = between_levels_.size();
  return factor < nb ? between_labels_[factor][level] : d_->within_levels[factor - nb][level];
}

const std::string& MultivariateModel::name(size_t factor) const {
  const size_t nb = between_levels_.size();
  return factor < nb ? d_->between_names[factor] : d_->within_names[factor - nb];
}

void MultivariateModel::scores(const FactorWeights& w, std::vector<double>& a, std::vector<double>& x) const {
  assert(w.size() == factors() && "MultivariateModel: one weight vector per factor");
  const size_t nb = between_levels_.size();
  a.assign(n_.size(), 0.0);
  for (size_t cell = 0; cell < n_.size(); ++cell) {
    std::vector<size_t> lv(nb);
    for (size_t f = nb, rest = cell; f-- > 0; rest /= between_levels_[f]) lv[f] = rest % between_levels_[f];
    a[cell] = product_weight(w, 0, lv);
  }
  std::vector<double> wc(d_->cells);
  for (size_t c = 0; c < d_->cells; ++c) wc[c] = product_weight(w, nb, d_->cell_levels(c));
  x.assign(d_->subjects.size(), 0.0);
  for (size_t s = 0; s < x.size(); ++s) {
    Sum sum;
    for (size_t c = 0; c < d_->cells; ++c)
      if (wc[c] != 0) sum.add(wc[c] * std::ldexp(d_->delta[s][c], -exponent_));
    x[s] = sum.value();
  }
}

ContrastEstimate MultivariateModel::estimate(const FactorWeights& w) const {
  std::vector<double> a, x;
  scores(w, a, x);
  std::vector<Sum> cell_sum(n_.size());
  for (size_t s = 0; s < x.size(); ++s) cell_sum[cell_of_[s]].add(x[s]);
  std::vector<double> mean(n_.size());
  Sum est, spread;
  for (size_t g = 0; g < n_.size(); ++g) {
    mean[g] = cell_sum[g].value() / n_[g];
    est.add(a[g] * mean[g]);
    spread.add(a[g] * a[g] / n_[g]);
  }
  Sum ss;
  for (size_t s = 0; s < x.size(); ++s) ss.add((x[s] - mean[cell_of_[s]]) * (x[s] - mean[cell_of_[s]]));
  ContrastEstimate r;
  const double var = ss.value() / dfe_;
  r.df = dfe_;
  r.estimate = std::ldexp(est.value(), exponent_);
  r.se = std::ldexp(std::sqrt(var * spread.value()), exponent_);
  r.sd = std::ldexp(std::sqrt(var), exponent_);
  return r;
}

JointTest MultivariateModel::joint(const std::vector<FactorWeights>& rows) const {
  const size_t R = rows.size();
  std::vector<std::vector<double>> a(R), x(R), e(R);
  std::vector<double> est(R);
  for (size_t r = 0; r < R; ++r) {
    scores(rows[r], a[r], x[r]);
    std::vector<Sum> cell_sum(n_.size());
    for (size_t s = 0; s < x[r].size(); ++s) cell_sum[cell_of_[s]].add(x[r][s]);
    Sum sum;
    std::vector<double> mean(n_.size());
    for (size_t g = 0; g < n_.size(); ++g) {
      mean[g] = cell_sum[g].value() / n_[g];
      sum.add(a[r][g] * mean[g]);
    }
    est[r] = sum.value();
    e[r].resize(x[r].size());
    for (size_t s = 0; s < x[r].size(); ++s) e[r][s] = x[r][s] - mean[cell_of_[s]];
  }
  Matrix V(R, R);  // V_rt = (e_r . e_t / dfe) sum_g a_rg a_tg / n_g
  for (size_t r = 0; r < R; ++r)
    for (size_t t = 0; t <= r; ++t) {
      Sum cov, spread;
      for (size_t s = 0; s < e[r].size(); ++s) cov.add(e[r][s] * e[t][s]);
      for (size_t g = 0; g < n_.size(); ++g) spread.add(a[r][g] * a[t][g] / n_[g]);
      V(r, t) = V(t, r) = cov.value() / dfe_ * spread.value();
    }
  JointTest j;
  j.df1 = static_cast<double>(R);
  j.df2 = dfe_;
  const auto Vinv = spd_inverse(V);
  if (!Vinv) {
    j.F = kNaN;
    return j;
  }
  Sum q;
  for (size_t r = 0; r < R; ++r)
    for (size_t t = 0; t < R; ++t) q.add(est[r] * (*Vinv)(r, t) * est[t]);
  j.F = q.value() / static_cast<double>(R);
  return j;
}

FactorWeights MultivariateModel::averaging() const {
  FactorWeights w(factors());
  for (size_t f = 0; f < w.size(); ++f) w[f].assign(levels(f), 1.0 / static_cast<double>(levels(f)));
  return w;
}

Comparison MultivariateModel::pair(size_t factor, size_t i, size_t j, FactorWeights w) const {
  w[factor].assign(levels(factor), 0.0);
  w[factor][i] = 1.0;
  w[factor][j] = -1.0;
  const ContrastEstimate ce = estimate(w);
  Comparison c;
  c.a = label(factor, i);
  c.b = label(factor, j);
  c.test = "emmeans t";
  c.n = subjects();
  c.estimate = ce.estimate;
  c.se = ce.se;
  c.df = ce.df;
  c.statistic = ce.estimate / ce.se;
  c.p = t_two_sided(c.statistic, c.df).p;
  const double q = t_quantile(0.975, c.df);
  c.ci_low = c.estimate - q * c.se;
  c.ci_high = c.estimate + q * c.se;
  c.dz = ce.estimate / ce.sd;
  return c;
}

JointTest MultivariateModel::levels_differ(size_t factor, const FactorWeights& w) const {
  std::vector<FactorWeights> rows;
  const size_t L = levels(factor);
  for (size_t i = 0; i + 1 < L; ++i) {
    FactorWeights r = w;
    r[factor].assign(L, 0.0);
    r[factor][i] = 1.0;
    r[factor][L - 1] = -1.0;
    rows.push_back(std::move(r));
  }
  return joint(rows);
}

}  // namespace dtlab::stats::detail

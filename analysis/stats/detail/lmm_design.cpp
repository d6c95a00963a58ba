// Fixed and random design of a mixed model; see lmm_design.h.
#include "analysis/stats/detail/lmm_design.h"

#include <algorithm>
#include <bit>
#include <cassert>
#include <numeric>
#include <optional>
#include <unordered_map>

#include "analysis/stats/measurements.h"

namespace dtlab::stats::detail {

CodedFactor code_factor(const std::string& name, const std::vector<std::string>& labels, bool within) {
  CodedFactor f;
  f.name = name;
  f.within = within;
  std::unordered_map<std::string, int> seen;
  std::vector<std::string> distinct;
  for (const auto& l : labels)
    if (seen.emplace(l, 0).second) distinct.push_back(l);
  std::vector<std::optional<Decimal>> numbers;
  bool numeric = true;
  for (const auto& l : distinct) {
    numbers.push_back(parse_decimal(l));
    numeric = numeric && numbers.back().has_value();
  }
  std::vector<size_t> order(distinct.size());
  std::iota(order.begin(), order.end(), 0);
  if (numeric)
    std::stable_sort(order.begin(), order.end(),
                     [&](size_t a, size_t b) { return numbers[a]->value < numbers[b]->value; });
  else
    std::sort(order.begin(), order.end(), [&](size_t a, size_t b) { return distinct[a] < distinct[b]; });
  for (size_t i = 0; i < order.size(); ++i) {
    f.levels.push_back(distinct[order[i]]);
    seen[distinct[order[i]]] = static_cast<int>(i);
  }
  f.index.reserve(labels.size());
  for (const auto& l : labels) f.index.push_back(seen[l]);
  return f;
}

double contr_sum(int level, int column, int levels) {
  if (level == levels - 1) return -1.0;
  return level == column ? 1.0 : 0.0;
}

Eigen::RowVectorXd FixedDesign::cell_row(const std::vector<int>& levels) const {
  Eigen::RowVectorXd row = Eigen::RowVectorXd::Zero(static_cast<Eigen::Index>(column_names.size()));
  row(0) = 1.0;
  for (const auto& t : terms) {
    // columns of the term: products of contrast columns, first factor fastest
    std::vector<int> col(t.factors.size(), 0);
    for (int c : t.columns) {
      double v = 1.0;
      for (size_t k = 0; k < t.factors.size(); ++k) {
        const auto& f = factors[static_cast<size_t>(t.factors[k])];
        v *= contr_sum(levels[static_cast<size_t>(t.factors[k])], col[k], static_cast<int>(f.levels.size()));
      }
      row(c) = v;
      for (size_t k = 0; k < t.factors.size(); ++k) {  // odometer, first factor fastest
        if (++col[k] < static_cast<int>(factors[static_cast<size_t>(t.factors[k])].levels.size()) - 1) break;
        col[k] = 0;
      }
    }
  }
  return row;
}

FixedDesign fixed_design(std::vector<CodedFactor> factors) {
  FixedDesign d;
  d.factors = std::move(factors);
  const int nf = static_cast<int>(d.factors.size());
  std::vector<unsigned> masks;
  for (unsigned m = 1; m < (1u << nf); ++m) masks.push_back(m);
  std::stable_sort(masks.begin(), masks.end(),
                   [](unsigned a, unsigned b) { return std::popcount(a) < std::popcount(b); });
  d.column_names = {"(Intercept)"};
  for (unsigned m : masks) {
    FixedTerm t;
    size_t width = 1;
    for (int f = 0; f < nf; ++f)
      if (m & (1u << f)) {
        t.factors.push_back(f);
        t.name += (t.name.empty() ? "" : ":") + d.factors[static_cast<size_t>(f)].name;
        width *= d.factors[static_cast<size_t>(f)].levels.size() - 1;
      }
    std::vector<size_t> col(t.factors.size(), 0);
    for (size_t c = 0; c < width; ++c) {
      std::string name;
      for (size_t k = 0; k < t.factors.size(); ++k)
        name += (k ? ":" : "") + d.factors[static_cast<size_t>(t.factors[k])].name + std::to_string(col[k] + 1);
      t.columns.push_back(static_cast<int>(d.column_names.size()));
      d.column_names.push_back(name);
      for (size_t k = 0; k < t.factors.size(); ++k) {
        if (++col[k] < d.factors[static_cast<size_t>(t.factors[k])].levels.size() - 1) break;
        col[k] = 0;
      }
    }
    d.terms.push_back(std::move(t));
  }
  const size_t n = d.factors.empty() ? 0 : d.factors.front().index.size();
  d.X.resize(static_cast<Eigen::Index>(n), static_cast<Eigen::Index>(d.column_names.size()));
  std::vector<int> levels(d.factors.size());
  for (size_t r = 0; r < n; ++r) {
    for (size_t f = 0; f < d.factors.size(); ++f) levels[f] = d.factors[f].index[r];
    d.X.row(static_cast<Eigen::Index>(r)) = d.cell_row(levels);
  }
  return d;
}

Eigen::MatrixXd type3_hypothesis(const FixedDesign& design, const FixedTerm& term) {
  const Eigen::Index p = static_cast<Eigen::Index>(design.column_names.size());
  // one factor's row: contr.sum row of `level` minus that of the first level
  auto factor_row = [&](int f, int level) {
    const int k = static_cast<int>(design.factors[static_cast<size_t>(f)].levels.size());
    Eigen::VectorXd v(k - 1);
    for (int c = 0; c < k - 1; ++c) v(c) = contr_sum(level, c, k) - contr_sum(0, c, k);
    return v;
  };
  const Eigen::Index rows = static_cast<Eigen::Index>(term.columns.size());
  Eigen::MatrixXd L = Eigen::MatrixXd::Zero(rows, p);
  std::vector<int> level(term.factors.size(), 1);
  for (Eigen::Index r = 0; r < rows; ++r) {
    // Kronecker product of the factors' rows, first factor fastest
    Eigen::VectorXd kron = Eigen::VectorXd::Ones(1);
    for (size_t k = 0; k < term.factors.size(); ++k) {
      const Eigen::VectorXd v = factor_row(term.factors[k], level[k]);
      Eigen::VectorXd next(kron.size() * v.size());
      for (Eigen::Index j = 0; j < v.size(); ++j) next.segment(j * kron.size(), kron.size()) = v(j) * kron;
      kron = next;
    }
    for (Eigen::Index c = 0; c < kron.size(); ++c) L(r, term.columns[static_cast<size_t>(c)]) = kron(c);
    for (size_t k = 0; k < term.factors.size(); ++k) {
      const int nl = static_cast<int>(design.factors[static_cast<size_t>(term.factors[k])].levels.size());
      if (++level[k] < nl) break;
      level[k] = 1;
    }
  }
  return L;
}

std::vector<RandomTerm> lme4_term_order(std::vector<RandomTerm> terms, const std::vector<Grouping>& groupings) {
  std::vector<size_t> nl;
  for (const auto& t : terms) nl.push_back(groupings[static_cast<size_t>(t.grouping)].levels.size());
  bool increase = false;
  for (size_t i = 1; i < nl.size(); ++i) increase = increase || nl[i] > nl[i - 1];
  if (!increase) return terms;
  std::vector<size_t> order(terms.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) { return nl[a] < nl[b]; });
  std::reverse(order.begin(), order.end());
  std::vector<RandomTerm> sorted;
  for (size_t i : order) sorted.push_back(terms[i]);
  return sorted;
}

}  // namespace dtlab::stats::detail

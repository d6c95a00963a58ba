// Repeated-measures and mixed ANOVA; see rm_anova.h for the method.
#include "analysis/stats/rm_anova.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <tuple>

#include "analysis/stats/detail/design.h"
#include "analysis/stats/detail/linalg.h"
#include "analysis/stats/detail/sum.h"
#include "analysis/stats/distributions.h"

namespace dtlab::stats {
namespace {

using detail::Matrix;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

// Subsets of {0..n-1}: the empty set, then by size, each size in lexicographic order (R's term order).
std::vector<std::vector<size_t>> terms(size_t n) {
  std::vector<std::vector<size_t>> out{{}};
  for (size_t k = 1; k <= n; ++k) {
    std::vector<size_t> c(k);
    for (size_t i = 0; i < k; ++i) c[i] = i;
    while (true) {
      out.push_back(c);
      size_t i = k;
      while (i > 0 && c[i - 1] == n - k + i - 1) --i;
      if (i == 0) break;
      ++c[i - 1];
      for (size_t j = i; j < k; ++j) c[j] = c[j - 1] + 1;
    }
  }
  return out;
}

bool contains(const std::vector<size_t>& set, size_t x) { return std::find(set.begin(), set.end(), x) != set.end(); }

// Sum-to-zero contrasts (R's contr.sum) for one factor: levels x (levels-1).
Matrix contr_sum(size_t levels) {
  Matrix m(levels, levels > 0 ? levels - 1 : 0);
  for (size_t j = 0; j + 1 < levels; ++j) {
    m(j, j) = 1.0;
    m(levels - 1, j) = -1.0;
  }
  return m;
}

// The design: X's columns grouped by between term.
struct BetweenDesign {
  Matrix X;                                  // N x q
  std::vector<std::vector<size_t>> terms;    // between terms, intercept first
  std::vector<std::vector<size_t>> columns;  // columns[t]: X columns of term t
  std::vector<size_t> df;                    // df of each term
};

BetweenDesign between_design(const std::vector<std::vector<size_t>>& group, const std::vector<size_t>& levels) {
  BetweenDesign b;
  const size_t n = group.size();
  b.terms = terms(levels.size());
  std::vector<Matrix> cs;
  for (size_t L : levels) cs.push_back(contr_sum(L));
  std::vector<std::vector<double>> cols;
  for (const auto& t : b.terms) {
    // columns of the term: products over its factors of one contrast column each
    std::vector<std::vector<double>> tc{std::vector<double>(n, 1.0)};
    size_t df = 1;
    for (size_t f : t) {
      std::vector<std::vector<double>> next;
      for (const auto& prev : tc)
        for (size_t j = 0; j < cs[f].cols; ++j) {
          std::vector<double> c(n);
          for (size_t s = 0; s < n; ++s) c[s] = prev[s] * cs[f](group[s][f], j);
          next.push_back(std::move(c));
        }
      tc = std::move(next);
      df *= levels[f] - 1;
    }
    std::vector<size_t> idx;
    for (auto& c : tc) {
      idx.push_back(cols.size());
      cols.push_back(std::move(c));
    }
    b.columns.push_back(std::move(idx));
    b.df.push_back(df);
  }
  b.X = Matrix(n, cols.size());
  for (size_t j = 0; j < cols.size(); ++j)
    for (size_t s = 0; s < n; ++s) b.X(s, j) = cols[j][s];
  return b;
}

Matrix submatrix(const Matrix& m, const std::vector<size_t>& rows, const std::vector<size_t>& cols) {
  Matrix s(rows.size(), cols.size());
  for (size_t i = 0; i < rows.size(); ++i)
    for (size_t j = 0; j < cols.size(); ++j) s(i, j) = m(rows[i], cols[j]);
  return s;
}

// car's Mauchly test: {W, p}.
std::pair<double, double> mauchly(const Matrix& E, double n, size_t cells) {
  const double pp = static_cast<double>(E.rows);
  const double tr = detail::trace(E);
  const double log_det = detail::spd_log_det(E);
  if (n < pp) return {0.0, kNaN};
  const double log_w = log_det - pp * std::log(tr / pp);
  const double w = std::isinf(log_w) ? 0.0 : std::exp(log_w);
  const double rho = 1.0 - (2.0 * pp * pp + pp + 2.0) / (6.0 * pp * n);
  const double w2 = (pp + 2.0) * (pp - 1.0) * (pp - 2.0) *
                    (2.0 * pp * pp * pp + 6.0 * pp * pp + 3.0 * static_cast<double>(cells) + 2.0) /
                    (288.0 * (n * pp * rho) * (n * pp * rho));
  const double z = -n * rho * log_w;
  const double f = pp * (pp + 1.0) / 2.0 - 1.0;
  const double pr1 = chi_squared_upper(z, f).p;
  const double pr2 = chi_squared_upper(z, f + 4.0).p;
  return {w, pr1 + w2 * (pr2 - pr1)};
}

void set_test(Effect& e, bool zero_error) {
  if (e.df2 == 0) {
    e.F = e.p = e.log10_p = kNaN;
  } else if (zero_error) {
    if (e.ss > 0) {
      e.F = kInf;
      e.p = 0.0;
      e.log10_p = -kInf;
    } else {
      e.F = e.p = e.log10_p = kNaN;
    }
  } else {
    e.F = (e.ss / e.df1) / (e.ss_error / e.df2);
    const Tail t = f_upper(e.F, e.df1, e.df2);
    e.p = t.p;
    e.log10_p = t.log10_p;
  }
}

}  // namespace

Result<RmAnovaResult> rm_anova(const LongData& data, const RmAnovaOptions& options) {
  auto built = detail::build_cell_design(data);
  if (!built) return built.error();
  detail::CellDesign& d = *built;

  RmAnovaResult r;
  r.within = d.within_names;
  r.between = d.between_names;
  r.dropped_subjects = d.dropped;
  r.warnings = d.warnings;
  const size_t N = d.subjects.size();
  r.n_subjects = N;
  if (N == 0) return Error{data.source, 0, 0, "", "no subject has every cell: nothing left after listwise deletion"};

  // Between levels that survive deletion, renumbered.
  const size_t nb = d.between_names.size(), nw = d.within_names.size(), C = d.cells;
  std::vector<size_t> blevels(nb);
  std::vector<std::vector<std::string>> blabels(nb);
  std::vector<std::vector<size_t>> group(N, std::vector<size_t>(nb));
  for (size_t f = 0; f < nb; ++f) {
    std::map<size_t, size_t> remap;
    for (size_t s = 0; s < N; ++s) {
      auto [it, ins] = remap.emplace(d.group[s][f], remap.size());
      if (ins) blabels[f].push_back(d.between_levels[f][d.group[s][f]]);
      group[s][f] = it->second;
    }
    blevels[f] = remap.size();
  }
  // Every between cell needs a subject, else the full-factorial model is not estimable.
  {
    std::map<std::vector<size_t>, size_t> seen;
    for (const auto& g : group) ++seen[g];
    size_t expected = 1;
    for (size_t L : blevels) expected *= L;
    if (seen.size() < expected)
      return Error{data.source, 0, 0, "", "some combination of the between-subject factors has no subject (after listwise "
                                          "deletion): the full-factorial between design cannot be estimated"};
  }
  for (size_t f = 0; f < nb; ++f)
    if (blevels[f] < 2) r.warnings.push_back("between factor '" + d.between_names[f] + "' has one level: its effects are not tested");
  for (size_t f = 0; f < nw; ++f)
    if (d.within_levels[f].size() < 2) r.warnings.push_back("within factor '" + d.within_names[f] + "' has one level: its effects are not tested");
  if (N == 1) r.warnings.push_back("one subject: no error degrees of freedom, F and p are undefined");

  const BetweenDesign bd = between_design(group, blevels);
  const size_t q = bd.X.cols;
  const auto V = detail::spd_inverse(detail::crossprod(bd.X));
  if (!V) return Error{data.source, 0, 0, "", "the between-subjects design matrix is singular"};
  const Matrix Xt = detail::transpose(bd.X);
  const double dfe = static_cast<double>(N) - static_cast<double>(q);
  if (N > 1 && dfe == 0) r.warnings.push_back("as many subjects as between-subject cells: no error degrees of freedom");

  Matrix Y(N, C);
  detail::Sum sumsq;
  for (size_t s = 0; s < N; ++s)
    for (size_t c = 0; c < C; ++c) {
      Y(s, c) = d.delta[s][c];
      sumsq.add(d.delta[s][c] * d.delta[s][c]);
    }
  const double zero_threshold = 2e-28 * static_cast<double>(C) * sumsq.value();

  struct Pending {
    Effect e;
    size_t stratum;
    std::vector<size_t> factors_between, factors_within;
  };
  std::vector<Pending> pending;
  std::vector<double> stratum_error;
  const auto wterms = terms(nw);
  for (size_t si = 0; si < wterms.size(); ++si) {
    const auto& S = wterms[si];
    Matrix M(1, 1, 1.0);
    for (size_t f = 0; f < nw; ++f) {
      const size_t L = d.within_levels[f].size();
      M = detail::kronecker(M, contains(S, f) ? detail::orthonormal_contrasts(L) : detail::normalized_mean_row(L));
    }
    const size_t p = M.rows;
    if (p == 0) continue;
    const Matrix Z = detail::multiply(Y, detail::transpose(M));
    Matrix B = detail::multiply(*V, detail::multiply(Xt, Z));
    Matrix R = Z;
    for (int pass = 0; pass < 2; ++pass) {  // residuals, then one step of iterative refinement of B
      const Matrix fit = detail::multiply(bd.X, B);
      for (size_t i = 0; i < R.a.size(); ++i) R.a[i] = Z.a[i] - fit.a[i];
      if (pass == 0) {
        const Matrix dB = detail::multiply(*V, detail::multiply(Xt, R));
        for (size_t i = 0; i < B.a.size(); ++i) B.a[i] += dB.a[i];
      }
    }
    const Matrix E = detail::crossprod(R);
    double ss_error = detail::trace(E);
    const bool zero_error = dfe > 0 && ss_error <= zero_threshold;
    if (zero_error) ss_error = 0.0;
    stratum_error.push_back(ss_error);
    if (zero_error && dfe > 0)
      r.warnings.push_back(std::string("zero error variance in stratum ") + (S.empty() ? "between subjects" : "of the within term") +
                           ": F is infinite (or 0/0) there");

    // Sphericity of this stratum.
    double gg = 1.0, hf = 1.0, mw = kNaN, mp = kNaN;
    if (S.empty()) {
      gg = hf = kNaN;
    } else if (p >= 2) {
      if (zero_error || dfe <= 0) {
        gg = hf = kNaN;
      } else {
        const Matrix E2 = detail::multiply(E, E);
        const double pd = static_cast<double>(p);
        if (dfe == 1) {  // E has rank 1: GG = 1/p exactly and the HF formula is 0/0
          gg = 1.0 / pd;
          hf = kNaN;
        } else {
          gg = ss_error * ss_error / (pd * detail::trace(E2));
          hf = ((dfe + 1.0) * pd * gg - 2.0) / (pd * (dfe - pd * gg));
        }
        std::tie(mw, mp) = mauchly(E, dfe, C);
      }
    }

    for (size_t ti = 0; ti < bd.terms.size(); ++ti) {
      const auto& T = bd.terms[ti];
      if (S.empty() && T.empty()) continue;  // the intercept is not reported (afex intercept = FALSE)
      if (bd.df[ti] == 0) continue;
      Effect e;
      std::string name;
      for (size_t f : T) name += (name.empty() ? "" : ":") + d.between_names[f];
      for (size_t f : S) name += (name.empty() ? "" : ":") + d.within_names[f];
      e.name = name;
      e.within = !S.empty();
      const Matrix Bt = submatrix(B, bd.columns[ti], [&] {
        std::vector<size_t> all(p);
        for (size_t j = 0; j < p; ++j) all[j] = j;
        return all;
      }());
      const auto Vinv = detail::spd_inverse(submatrix(*V, bd.columns[ti], bd.columns[ti]));
      if (!Vinv) return Error{data.source, 0, 0, "", "singular between-subjects term " + name};
      const Matrix H = detail::multiply(detail::transpose(Bt), detail::multiply(*Vinv, Bt));
      e.ss = detail::trace(H);
      e.ss_error = ss_error;
      e.df1 = static_cast<double>(bd.df[ti] * p);
      e.df2 = std::max(0.0, dfe) * static_cast<double>(p);
      set_test(e, zero_error);
      e.eta_p2 = (e.ss + e.ss_error) > 0 ? e.ss / (e.ss + e.ss_error) : kNaN;
      if (!e.within) {
        e.gg_epsilon = e.hf_epsilon = e.mauchly_W = e.mauchly_p = kNaN;
        e.p_gg = e.log10_p_gg = e.p_hf = e.log10_p_hf = kNaN;
      } else {
        e.gg_epsilon = gg;
        e.hf_epsilon = hf;
        e.mauchly_W = mw;
        e.mauchly_p = mp;
        if (p == 1 || (zero_error && p >= 2)) {
          e.p_gg = e.p_hf = e.p;
          e.log10_p_gg = e.log10_p_hf = e.log10_p;
        } else {
          const Tail tg = f_upper(e.F, e.df1 * gg, e.df2 * gg);
          e.p_gg = tg.p;
          e.log10_p_gg = tg.log10_p;
          const double h = std::isnan(hf) ? kNaN : std::min(1.0, hf);
          const Tail th = h > 0 ? f_upper(e.F, e.df1 * h, e.df2 * h) : Tail{kNaN, kNaN};
          e.p_hf = th.p;
          e.log10_p_hf = th.log10_p;
        }
      }
      pending.push_back({e, stratum_error.size() - 1, T, S});
    }
  }

  // Generalized eta squared (afex): distinct error SS of all strata, plus observed effects.
  std::vector<double> distinct;
  for (double v : stratum_error)
    if (std::find(distinct.begin(), distinct.end(), v) == distinct.end()) distinct.push_back(v);
  detail::Sum err_sum;
  for (double v : distinct) err_sum.add(v);
  auto is_observed = [&](const Pending& pe) {
    for (const auto& o : options.observed) {
      for (size_t f : pe.factors_between)
        if (d.between_names[f] == o) return true;
      for (size_t f : pe.factors_within)
        if (d.within_names[f] == o) return true;
    }
    return false;
  };
  for (const auto& o : options.observed)
    if (std::find(d.between_names.begin(), d.between_names.end(), o) == d.between_names.end() &&
        std::find(d.within_names.begin(), d.within_names.end(), o) == d.within_names.end())
      return Error{data.source, 0, 0, o, "observed factor is not a factor of the design"};
  double obs_ss = 0.0;
  for (const auto& pe : pending)
    if (is_observed(pe)) obs_ss += pe.e.ss;
  for (auto& pe : pending) {
    const double denom = pe.e.ss + err_sum.value() + obs_ss - (is_observed(pe) ? pe.e.ss : 0.0);
    pe.e.eta_g2 = denom > 0 ? pe.e.ss / denom : kNaN;
    r.effects.push_back(pe.e);
  }

  // Descriptives of the subjects' cell means, per between group and within cell.
  std::map<std::vector<size_t>, std::vector<size_t>> members;
  for (size_t s = 0; s < N; ++s) members[group[s]].push_back(s);
  for (const auto& [g, subjects] : members)
    for (size_t c = 0; c < C; ++c) {
      CellSummary cs;
      for (size_t f = 0; f < nb; ++f) cs.levels.emplace_back(d.between_names[f], blabels[f][g[f]]);
      const auto lv = d.cell_levels(c);
      for (size_t f = 0; f < nw; ++f) cs.levels.emplace_back(d.within_names[f], d.within_levels[f][lv[f]]);
      std::vector<double> x;
      for (size_t s : subjects) x.push_back(d.delta[s][c]);
      cs.d = describe(x, d.offset);
      r.cells.push_back(std::move(cs));
    }
  return r;
}

}  // namespace dtlab::stats

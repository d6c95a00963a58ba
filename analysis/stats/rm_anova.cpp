// Repeated-measures and mixed ANOVA; see rm_anova.h for the method. One
// stratum per within term: its residual is formed in double-double from the
// subject x cell deltas (exact when the data are), its sums of squares and
// products give the error SS, the sphericity statistics and Mauchly's test;
// each between term's SS comes from the multivariate regression.
#include "analysis/stats/rm_anova.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <tuple>

#include "analysis/stats/csv.h"
#include "analysis/stats/detail/dd.h"
#include "analysis/stats/detail/design.h"
#include "analysis/stats/detail/linalg.h"
#include "analysis/stats/detail/numbers.h"
#include "analysis/stats/detail/sum.h"
#include "analysis/stats/distributions.h"
#include "analysis/stats/effect_size.h"

namespace dtlab::stats {
namespace {

using detail::CellDesign;
using detail::DD;
using detail::Matrix;

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

// The between-subject groups that survive listwise deletion, renumbered.
struct Groups {
  std::vector<size_t> levels;                     // per between factor
  std::vector<std::vector<std::string>> labels;   // per between factor
  std::vector<std::vector<size_t>> of;            // of[s][f]: level of subject s
  std::vector<size_t> id;                         // id[s]: index of the subject's between cell
  size_t count = 0;                               // between cells
};

Result<Groups> surviving_groups(const CellDesign& d, const std::string& source) {
  const size_t N = d.subjects.size(), nb = d.between_names.size();
  Groups g;
  g.levels.resize(nb);
  g.labels.resize(nb);
  g.of.assign(N, std::vector<size_t>(nb));
  for (size_t f = 0; f < nb; ++f) {
    std::map<size_t, size_t> remap;
    for (size_t s = 0; s < N; ++s) {
      auto [it, ins] = remap.emplace(d.group[s][f], remap.size());
      if (ins) g.labels[f].push_back(d.between_levels[f][d.group[s][f]]);
      g.of[s][f] = it->second;
    }
    g.levels[f] = remap.size();
  }
  std::map<std::vector<size_t>, size_t> cell;
  for (const auto& o : g.of) g.id.push_back(cell.emplace(o, cell.size()).first->second);
  g.count = cell.size();
  size_t expected = 1;
  for (size_t L : g.levels) expected *= L;
  if (g.count < expected)
    return Error{source, 0, 0, "", "some combination of the between-subject factors has no subject (after listwise "
                                   "deletion): the full-factorial between design cannot be estimated"};
  return g;
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

std::vector<size_t> all_indices(size_t n) {
  std::vector<size_t> v(n);
  for (size_t i = 0; i < n; ++i) v[i] = i;
  return v;
}

// The residual of within term S in cell space, Y_res P_S, in double-double:
// Y minus its between-cell means (the full-factorial between model), then for
// every within factor the deviation from the mean over its levels (factor in
// S) or that mean itself (factor not in S). P_S is the projection onto the
// contrasts M_S, so U M_S' equals the residual of Z = Y M_S'.
Matrix stratum_residual(const Matrix& Y, const Groups& g, const CellDesign& d, const std::vector<size_t>& S) {
  const size_t N = Y.rows, C = Y.cols;
  std::vector<DD> u(N * C);
  std::vector<DD> sum(g.count * C);
  std::vector<double> members(g.count, 0.0);
  for (size_t s = 0; s < N; ++s) {
    members[g.id[s]] += 1.0;
    for (size_t c = 0; c < C; ++c) sum[g.id[s] * C + c] = sum[g.id[s] * C + c] + DD(Y(s, c));
  }
  for (size_t s = 0; s < N; ++s)
    for (size_t c = 0; c < C; ++c) u[s * C + c] = DD(Y(s, c)) - detail::divide(sum[g.id[s] * C + c], members[g.id[s]]);
  size_t stride = C;
  for (size_t f = 0; f < d.within_levels.size(); ++f) {
    const size_t L = d.within_levels[f].size();
    stride /= L;
    const bool centre = contains(S, f);
    for (size_t s = 0; s < N; ++s)
      for (size_t base = 0; base < C; ++base) {
        if ((base / stride) % L != 0) continue;  // one line along factor f per base
        DD mean;
        for (size_t l = 0; l < L; ++l) mean = mean + u[s * C + base + l * stride];
        mean = detail::divide(mean, static_cast<double>(L));
        for (size_t l = 0; l < L; ++l) {
          DD& x = u[s * C + base + l * stride];
          x = centre ? x - mean : mean;
        }
      }
  }
  Matrix out(N, C);
  for (size_t i = 0; i < N * C; ++i) out.a[i] = u[i].value();
  return out;
}

// car's Mauchly test from the residual contrast scores R (E = R'R): {W, p}.
std::pair<double, double> mauchly(const Matrix& R, double tr, double n, size_t cells) {
  const double pp = static_cast<double>(R.cols);
  if (n < pp) return {0.0, kNaN};
  const double log_w = detail::gram_log_det(R) - pp * std::log(tr / pp);
  const double w = std::exp(log_w);
  const double rho = 1.0 - (2.0 * pp * pp + pp + 2.0) / (6.0 * pp * n);
  const double w2 = (pp + 2.0) * (pp - 1.0) * (pp - 2.0) *
                    (2.0 * pp * pp * pp + 6.0 * pp * pp + 3.0 * static_cast<double>(cells) + 2.0) /
                    (288.0 * (n * pp * rho) * (n * pp * rho));
  const double z = -n * rho * log_w;
  const double f = pp * (pp + 1.0) / 2.0 - 1.0;
  const double pr1 = chi_squared_upper(z, f).p;
  const double pr2 = chi_squared_upper(z, f + 4.0).p;
  return {w, std::min(1.0, std::max(0.0, pr1 + w2 * (pr2 - pr1)))};
}

// One within term's stratum: contrast scores, residual, error SS, sphericity.
struct Stratum {
  std::vector<size_t> S;
  size_t p = 0;            // contrasts of the term (rows of M_S)
  Matrix Z;                // N x p transformed data Y M_S'
  double ss_error = 0;     // scaled units
  bool zero_error = false;
  double gg = 1, hf = 1, mauchly_W = kNaN, mauchly_p = kNaN;
};

// Which factors M_S contrasts (the others it averages), and the levels of all.
std::vector<bool> in_term(const std::vector<size_t>& S, size_t factors) {
  std::vector<bool> in(factors, false);
  for (size_t f : S) in[f] = true;
  return in;
}

size_t contrast_count(const std::vector<size_t>& S, const CellDesign& d) {
  size_t p = 1;
  for (size_t f : S) p *= d.within_levels[f].size() - 1;
  return p;
}

Stratum within_stratum(const std::vector<size_t>& S, const Matrix& Y, const Groups& g, const CellDesign& d, double dfe,
                       double zero_threshold) {
  Stratum st;
  st.S = S;
  st.p = contrast_count(S, d);
  const size_t p = st.p;
  if (p == 0) return st;
  std::vector<size_t> levels;
  for (const auto& lv : d.within_levels) levels.push_back(lv.size());
  const std::vector<bool> in = in_term(S, levels.size());
  st.Z = detail::contrast_scores(Y, levels, in);
  const Matrix R = detail::contrast_scores(stratum_residual(Y, g, d, S), levels, in);
  st.ss_error = detail::sum_of_squares(R);
  st.zero_error = dfe > 0 && st.ss_error <= zero_threshold;
  if (st.zero_error) st.ss_error = 0.0;
  if (S.empty()) {
    st.gg = st.hf = kNaN;
  } else if (p >= 2) {
    if (st.zero_error || dfe <= 0) {
      st.gg = st.hf = kNaN;
    } else {
      const double pd = static_cast<double>(p);
      if (dfe == 1) {  // E has rank 1: GG = 1/p exactly and the HF formula is 0/0
        st.gg = 1.0 / pd;
        st.hf = kNaN;
      } else {
        st.gg = st.ss_error * st.ss_error / (pd * detail::gram_square_trace(R));
        st.hf = ((dfe + 1.0) * pd * st.gg - 2.0) / (pd * (dfe - pd * st.gg));
      }
      std::tie(st.mauchly_W, st.mauchly_p) = mauchly(R, st.ss_error, dfe, d.cells);
    }
  }
  return st;
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

// Sphericity fields of a within effect from its stratum.
void set_sphericity(Effect& e, const Stratum& st) {
  e.gg_epsilon = st.gg;
  e.hf_epsilon = st.hf;
  e.mauchly_W = st.mauchly_W;
  e.mauchly_p = st.mauchly_p;
  if (st.p == 1 || st.zero_error) {
    e.p_gg = e.p_hf = e.p;
    e.log10_p_gg = e.log10_p_hf = e.log10_p;
    return;
  }
  const Tail tg = f_upper(e.F, e.df1 * st.gg, e.df2 * st.gg);
  e.p_gg = tg.p;
  e.log10_p_gg = tg.log10_p;
  const double h = std::isnan(st.hf) ? kNaN : std::min(1.0, st.hf);
  const Tail th = h > 0 ? f_upper(e.F, e.df1 * h, e.df2 * h) : Tail{kNaN, kNaN};
  e.p_hf = th.p;
  e.log10_p_hf = th.log10_p;
}

std::string term_name(const std::vector<size_t>& T, const std::vector<size_t>& S, const CellDesign& d) {
  std::string name;
  for (size_t f : T) name += (name.empty() ? "" : ":") + d.between_names[f];
  for (size_t f : S) name += (name.empty() ? "" : ":") + d.within_names[f];
  return name;
}

// An effect that is recorded with its stratum and factors (for generalized eta squared).
struct Pending {
  Effect e;
  size_t stratum;
  std::vector<size_t> factors_between, factors_within;
};

// What every stratum's effects share: the between design, its inverse cross
// product, X' and the error df.
struct Regression {
  const BetweenDesign& bd;
  const Matrix& V;
  const Matrix& Xt;
  double dfe;
};

// The rows of within term st.S crossed with every between term (type III
// multivariate SS), in the scaled units of the deltas (F and the effect sizes
// do not depend on the scale; unscale() converts SS and MSE afterwards).
// Error: a singular between term.
Status stratum_effects(const Stratum& st, const Regression& reg, const CellDesign& d, size_t stratum,
                       std::vector<Pending>& pending) {
  const size_t p = st.p;
  Matrix B = detail::multiply(reg.V, detail::multiply(reg.Xt, st.Z));
  const Matrix fit = detail::multiply(reg.bd.X, B);  // one step of iterative refinement of B
  Matrix res = st.Z;
  for (size_t i = 0; i < res.a.size(); ++i) res.a[i] -= fit.a[i];
  const Matrix dB = detail::multiply(reg.V, detail::multiply(reg.Xt, res));
  for (size_t i = 0; i < B.a.size(); ++i) B.a[i] += dB.a[i];
  for (size_t ti = 0; ti < reg.bd.terms.size(); ++ti) {
    const auto& T = reg.bd.terms[ti];
    if ((st.S.empty() && T.empty()) || reg.bd.df[ti] == 0) continue;  // no intercept row (afex intercept = FALSE)
    Effect e;
    e.name = term_name(T, st.S, d);
    e.within = !st.S.empty();
    const Matrix Bt = submatrix(B, reg.bd.columns[ti], all_indices(p));
    const auto Vinv = detail::spd_inverse(submatrix(reg.V, reg.bd.columns[ti], reg.bd.columns[ti]));
    if (!Vinv) return Error{"", 0, 0, "", "singular between-subjects term " + e.name};
    e.ss = detail::trace(detail::multiply(detail::transpose(Bt), detail::multiply(*Vinv, Bt)));
    e.ss_error = st.ss_error;
    e.df1 = static_cast<double>(reg.bd.df[ti] * p);
    e.df2 = std::max(0.0, reg.dfe) * static_cast<double>(p);
    set_test(e, st.zero_error);
    e.eta_p2 = (e.ss + e.ss_error) > 0 ? e.ss / (e.ss + e.ss_error) : kNaN;
    if (e.within) {
      set_sphericity(e, st);
    } else {
      e.gg_epsilon = e.hf_epsilon = e.mauchly_W = e.mauchly_p = kNaN;
      e.p_gg = e.log10_p_gg = e.p_hf = e.log10_p_hf = kNaN;
    }
    pending.push_back({e, stratum, T, st.S});
  }
  return {};
}

// SS, SS_error and MSE back in the data's units (times 2^(2 exponent)), the
// derived columns, and whether a sum of squares underflowed (printed as a
// subnormal or 0 while F and the effect sizes, computed scaled, stay exact).
// false: a sum of squares overflowed.
bool unscale(std::vector<Pending>& pending, int exponent, bool& underflow) {
  for (auto& pe : pending) {
    Effect& e = pe.e;
    const double ss = e.ss, ss_error = e.ss_error;
    e.ss = std::ldexp(ss, 2 * exponent);
    e.ss_error = std::ldexp(ss_error, 2 * exponent);
    if (!std::isfinite(e.ss) || !std::isfinite(e.ss_error)) return false;
    underflow = underflow || (ss > 0 && e.ss < std::numeric_limits<double>::min()) ||
                (ss_error > 0 && e.ss_error < std::numeric_limits<double>::min());
    complete_effect(e);
  }
  return true;
}

// Generalized eta squared (afex): distinct error SS of all strata, plus observed effects.
Status generalized_eta(std::vector<Pending>& pending, const std::vector<double>& stratum_error, const CellDesign& d,
                       const std::vector<std::string>& observed, const std::string& source) {
  for (const auto& o : observed)
    if (std::find(d.between_names.begin(), d.between_names.end(), o) == d.between_names.end() &&
        std::find(d.within_names.begin(), d.within_names.end(), o) == d.within_names.end())
      return Error{source, 0, 0, o, "observed factor is not a factor of the design"};
  std::vector<double> distinct;
  for (double v : stratum_error)
    if (std::find(distinct.begin(), distinct.end(), v) == distinct.end()) distinct.push_back(v);
  detail::Sum err_sum;
  for (double v : distinct) err_sum.add(v);
  auto is_observed = [&](const Pending& pe) {
    for (const auto& o : observed) {
      for (size_t f : pe.factors_between)
        if (d.between_names[f] == o) return true;
      for (size_t f : pe.factors_within)
        if (d.within_names[f] == o) return true;
    }
    return false;
  };
  double obs_ss = 0.0;
  for (const auto& pe : pending)
    if (is_observed(pe)) obs_ss += pe.e.ss;
  for (auto& pe : pending) {
    const double denom = pe.e.ss + err_sum.value() + obs_ss - (is_observed(pe) ? pe.e.ss : 0.0);
    pe.e.eta_g2 = denom > 0 ? pe.e.ss / denom : kNaN;
  }
  return {};
}

// Descriptives of the subjects' cell means, per between group and within cell.
std::vector<CellSummary> cell_summaries(const CellDesign& d, const Groups& g) {
  std::vector<CellSummary> out;
  std::map<std::vector<size_t>, std::vector<size_t>> members;
  for (size_t s = 0; s < d.subjects.size(); ++s) members[g.of[s]].push_back(s);
  for (const auto& [grp, subjects] : members)
    for (size_t c = 0; c < d.cells; ++c) {
      CellSummary cs;
      for (size_t f = 0; f < d.between_names.size(); ++f) cs.levels.emplace_back(d.between_names[f], g.labels[f][grp[f]]);
      const auto lv = d.cell_levels(c);
      for (size_t f = 0; f < d.within_names.size(); ++f) cs.levels.emplace_back(d.within_names[f], d.within_levels[f][lv[f]]);
      std::vector<double> x;
      for (size_t s : subjects) x.push_back(d.delta[s][c]);
      cs.d = describe(x, d.offset);
      out.push_back(std::move(cs));
    }
  return out;
}

Status check_size(const CellDesign& d, const std::string& source) {
  std::vector<size_t> levels;
  for (const auto& lv : d.within_levels) levels.push_back(lv.size());
  const double work = rm_anova_work(d.subjects.size(), levels);
  if (work <= kRmAnovaWorkBound) return {};
  const double N = static_cast<double>(d.subjects.size());
  double worst = 0;
  std::vector<size_t> worst_term;
  for (const auto& S : terms(levels.size())) {
    const double p = static_cast<double>(contrast_count(S, d));
    if (N * p * std::min(N, p) > worst) worst = N * p * std::min(N, p), worst_term = S;
  }
  char text[96];
  std::snprintf(text, sizeof text, "%.2g", work);
  return Error{source, 0, 0, "",
               "design too large for rm-anova: " + std::to_string(d.subjects.size()) + " subjects and " +
                   std::to_string(contrast_count(worst_term, d)) + " contrasts in the within term " +
                   term_name({}, worst_term, d) + " need about " + text +
                   " multiply-adds for the sphericity statistics (N x p x min(N, p) summed over the within terms), "
                   "above the bound of 4e9 (about ten seconds of CPU); average levels into fewer (e.g. --where or "
                   "--aggregate on a coarser factor) or analyse subsets"};
}

Error overflow_error(const std::string& source, const std::string& dv, const char* what) {
  return Error{source, 0, 0, name_for_message(dv),
               std::string("overflow: ") + what +
                   " exceed the largest double (about 1.8e308), so F and p cannot be computed; divide the "
                   "column by a power of ten (e.g. 1e300) and run again"};
}

}  // namespace

double rm_anova_work(size_t subjects, const std::vector<size_t>& within_levels) {
  const double N = static_cast<double>(subjects);
  double work = 0;
  for (const auto& S : terms(within_levels.size())) {
    double p = 1;
    for (size_t f : S) p *= static_cast<double>(within_levels[f]) - 1;
    work += N * p * std::min(N, p);
  }
  return work;
}

Result<RmAnovaResult> rm_anova(const LongData& data, const RmAnovaOptions& options) {
  auto built = detail::build_cell_design(data);
  if (!built) return built.error();
  const CellDesign& d = *built;

  RmAnovaResult r;
  r.within = d.within_names;
  r.between = d.between_names;
  r.dropped_subjects = d.dropped;
  r.warnings = d.warnings;
  const size_t N = d.subjects.size(), C = d.cells;
  r.n_subjects = N;
  if (N == 0) return Error{data.source, 0, 0, "", "no subject has every cell: nothing left after listwise deletion"};
  auto groups = surviving_groups(d, data.source);
  if (!groups) return groups.error();
  const Groups& g = *groups;
  for (size_t f = 0; f < g.levels.size(); ++f)
    if (g.levels[f] < 2) r.warnings.push_back("between factor '" + d.between_names[f] + "' has one level: its effects are not tested");
  for (size_t f = 0; f < d.within_names.size(); ++f)
    if (d.within_levels[f].size() < 2) r.warnings.push_back("within factor '" + d.within_names[f] + "' has one level: its effects are not tested");
  if (N == 1) r.warnings.push_back("one subject: no error degrees of freedom, F and p are undefined");

  const BetweenDesign bd = between_design(g.of, g.levels);
  const auto V = detail::spd_inverse(detail::crossprod(bd.X));
  if (!V) return Error{data.source, 0, 0, "", "the between-subjects design matrix is singular"};
  const Matrix Xt = detail::transpose(bd.X);
  const double dfe = static_cast<double>(N) - static_cast<double>(bd.X.cols);
  if (N > 1 && dfe == 0) r.warnings.push_back("as many subjects as between-subject cells: no error degrees of freedom");
  if (auto s = check_size(d, data.source); !s) return s.error();

  // Deltas scaled by a power of two (exact) so that no square over- or underflows.
  double largest = 0;
  for (size_t s = 0; s < N; ++s)
    for (size_t c = 0; c < C; ++c) largest = std::max(largest, std::fabs(d.delta[s][c]));
  if (!std::isfinite(largest)) return overflow_error(data.source, data.dv_name, "differences between the values");
  int exponent = 0;
  if (largest > 0) std::frexp(largest, &exponent);
  Matrix Y(N, C);
  detail::Sum sumsq, noise2;
  for (size_t s = 0; s < N; ++s)
    for (size_t c = 0; c < C; ++c) {
      Y(s, c) = std::ldexp(d.delta[s][c], -exponent);
      const double n = std::ldexp(d.noise[s][c], -exponent);
      sumsq.add(Y(s, c) * Y(s, c));
      noise2.add(n * n);
    }
  // Zero error SS: at most twice the rounding error of the data in norm (0 for
  // exact data), or the double-double floor of the residual.
  const double zero_threshold = 4.0 * noise2.value() + 1e-60 * sumsq.value();

  std::vector<Pending> pending;
  std::vector<double> stratum_error;  // scaled, as the pending effects
  for (const auto& S : terms(d.within_names.size())) {
    const Stratum st = within_stratum(S, Y, g, d, dfe, zero_threshold);
    if (st.p == 0) continue;
    stratum_error.push_back(st.ss_error);
    if (st.zero_error)
      r.warnings.push_back(std::string("zero error variance in stratum ") + (S.empty() ? "between subjects" : "of the within term") +
                           ": F is infinite (or 0/0) there");
    if (auto added = stratum_effects(st, {bd, *V, Xt, dfe}, d, stratum_error.size() - 1, pending); !added)
      return Error{data.source, 0, 0, "", added.error().message};
  }
  if (auto s = generalized_eta(pending, stratum_error, d, options.observed, data.source); !s) return s.error();
  bool underflow = false;
  if (!unscale(pending, exponent, underflow)) return overflow_error(data.source, data.dv_name, "the sums of squares");
  if (underflow)
    r.warnings.push_back(underflow_warning());
  for (const auto& pe : pending) r.effects.push_back(pe.e);
  r.cells = cell_summaries(d, g);
  return r;
}

}  // namespace dtlab::stats

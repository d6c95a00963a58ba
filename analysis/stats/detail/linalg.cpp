// Dense matrix helpers; see linalg.h.
#include "analysis/stats/detail/linalg.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "analysis/stats/detail/dd.h"
#include "analysis/stats/detail/sum.h"

namespace dtlab::stats::detail {

Matrix transpose(const Matrix& m) {
  Matrix t(m.cols, m.rows);
  for (size_t r = 0; r < m.rows; ++r)
    for (size_t c = 0; c < m.cols; ++c) t(c, r) = m(r, c);
  return t;
}

Matrix multiply(const Matrix& x, const Matrix& y) {
  assert(x.cols == y.rows && "multiply: inner dimensions differ");
  Matrix p(x.rows, y.cols);
  for (size_t r = 0; r < x.rows; ++r)
    for (size_t c = 0; c < y.cols; ++c) {
      Sum s;
      for (size_t k = 0; k < x.cols; ++k) s.add(x(r, k) * y(k, c));
      p(r, c) = s.value();
    }
  return p;
}

Matrix crossprod(const Matrix& x) {
  const Matrix t = transpose(x);  // columns of x as contiguous rows
  Matrix p(x.cols, x.cols);
  for (size_t i = 0; i < x.cols; ++i)
    for (size_t j = 0; j <= i; ++j) {
      const double* a = &t.a[i * t.cols];
      const double* b = &t.a[j * t.cols];
      Sum s;
      for (size_t r = 0; r < t.cols; ++r) s.add(a[r] * b[r]);
      p(i, j) = p(j, i) = s.value();
    }
  return p;
}

double trace(const Matrix& m) {
  Sum s;
  for (size_t i = 0; i < std::min(m.rows, m.cols); ++i) s.add(m(i, i));
  return s.value();
}

Matrix contrast_scores(const Matrix& y, const std::vector<size_t>& levels, const std::vector<bool>& contrast) {
  assert(levels.size() == contrast.size() && "contrast_scores: one flag per factor");
  // x holds, per row of y, the tensor (done, L_f, rest): factors before f already
  // transformed (their output sizes multiply to `done`), f and those after not yet.
  std::vector<double> x = y.a;
  size_t rest = y.cols, done = 1;
  for (size_t f = 0; f < levels.size(); ++f) {
    const size_t L = levels[f];
    rest /= L;
    const size_t out = contrast[f] ? L - 1 : 1, in_row = done * L * rest, out_row = done * out * rest;
    std::vector<double> z(y.rows * out_row);
    for (size_t s = 0; s < y.rows; ++s)
      for (size_t a = 0; a < done; ++a)
        for (size_t r = 0; r < rest; ++r) {
          const double* in = &x[s * in_row + a * L * rest + r];  // level l at in[l * rest]
          double* o = &z[s * out_row + a * out * rest + r];      // output j at o[j * rest]
          DD prefix(in[0]);
          for (size_t j = 0; j + 1 < L; ++j) {  // prefix = sum of levels 0..j
            const double k = static_cast<double>(j + 1), v = in[(j + 1) * rest];
            if (contrast[f]) {
              const double hi = k * v;
              const DD scaled(hi, std::fma(k, v, -hi));  // k v exactly
              o[j * rest] = (scaled - prefix).value() / std::sqrt(k * (k + 1.0));
            }
            prefix = prefix + DD(v);
          }
          if (!contrast[f]) o[0] = prefix.value() / std::sqrt(static_cast<double>(L));
        }
    x = std::move(z);
    done *= out;
  }
  Matrix m(y.rows, done);
  m.a = std::move(x);
  return m;
}

double sum_of_squares(const Matrix& r) {
  Sum s;
  for (double v : r.a) s.add(v * v);
  return s.value();
}

double gram_square_trace(const Matrix& r) {
  Sum s;
  if (r.rows <= r.cols) {  // r r' (rows x rows): one pass over pairs of rows
    for (size_t i = 0; i < r.rows; ++i)
      for (size_t j = 0; j <= i; ++j) {
        Sum dot;
        for (size_t c = 0; c < r.cols; ++c) dot.add(r(i, c) * r(j, c));
        const double g = dot.value();
        s.add((i == j ? 1.0 : 2.0) * g * g);
      }
    return s.value();
  }
  const Matrix e = crossprod(r);
  for (double v : e.a) s.add(v * v);
  return s.value();
}

namespace {

// Cholesky factor L (lower) of m; false if a pivot is not positive beyond tolerance.
bool cholesky(const Matrix& m, Matrix& l) {
  const size_t n = m.rows;
  l = Matrix(n, n);
  double maxdiag = 0.0;
  for (size_t i = 0; i < n; ++i) maxdiag = std::max(maxdiag, std::fabs(m(i, i)));
  const double tol = 1e-12 * maxdiag;
  for (size_t j = 0; j < n; ++j) {
    double d = m(j, j);
    for (size_t k = 0; k < j; ++k) d -= l(j, k) * l(j, k);
    if (!(d > tol)) return false;
    l(j, j) = std::sqrt(d);
    for (size_t i = j + 1; i < n; ++i) {
      double s = m(i, j);
      for (size_t k = 0; k < j; ++k) s -= l(i, k) * l(j, k);
      l(i, j) = s / l(j, j);
    }
  }
  return true;
}

}  // namespace

std::optional<Matrix> spd_inverse(const Matrix& m) {
  assert(m.rows == m.cols && "spd_inverse: matrix must be square");
  Matrix l;
  if (!cholesky(m, l)) return std::nullopt;
  const size_t n = m.rows;
  Matrix inv(n, n);
  for (size_t col = 0; col < n; ++col) {
    std::vector<double> y(n, 0.0);
    for (size_t i = 0; i < n; ++i) {  // L y = e_col
      double s = i == col ? 1.0 : 0.0;
      for (size_t k = 0; k < i; ++k) s -= l(i, k) * y[k];
      y[i] = s / l(i, i);
    }
    for (size_t ii = n; ii-- > 0;) {  // L^T x = y
      double s = y[ii];
      for (size_t k = ii + 1; k < n; ++k) s -= l(k, ii) * inv(k, col);
      inv(ii, col) = s / l(ii, ii);
    }
  }
  return inv;
}

double gram_log_det(const Matrix& r) {
  assert(r.rows >= r.cols && "gram_log_det: needs at least as many rows as columns");
  Matrix a = transpose(r);  // column j of r is row j of a (contiguous)
  const size_t n = r.rows;
  double log_det = 0.0;
  std::vector<double> v;
  for (size_t j = 0; j < a.rows; ++j) {
    // Householder reflection zeroing r(j+1.., j); the new r(j, j) is -+ the column norm.
    const double* col = &a.a[j * n];
    double scale = 0.0;
    for (size_t i = j; i < n; ++i) scale = std::max(scale, std::fabs(col[i]));
    if (scale == 0.0) return -std::numeric_limits<double>::infinity();
    Sum ss;
    for (size_t i = j; i < n; ++i) ss.add((col[i] / scale) * (col[i] / scale));
    const double norm = scale * std::sqrt(ss.value());
    const double alpha = col[j] > 0 ? -norm : norm;
    log_det += 2.0 * std::log(norm);
    v.assign(col + j, col + n);
    v[0] -= alpha;
    Sum vv;
    for (double x : v) vv.add(x * x);
    if (vv.value() == 0.0) continue;
    for (size_t c = j + 1; c < a.rows; ++c) {
      double* other = &a.a[c * n];
      Sum dot;
      for (size_t i = j; i < n; ++i) dot.add(v[i - j] * other[i]);
      const double f = 2.0 * dot.value() / vv.value();
      for (size_t i = j; i < n; ++i) other[i] -= f * v[i - j];
    }
  }
  return log_det;
}

}  // namespace dtlab::stats::detail

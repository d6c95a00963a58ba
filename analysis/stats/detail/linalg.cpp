// Dense matrix helpers; see linalg.h.
#include "analysis/stats/detail/linalg.h"

#include <algorithm>
#include <cmath>
#include <limits>

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

Matrix kronecker(const Matrix& x, const Matrix& y) {
  Matrix k(x.rows * y.rows, x.cols * y.cols);
  for (size_t a = 0; a < x.rows; ++a)
    for (size_t b = 0; b < x.cols; ++b)
      for (size_t c = 0; c < y.rows; ++c)
        for (size_t d = 0; d < y.cols; ++d) k(a * y.rows + c, b * y.cols + d) = x(a, b) * y(c, d);
  return k;
}

Matrix crossprod(const Matrix& x) {
  Matrix p(x.cols, x.cols);
  for (size_t i = 0; i < x.cols; ++i)
    for (size_t j = 0; j <= i; ++j) {
      Sum s;
      for (size_t r = 0; r < x.rows; ++r) s.add(x(r, i) * x(r, j));
      p(i, j) = p(j, i) = s.value();
    }
  return p;
}

double trace(const Matrix& m) {
  Sum s;
  for (size_t i = 0; i < std::min(m.rows, m.cols); ++i) s.add(m(i, i));
  return s.value();
}

Matrix orthonormal_contrasts(size_t levels) {
  // Row j (0-based) contrasts level j+1 with the mean of levels 0..j.
  Matrix h(levels > 0 ? levels - 1 : 0, levels);
  for (size_t j = 0; j + 1 < levels; ++j) {
    const double k = static_cast<double>(j + 1);
    const double norm = std::sqrt(k * (k + 1.0));
    for (size_t i = 0; i <= j; ++i) h(j, i) = -1.0 / norm;
    h(j, j + 1) = k / norm;
  }
  return h;
}

Matrix normalized_mean_row(size_t levels) {
  return Matrix(1, levels, 1.0 / std::sqrt(static_cast<double>(levels)));
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
  Matrix a = r;
  double log_det = 0.0;
  for (size_t j = 0; j < a.cols; ++j) {
    // Householder reflection zeroing a(j+1.., j); the new a(j, j) is -+ the column norm.
    double scale = 0.0;
    for (size_t i = j; i < a.rows; ++i) scale = std::max(scale, std::fabs(a(i, j)));
    if (scale == 0.0) return -std::numeric_limits<double>::infinity();
    Sum ss;
    for (size_t i = j; i < a.rows; ++i) ss.add((a(i, j) / scale) * (a(i, j) / scale));
    const double norm = scale * std::sqrt(ss.value());
    const double alpha = a(j, j) > 0 ? -norm : norm;
    log_det += 2.0 * std::log(norm);
    std::vector<double> v(a.rows - j);
    for (size_t i = j; i < a.rows; ++i) v[i - j] = a(i, j);
    v[0] -= alpha;
    Sum vv;
    for (double x : v) vv.add(x * x);
    if (vv.value() == 0.0) continue;
    for (size_t c = j + 1; c < a.cols; ++c) {
      Sum dot;
      for (size_t i = j; i < a.rows; ++i) dot.add(v[i - j] * a(i, c));
      const double f = 2.0 * dot.value() / vv.value();
      for (size_t i = j; i < a.rows; ++i) a(i, c) -= f * v[i - j];
    }
  }
  return log_det;
}

}  // namespace dtlab::stats::detail

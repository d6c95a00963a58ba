// Small dense matrices for the repeated-measures ANOVA (contrast matrices,
// sums of squares and products, the between-subjects normal equations). Row
// major, sizes checked by assert. Only what the ANOVA needs: products, the
// symmetric positive-definite inverse by Cholesky, and the log-determinant of
// a Gram matrix R'R from a Householder QR of R (no cut-off: a nearly singular
// R'R keeps its tiny determinant to about eps / smallest singular value).
#pragma once
#include <cassert>
#include <cstddef>
#include <optional>
#include <vector>

namespace dtlab::stats::detail {

struct Matrix {
  size_t rows = 0, cols = 0;
  std::vector<double> a;

  Matrix() = default;
  Matrix(size_t r, size_t c, double fill = 0.0) : rows(r), cols(c), a(r * c, fill) {}
  double& operator()(size_t r, size_t c) { assert(r < rows && c < cols && "Matrix index out of range"); return a[r * cols + c]; }
  double operator()(size_t r, size_t c) const { assert(r < rows && c < cols && "Matrix index out of range"); return a[r * cols + c]; }
};

Matrix transpose(const Matrix& m);
Matrix multiply(const Matrix& x, const Matrix& y);  // x.cols == y.rows
Matrix kronecker(const Matrix& x, const Matrix& y);
Matrix crossprod(const Matrix& x);                  // x^T x, accumulated with compensated sums
double trace(const Matrix& m);

// Orthonormal contrasts for a factor with `levels` levels: (levels-1) x levels,
// rows orthonormal and orthogonal to the constant vector (normalized Helmert).
Matrix orthonormal_contrasts(size_t levels);
// 1 x levels row of 1/sqrt(levels): the normalized mean over a factor.
Matrix normalized_mean_row(size_t levels);

// Inverse of a symmetric positive-definite matrix; nullopt if it is not
// (numerically) positive definite.
std::optional<Matrix> spd_inverse(const Matrix& m);
// log det(r' r) for r with rows >= cols, as 2 sum log |R_jj| of r's
// Householder QR; -inf only when r has exactly dependent columns (a zero R_jj).
double gram_log_det(const Matrix& r);

}  // namespace dtlab::stats::detail

// Small dense matrices for the repeated-measures ANOVA (contrast scores,
// sums of squares and products, the between-subjects normal equations). Row
// major, sizes checked by assert. Only what the ANOVA needs: products, the
// contrast scores Y M' of a Kronecker product of per-factor contrasts applied
// factor by factor (never forming M: O(N C factors), so 3000 levels cost what
// 3000 cells do), traces of R'R and (R'R)^2 through the smaller Gram matrix,
// the symmetric positive-definite inverse by Cholesky, and the log-determinant
// of a Gram matrix R'R from a Householder QR of R (no cut-off: a nearly
// singular R'R keeps its tiny determinant to about eps / smallest singular value).
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

// Y M' for the cells of Y (N x C, C = prod levels, last factor fastest) and
// M = kron over factors f of H_f (levels-1 rows: orthonormal Helmert
// contrasts, row j contrasting level j+1 with the mean of levels 0..j) where
// contrast[f], else of the 1 x levels row 1/sqrt(levels) (the normalized
// mean). Columns in Kronecker order (first factor slowest). Each score is
// formed in double-double and rounded once.
Matrix contrast_scores(const Matrix& y, const std::vector<size_t>& levels, const std::vector<bool>& contrast);

// tr(r' r): the sum of squares of r's entries (compensated).
double sum_of_squares(const Matrix& r);
// tr((r' r)^2) = tr((r r')^2), through the smaller of the two Gram matrices:
// O(min(rows, cols)^2 max(rows, cols)).
double gram_square_trace(const Matrix& r);

// Inverse of a symmetric positive-definite matrix; nullopt if it is not
// (numerically) positive definite.
std::optional<Matrix> spd_inverse(const Matrix& m);
// log det(r' r) for r with rows >= cols, as 2 sum log |R_jj| of r's
// Householder QR; -inf only when r has exactly dependent columns (a zero R_jj).
double gram_log_det(const Matrix& r);

}  // namespace dtlab::stats::detail

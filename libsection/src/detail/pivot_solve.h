// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// A 3 x 3 linear solve with full pivoting, the arithmetic of Eigen's
// FullPivLU<Matrix3d>::solve step for step on fixed storage: Eigen runs its 3 x 3 case
// through dynamic-size blocks and triangular-solve kernels, five times the work, and the
// inscribed-circle Newton (solve_circle) solves ~10^5 such systems per 20 sections.
#include <Eigen/Core>

#include <cmath>
#include <limits>
#include <utility>

namespace section::detail {

/// The x of a x = b as a.fullPivLu().solve(b) gives it, to the bit: the pivot is the first
/// largest |a_ij| in column-major order; the rank counts the pivots above Eigen's threshold
/// (|largest pivot| x 3 epsilon), the unknowns past it are 0; the triangular solves run
/// column by column and pass over a zero right-hand side, as Eigen's do.
inline Eigen::Vector3d full_pivot_solve(Eigen::Matrix3d lu, const Eigen::Vector3d& b) {
  int row_swap[3] = {0, 1, 2}, col_swap[3] = {0, 1, 2};
  int nonzero = 3;
  double max_pivot = 0;
  for (int k = 0; k < 3; ++k) {
    int pr = k, pc = k;
    double big = std::abs(lu(k, k));
    for (int j = k; j < 3; ++j)
      for (int i = j == k ? k + 1 : k; i < 3; ++i) {
        const double v = std::abs(lu(i, j));
        if (v > big) big = v, pr = i, pc = j;
      }
    if (big == 0) {
      nonzero = k;
      break;
    }
    if (big > max_pivot) max_pivot = big;
    row_swap[k] = pr, col_swap[k] = pc;
    if (pr != k) lu.row(k).swap(lu.row(pr));
    if (pc != k) lu.col(k).swap(lu.col(pc));
    for (int i = k + 1; i < 3; ++i) lu(i, k) /= lu(k, k);
    for (int j = k + 1; j < 3; ++j)
      for (int i = k + 1; i < 3; ++i) lu(i, j) -= lu(i, k) * lu(k, j);
  }
  const double threshold = std::abs(max_pivot) * (std::numeric_limits<double>::epsilon() * 3.0);
  int rank = 0;
  for (int i = 0; i < nonzero; ++i) rank += std::abs(lu(i, i)) > threshold;
  Eigen::Vector3d x = Eigen::Vector3d::Zero();
  if (rank == 0) return x;
  Eigen::Vector3d c = b;
  for (int k = 0; k < 3; ++k) std::swap(c(k), c(row_swap[k]));
  for (int i = 0; i < 3; ++i)  // unit lower triangle
    if (c(i) != 0)
      for (int r = i + 1; r < 3; ++r) c(r) -= c(i) * lu(r, i);
  for (int i = rank - 1; i >= 0; --i)  // upper triangle of the rank's corner
    if (c(i) != 0) {
      c(i) /= lu(i, i);
      for (int r = 0; r < i; ++r) c(r) -= c(i) * lu(r, i);
    }
  int column[3] = {0, 1, 2};
  for (int k = 0; k < 3; ++k) std::swap(column[k], column[col_swap[k]]);
  for (int i = 0; i < rank; ++i) x(column[i]) = c(i);
  return x;
}

}  // namespace section::detail

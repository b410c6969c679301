// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// Sparse symmetric positive definite solves through CHOLMOD (simplicial LL'): the library's
// one door to CHOLMOD. The pattern is analysed once; each factor refills the values and
// factors them again, and a factor serves any number of solves.
#include <Eigen/Core>

#include <memory>
#include <string>
#include <vector>

namespace section::detail {

/// A solver that keeps the analysis of one matrix pattern, given in its elimination order.
class CholmodSolver {
public:
  /// P A P' of the n x n matrix A in upper form, column by column: rows[col_start[c] ..
  /// col_start[c + 1]) are the rows of column c's entries (sorted, none below the diagonal),
  /// and source[k] the place of entry k's value in the array given to factor. Row k of
  /// P A P' is row order[k] of A: right-hand sides and solutions are in A's order. The
  /// order is the caller's fill-reducing one, factored as given (no search, no postorder).
  /// Errors begin with `who`.
  CholmodSolver(int n, const std::vector<int>& col_start, const std::vector<int>& rows,
                std::vector<int> source, const std::string& who, std::vector<int> order);
  ~CholmodSolver();
  CholmodSolver(const CholmodSolver&) = delete;
  CholmodSolver& operator=(const CholmodSolver&) = delete;

  /// Factors A, its entries read from `values` at `source`. Throws section::Error when A is
  /// not positive definite.
  void factor(const double* values);

  /// Solves A x = rhs (two right-hand sides) with the last factor.
  void solve(const Eigen::MatrixX2d& rhs, Eigen::MatrixX2d& x);

private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace section::detail

// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// Sparse symmetric positive definite solves through CHOLMOD (simplicial LL'): the library's
// one door to CHOLMOD. The pattern is analysed once; each solve refills the values and
// factors them again (smooth: one solve per outer iteration on the same pattern).
#include <Eigen/Core>

#include <memory>
#include <string>
#include <vector>

namespace section::detail {

/// A solver that keeps the analysis (ordering, permuted pattern) of one matrix pattern.
class CholmodSolver {
public:
  /// The n x n matrix's pattern, column by column: rows[col_start[c] .. col_start[c + 1])
  /// are the rows of column c's entries (both triangles, sorted), and source[k] the place
  /// of entry k's value in the array given to solve. Errors begin with `who`. `order`, when
  /// not empty, is a fill-reducing order the caller knows (row `order[k]` eliminated k-th);
  /// otherwise CHOLMOD's analysis picks one (AMD).
  CholmodSolver(int n, const std::vector<int>& col_start, const std::vector<int>& rows,
                std::vector<int> source, const std::string& who, const std::vector<int>& order = {});
  ~CholmodSolver();
  CholmodSolver(const CholmodSolver&) = delete;
  CholmodSolver& operator=(const CholmodSolver&) = delete;

  /// Solves A x = rhs (two right-hand sides), A's entries read from `values` at `source`.
  /// Throws section::Error when A is not positive definite.
  void solve(const double* values, const Eigen::MatrixX2d& rhs, Eigen::MatrixX2d& x);

private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace section::detail

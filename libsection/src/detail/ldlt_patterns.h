// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// Sparse LDLT factorisations of systems whose pattern repeats (the least-squares fits of
// fit_spline's rounds, and of the sections of a scan: mostly the same knot counts).
#include "detail/recent_cache.h"

#include <Eigen/Sparse>
#include <Eigen/SparseCholesky>

#include <algorithm>
#include <memory>
#include <vector>

namespace section::detail {

using Ldlt = Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>>;

/// A factored as Ldlt(A) factors it, bit for bit: the analysis (the AMD ordering and the
/// elimination tree) depends on A's pattern only, so it is kept for the last 8 patterns
/// met on this thread and a matrix of one of them is only factored.
inline Ldlt& factored(const Eigen::SparseMatrix<double>& A) {
  struct Analysed {
    std::vector<int> outer, inner;  // the pattern (compressed)
    Ldlt ldlt;
  };
  thread_local std::vector<std::unique_ptr<Analysed>> recent;
  const int* outer = A.outerIndexPtr();
  const int* inner = A.innerIndexPtr();
  const std::size_t columns = static_cast<std::size_t>(A.outerSize()) + 1;
  Analysed& kept = recently_used(
      recent, 8,
      [&](const Analysed& a) {
        return a.outer.size() == columns && std::equal(a.outer.begin(), a.outer.end(), outer) &&
               std::equal(a.inner.begin(), a.inner.end(), inner);
      },
      [&](Analysed& a) {
        a.ldlt.analyzePattern(A);
        a.outer.assign(outer, outer + columns);
        a.inner.assign(inner, inner + A.nonZeros());
      });
  kept.ldlt.factorize(A);
  return kept.ldlt;
}

}  // namespace section::detail

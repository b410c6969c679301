// SPDX-License-Identifier: GPL-3.0-or-later
#include "detail/cholmod_solver.h"

#include "section/error.h"

#include <cholmod.h>

#include <algorithm>

namespace section::detail {

/// The caller gives P A P' itself (upper form), so the factorisation needs no permuted
/// transpose per call, and the analysis is that of the natural order: CHOLMOD factors P A P'
/// exactly as the permuting factorisation of A with P would, with its values refilled in
/// place per factor.
struct CholmodSolver::Impl {
  explicit Impl(std::string who) : who(std::move(who)) {
    cholmod_start(&common);
    // CHOLMOD prints its warnings with printf, on standard output: the tools' stream. A
    // failed factor throws with the caller's words instead.
    common.print = 0;
    common.final_asis = 0;
    common.supernodal = CHOLMOD_SIMPLICIAL;
    common.final_ll = 1;
    common.nmethods = 1;
    common.method[0].ordering = CHOLMOD_NATURAL;
    common.postorder = 0;  // the caller's order as given
  }
  Impl(const Impl&) = delete;
  Impl& operator=(const Impl&) = delete;
  ~Impl() {
    cholmod_free_dense(&x, &common);
    cholmod_free_dense(&y, &common);
    cholmod_free_dense(&e, &common);
    cholmod_free_dense(&rhs, &common);
    cholmod_free_factor(&factor, &common);
    cholmod_free_sparse(&pap, &common);
    cholmod_finish(&common);
  }
  void setup(int n, const std::vector<int>& col_start, const std::vector<int>& rows);

  std::string who;
  int n = 0;
  cholmod_common common;
  std::vector<int> from;  // entry of P A P' -> its value in the caller's array
  std::vector<int> perm;
  cholmod_sparse* pap = nullptr;
  cholmod_factor* factor = nullptr;
  cholmod_dense *rhs = nullptr, *x = nullptr, *y = nullptr, *e = nullptr;
};

void CholmodSolver::Impl::setup(int size, const std::vector<int>& col_start, const std::vector<int>& rows) {
  n = size;
  if (perm.size() != static_cast<std::size_t>(n) || from.size() != rows.size() ||
      col_start.size() != static_cast<std::size_t>(n) + 1 ||
      col_start.back() != static_cast<int>(rows.size()))
    throw Error(who + ": a pattern, order or source of the wrong size");
  pap = cholmod_allocate_sparse(n, n, rows.size(), 1, 1, 1, CHOLMOD_REAL, &common);
  if (!pap) throw Error(who + ": CHOLMOD could not allocate the system");
  std::copy(col_start.begin(), col_start.end(), static_cast<int*>(pap->p));
  std::copy(rows.begin(), rows.end(), static_cast<int*>(pap->i));
  factor = cholmod_analyze(pap, &common);
  if (!factor) throw Error(who + ": CHOLMOD could not analyse the system");
  if (factor->is_super || factor->xtype != CHOLMOD_PATTERN || factor->ordering != CHOLMOD_NATURAL)
    throw Error(who + ": CHOLMOD gave an unexpected analysis");
  rhs = cholmod_allocate_dense(n, 2, n, CHOLMOD_REAL, &common);
  if (!rhs) throw Error(who + ": CHOLMOD could not allocate the right-hand side");
}

CholmodSolver::CholmodSolver(int n, const std::vector<int>& col_start, const std::vector<int>& rows,
                             std::vector<int> source, const std::string& who, std::vector<int> order)
    : impl_(new Impl(who)) {
  impl_->from = std::move(source);
  impl_->perm = std::move(order);
  impl_->setup(n, col_start, rows);  // on a throw, ~Impl releases what was made
}

CholmodSolver::~CholmodSolver() = default;

void CholmodSolver::factor(const double* values) {
  Impl& s = *impl_;
  double* px = static_cast<double*>(s.pap->x);
  for (std::size_t k = 0; k < s.from.size(); ++k) px[k] = values[s.from[k]];
  double beta[2] = {0, 0};
  cholmod_factorize_p(s.pap, beta, nullptr, 0, s.factor, &s.common);
  if (s.common.status < CHOLMOD_OK || s.factor->minor != s.factor->n)
    throw Error(s.who + ": CHOLMOD could not factor the system (not positive definite?)");
}

void CholmodSolver::solve(const Eigen::MatrixX2d& b, Eigen::MatrixX2d& out) {
  Impl& s = *impl_;
  if (s.factor->xtype == CHOLMOD_PATTERN) throw Error(s.who + ": solve before factor");
  const int n = s.n;
  double* r = static_cast<double*>(s.rhs->x);
  for (int k = 0; k < n; ++k) {
    r[k] = b(s.perm[k], 0);
    r[n + k] = b(s.perm[k], 1);
  }
  if (!cholmod_solve2(CHOLMOD_A, s.factor, s.rhs, nullptr, &s.x, nullptr, &s.y, &s.e, &s.common))
    throw Error(s.who + ": CHOLMOD solve failed");
  const double* v = static_cast<const double*>(s.x->x);
  const std::size_t d = s.x->d;
  out.resize(n, 2);
  for (int k = 0; k < n; ++k) {
    out(s.perm[k], 0) = v[k];
    out(s.perm[k], 1) = v[d + k];
  }
}

}  // namespace section::detail

// SPDX-License-Identifier: GPL-3.0-or-later
#include "detail/cholmod_solver.h"

#include "section/error.h"

#include <cholmod.h>

namespace section::detail {

/// The factorisation of A with the fill-reducing permutation P first builds P A P' (a sparse
/// transpose) at every call; here P A P' is built once, its values refilled in place per
/// solve, and factored with the natural ordering: CHOLMOD then does the same arithmetic on
/// the same matrix, without the transpose and the allocations around it, so the solution
/// is bit for bit that of the permuting factorisation.
/// One analysis serves both: that of A gives P, and with P made the identity it is the
/// analysis of P A P' in the natural ordering.
struct CholmodSolver::Impl {
  explicit Impl(std::string who) : who(std::move(who)) {
    cholmod_start(&common);
    common.final_asis = 0;
    common.supernodal = CHOLMOD_SIMPLICIAL;
    common.final_ll = 1;
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
  void setup(int n, const std::vector<int>& col_start, const std::vector<int>& rows,
             const std::vector<int>& source, const std::vector<int>& order);

  std::string who;
  int n = 0;
  cholmod_common common;
  std::vector<int> from;  // entry of P A P' -> its value in the caller's array
  std::vector<int> perm;
  cholmod_sparse* pap = nullptr;
  cholmod_factor* factor = nullptr;
  cholmod_dense *rhs = nullptr, *x = nullptr, *y = nullptr, *e = nullptr;
};

void CholmodSolver::Impl::setup(int size, const std::vector<int>& col_start, const std::vector<int>& rows,
                                const std::vector<int>& source, const std::vector<int>& order_given) {
  n = size;
  // A with its entry numbers as values (to follow them), read as its lower triangle.
  std::vector<int> ap = col_start, ai = rows;
  std::vector<double> ax(ai.size());
  for (std::size_t k = 0; k < ax.size(); ++k) ax[k] = double(k);
  cholmod_sparse a{};
  a.nrow = a.ncol = n;
  a.nzmax = ai.size();
  a.p = ap.data();
  a.i = ai.data();
  a.x = ax.data();
  a.stype = -1;
  a.itype = CHOLMOD_INT;
  a.xtype = CHOLMOD_REAL;
  a.dtype = CHOLMOD_DOUBLE;
  a.sorted = 1;
  a.packed = 1;
  // The fill-reducing ordering: the caller's, or the one an analysis of A picks.
  if (!order_given.empty()) {
    if (order_given.size() != static_cast<std::size_t>(n)) throw Error(who + ": an order of the wrong size");
    common.nmethods = 1;
    common.method[0].ordering = CHOLMOD_GIVEN;
    std::vector<int> given = order_given;  // cholmod_analyze_p takes a non-const pointer
    factor = cholmod_analyze_p(&a, given.data(), nullptr, 0, &common);
  } else {
    factor = cholmod_analyze(&a, &common);
  }
  if (!factor) throw Error(who + ": CHOLMOD could not analyse the system");
  int* order = static_cast<int*>(factor->Perm);
  perm.assign(order, order + n);
  // P A P' in upper form, as the permuting factorisation builds it; each of its entries
  // carries the number of the entry of A it came from.
  pap = cholmod_ptranspose(&a, 1, perm.data(), nullptr, 0, &common);
  if (!pap) throw Error(who + ": CHOLMOD could not permute the system");
  const std::size_t nz = cholmod_nnz(pap, &common);
  const double* px = static_cast<const double*>(pap->x);
  from.resize(nz);
  for (std::size_t k = 0; k < nz; ++k) from[k] = source[static_cast<std::size_t>(px[k])];
  // The analysis of P A P' in the natural ordering is the same symbolic factor (column
  // counts in the order of P, postordered) without the permutation: P A P' is factored
  // as given, with no second analysis.
  if (factor->is_super || factor->xtype != CHOLMOD_PATTERN)
    throw Error(who + ": CHOLMOD gave an unexpected analysis");
  for (int k = 0; k < n; ++k) order[k] = k;
  factor->ordering = CHOLMOD_NATURAL;
  rhs = cholmod_allocate_dense(n, 2, n, CHOLMOD_REAL, &common);
  if (!rhs) throw Error(who + ": CHOLMOD could not allocate the right-hand side");
}

CholmodSolver::CholmodSolver(int n, const std::vector<int>& col_start, const std::vector<int>& rows,
                             std::vector<int> source, const std::string& who, const std::vector<int>& order)
    : impl_(new Impl(who)) {
  impl_->setup(n, col_start, rows, source, order);  // on a throw, ~Impl releases what was made
}

CholmodSolver::~CholmodSolver() = default;

void CholmodSolver::solve(const double* values, const Eigen::MatrixX2d& b, Eigen::MatrixX2d& out) {
  Impl& s = *impl_;
  double* px = static_cast<double*>(s.pap->x);
  for (std::size_t k = 0; k < s.from.size(); ++k) px[k] = values[s.from[k]];
  double beta[2] = {0, 0};
  cholmod_factorize_p(s.pap, beta, nullptr, 0, s.factor, &s.common);
  if (s.common.status < CHOLMOD_OK || s.factor->minor != s.factor->n)
    throw Error(s.who + ": CHOLMOD could not factor the system (not positive definite?)");
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

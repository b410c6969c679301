// SPDX-License-Identifier: GPL-3.0-or-later
// The linear program of a minimum-zone step: min z subject to |r_i + g_i . x| <= z and
// |x_j| <= box, solved by the revised simplex method on its dual.
//
// The primal has k + 1 free variables w = (x, z) and 2 N + 2 k constraints G w <= h:
//   ( g_i, -1) w <= -r_i,  (-g_i, -1) w <= r_i,  ( e_j, 0) w <= box,  (-e_j, 0) w <= box.
// Its dual, min h . y subject to G^T y = -(0, ..., 0, 1), y >= 0, has k + 1 rows only: a
// basis is a (k + 1)-square matrix, and at the optimum the simplex multipliers are w.
#include "compare_steps.h"

#include <Eigen/LU>

#include <algorithm>
#include <cmath>
#include <vector>

namespace section::compare {

namespace {

struct Dual {
  const Eigen::MatrixXd& g;
  const Eigen::VectorXd& r;
  double box;
  int n, k;

  int columns() const { return 2 * n + 2 * k; }
  Eigen::VectorXd column(int c) const {
    Eigen::VectorXd a = Eigen::VectorXd::Zero(k + 1);
    if (c < 2 * n) {
      const int i = c % n;
      const double sign = c < n ? 1.0 : -1.0;
      a.head(k) = sign * g.row(i).transpose();
      a(k) = -1;
    } else {
      const int j = (c - 2 * n) / 2;
      a(j) = (c - 2 * n) % 2 == 0 ? 1.0 : -1.0;
    }
    return a;
  }
  double cost(int c) const {
    if (c < n) return -r(c);
    if (c < 2 * n) return r(c - n);
    return box;
  }
  // h_c - pi . a_c without forming a_c.
  double reduced(int c, const Eigen::VectorXd& pi) const {
    if (c < 2 * n) {
      const int i = c % n;
      const double sign = c < n ? 1.0 : -1.0;
      return cost(c) - sign * g.row(i).dot(pi.head(k)) + pi(k);
    }
    const int j = (c - 2 * n) / 2;
    return box - ((c - 2 * n) % 2 == 0 ? pi(j) : -pi(j));
  }
};

// The first basis: the point of largest |r| at the top of its band, and the box multipliers
// that balance its gradient.
std::vector<int> first_basis(const Dual& d) {
  int worst = 0;
  for (int i = 1; i < d.n; ++i)
    if (std::abs(d.r(i)) > std::abs(d.r(worst))) worst = i;
  const int c0 = d.r(worst) >= 0 ? worst : d.n + worst;
  std::vector<int> basis{c0};
  const Eigen::VectorXd a = d.column(c0);
  for (int j = 0; j < d.k; ++j) basis.push_back(2 * d.n + 2 * j + (a(j) > 0 ? 1 : 0));
  return basis;
}

}  // namespace

MinimaxStep minimax_step(const Eigen::MatrixXd& g, const Eigen::VectorXd& r, double box) {
  const Dual d{g, r, box, static_cast<int>(g.rows()), static_cast<int>(g.cols())};
  const int m = d.k + 1;
  std::vector<int> basis = first_basis(d);
  std::vector<char> in_basis(d.columns(), 0);
  for (int c : basis) in_basis[c] = 1;
  Eigen::VectorXd b = Eigen::VectorXd::Zero(m);
  b(d.k) = -1;
  const double scale = 1 + r.cwiseAbs().maxCoeff() + box;
  const double tol = 1e-13 * scale;
  Eigen::VectorXd pi = Eigen::VectorXd::Zero(m);
  int degenerate = 0;
  const int limit = 50 * (d.columns() + 10);
  for (int it = 0; it < limit; ++it) {
    Eigen::MatrixXd B(m, m);
    Eigen::VectorXd cb(m);
    for (int i = 0; i < m; ++i) {
      B.col(i) = d.column(basis[i]);
      cb(i) = d.cost(basis[i]);
    }
    const Eigen::FullPivLU<Eigen::MatrixXd> lu(B);
    const Eigen::VectorXd xb = lu.solve(b);
    pi = B.transpose().fullPivLu().solve(cb);
    // Entering column: the most negative reduced cost; the first negative one (Bland's rule,
    // which cannot cycle) after a run of steps that did not move.
    const bool bland = degenerate > 20;
    int enter = -1;
    double best = -tol;
    for (int c = 0; c < d.columns(); ++c) {
      if (in_basis[c]) continue;
      const double rc = d.reduced(c, pi);
      if (rc < best) {
        best = rc;
        enter = c;
        if (bland) break;
      }
    }
    if (enter < 0) break;
    const Eigen::VectorXd u = lu.solve(d.column(enter));
    int leave = -1;
    double ratio = 0;
    for (int i = 0; i < m; ++i) {
      if (u(i) <= 1e-12) continue;
      const double q = std::max(xb(i), 0.0) / u(i);
      if (leave < 0 || q < ratio - 1e-15 || (q <= ratio + 1e-15 && basis[i] < basis[leave])) {
        leave = i;
        ratio = q;
      }
    }
    if (leave < 0) break;  // unbounded dual: cannot happen with the box
    degenerate = ratio <= 1e-15 ? degenerate + 1 : 0;
    in_basis[basis[leave]] = 0;
    in_basis[enter] = 1;
    basis[leave] = enter;
  }
  MinimaxStep out;
  out.x = pi.head(d.k);
  out.z = pi(d.k);
  // The multipliers solve the active constraints; the true largest |residual| of x is z
  // at the optimum, and bounds it otherwise.
  out.z = (r + g * out.x).cwiseAbs().maxCoeff();
  return out;
}

}  // namespace section::compare

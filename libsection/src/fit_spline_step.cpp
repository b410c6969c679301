// SPDX-License-Identifier: GPL-3.0-or-later
// One Gauss-Newton step of squared-distance minimisation: each measured point q_k with
// foot C(t_k), unit tangent T and outward normal N contributes
//   ((C(t_k) - q_k) . N)^2 + alpha ((C(t_k) - q_k) . T)^2,
// alpha = |d| / (|d| + rho) on the convex side and 0 (tangent distance) on the concave side
// within the radius of curvature rho (Wang, Pottmann and Liu 2006, eq. 9), kept above a
// small floor so that sliding along the curve stays bounded.
#include "fit_spline_steps.h"
#include "detail/recent_cache.h"

#include "section/error.h"

#include <algorithm>
#include <cmath>
#include <memory>

namespace section::fit {

namespace {

// The normal equations of a step: each point couples p + 1 consecutive control points, so
// their 2x2 blocks lie in a band (row i, offset 0..p).
struct Normal {
  int n = 0, p = 0;
  std::vector<Eigen::Matrix2d> band;
  Eigen::VectorXd rhs;
  double trace = 0;  // sum of the data term's weights, for the relative weights below

  Normal(int n, int p)
      : n(n),
        p(p),
        band(static_cast<std::size_t>(n) * (p + 1), Eigen::Matrix2d::Zero()),
        rhs(Eigen::VectorXd::Zero(2 * n)) {}
  Eigen::Matrix2d& at(int i, int offset) { return band[static_cast<std::size_t>(i) * (p + 1) + offset]; }
};

// The data term of the measured points. Degree: the curve's when 0, else equal to it (the
// same arithmetic, with the loops unrolled).
template <int Degree>
void add_points(const detail::PiecewiseCurve& pc, const Points& q, const Feet& f,
                const std::vector<double>& w, Normal& eq) {
  const int n = eq.n, p = Degree > 0 ? Degree : eq.p;
  double val[8];
  double trace = eq.trace;                // a local: the band's stores cannot change it
  detail::PiecewiseCurve::Cursor cursor;  // the last span located: consecutive points are close
  for (std::size_t k = 0; k < q.size(); ++k) {
    if (w[k] <= 0) continue;
    const detail::PiecewiseCurve::Local at = pc.locate(f.t[k], cursor);
    const int first = pc.basis(at, val);
    const detail::CurveJet jet = pc.jet(at);
    const Eigen::Vector2d tangent = jet.d1.normalized();
    const Eigen::Vector2d normal(tangent.y(), -tangent.x());
    const double d = f.signed_distance[k];
    const double kappa = jet.curvature();
    double alpha = 1;
    if (kappa == 0) {
      alpha = 0;
    } else {
      const double rho = 1 / std::abs(kappa);
      const bool centre_side = d * kappa < 0;
      alpha = centre_side ? (std::abs(d) < rho ? 0 : 1) : std::abs(d) / (std::abs(d) + rho);
    }
    alpha = std::max(alpha, 1e-3);
    const Eigen::Matrix2d M = w[k] * (normal * normal.transpose() + alpha * tangent * tangent.transpose());
    const Eigen::Vector2d Mq = M * q[k];
    for (int a = 0; a <= p; ++a) {
      const int i = first + a < n ? first + a : first + a - n;
      eq.rhs.segment<2>(2 * i) += val[a] * Mq;
      Eigen::Matrix2d* row = &eq.at(i, 0);  // blocks (i, 0..p - a)
      for (int b = a; b <= p; ++b) row[b - a] += val[a] * val[b] * M;
      trace += w[k] * val[a] * val[a];
    }
  }
  eq.trace = trace;
}

// Change of curvature: the normal component of C''' (for a curve parameterised by arc
// length, dk/ds), integrated over each span with the normal of the current curve, which
// keeps the term quadratic. It is zero on lines and circular arcs (edges keep their
// radius) and large on the wiggles a dense knot vector makes between sparse noisy points.
// Weight: mean point density times length^6, so that it balances the data on wiggles
// about 2 pi smoothing_length long where the data are of mean density (and on longer ones
// where they are sparser), times (noise sigma / 5 um)^2: exact data need no smoothing (it
// rounds the curvature jump where an edge meets a flank). Cubic curves only.
void add_change_of_curvature(const BSpline& c, const detail::PiecewiseCurve& pc, const Feet& f,
                             const std::vector<double>& w, double smoothing_length, Normal& eq) {
  const int n = eq.n, p = eq.p;
  double points = 0;
  for (double x : w) points += std::max(x, 0.0);
  const double noise = noise_sigma(f, w) / 0.005;
  const double lambda3 = points / (c.t_max() - c.t_min()) * std::pow(smoothing_length, 6) * noise * noise;
  double v[4][8], jerk[4];
  int idx[8];
  for (int j = 0; j < n; ++j) {
    const double a = c.knots[j], h = (c.knots[j + 1] - a) / 4;
    if (!(h > 0)) continue;
    // C''' is constant on a cubic span: the third difference of the basis values at
    // four equally spaced parameters.
    int first = 0;
    detail::PiecewiseCurve::Local l[4];  // span j, unless knots repeat
    for (int g = 0; g < 4; ++g) first = pc.basis(l[g] = pc.locate(a + (g + 0.5) * h, j), v[g]);
    for (int b = 0; b <= p; ++b) {
      idx[b] = first + b < n ? first + b : first + b - n;
      jerk[b] = (v[3][b] - 3 * v[2][b] + 3 * v[1][b] - v[0][b]) / (h * h * h);
    }
    for (int g = 0; g < 4; ++g) {
      const Eigen::Vector2d d1 = pc.jet(l[g]).d1;
      const double speed = d1.norm();
      if (!(speed > 0)) continue;
      const Eigen::Vector2d normal(d1.y() / speed, -d1.x() / speed);
      const Eigen::Matrix2d M = lambda3 * h * normal * normal.transpose();
      for (int a2 = 0; a2 <= p; ++a2)
        for (int b = a2; b <= p; ++b) eq.at(idx[a2], b - a2) += jerk[a2] * jerk[b] * M;
    }
  }
}

// The band's blocks of offset > 0 that are exactly zero (no point couples their control
// points): left out of the matrix's pattern.
std::vector<char> skipped_blocks(const Normal& eq) {
  std::vector<char> skipped(eq.band.size(), 0);
  for (std::size_t k = 0; k < eq.band.size(); ++k) skipped[k] = k % (eq.p + 1) > 0 && eq.band[k].isZero(0);
  return skipped;
}

// The terms of the system's matrix H, each as add(row, column, value), in the order
// setFromTriplets would sum an entry's terms in: the band, then fairness (second
// differences of the control polygon), which keeps spans without data determined, and a
// tiny pull toward the current control points, which keeps the system definite. Only the
// lower triangle: the LDLT (orderings included) reads no other.
template <class Add>
void system_terms(const Normal& eq, const std::vector<char>& skipped, double fairness, Add&& add) {
  const int n = eq.n, p = eq.p;
  for (int i = 0; i < n; ++i)
    for (int o = 0; o <= p; ++o) {
      if (skipped[static_cast<std::size_t>(i) * (p + 1) + o]) continue;
      const Eigen::Matrix2d& B = eq.band[static_cast<std::size_t>(i) * (p + 1) + o];
      const int j = (i + o) % n;
      for (int r = 0; r < 2; ++r)
        for (int s = 0; s < 2; ++s) {
          if (o == 0 ? r >= s : j < i) add(2 * i + r, 2 * j + s, B(r, s));
          if (o > 0 && j > i) add(2 * j + s, 2 * i + r, B(r, s));
        }
    }
  const double lambda = fairness * std::max(eq.trace / n, 1e-12);
  const double mu = 1e-9 * std::max(eq.trace / n, 1e-12);
  for (int i = 0; i < n; ++i) {
    const int ids[3] = {(i + n - 1) % n, i, (i + 1) % n};
    const double coef[3] = {1, -2, 1};
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b)
        for (int r = 0; r < 2; ++r)
          if (ids[a] >= ids[b]) add(2 * ids[a] + r, 2 * ids[b] + r, lambda * coef[a] * coef[b]);
    for (int r = 0; r < 2; ++r) add(2 * i + r, 2 * i + r, mu);
  }
}

// A new pattern: H assembled once as SimplicialLDLT<AMD> would take it, its ordering as that
// solver computes it, P H P' as it would permute it (H's entry numbers in place of its
// values tell where each lands) and the analysis of P H P' in its natural order, which is
// what that solver factors: the same factor, bit for bit.
void analyse(const Normal& eq, std::vector<char> skipped, double fairness, StepSolver& solver) {
  std::vector<Eigen::Triplet<double>> trip;
  trip.reserve(static_cast<std::size_t>(eq.n) * (8 * (eq.p + 1) + 40));
  system_terms(eq, skipped, fairness, [&](int r, int c, double v) { trip.emplace_back(r, c, v); });
  Eigen::SparseMatrix<double> H(2 * eq.n, 2 * eq.n);
  H.setFromTriplets(trip.begin(), trip.end());
  // The solver orders the full matrix A as A' + A; A is symmetric, so that sum has A's
  // entries in A's order, and the view's overload orders A itself without forming it.
  Eigen::AMDOrdering<int>()(H.selfadjointView<Eigen::Lower>(), solver.Pinv);
  solver.P = solver.Pinv.inverse();
  for (Eigen::Index e = 0; e < H.nonZeros(); ++e) H.valuePtr()[e] = static_cast<double>(e);
  solver.permuted.resize(H.rows(), H.cols());
  solver.permuted.selfadjointView<Eigen::Upper>() = H.selfadjointView<Eigen::Lower>().twistedBy(solver.P);
  std::vector<int> landing(static_cast<std::size_t>(H.nonZeros()));
  for (Eigen::Index e = 0; e < H.nonZeros(); ++e)
    landing[static_cast<std::size_t>(solver.permuted.valuePtr()[e])] = static_cast<int>(e);
  std::vector<char> seen(landing.size(), 0);
  solver.slot.resize(trip.size());
  const int* rows = H.innerIndexPtr();
  for (std::size_t k = 0; k < trip.size(); ++k) {
    int e = H.outerIndexPtr()[trip[k].col()];  // a column holds a few entries
    while (rows[e] != trip[k].row()) ++e;
    const int at = landing[static_cast<std::size_t>(e)];
    solver.slot[k] = seen[static_cast<std::size_t>(at)] ? at : -1 - at;
    seen[static_cast<std::size_t>(at)] = 1;
  }
  solver.ldlt.analyzePattern(solver.permuted);
  solver.n = eq.n;
  solver.p = eq.p;
  solver.skipped = std::move(skipped);
}

// The solver analysed for the pattern of eq's system: one of the last patterns met on this
// thread, or a new analysis. The analysis depends on the pattern only, so a solver taken
// over from another fit (the sections of a scan mostly share their knot counts: 17
// patterns over 102 rounds of knots on the 1 M point bench scan) factors bit for bit as a
// new one would. 8 patterns kept miss 24 times there (16: 17), each about 40 KB at 60
// control points.
StepSolver& solver_for(const Normal& eq, double fairness) {
  thread_local std::vector<std::unique_ptr<StepSolver>> recent;
  std::vector<char> skipped = skipped_blocks(eq);
  return detail::recently_used(
      recent, 8, [&](const StepSolver& s) { return s.n == eq.n && s.p == eq.p && s.skipped == skipped; },
      [&](StepSolver& s) { analyse(eq, std::move(skipped), fairness, s); });
}

// Solves H x = rhs: the terms written into P H P' (of the pattern's analysis), factored,
// and the solution permuted back.
Eigen::VectorXd solve(const Normal& eq, double fairness) {
  StepSolver& solver = solver_for(eq, fairness);
  double* value = solver.permuted.valuePtr();
  std::size_t k = 0;
  system_terms(eq, solver.skipped, fairness, [&](int, int, double v) {
    const int at = solver.slot[k++];
    if (at < 0)
      value[-1 - at] = v;
    else
      value[at] += v;
  });
  solver.ldlt.factorize(solver.permuted);
  if (solver.ldlt.info() != Eigen::Success)
    throw Error("fit_spline: the distance-minimisation system is singular");
  const Eigen::VectorXd b = solver.P * eq.rhs;
  Eigen::VectorXd x = solver.ldlt.solve(b);
  if (solver.ldlt.info() != Eigen::Success || !x.allFinite())
    throw Error("fit_spline: the distance-minimisation system is singular");
  x = solver.Pinv * x;
  return x;
}

}  // namespace

BSpline sdm_step(const BSpline& c, const detail::PiecewiseCurve& pc, const Points& q, const Feet& f,
                 const std::vector<double>& w, double fairness, double smoothing_length) {
  const int n = static_cast<int>(c.control.size());
  Normal eq(n, c.degree);
  if (c.degree == 3)
    add_points<3>(pc, q, f, w, eq);
  else
    add_points<0>(pc, q, f, w, eq);
  if (smoothing_length > 0 && c.degree == 3) add_change_of_curvature(c, pc, f, w, smoothing_length, eq);
  // The pull toward the current control points (see system_terms), on the right.
  const double mu = 1e-9 * std::max(eq.trace / n, 1e-12);
  for (int i = 0; i < n; ++i)
    for (int r = 0; r < 2; ++r) eq.rhs(2 * i + r) += mu * c.control[i](r);
  const Eigen::VectorXd x = solve(eq, fairness);
  BSpline out = c;
  for (int i = 0; i < n; ++i) out.control[i] = Eigen::Vector2d(x(2 * i), x(2 * i + 1));
  return out;
}

}  // namespace section::fit

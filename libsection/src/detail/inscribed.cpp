// SPDX-License-Identifier: GPL-3.0-or-later
#include "detail/inscribed.h"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <limits>

namespace section::detail {

bool solve_circle(const PiecewiseCurve& curve, const Eigen::Vector2d& p, const Eigen::Vector2d& n, double ta,
                  double tb, double scale, InscribedCircle& out, double* kappa) {
  double lambda = 0;
  const double tol = 1e-13 * scale;
  double previous = std::numeric_limits<double>::infinity();
  PiecewiseCurve::Cursor at_a, at_b;  // the contacts move little: their spans are tried first
  for (int it = 0; it < 30; ++it) {
    const CurveJet ja = curve.jet(curve.locate(ta, at_a)), jb = curve.jet(curve.locate(tb, at_b));
    const Eigen::Vector2d &a = ja.point, &a1 = ja.d1, &a2 = ja.d2, &b = jb.point, &b1 = jb.d1, &b2 = jb.d2;
    const Eigen::Vector2d c = p + lambda * n;
    const Eigen::Vector3d f((c - a).dot(a1), (c - b).dot(b1),
                            0.5 * ((c - a).squaredNorm() - (c - b).squaredNorm()));
    Eigen::Matrix3d j;
    j << -a1.squaredNorm() + (c - a).dot(a2), 0, n.dot(a1),  //
        0, -b1.squaredNorm() + (c - b).dot(b2), n.dot(b1),   //
        -f(0), f(1), (b - a).dot(n);
    // The cofactor inverse, unless the system is near singular (the contacts merging at a
    // branch's end): an LU with full pivoting there, at several times the cost. Either
    // gives a Newton step; the circle is where f vanishes, whichever solved for it.
    Eigen::Matrix3d inverse;
    bool invertible = false;
    j.computeInverseWithCheck(inverse, invertible,
                              1e-10 * j.row(0).norm() * j.row(1).norm() * j.row(2).norm());
    Eigen::Vector3d dx =
        invertible ? Eigen::Vector3d(-(inverse * f)) : Eigen::Vector3d(-j.fullPivLu().solve(f));
    if (!dx.allFinite()) return false;
    const double sa = a1.norm(), sb = b1.norm();
    const double r = std::max(0.5 * ((c - a).norm() + (c - b).norm()), 1e-6 * scale);
    double step = std::max({std::abs(dx(0)) * sa, std::abs(dx(1)) * sb, std::abs(dx(2))});
    if (step > 0.5 * r) dx *= 0.5 * r / step;  // damped far from the solution
    ta += dx(0);
    tb += dx(1);
    lambda += dx(2);
    // Converged, or stalled at the round-off floor of a near-singular system (close to
    // the end of a branch, where the contacts merge or osculate).
    const bool stalled = step < 1e-8 * scale && step > 0.25 * previous;
    previous = step;
    if (step < tol || stalled) {
      out.center = p + lambda * n;
      out.t_left = ta;
      out.t_right = tb;
      out.left = curve.point(curve.locate(ta, at_a));
      out.right = curve.point(curve.locate(tb, at_b));
      out.radius = 0.5 * ((out.center - out.left).norm() + (out.center - out.right).norm());
      if (kappa) {  // signed curvatures at the contacts, from the last iterate's derivatives
        kappa[0] = cross(a1, a2) / std::pow(a1.norm(), 3);
        kappa[1] = cross(b1, b2) / std::pow(b1.norm(), 3);
      }
      return std::isfinite(out.radius);
    }
  }
  return false;
}

bool valid_circle(const SampledProfile& pr, const Eigen::Vector2d& n, const InscribedCircle& c,
                  const double* kappa, int end) {
  const double r = c.radius;
  if (!(r > 1e-9 * pr.scale)) return false;
  if ((c.left - c.center).dot(n) <= 0 || (c.right - c.center).dot(n) >= 0) return false;
  if ((c.left - c.right).norm() < 1e-7 * pr.scale) return false;
  if (std::abs((c.center - c.left).norm() - (c.center - c.right).norm()) > 1e-6 * r) return false;
  const double ka = kappa ? pr.sigma * kappa[0] : pr.convexity(c.t_left);
  const double kb = kappa ? pr.sigma * kappa[1] : pr.convexity(c.t_right);
  // Local osculation test, loose: a spline's curvature ripples by O(h^2), a noisy
  // profile's much more; the macroscopic test below locates the ends.
  if (r * ka >= 2 || r * kb >= 2) return false;
  if (end >= 0) {
    // Toward an end the circle must stay clear of the profile between its contacts,
    // through that end: past the branch's end it would cut through the tip. This
    // macroscopic test is what locates the end, immune to curvature ripples.
    const bool from_left = (end == 0) == (pr.sigma > 0);
    const double from = from_left ? c.t_left : c.t_right, to = from_left ? c.t_right : c.t_left;
    const double length = pr.forward(from, to);
    PiecewiseCurve::Cursor at;  // in order: the span before is tried first
    for (int i = 1; i < 24; ++i) {
      const double t = from + length * (0.05 + 0.9 * i / 24.0);
      if ((pr.fast.point(pr.fast.locate(t, at)) - c.center).norm() < r * (1 - 1e-4)) return false;
    }
  }
  return !pr.sample_within(c.center, r * (1 - 1e-3));
}

bool circle_on_normal(const SampledProfile& pr, const Eigen::Vector2d& p, const Eigen::Vector2d& n,
                      const InscribedCircle* guess, InscribedCircle& out, bool fresh, int end) {
  double k[2];
  if (guess && solve_circle(pr.fast, p, n, guess->t_left, guess->t_right, pr.scale, out, k) &&
      valid_circle(pr, n, out, k, end))
    return true;
  if (guess && fresh == false) return false;
  const int l = pr.nearest_on_side(p, n), r = pr.nearest_on_side(p, -n);
  if (l < 0 || r < 0) return false;
  return solve_circle(pr.fast, p, n, pr.ts[l], pr.ts[r], pr.scale, out, k) &&
         valid_circle(pr, n, out, k, end);
}

bool snap_to_axis(const SampledProfile& pr, const Eigen::Vector2d& p, const Eigen::Vector2d& n,
                  const InscribedCircle& guess, InscribedCircle& out) {
  return solve_circle(pr.fast, p, n, guess.t_left, guess.t_right, pr.scale, out) &&
         valid_circle(pr, n, out, nullptr) && (out.center - p).norm() < 0.5 * out.radius;
}

}  // namespace section::detail

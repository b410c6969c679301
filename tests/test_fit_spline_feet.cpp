// SPDX-License-Identifier: GPL-3.0-or-later
#include "fit_spline_steps.h"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <vector>

using Eigen::Vector2d;

namespace {

const double pi = std::acos(-1.0);

// Distance from p to the nearest of the dense points.
double nearest_distance(const std::vector<Vector2d>& dense, const Vector2d& p) {
  double best = 1e300;
  for (const Vector2d& s : dense) best = std::min(best, (s - p).squaredNorm());
  return std::sqrt(best);
}

}  // namespace

// Points in order along a thin loop (as slice gives them), some pushed through to the far
// side's neighbourhood: each foot must be the nearest point of the curve, on whichever
// side that is, not the continuation of its neighbour's.
TEST_CASE("foot_points: feet of ordered points are the nearest, across a thin section too", "[fit_spline]") {
  const double a = 20, b = 1;  // thickness 2 mm at the middle, end radius 0.05 mm
  std::vector<Vector2d> loop;
  for (int i = 0; i < 2000; ++i) {
    const double u = 2 * pi * i / 2000;
    loop.emplace_back(a * std::cos(u), b * std::sin(u));
  }
  const section::BSpline curve = section::fit_curve(loop, {3, 200, 1e-6, true});
  const section::detail::PiecewiseCurve pc(curve);
  std::vector<Vector2d> q;
  for (int i = 0; i < 1200; ++i) {
    const double u = 2 * pi * (i + 0.3) / 1200;
    const Vector2d p(a * std::cos(u), b * std::sin(u));
    const Vector2d outward = Vector2d(b * std::cos(u), a * std::sin(u)).normalized();
    // The upper side's middle points 1.6 mm inward: 0.4 mm from the lower side. Points
    // around the right end 0.1 mm outside (beyond the tip: nearest at the tip).
    double offset = 0.01 * std::sin(7.0 * i);
    if (i > 200 && i < 400) offset = -1.6;
    if (i < 20 || i > 1180) offset = 0.1;
    q.push_back(p + offset * outward);
  }
  const std::vector<Vector2d> dense = pc.points(pc.t_min(), pc.t_max(), 100000);
  const section::fit::Feet f = section::fit::foot_points(curve, pc, q);
  int wrong = 0;
  for (std::size_t k = 0; k < q.size(); ++k) {
    // The foot is a point of the curve at that distance, and no point of the curve is
    // nearer (a foot on the wrong side would be 0.1 mm or more farther than some).
    const double d = std::abs(f.signed_distance[k]);
    const bool on_curve = std::abs((q[k] - pc.point(f.t[k])).norm() - d) < 1e-9;
    if (!on_curve || !(d <= nearest_distance(dense, q[k]) + 1e-9)) ++wrong;
  }
  REQUIRE(wrong == 0);
  // The points pushed through lie 0.1 to 0.4 mm from the lower side, inside the loop.
  for (int i = 201; i < 400; ++i) {
    REQUIRE(pc.point(f.t[i]).y() < 0);
    REQUIRE(f.signed_distance[i] < -0.1);
    REQUIRE(f.signed_distance[i] > -0.45);
  }
}

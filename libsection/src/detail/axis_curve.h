// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The medial axis as a curve, shared by the camber stages: an open spline through the
// inscribed circles' centres, extended straight beyond its ends, and its arc-length table.
#include "detail/piecewise_curve.h"
#include "section/bspline.h"

#include <Eigen/Core>

#include <vector>

namespace section::detail {

/// An open cubic spline least-squares fitted to `points` (see CurveFitOptions).
BSpline fit_open(const std::vector<Eigen::Vector2d>& points, int control_points, double fairness);

/// An open spline, extended straight beyond its ends.
struct AxisCurve {
  BSpline spline;
  double a = 0, b = 1;  ///< parameter range of the spline
  PiecewiseCurve f;
  AxisCurve() = default;  ///< no axis yet (a state to assign one to)
  explicit AxisCurve(BSpline s);
  /// Point at u, on the straight extension when u lies outside [a, b].
  Eigen::Vector2d point(double u) const;
  /// Unit tangent at u (the end's beyond the ends).
  Eigen::Vector2d tangent(double u) const;
};

/// The axis through the centres `points` (repeated points dropped): an open cubic with
/// half as many control points (4-200) and the given fairness. Throws section::Error when
/// fewer than 4 distinct points remain.
AxisCurve make_axis(const std::vector<Eigen::Vector2d>& points, double fairness);

/// Arc-length table of an open spline (`pieces` equal parameter steps, 5-point
/// Gauss-Legendre each) for the maps between parameter and arc length. Made from the
/// spline's piecewise form (an AxisCurve's own: converted once).
struct ArcLengthTable {
  PiecewiseCurve f;
  std::vector<double> t, s;  ///< parameter and arc length at each step
  ArcLengthTable(PiecewiseCurve c, int pieces);
  double length() const { return s.back(); }
  /// Parameter at arc length `target` (clamped to the curve).
  double param(double target) const;
  /// Arc length at parameter `param_t`.
  double arc(double param_t) const;
};

}  // namespace section::detail

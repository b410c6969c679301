// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// @file bspline.h
/// Planar cubic (or any degree) B-spline curves, open (clamped) or closed (periodic):
/// evaluation, derivatives, closest-point projection, least-squares fitting.
#include <Eigen/Core>
#include <cstddef>
#include <vector>

namespace section {

/// Highest degree the functions here evaluate and fit.
inline constexpr int max_spline_degree = 7;

/// A planar B-spline curve.
/// Open curves use a clamped knot vector of size control.size() + degree + 1.
/// Closed curves store the n distinct control points once; the knot vector holds the
/// n + 1 breakpoints t_0 < ... < t_n of one period (t_n - t_0 is the period), and the
/// curve wraps around: control point i + n is control point i.
struct BSpline {
  int degree = 3;                        ///< polynomial degree
  bool closed = false;                   ///< periodic curve
  std::vector<double> knots;             ///< see above
  std::vector<Eigen::Vector2d> control;  ///< control points

  double t_min() const;  ///< first parameter of the curve
  double t_max() const;  ///< last parameter (one period later when closed)
  /// Point at parameter t (wrapped into one period when closed, clamped when open).
  Eigen::Vector2d point(double t) const;
  /// k-th derivative at t (k = 0 gives the point).
  Eigen::Vector2d derivative(double t, int k) const;
  /// The point and the derivatives up to order k at t into out[0..k], from one evaluation
  /// of the basis (each equal to derivative(t, i)); orders above the degree are zero.
  void derivatives(double t, int k, Eigen::Vector2d* out) const;
  /// Signed curvature at t (positive turning counterclockwise).
  double curvature(double t) const;
  /// Basis functions non-zero at t: their control indices (already wrapped) and values.
  /// Used to linearise fits in the control points.
  void basis(double t, std::vector<int>& index, std::vector<double>& value) const;
};

/// Throws section::Error naming the first defect of a curve the functions here cannot
/// evaluate: a degree outside 1..7, control point and knot counts that do not match, a
/// knot or control point that is not finite, knots that decrease, more than degree + 1
/// equal knots in a row, or an empty parameter range (closed: a period not above 0).
/// The functions that take a curve from outside (clamped, flatten, camber, compare)
/// call it; evaluation checks only the degree and counts, to stay cheap.
void check_spline(const BSpline& curve);

/// Closest point of a curve to a query point.
struct ClosestPoint {
  double t = 0;           ///< curve parameter of the foot point
  Eigen::Vector2d point;  ///< the foot point
  double distance = 0;    ///< distance from the query to the foot point
};

/// Closest point on `curve` to `q`: a global search over `samples` samples per knot span
/// followed by Newton iterations, so that the result is the global minimum.
ClosestPoint closest_point(const BSpline& curve, const Eigen::Vector2d& q, int samples = 8);

/// Closest point searched only around the parameter `t_guess` (Newton from there with
/// a bracket of one knot span each side); for tracking points that move little.
ClosestPoint closest_point_near(const BSpline& curve, const Eigen::Vector2d& q, double t_guess);

/// Chord-length parameters of a polyline (closed: the last parameter is the full
/// length, for the segment back to the first point), starting at 0.
std::vector<double> chord_length_parameters(const std::vector<Eigen::Vector2d>& points, bool closed);

/// Options of fit_curve (lengths in the points' units).
struct CurveFitOptions {
  int degree = 3;          ///< spline degree
  int control_points = 0;  ///< number of control points; 0 = points/4, at least 8
  double fairness = 1e-6;  ///< weight of the second-difference fairness term, relative
  bool closed = true;      ///< fit a closed (periodic) curve
};

/// Least-squares B-spline through ordered points with chord-length parameters and
/// uniform knots in that parameter. Throws section::Error when there are fewer points
/// than control points or the points are degenerate (all equal, all on a line when closed).
BSpline fit_curve(const std::vector<Eigen::Vector2d>& points, const CurveFitOptions& options = {});

/// Least-squares control points for the knots, degree and closedness of `shape` (its
/// control points are ignored) through `points` at the given curve `parameters`, with
/// optional per-point `weights` (empty = all 1) and the relative second-difference
/// `fairness` weight of CurveFitOptions. Throws section::Error when the system is singular.
BSpline fit_control_points(const std::vector<Eigen::Vector2d>& points, const std::vector<double>& parameters,
                           const BSpline& shape, double fairness = 1e-6,
                           const std::vector<double>& weights = {});

/// `count` points spread evenly in parameter over the curve (closed: the end point is not
/// repeated).
std::vector<Eigen::Vector2d> sample(const BSpline& curve, int count);

/// Arc length between parameters a < b (Gauss-Legendre per knot span).
double arc_length(const BSpline& curve, double a, double b);

/// Parameters of `per_span` samples evenly spaced in every knot span of `curve`.
std::vector<double> span_samples(const BSpline& curve, int per_span);

/// The same curve as an open curve with a clamped knot vector (each end knot degree + 1
/// times), the form CAD formats (DXF SPLINE, IGES 126) read most widely. A closed curve is
/// cut at its first knot t_0 by knot insertion (Boehm), which leaves the curve and its
/// parameter unchanged: point(t) agrees for every t in [t_0, t_0 + period], and the first
/// and last control points are the point at t_0. An open curve is returned as it is.
/// Throws section::Error for a curve bspline.h does not accept (degree, knot counts).
BSpline clamped(const BSpline& curve);

/// The points a polyline of flatten may take by default.
inline constexpr std::size_t max_flatten_points = 1000000;

/// Parameters of a polyline through the curve that stays within `tolerance` (in the
/// control points' units) of it: every knot span is bisected (into 2 pieces at least)
/// until the curve at each piece's midpoint and quarter points in parameter lies within
/// half the tolerance of the piece's chord.
/// Ascending from t_min(); closed curves do not repeat the end (t_max() is t_min()).
/// Throws section::Error when the tolerance is not above 0 or below the resolution of
/// the coordinates (64 units in the last place of the largest), or when the polyline
/// would need more than `max_points` points.
std::vector<double> flatten(const BSpline& curve, double tolerance,
                            std::size_t max_points = max_flatten_points);

}  // namespace section

// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The steps of compare (src/compare.cpp): the nominal prepared for foot points, arc length
// and zones (compare_nominal.cpp), the rigid fits over one or more sections
// (compare_fit.cpp) and the linear program of a minimum-zone step (compare_minimax.cpp).
#include "detail/piecewise_curve.h"
#include "fit_spline_steps.h"
#include "section/compare.h"

#include <Eigen/Core>

#include <array>
#include <cstddef>
#include <vector>

namespace section::compare {

/// The nominal of a section prepared for many queries: foot points, arc length, zones.
struct Geometry {
  explicit Geometry(const NominalSection& nominal, double edge_zone);

  const BSpline& curve;
  detail::PiecewiseCurve pc;
  fit::FootSearch search;          // the full search of the feet, built once
  double orientation = 1;          // +1 counterclockwise, -1 clockwise
  std::vector<double> ts, arc;     // dense samples: parameter, arc length from t_min
  double perimeter = 0;            // the curve's length
  double origin = 0;               // arc length (from t_min) where the LE zone begins
  std::array<double, 3> ends{};    // from `origin`: ends of the LE zone, side A, TE zone
  bool a_is_pressure = true;       // side A (from the LE zone toward the TE) is the pressure side
  Eigen::Vector2d centroid{0, 0};  // the nominal's area centroid

  /// Arc length of parameter t from t_min, in [0, perimeter).
  double arc_at(double t) const;
  /// Arc length of parameter t from the LE zone's start, in [0, perimeter).
  double position(double t) const;
  /// The zone of the foot at parameter t.
  Zone zone_at(double t) const;
  /// The zone's interval of position(): [begin, end) (whole: [0, perimeter)).
  std::array<double, 2> interval(Zone zone) const;
  /// Outward unit normal at parameter t.
  Eigen::Vector2d normal_at(double t) const;
};

/// What prepare_nominal keeps: the nominal and its Geometry (which refers to it).
struct Prepared {
  Prepared(const NominalSection& n, double edge_zone) : nominal(n), geometry(nominal, edge_zone) {}
  NominalSection nominal;
  Geometry geometry;
};

/// One section in a fit: its points, how the fit's parameters move it, where it stands.
struct Block {
  const Geometry* nominal = nullptr;
  std::vector<Eigen::Vector2d> points;  // the points fitted, as measured
  std::vector<double> zone_weight;      // weighted fit: weight by zone index (empty: all 1)
  // The local move (angle in radians, translation u, v) per fit parameter, and the centre
  // the local rotation turns about (in the nominal's coordinates).
  Eigen::Matrix<double, 3, Eigen::Dynamic> map;
  Eigen::Vector2d center{0, 0};
  // The motion so far (p -> R(angle) p + translation), the moved points and their feet.
  double angle = 0;
  Eigen::Vector2d translation{0, 0};
  std::vector<Eigen::Vector2d> moved;
  fit::Feet feet;

  /// Moves the points by the motion so far and finds their feet (tracked from the last).
  void place();
  /// Signed deviation of point k (positive = outside the nominal).
  double deviation(std::size_t k) const { return nominal->orientation * feet.signed_distance[k]; }
};

/// How a fit ended.
struct FitRun {
  int iterations = 0;
  bool converged = true;
};

/// Least squares (weighted when the blocks have zone weights) over all blocks' points:
/// Gauss-Newton on the point-to-tangent distances, each step composed exactly.
FitRun fit_least_squares(std::vector<Block>& blocks, const FitOptions& options);

/// Minimum zone over all blocks' points: sequential linear programs (minimax_step) in a
/// trust region, from the motion the blocks hold (the least-squares fit).
FitRun fit_minimum_zone(std::vector<Block>& blocks, const FitOptions& options);

/// The largest |deviation| and the rms over all blocks' points.
std::array<double, 2> spread(const std::vector<Block>& blocks);

/// The step x (k values) minimising max_i |r_i + g_i . x| subject to |x_j| <= box, by the
/// simplex method on the dual (k + 1 rows, 2 N + 2 k columns); `z` the minimum reached.
struct MinimaxStep {
  Eigen::VectorXd x;
  double z = 0;
};
MinimaxStep minimax_step(const Eigen::MatrixXd& g, const Eigen::VectorXd& r, double box);

}  // namespace section::compare

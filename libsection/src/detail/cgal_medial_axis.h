// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// Seed of the medial axis of a closed polygon from a CGAL constrained Delaunay
// triangulation (the only place camber touches CGAL).
#include <Eigen/Core>
#include <vector>

namespace section::detail {

/// Main branch of the discrete medial axis of a simple closed polygon.
struct MedialSeed {
  std::vector<Eigen::Vector2d> points;  ///< branch points (triangle circumcentres), end to end
  std::vector<double> radius;           ///< distance from each point to its triangle's corners
  int triangles = 0;                    ///< triangles found inside the polygon
};

/// Triangulates `polygon` (closed, either orientation, no repeated end point) with its
/// edges as constraints, keeps the triangles inside, and returns the longest path of
/// their dual tree (circumcentres joined across shared edges): the main branch of the
/// medial axis, from one end of the shape to the other. Empty when fewer than 3 points.
MedialSeed medial_axis_seed(const std::vector<Eigen::Vector2d>& polygon);

}  // namespace section::detail

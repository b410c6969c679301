// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// Nearest-neighbour queries through a FLANN kd-tree (single tree, exact search): the
// library's one door to FLANN, for 2D points (curve feet) and 3D points (spacing, ICP).
#include <Eigen/Core>

#include <cstddef>
#include <memory>
#include <vector>

namespace section::detail {

/// Exact nearest neighbours among a fixed set of points of dimension Dim (2 or 3).
template <int Dim>
class NearestPoints {
public:
  using Point = Eigen::Matrix<double, Dim, 1>;

  /// A kd-tree over `points` (copied; not empty) with leaves of `leaf_size` points. The
  /// answers are exact for any leaf size; between equidistant points it may decide.
  explicit NearestPoints(const std::vector<Point>& points, int leaf_size = 12);
  ~NearestPoints();
  NearestPoints(const NearestPoints&) = delete;
  NearestPoints& operator=(const NearestPoints&) = delete;

  /// Index of the point nearest to each query (queries.size() results).
  std::vector<int> nearest(const std::vector<Point>& queries) const;

  /// The nearest point within `radius` of each query: `index` (-1 where there is none)
  /// and `d2`, its squared distance (0 where there is none).
  void nearest_within(const std::vector<Point>& queries, double radius, std::vector<int>& index,
                      std::vector<double>& d2) const;

  /// The k nearest points to q, nearest first (q itself when it is one of the points):
  /// k indices into `index` and their squared distances into `d2`.
  void k_nearest(const Point& q, int k, int* index, double* d2) const;

private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace section::detail

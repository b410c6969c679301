#pragma once
// Nearest-neighbour queries among 2D points through a FLANN kd-tree (single tree, exact).
#include <Eigen/Core>

#include <memory>
#include <vector>

namespace section::detail {

/// Exact nearest neighbours among a fixed set of 2D points.
class NearestPoints {
public:
  explicit NearestPoints(const std::vector<Eigen::Vector2d>& points);
  ~NearestPoints();
  NearestPoints(const NearestPoints&) = delete;
  NearestPoints& operator=(const NearestPoints&) = delete;

  /// Index of the point nearest to each query (queries.size() results).
  std::vector<int> nearest(const std::vector<Eigen::Vector2d>& queries) const;

private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace section::detail

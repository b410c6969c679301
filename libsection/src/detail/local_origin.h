// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// A local origin for geometry far from the origin: integrals and fits subtract it first.
#include <Eigen/Core>

#include <cmath>
#include <vector>

namespace section::detail {

/// The centre of the bounding box of `points` when it lies farther from the origin than the
/// box is wide, else 0. Coordinates of 1e6 or 1e9 (a part in machine coordinates) lose their
/// digits in squares and products (an area integral of x^2 y' keeps none at 1e9), so the
/// stages work on p - origin; near the origin nothing is gained, and 0 keeps their results
/// bit for bit.
inline Eigen::Vector2d local_origin(const std::vector<Eigen::Vector2d>& points) {
  if (points.empty()) return {0, 0};
  Eigen::Vector2d lo = points[0], hi = points[0];
  for (const auto& p : points) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  const Eigen::Vector2d centre = 0.5 * (lo + hi);
  if (!centre.allFinite() || !(centre.cwiseAbs().maxCoeff() > (hi - lo).maxCoeff())) return {0, 0};
  return centre;
}

/// `points` moved by -origin.
inline std::vector<Eigen::Vector2d> moved(const std::vector<Eigen::Vector2d>& points,
                                          const Eigen::Vector2d& origin) {
  std::vector<Eigen::Vector2d> out;
  out.reserve(points.size());
  for (const auto& p : points) out.push_back(p - origin);
  return out;
}

}  // namespace section::detail

// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The foot of a point on a line segment, for the nearest-segment searches of the stages.
#include <Eigen/Core>

#include <algorithm>

namespace section::detail {

/// Where p's foot lies on segment [a, b]: its parameter t in [0, 1] along a -> b (0 on a
/// segment of zero length) and p's squared distance to it.
struct SegmentFoot {
  double t = 0;
  double d2 = 0;
};

inline SegmentFoot segment_foot(const Eigen::Vector2d& a, const Eigen::Vector2d& b,
                                const Eigen::Vector2d& p) {
  const Eigen::Vector2d e = b - a;
  const double e2 = e.squaredNorm();
  const double t = e2 > 0 ? std::clamp((p - a).dot(e) / e2, 0.0, 1.0) : 0.0;
  return {t, (a + t * e - p).squaredNorm()};
}

}  // namespace section::detail

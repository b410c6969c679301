// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// What a least-squares curve fit asks of its points, for fits that place their own knots.
#include <Eigen/Core>

#include <vector>

namespace section::detail {

/// Throws section::Error (`fit_curve: ...`) when a point is not finite, all points are
/// equal, or, for a closed curve, all lie on a line: no curve is determined by them.
void check_fit_points(const std::vector<Eigen::Vector2d>& points, bool closed);

}  // namespace section::detail

// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The camber line at an arc length from its LE point, shared by camber_line's samples and
// the thickness stations (src/camber.cpp).
#include "detail/axis_curve.h"
#include "section/camber.h"

#include <Eigen/Core>

namespace section::detail {

/// A point of the axis: its parameter, the point and the unit normal left of the axis.
struct AxisSample {
  double t = 0;
  Eigen::Vector2d point{0, 0}, normal{0, 0};
};

/// The axis at arc length s from the LE point (between the extensions, the LE one `ext_le`
/// long), the spline's arc length taken from `table`.
AxisSample axis_sample(const AxisCurve& ax, const ArcLengthTable& table, double ext_le, double s);

/// The point at arc length s on the straight extensions of `camber`: the LE one when
/// s <= ext_le, else the TE one.
Eigen::Vector2d extension_point(const CamberResult& camber, double s);

}  // namespace section::detail

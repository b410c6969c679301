// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The camber line at an arc length from its LE point, shared by camber_line's samples and
// the thickness stations (src/camber.cpp); camber_line and the thickness stations on one
// sampled profile and axis (the camber stream measures both).
#include "detail/axis_curve.h"
#include "detail/sampled_profile.h"
#include "section/camber.h"
#include "section/params.h"

#include <Eigen/Core>

#include <memory>
#include <vector>

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

/// Throws section::Error naming the first option of `options` outside its range (camber_line
/// and camber_stream; medial_axis checks options.medial alone): a tolerance of 1e-16 or a
/// count of INT_MAX hung, an edge_prune of 90 degrees trimmed a 49 mm camber line to 11.
void check_options(const MedialAxisOptions& options);
void check_options(const CamberOptions& options);

/// Throws section::Error for a profile of degree 1: its corners pass for edges.
void check_profile_degree(const BSpline& profile);

/// The axis camber_line ends with and its arc-length table (what thickness_stations
/// rebuilds from CamberResult::medial).
struct CamberAxis {
  AxisCurve ax;
  ArcLengthTable table;
};

/// camber_line on `pr` (the profile sampled with options.medial.samples); its final axis
/// into `axis` when given.
CamberResult camber_line(const SampledProfile& pr, const CamberOptions& options,
                         const std::vector<Eigen::Vector2d>& measured, std::unique_ptr<CamberAxis>* axis);

/// The samples thickness_stations measures the profile by.
constexpr int thickness_samples = 1000;

/// thickness_stations on `pr` (the profile sampled with thickness_samples) and on the axis
/// camber_line gave `camber` with.
std::vector<ThicknessStation> thickness_stations(const SampledProfile& pr, const CamberAxis& axis,
                                                 const CamberResult& camber,
                                                 const std::vector<double>& fractions);

/// Whether the pressure side runs forward (in the curve's direction) from the LE point to the
/// TE point: it lies right of the LE-to-TE direction on a counterclockwise profile, and vice
/// versa.
inline bool pressure_runs_forward(const CamberResult& camber) {
  return (camber.pressure_side < 0) == (camber.orientation > 0);
}

/// section_params and split_sides on f, the profile's piecewise form (made once for all
/// that measure a section: the camber line's samples, the checks' and these).
SectionParams section_params(const BSpline& profile, const PiecewiseCurve& f, const CamberResult& camber);
Sides split_sides(const PiecewiseCurve& f, const CamberResult& camber, int count);

}  // namespace section::detail

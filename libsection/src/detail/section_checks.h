// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// check_section and points_noise on a profile sampled by the caller: the camber stream runs
// both on every section of few points, on the same samples.
#include "detail/sampled_profile.h"
#include "section/checks.h"

#include <Eigen/Core>

#include <algorithm>
#include <vector>

namespace section::detail {

/// The samples the checks measure the profile by.
constexpr int check_samples = 4000;

/// check_section on `pr`, the profile sampled with check_samples.
SectionCheck check_section(const SampledProfile& pr, const CamberResult& camber, const SectionParams& params,
                           const CheckOptions& options);

/// The sine of the half angle between the profile's two flanks seen from `vertex`, each
/// taken `reach` away from it along the profile; 0 when the profile is too short for it.
double wedge_sine(const SampledProfile& pr, const Eigen::Vector2d& vertex, double reach);

/// A round edge radius's spread, as the le_radius/te_radius checks judge it: the standard
/// error of the circle fitted on the measured points, taken or not; else, under 8 of them on
/// the arc, the spread a circle fitted on them would have at `noise` (or the arc's rms about
/// its circle, if more), from where they lie; 0 when not known (infinite with under 3).
inline double edge_spread(const Edge& e, double noise) {
  if (e.radius_sigma > 0) return e.radius_sigma;
  if (e.points_sigma > 0) return e.points_sigma;
  const bool few = e.arc_points >= 0 && e.arc_points < 8;
  return few && noise > 0 ? std::max(noise, e.fit_rms) * std::max(1.0, e.arc_spread) : 0;
}

/// The standard errors of `params`' chord, maximum thickness and end angles through the
/// points' noise (options' points_noise over its points); all 0 when the noise is unknown.
ValueSigmas value_sigmas(const SampledProfile& pr, const CamberResult& camber, const SectionParams& params,
                         const CheckOptions& options);

/// points_noise on `pr`, the profile sampled with check_samples.
PointsNoise points_noise(const SampledProfile& pr, const std::vector<Eigen::Vector2d>& points);

}  // namespace section::detail

// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// check_section and points_noise on a profile sampled by the caller: the camber stream runs
// both on every section of few points, on the same samples.
#include "detail/sampled_profile.h"
#include "section/checks.h"

#include <Eigen/Core>

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

/// The standard errors of `params`' chord, maximum thickness and end angles through the
/// points' noise (options' points_noise over its points); all 0 when the noise is unknown.
ValueSigmas value_sigmas(const SampledProfile& pr, const CamberResult& camber, const SectionParams& params,
                         const CheckOptions& options);

/// points_noise on `pr`, the profile sampled with check_samples.
PointsNoise points_noise(const SampledProfile& pr, const std::vector<Eigen::Vector2d>& points);

}  // namespace section::detail

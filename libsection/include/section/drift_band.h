// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// @file drift_band.h
/// A band of scan points around a section plane, wider than the slab, for more points on
/// thin edges: each point is carried onto the plane along the section's drift with height
/// (lean, sweep, twist, taper), fitted as a quadratic field V over the section against
/// the slab's ordered profile, instead of projected straight (which would smear the
/// profile by z V): p at height z goes to p - z V(p) (docs/MORPHOLOGY.md).
#include "section/morphology.h"

#include <Eigen/Core>
#include <cstddef>
#include <vector>

namespace section {

/// Points of `nearby` (u, v, signed height above the plane) within `half_width` of the
/// plane, carried onto it along the section's drift. With `spacing` > 0 and
/// `sparse_half_width` > `half_width`, beside a stretch of the profile where the slab's
/// points lie sparser, as far from the plane as it takes for about one point per
/// `spacing` there, up to `sparse_half_width`. The drift is fitted against loop 0 of `ordered`
/// (what order_section made of the slab of width `slab`) from the points within
/// max(2 half_width, 3 slab) of the plane. Points keep the order of `nearby`. Empty when
/// the drift cannot be fitted (fewer than 64 points pair with the profile, or the fit is
/// inconsistent). Deterministic for given inputs.
std::vector<Eigen::Vector2d> drift_band(const MorphologyResult& ordered,
                                        const std::vector<Eigen::Vector3d>& nearby, double slab,
                                        double half_width, double spacing = 0, double sparse_half_width = 0);

/// The half width of the band for one section: wide enough for one point per `spacing`
/// along the profile, given that the slab (width `slab`) holds `slab_points` points on a
/// profile `length` long; at least slab / 2 (the slab itself), at most `max_widths` slabs.
double band_half_width(std::size_t slab_points, double length, double slab, double spacing,
                       double max_widths);

}  // namespace section

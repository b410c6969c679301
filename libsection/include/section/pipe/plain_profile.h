// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// @file pipe/plain_profile.h
/// A plain profile (an airfoil file, a CMM section: x y a point, in order around it) made a
/// stream for camber_stream, measured the same whichever point it starts at, and its values
/// checked against the same points fitted from the profile's other end.
#include "section/camber.h"
#include "section/checks.h"
#include "section/fit_spline.h"
#include "section/io/stream.h"

#include <Eigen/Core>
#include <future>
#include <vector>

namespace section {

/// The stream of a plain profile (points in mm, in order around it): the spline fit_spline
/// fits to them from their canonical start (canonical_loop), with the points as measured
/// (profile_stream). The same stream whichever point the profile starts at and whichever
/// way it runs. Throws section::Error as fit_spline.
Stream plain_profile_stream(const std::vector<Eigen::Vector2d>& points, const FitSplineOptions& options = {});

/// What flag_start_dependence compares a plain profile's stream with: the same points fitted
/// from the other end of the profile (the point farthest from canonical_loop's start) and
/// measured by camber_stream (not across sections). An empty stream where that fit or its
/// measurement fails: its own issues are not the profile's.
Stream other_end_stream(const std::vector<Eigen::Vector2d>& points, const CamberOptions& options = {},
                        const FitSplineOptions& fit = {});

/// other_end_stream on a thread of its own, started now, so that it runs beside the
/// profile's own fit and measurement: unless `options.threads` is 1 (0 = all cores, one core
/// counting as 1) or no thread can start, when it is made as the future is read. The same
/// stream either way.
std::future<Stream> other_end_stream_async(std::vector<Eigen::Vector2d> points,
                                           const CamberOptions& options = {},
                                           const FitSplineOptions& fit = {});

/// After camber_stream on plain_profile_stream(points): compares its edges with `other`'s,
/// other_end_stream of the same points. Where the curve between the points is not fixed by
/// them, the two fits differ at an edge: an edge whose point moves by more than
/// `CheckOptions::accuracy` of the caliper chord, whose radius by more than its tolerance
/// (le/te_radius_tolerance, or from 0 to a round edge), or whose metal angle by more than
/// 0.5 deg gets the check le_start or te_start in the params row (and the thickness
/// stations) and an issue saying by how much. Nothing is flagged where the other stream
/// measures nothing. Returns the checks it set.
CheckBits flag_start_dependence(Stream& stream, const Stream& other);

/// flag_start_dependence against other_end_stream(points, options, fit), made here.
CheckBits flag_start_dependence(Stream& stream, const std::vector<Eigen::Vector2d>& points,
                                const CamberOptions& options = {}, const FitSplineOptions& fit = {});

}  // namespace section

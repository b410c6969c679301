// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// A sharp edge's vertex where its flanks meet (src/flanks.cpp): the edges' (src/edge.cpp)
// and the checks' (src/checks.cpp).
#include "detail/sampled_profile.h"

#include <Eigen/Core>

#include <vector>

namespace section::detail {

/// Where a sharp edge's flanks meet. A fitted curve rounds a corner where its points are
/// sparse (rows 0.2 mm apart: 25-95 um short of a 13 deg trailing edge), and its rounding
/// reaches about as far as the points are apart; the flanks beyond it are smooth.
struct FlankVertex {
  bool found = false;
  Eigen::Vector2d point{0, 0};
  double sine = 0;          ///< of the half angle between the flanks' axes
  double models_apart = 0;  ///< how far the lines' meeting lies from the parabolas'
  bool parabolas = false;   ///< the point is the parabolas' meeting (else the lines')
};

/// The flanks of the profile's samples on each side of `tip` (the profile's point at the
/// vertex), those between `near` and `far` from it: each fitted by a line in the frame of
/// its principal axis, or by a parabola where the parabolas meet farther from the lines'
/// meeting than 4 times the profile's `noise` moves it (noise / sine along the edge). A
/// line is biased on a curved flank (37 um on NACA 0012's exact TE, flanks 0.5-5 mm), a
/// parabola follows the noise more (chord rms 19-21 against 10-11 um on the generated sharp
/// TE). `found` is false when a flank has under 6 samples there or the flanks are nearly
/// parallel.
FlankVertex flank_meeting(const SampledProfile& pr, const Eigen::Vector2d& tip, double near, double far,
                          double noise);

/// The same from the measured points between `near` and `far` from `tip` ahead of it along
/// `inward` (into the blade), each flank the points on one side of that line, those beyond
/// 3 robust sigmas of its line left out once: the fitted curve's rounding is not in them.
FlankVertex measured_flank_meeting(const std::vector<Eigen::Vector2d>& measured, const Eigen::Vector2d& tip,
                                   const Eigen::Vector2d& inward, double near, double far, double noise);

}  // namespace section::detail

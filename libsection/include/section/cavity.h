// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// @file cavity.h
/// The cavities of a blade section: the loops a hollow blade's section holds inside its
/// profile (cooling channels, a CT scan's inner walls), each with the thinnest wall between
/// it and the profile (docs/CAMBER.md, "Hollow blades").
#include "section/bspline.h"

#include <Eigen/Core>

#include <array>
#include <utility>
#include <vector>

namespace section {

/// Where a closed loop lies against a section's profile.
enum class LoopPlace {
  inside,    ///< wholly inside the profile, apart from it: a cavity
  outside,   ///< wholly outside it (beside it, or around it)
  crossing,  ///< partly inside: the two curves cross or touch
};

/// Options of measure_cavity.
struct CavityOptions {
  int samples =
      4000;  ///< profile samples the wall is first looked for at (the loop's a quarter; at least 256)
  double thin = 0.25;  ///< the thin stretch: where the wall is within this fraction of the least
};

/// A loop against a section's profile and, when it lies inside, the thinnest wall between
/// them: the least distance from the loop to the profile, exact on the two curves.
struct Cavity {
  LoopPlace place = LoopPlace::outside;
  double area = 0;                 ///< the area the loop encloses (of its samples' polygon)
  Eigen::Vector2d centroid{0, 0};  ///< the centroid of that area (a core's position)
  double length = 0;               ///< its length (of the same polygon)
  double wall = 0;                 ///< inside: the least distance from the loop to the profile (else 0)
  /// Inside: where the wall is thinnest, the two nearest points and their parameters.
  Eigen::Vector2d profile_point{0, 0}, cavity_point{0, 0};
  double profile_t = 0, cavity_t = 0;
  /// Inside: the thin stretch, the loop's samples whose distance to the profile's nearest
  /// sample is within options.thin of the least wall, as (loop parameter, that profile
  /// sample's parameter): where a hole in the data could hide a thinner wall (the walls
  /// either side of a channel centred between them are both in it).
  std::vector<std::pair<double, double>> thin;
};

/// Where closed `loop` lies against closed `profile` and, inside it, its wall. Throws
/// section::Error for a curve that is open or degenerate, or fewer than 256 samples.
Cavity measure_cavity(const BSpline& profile, const BSpline& loop, const CavityOptions& options = {});

/// The thinnest wall between a cavity and one stretch of the profile (one side of a blade).
struct CavityWall {
  double wall = 0;  ///< the least distance from the cavity to the stretch
  /// Where it is thinnest: the stretch's point (an end of it when the least lies there)
  /// and the cavity's, and their parameters.
  Eigen::Vector2d profile_point{0, 0}, cavity_point{0, 0};
  double profile_t = 0, cavity_t = 0;
  /// The thin stretch, as Cavity::thin, against this stretch of the profile alone.
  std::vector<std::pair<double, double>> thin;
};

/// The walls between `loop`, a cavity inside `profile`, and each of the two stretches of the
/// profile that its parameters `t0` and `t1` part (a blade section's sides, parted at its
/// LE and TE points): [0] against the stretch from t0 forward to t1, [1] against the one
/// from t1 forward to t0. The lesser of the two is measure_cavity's wall: a cavity near
/// one side has its thinnest wall there, and the other side's tells how far the cavity
/// sits from it (a casting's core shifted toward one side thins that wall and thickens the
/// other). Throws section::Error for curves measure_cavity refuses, a loop not inside the
/// profile, or t0 and t1 the same point.
std::array<CavityWall, 2> side_walls(const BSpline& profile, const BSpline& loop, double t0, double t1,
                                     const CavityOptions& options = {});

}  // namespace section

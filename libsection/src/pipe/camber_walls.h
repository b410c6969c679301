// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// camber_stream's cavities: the loops a hollow blade's section holds inside its profile, and
// the walls table's rows of their thinnest walls (docs/CAMBER.md, "Hollow blades").
#include "detail/piecewise_curve.h"
#include "section/bspline.h"
#include "section/camber.h"
#include "section/cavity.h"
#include "section/checks.h"
#include "section/frame.h"
#include "section/io/stream.h"

#include <Eigen/Core>

#include <map>
#include <utility>
#include <vector>

namespace section::pipe {

/// A loop of a section inside its profile: a cavity, its curve about the section's local origin.
struct SectionCavity {
  int loop = 0;
  BSpline curve;
  Cavity cavity;
};

/// The loops of `section` beside its profile (loop 0; `local`, moved by -origin), each
/// inside it and apart from it and from the others: a hollow blade's cavities, measured
/// about `origin`. `curves`: every fitted loop by (section, loop); `listed`: slice's loops of
/// each section and their areas; `loops`: the section's count. Throws the section's refusal
/// when a loop lies elsewhere (beside the profile, crossing it, within a cavity) or was
/// listed by slice but not fitted: loop 0 alone may then be no profile of the section.
std::vector<SectionCavity> cavities_of(int section, const BSpline& local, const Eigen::Vector2d& origin,
                                       const std::map<std::pair<int, int>, BSpline>& curves,
                                       const std::map<int, std::map<int, double>>& listed, int loops);

/// A wall's standard error through the points' noise: sigma x sqrt(the profile's fit's
/// coefficients a point + the cavity's), each fit's pointwise variance over the noise's;
/// flagged noise when twice it exceeds the accuracy's limit (as an edge radius's spread
/// against its tolerance). Not made when sigma is 0 (the noise unknown).
struct WallNoise {
  double sigma = 0;          ///< the points' noise (the larger of their scatter and the fit's rms)
  double profile_share = 1;  ///< the profile's fit: coefficients over points, at most 1
  double limit = 0;          ///< CheckOptions::accuracy x the profile's size
};

/// What add_walls needs of a measured section.
struct WallsInput {
  int section;
  const Frame& frame;
  const BSpline& curve;                          ///< loop 0 about the local origin
  const detail::PiecewiseCurve& profile;         ///< ... its piecewise form
  double le_t, te_t;                             ///< the LE and TE points' parameters on it
  bool forward_is_pressure;                      ///< the pressure side runs forward from le_t
  const std::vector<Eigen::Vector2d>& measured;  ///< loop 0's measured points, about it too
  const std::map<std::pair<int, int>, std::vector<Eigen::Vector2d>>& loop_points;  ///< the others', as read
  const CamberOptions& options;
  double chord;
  CheckBits section_flags;  ///< the params row's checks that flag the wall
  Eigen::Vector2d origin;   ///< the local origin
  WallNoise noise;
};

/// Appends the walls table's rows of `cavities` to `rows`, each wall flagged wall_measured
/// (with an issue in `issues`) where its thin stretch (Cavity::thin) rests, on either side,
/// on a stretch without measured points longer than the wall (at most thickness_hole of the
/// chord, as a thickness station's contact) and than thickness_hole_spacings times the
/// points' mean distance there: the fits' bridge over it may hide a thinner wall, or be it;
/// and flagged noise where the points' noise leaves it uncertain beyond the accuracy
/// (WallNoise; the cavity's share its curve's control points over its measured points),
/// its standard error in the row. Each row holds the walls to the pressure and the suction
/// side too (side_walls, parted at the LE and TE points), each flagged by the same checks,
/// wall_measured for a hole under its own thin stretch. Each cavity's wall map (options
/// wall_stations evenly along it, each station's least distance to the profile) goes to
/// `map_rows`, flagged as the walls to each side, wall_measured where a hole lies at the
/// station or at its nearest profile point.
void add_walls(const WallsInput& in, const std::vector<SectionCavity>& cavities, std::vector<double>& rows,
               std::vector<double>& map_rows, std::vector<SectionIssue>& issues);

}  // namespace section::pipe

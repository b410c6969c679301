// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// Which stretches of a section's profile the measured points cover: about an edge, and
// along the whole profile for the inscribed circles' contacts (camber's checks le_measured,
// te_measured and thickness_measured rest on it).
#include "detail/piecewise_curve.h"
#include "section/camber.h"

#include <Eigen/Core>

#include <vector>

namespace section::pipe {

/// The edge's own scale: its radius, or a blunt edge's face width (0 for a sharp edge).
inline double edge_size(const Edge& e) {
  return e.radius > 0 ? e.radius : e.face;
}

/// How well the measured points cover an edge (lengths along the profile).
struct EdgeCoverage {
  /// The stretch around the edge point that no measured point covers (a hole over the edge,
  /// or an edge sampled more sparsely than its radius): there the edge point and radius
  /// come from the fit bridging the hole, not from measurements.
  double around = 0;
  /// The longest stretch without measured points that begins within the edge arc, and its
  /// distance from the edge point (0 when it holds it): part of the fitted arc is a bridge.
  double hole = 0, hole_distance = 0;
  /// A sharp edge: the stretch without measured points that holds its vertex, where it is a
  /// hole (longer than 4 times the points' mean distance beside it and 10 times the sharp
  /// radius): the vertex is where the fit's bridge over it turns; 0 otherwise.
  double vertex_hole = 0;
  /// Of the stretches without measured points beginning within the arc reach, the most the
  /// curve bridging one bends away from the straight line between its ends (its sagitta),
  /// with that stretch's length and its distance from the edge point. A bridge strays from
  /// the blade by a share of its bend, and the edge's values with it, however short the
  /// hole is beside the radius (docs/CAMBER.md, "Edges partly not measured").
  double bend = 0, bend_hole = 0, bend_distance = 0;
};

/// The coverage of `edge` of `curve` by the `measured` points; the hole must begin within
/// `arc_reach` edge sizes (radius, or a blunt edge's face width) of the edge point, and the
/// bend's be longer than `hole_spacings` times the points' mean distance beside it.
EdgeCoverage edge_coverage(const detail::PiecewiseCurve& curve, const Edge& edge,
                           const std::vector<Eigen::Vector2d>& measured, double arc_reach,
                           double hole_spacings);

/// How well the measured points cover the profile about a point of it (an inscribed
/// circle's contact; lengths along the profile).
struct ContactCoverage {
  /// The longest stretch that no measured point covers beginning within `near` of the
  /// point, and its distance from it (0 when it holds the point).
  double hole = 0, hole_distance = 0;
  /// The points' mean distance over the reach either side of that hole, the larger of the
  /// two (0: no point).
  double spacing = 0;
};

/// True when `c` holds a hole an inscribed circle's contact may not rest on: longer than
/// `limit` and than `spacings` times the points' mean distance there (evenly sparse points,
/// a CMM row's, are no hole).
bool unmeasured(const ContactCoverage& c, double limit, double spacings);

/// The measured points' coverage of a closed profile: samples every `h` of arc length
/// around it, each counting the points nearest to it within 2h. Built once a section, it
/// answers for every contact.
class ProfileCoverage {
public:
  /// `curve` closed; no samples (every answer empty) when `measured` is empty, h is not
  /// positive or the curve stops advancing (a zero speed).
  ProfileCoverage(const detail::PiecewiseCurve& curve, const std::vector<Eigen::Vector2d>& measured,
                  double h);

  /// The coverage about parameter `t`, over `reach` along the profile either side (a hole
  /// reaching beyond is taken as ending there); the hole must begin within `near` of t.
  ContactCoverage about(double t, double reach, double near) const;

  /// The coverage about the middle of the longest stretch no measured point covers,
  /// anywhere around the profile (none: all empty).
  ContactCoverage longest(double reach) const;

private:
  std::vector<double> t_;     // the samples' parameters, increasing over one period
  std::vector<int> covered_;  // the points each counts
  double h_ = 0, t_min_ = 0, period_ = 0;
};

}  // namespace section::pipe

// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// Which stretches of a section's profile the measured points cover: about an edge, and
// along the whole profile for the inscribed circles' contacts (camber's checks le_measured,
// te_measured and thickness_measured rest on it).
#include "detail/piecewise_curve.h"
#include "section/camber.h"
#include "section/medial_axis.h"

#include <Eigen/Core>

#include <vector>

namespace section::detail {

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
  /// When the hole holds the point: how far the point lies from the hole's nearer end (0
  /// when it lies outside).
  double inside = 0;
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

/// The weight in camber's end fits of a circle with a contact of coverage `c`: 1 outside a
/// hole; inside one, falling to 0 as the hole grows from `limit` and from twice `spacings`
/// times the points' mean distance beside it (a scan's own gaps reach 4-5 of its spacings)
/// to twice the longer of those, and as the contact lies up to a tenth of the hole from its
/// nearer end. Continuous in the hole's length and the contact's place, so that points
/// moved by their last bits (a float format, a pose) do not swap a circle in or out.
double end_fit_weight(const ContactCoverage& c, double limit, double spacings);

/// Sets the weight (InscribedCircle::fit_weight, end_fit_weight of its two contacts, the
/// smaller) of the circles of `circles` (ordered end to end) within `reach` of either end
/// (arc length along their centres), the two end circles apart, against holes in the
/// `measured` points on `curve` longer than `hole` and `spacings` times their mean distance.
void weigh_bridged(const PiecewiseCurve& curve, const std::vector<Eigen::Vector2d>& measured, double reach,
                   double hole, double spacings, std::vector<InscribedCircle>& circles);

}  // namespace section::detail

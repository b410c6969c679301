// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// @file edge.h
/// Leading and trailing edges of a blade section: their model, shapes and measures
/// (docs/CAMBER.md, method steps 4 and 4b). camber_line measures them.
#include <Eigen/Core>

namespace section {

/// Edge model: `round` fits a circle to every edge; `automatic` fits it only to edges
/// detected as round and reports blunt edges with radius 0. A blunt edge with a flat face
/// (Edge::face > 0) and a sharp edge get radius 0 in both models: a face or a vertex is
/// not a circle.
enum class EdgeModel { round, automatic };
/// Detected edge shape.
enum class EdgeShape { round = 0, blunt = 1, sharp = 2 };

/// Every edge shape with its name (the stream's params table writes the shape's number,
/// words go to people): adding a shape is adding it here and to EdgeShape.
struct EdgeShapeName {
  EdgeShape shape;
  const char* name;
};
inline constexpr EdgeShapeName edge_shape_names[] = {
    {EdgeShape::round, "round"}, {EdgeShape::blunt, "blunt"}, {EdgeShape::sharp, "sharp"}};

/// The name of an edge shape ("round", "blunt", "sharp").
inline const char* edge_shape_name(EdgeShape shape) {
  for (const auto& e : edge_shape_names)
    if (e.shape == shape) return e.name;
  return "unknown";
}

/// A leading or trailing edge. The edge point is where the camber line's end tangent meets
/// the profile, or the edge circle when `on_points` and the edge is round and circular.
struct Edge {
  Eigen::Vector2d point{0, 0};         ///< edge point (see above)
  double t = 0;                        ///< its profile parameter
  Eigen::Vector2d center{0, 0};        ///< centre of the circle fitted to the edge arc
  double radius = 0;                   ///< radius of that circle (0 when blunt or sharp in automatic mode)
  double fit_rms = 0;                  ///< rms distance of the edge arc from the fitted circle
  double arc = 0;                      ///< degrees: angle the fitted edge arc subtends at the fitted centre
  double arc_t0 = 0, arc_t1 = 0;       ///< profile parameter range of the edge arc
  double curvature_radius = 0;         ///< 1 / profile curvature at the edge point (0: flat or concave)
  EdgeShape shape = EdgeShape::round;  ///< detected shape
  /// False when the circle leaves the edge arc by more than edge_circularity x the profile
  /// noise: the radius depends on the arc taken, and the camber line keeps its medial end.
  bool circular = true;
  /// The misfit sampling leaves: an eighth of the sagitta h^2 / (8 R) of the widest gap h
  /// between the measured points on the arc (0 with under 8 of them or h > R). The
  /// circularity tolerance is at least edge_circularity x this.
  double sampling = 0;
  double face = 0;         ///< blunt edge with a flat face: the face's width (0 otherwise)
  bool on_points = false;  ///< the circle was refitted to the measured points on the arc
  /// Standard error of `radius` when the circle was refitted on the measured points
  /// (`on_points`): from the fit's covariance and the points' rms about the circle, so it
  /// grows with their noise, as they thin, and with a hole or a short arc (docs/CAMBER.md,
  /// "The edge radius's standard error"). 0 when the circle rests on the fitted curve's arc
  /// alone (no measured points given, too few of them on the arc, or a gap among them) or
  /// the radius is 0.
  double radius_sigma = 0;
  /// Standard error of the edge's point along the end direction when its circle was refitted
  /// on the measured points (`on_points`): the circle's centre and radius errors there, from
  /// the same fit; 0 otherwise.
  double point_sigma = 0;
  /// The measured points on the edge arc (within a quarter radius of its circle); -1 when no
  /// measured points were given. Under 8, too few to refit the circle on (`on_points`): its
  /// radius rests on the fitted curve through a handful of points, each off by the noise.
  int arc_points = -1;
  /// Standard error of the radius of the circle fitted on the measured points on the arc,
  /// whether or not it was taken (`on_points`: taken; not taken when an angular gap among
  /// them exceeds edge_point_gap of the arc, its standard error is over edge_point_sigma of
  /// its radius, or it moved far): 0 when none was fitted (no measured points given, or
  /// under 8 on the arc).
  double points_sigma = 0;
  /// The standard error of a circle's radius fitted on the measured points on the arc, per
  /// unit of their noise, from their angles alone (the linearised fit of centre and
  /// radius): how well so few points can fix it where under 8 lie on the arc (infinity with
  /// under 3, or all at one place); 0 when no measured points were given.
  double arc_spread = 0;
  /// Sharp (closed) edge: the medial branch runs into a vertex of the profile, which is
  /// the edge point (radius 0, centre = point, no arc): where the profile's flanks meet,
  /// off the fitted curve's rounding of the corner (docs/CAMBER.md, "Sharp (closed) edges").
  bool vertex = false;
};

}  // namespace section

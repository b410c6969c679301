#pragma once
/// @file camber.h
/// Mean-camber line of a blade section: the locus of the centres of the circles inscribed
/// in the closed profile (its medial axis, medial_axis.h), extended along its end tangents
/// to the leading and trailing edges (edge.h; Li et al. 2014, section "Mean camber line").
#include "section/bspline.h"
#include "section/edge.h"
#include "section/medial_axis.h"

#include <Eigen/Core>
#include <string>
#include <vector>

namespace section {

/// Options of camber_line and camber_stream (lengths in the profile's units, angles in degrees).
struct CamberOptions {
  MedialAxisOptions medial;        ///< medial-axis seeding and refinement
  EdgeModel edge = EdgeModel::round;  ///< edge model, see EdgeModel
  /// degrees; 0 (default) = the edge arc is grown geometrically: from a core of
  /// +-edge_core degrees around the edge point, as far as the profile stays within
  /// edge_residual core-fit rms of the fitted circle (see docs/CAMBER.md); > 0 = a fixed
  /// arc: the profile around the edge point whose normal turns at most edge_arc/2 either way
  double edge_arc = 0;
  double edge_core = 45;           ///< degrees: half-angle (seen from the edge centre) of the core arc that starts the growth and gives the noise level
  double edge_residual = 3;        ///< the edge arc grows while the profile stays within this many core-fit rms outside the circle
  double edge_noise_residual = 2;  ///< ... or within this many profile_noise, if more (a spline's noise ripples along a longer arc exceed its core's rms; 0 = off)
  double profile_noise = 0;        ///< rms distance of the measured points to the profile (0 = unknown: edge circles are not checked for circularity); camber_stream takes it from the splines table
  double edge_circularity = 3;     ///< an edge circle whose fit rms exceeds this many times max(profile_noise, 1e-4 x its radius) is not circular (Edge::circular)
  double edge_hole = 1;            ///< stream stage: an edge is reported "partly not measured" when a stretch of the profile without measured points, this many edge radii long or longer, begins within edge_hole_reach radii of the edge point
  double edge_hole_reach = 1.2;    ///< edge radii along the profile from the edge point (the half arc of a round edge is 1.57)
  double off_axis = 0.1;           ///< stream stage: a camber line that strays from the medial axis by more than this many inscribed radii (CamberResult::off_axis) is reported as an issue
  bool edge_on_points = true;      ///< with measured points given (camber_line's `measured`, the stream's "points" table): the edge circle is refitted to the measured points on the edge arc (the spline's arc is a little flattened at a tight edge); false = fitted to the spline's arc alone
  double edge_point_gap = 0.25;    ///< ... provided no angular gap between those points exceeds this fraction of the arc
  double edge_point_sigma = 0.05;  ///< ... and the refitted radius's standard error (from the points' scatter about the circle) is at most this fraction of it (a few sparse points on a short arc); else the spline's circle stands
  double edge_max_arc = 240;       ///< degrees: largest edge arc grown (a guard for blunt and unusual edges)
  double tangent_span = 0.15;      ///< fraction of the medial axis length: the end tangents (inlet/outlet angles, extensions) are fitted (cubic least squares) to the axis over this length from each end, averaging the profile noise at the edges; 0 = the axis spline's end slope (exact profiles)
  double edge_prune = 20;          ///< degrees: medial circles at the ends whose contacts subtend less than twice this are noise, trimmed
  double blunt_flatness = 2;       ///< an edge is blunt when its curvature radius at the edge point exceeds this many fitted radii (flat tip)
  double blunt_rms = 0.02;         ///< ... and the fit rms exceeds this fraction of the fitted radius
  double blunt_face = 0.8;         ///< an edge is blunt (cut off) when the profile's cap 0.1 W deep is straight and at least this fraction of W wide, W the blade's width near the end (a round edge's cap is 0.63 W)
  double sharp_ratio = 0.01;       ///< an edge is sharp when its fitted radius is below this fraction of the largest inscribed diameter
  double min_slenderness = 2;      ///< medial axis length / largest inscribed diameter below which the section is not a blade
  /// Leading-edge direction: when non-zero, the LE is the end lying farther along it;
  /// zero = the LE is the end nearer the maximum thickness.
  Eigen::Vector2d le_direction{0, 0};
  /// Stream stage: the leading-edge direction in 3D (the cloud's x, y, z), e.g. upstream
  /// along the machine axis; each section uses its projection onto the section's plane
  /// (table frames; a plain profile's plane is x, y). Used when non-zero and le_direction
  /// is zero.
  Eigen::Vector3d le_direction_3d{0, 0, 0};
  double le_thickness_margin = 0.05;  ///< stream stage: an LE chosen by thickness whose maximum thickness lies within this fraction of the camber length of mid-chord gets an issue (the rule is then a guess)
  int samples = 201;               ///< points of the sampled camber line (CamberResult::points)
  /// Stream stage: thickness stations as fractions of the camber length from the LE.
  std::vector<double> stations{0.05, 0.1, 0.15, 0.2, 0.25, 0.3, 0.35, 0.4, 0.45, 0.5,
                               0.55, 0.6, 0.65, 0.7, 0.75, 0.8, 0.85, 0.9, 0.95};
  int side_samples = 201;          ///< stream stage: points per side in the "sides" table
  int threads = 0;                 ///< stream stage: worker threads over the sections (output identical for any count); 0 = all cores
};

/// The mean-camber line from the LE point to the TE point.
struct CamberResult {
  MedialAxis medial;               ///< the medial branch, oriented LE to TE, edge centres as ends when round
  Edge le, te;                     ///< leading and trailing edges
  std::vector<Eigen::Vector2d> points;  ///< sampled camber line, LE point to TE point, extensions included
  std::vector<double> s;           ///< arc length of each point from the LE point
  std::vector<double> radius;      ///< inscribed radius at each point (the end circle's radius on the extensions)
  double length = 0;               ///< camber length, LE point to TE point
  Eigen::Vector2d le_tangent{1, 0}, te_tangent{1, 0};  ///< unit camber directions (toward the TE) at the edge ends
  double ext_le = 0, ext_te = 0;   ///< lengths of the straight extensions at each end
  InscribedCircle thickest;        ///< largest inscribed circle
  double thickest_s = 0;           ///< its arc length from the LE point
  /// +1 when the pressure (concave) side lies left of the LE-to-TE direction, -1 right.
  int pressure_side = -1;
  bool le_by_direction = false;    ///< LE chosen by CamberOptions::le_direction (else by thickness)
  double orientation = 1;          ///< +1 when the profile runs counterclockwise, -1 clockwise
  /// The largest amount by which a sample between the extensions lies nearer the profile
  /// than its inscribed radius says (0 on the medial axis), and its arc length from the LE
  /// point: where no inscribed circle could be solved the line is interpolated, and a
  /// large value means it strays from the axis there.
  double off_axis = 0, off_axis_s = 0;
};

/// Mean-camber line of the closed blade profile `profile`: the medial axis, with round
/// edges ending at the centre of the circle fitted to the edge arc, extended along its end
/// tangents to the profile (LE and TE points), oriented LE to TE. Lengths in the profile's
/// units. Throws section::Error `camber: ...` when the profile is not blade-like (a circle,
/// a square: medial axis shorter than min_slenderness largest diameters).
/// `measured`: the measured points of the profile, when known (the edge circles are then
/// fitted to those on the edge arcs, see CamberOptions::edge_on_points).
CamberResult camber_line(const BSpline& profile, const CamberOptions& options = {},
                         const std::vector<Eigen::Vector2d>& measured = {});

}  // namespace section

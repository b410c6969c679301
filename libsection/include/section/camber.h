// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// @file camber.h
/// Mean-camber line of a blade section: the medial axis of the closed profile (the locus
/// of the centres of its inscribed circles, medial_axis.h), ending at the edges' centres
/// (edge.h) and extended along its end tangents to the leading and trailing edges (Li et
/// al. 2014, section "Mean camber line"). docs/CAMBER.md explains each option.
#include "section/bspline.h"
#include "section/edge.h"
#include "section/medial_axis.h"

#include <Eigen/Core>
#include <string>
#include <vector>

namespace section {

/// Options of camber_line and camber_stream (lengths in the profile's units, angles in
/// degrees; "stream" marks what only camber_stream reads). Both refuse an option outside its
/// range with a section::Error naming it (the ranges: docs/ROBUSTNESS.md, "The library's API").
struct CamberOptions {
  MedialAxisOptions medial;           ///< medial-axis seeding and refinement
  EdgeModel edge = EdgeModel::round;  ///< edge model, see EdgeModel
  double edge_arc = 0;                ///< degrees; 0 = grow the edge arc, > 0 = fixed normal-turning arc
  double edge_core = 45;              ///< degrees: half-angle of the core arc the growth starts from
  double edge_residual = 3;           ///< the arc grows while within this many core-fit rms of the circle
  double edge_noise_residual = 2;     ///< ... or this many profile_noise, if more (0 = off)
  double profile_noise = 0;           ///< rms of the points about the profile (0 = unknown, no circularity)
  double edge_circularity = 3;        ///< not circular: fit rms over this x max(noise, 1e-4 R)
  double edge_hole = 1;               ///< stream: a hole this many edge radii long near an edge is an issue
  double edge_hole_reach = 1.2;       ///< stream: ... beginning within this many radii of the edge point
  /// Stream: a shorter hole there whose bridge bends (its sagitta) so far that this share of
  /// the bend exceeds the accuracy the values stand within is an issue too (0 = off). On the
  /// generated blades a bridge strayed by 12-23 % of its bend (median), nine in ten under 26-58 %.
  double edge_bridge = 0.1;
  /// Stream: the thickest circle touching the profile within a stretch without measured
  /// points longer than this fraction of the chord, and longer than thickness_hole_spacings
  /// times the points' mean distance there, flags the maximum thickness (the fit bridges it);
  /// a thickness station's circle touching one, that station's row of table thickness.
  double thickness_hole = 0.05;
  double thickness_hole_spacings = 4;  ///< stream: see thickness_hole
  double off_axis = 0.1;               ///< stream: inscribed radii off the medial axis that make an issue
  bool edge_on_points = true;          ///< refit the edge circle to the measured points on the arc
  double edge_point_gap = 0.25;        ///< ... if no angular gap between them exceeds this fraction of it
  double edge_point_sigma = 0.05;      ///< ... and the radius's standard error is at most this fraction
  double edge_max_arc = 240;           ///< degrees: largest edge arc grown
  double tangent_span = 0.15;          ///< axis length fraction the end tangents are fitted over (0 = spline)
  /// With measured points: a circle within twice tangent_span of an end whose contact lies in
  /// a stretch without measured points longer than this fraction of the axis length, and
  /// than twice thickness_hole_spacings times their mean distance beside it, counts less in
  /// the end fits, nothing from twice that length on (InscribedCircle::fit_weight; 0 = every
  /// circle counts fully). The fit's bridge over such a hole strays from the blade and tilts
  /// the end direction, and the edge point and chord with it.
  double end_hole = 0.01;
  double edge_prune = 20;      ///< degrees: end circles whose contacts subtend < 2x this are trimmed
  double blunt_flatness = 2;   ///< blunt: curvature radius at the edge point over this x radius
  double blunt_rms = 0.02;     ///< ... and the fit rms over this fraction of the radius
  double blunt_face = 0.8;     ///< blunt (cut off): a straight cap at least this fraction of W wide
  double sharp_ratio = 0.01;   ///< sharp: radius below this fraction of the largest diameter
  double min_slenderness = 2;  ///< not a blade: axis length below this x largest diameter
  /// The LE is the end farther along this direction when non-zero; zero = the LE is the
  /// blunter end (see le_bluntness), else the end nearer the maximum thickness.
  Eigen::Vector2d le_direction{0, 0};
  /// The blunter end is the LE when the other end is sharp (its last medial circle under
  /// sharp_ratio of the largest diameter) and this one's is at least this many times it;
  /// 0 = thickness alone.
  double le_bluntness = 3;
  /// Stream: the LE direction in 3D (the cloud's x, y, z), projected onto each section's
  /// plane; used when non-zero and le_direction is zero.
  Eigen::Vector3d le_direction_3d{0, 0, 0};
  double le_thickness_margin = 0.05;  ///< stream: LE by thickness this near mid-chord is an issue
  int samples = 201;                  ///< points of the sampled camber line (CamberResult::points)
  /// Stream: thickness stations as fractions of the camber length from the LE.
  std::vector<double> stations{0.05, 0.1, 0.15, 0.2, 0.25, 0.3, 0.35, 0.4, 0.45, 0.5,
                               0.55, 0.6, 0.65, 0.7, 0.75, 0.8, 0.85, 0.9, 0.95};
  int side_samples = 201;  ///< stream: points per side in the "sides" table
  int wall_stations =
      100;  ///< stream: stations of each cavity's wall map (table wall_map), evenly along it; 0 = none
  int threads = 0;  ///< stream: worker threads over the sections (0 = all cores)
  /// Stream: check the sections against each other (check_blade_stream, flag_scan_layers)
  /// and flag every params row when the stream's notes say its unit is doubtful or a view was registered
  /// unconfirmed. Off for one part of a stream split into parts: the check needs every
  /// section, so the caller does it across the parts (as `camber`'s StageRun::hold does).
  bool across_sections = true;
};

/// The mean-camber line from the LE point to the TE point.
struct CamberResult {
  MedialAxis medial;  ///< the medial branch, oriented LE to TE, edge centres as ends when round
  Edge le, te;        ///< leading and trailing edges
  std::vector<Eigen::Vector2d> points;  ///< sampled camber line, LE point to TE point, extensions included
  std::vector<double> s;                ///< arc length of each point from the LE point
  std::vector<double> radius;           ///< inscribed radius at each point (the end circle's on extensions)
  double length = 0;                    ///< camber length, LE point to TE point
  Eigen::Vector2d le_tangent{1, 0}, te_tangent{1, 0};  ///< unit camber directions (toward the TE) at the ends
  double ext_le = 0, ext_te = 0;                       ///< lengths of the straight extensions at each end
  InscribedCircle thickest;                            ///< largest inscribed circle
  double thickest_s = 0;                               ///< its arc length from the LE point
  /// +1 when the pressure (concave) side lies left of the LE-to-TE direction, -1 right.
  int pressure_side = -1;
  bool le_by_direction = false;  ///< LE chosen by CamberOptions::le_direction
  bool le_by_bluntness = false;  ///< LE chosen as the blunter end (else by thickness)
  double orientation = 1;        ///< +1 when the profile runs counterclockwise, -1 clockwise
  /// The most by which a sample between the extensions lies nearer the profile than its
  /// inscribed radius says (0 on the medial axis; large where the line was interpolated),
  /// and that sample's arc length from the LE point.
  double off_axis = 0, off_axis_s = 0;
  /// Degrees between the end directions that a cubic and a quartic give over the same
  /// span of the axis (CamberOptions::tangent_span; 0 without it): the cubic's bias where
  /// the camber's curvature changes fast near the edge. And the span's length.
  double le_fit_model = 0, te_fit_model = 0, tangent_span_length = 0;
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

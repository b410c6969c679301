// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// @file checks.h
/// Consistency checks of the measured parameters (docs/CAMBER.md, "Checks"): every value of
/// a params row is tested against the geometry it came from before it is written, and
/// across the sections of a blade against its neighbours. A value that fails a check is
/// flagged (a bit of the params table's `flags` column, each bit a named check) and
/// described in the section's issue; it is never printed bare.
#include "section/bspline.h"
#include "section/camber.h"
#include "section/params.h"

#include <cstdint>
#include <string>
#include <vector>

namespace section {

/// A mask of check bits: the params table's `flags` column (one bit a check; more checks
/// than 32, and a double holds every mask exactly).
using CheckBits = std::uint64_t;

/// The checks, one bit each in the params table's `flags` column (docs/FORMAT.md).
enum class Check : CheckBits {
  le_radius = 1u << 0,        ///< LE circle larger than the blade there, or off the profile over its arc
  te_radius = 1u << 1,        ///< the same at the TE
  le_circle = 1u << 2,        ///< LE not circular: its radius and point depend on the arc taken
  te_circle = 1u << 3,        ///< the same at the TE
  le_measured = 1u << 4,      ///< LE (partly) not measured: its values bridge a hole in the data
  te_measured = 1u << 5,      ///< the same at the TE
  le_point = 1u << 6,         ///< LE point off the profile
  te_point = 1u << 7,         ///< TE point off the profile
  chord = 1u << 8,            ///< chord disagrees with the profile's extent along it
  caliper = 1u << 9,          ///< caliper chord disagrees with the profile's extent along its line
  inlet_angle = 1u << 10,     ///< inlet angle off the camber line's direction near the LE
  outlet_angle = 1u << 11,    ///< outlet angle off the camber line's direction near the TE
  le_choice = 1u << 12,       ///< LE chosen by a near tie, or at the other end from the blade's LEs
  off_axis = 1u << 13,        ///< camber line off the medial axis (interpolated there)
  jump_chord = 1u << 14,      ///< chord jumps from the neighbouring sections
  jump_thickness = 1u << 15,  ///< max thickness jumps
  jump_stagger = 1u << 16,    ///< stagger jumps
  jump_inlet = 1u << 17,      ///< inlet angle jumps
  jump_outlet = 1u << 18,     ///< outlet angle jumps
  jump_camber = 1u << 19,     ///< camber angle jumps
  jump_le_radius = 1u << 20,  ///< LE radius jumps
  jump_te_radius = 1u << 21,  ///< TE radius jumps
  units = 1u << 22,           ///< the input's unit is doubtful (read as mm though it looks like inches or um)
  layers = 1u << 23,  ///< the points lie in two layers (views merged misregistered): the profile runs between
  le_vertex = 1u << 24,  ///< a sharp LE's vertex at a wedge so thin that the noise moves it far along it
  te_vertex = 1u << 25,  ///< the same at the TE
  le_sharp = 1u << 26,  ///< LE taken as sharp (radius 0), but the points resolve a small round edge there, or
                        ///< are too sparse to tell
  te_sharp = 1u << 27,  ///< the same at the TE
  noise = 1u << 28,     ///< the points' noise leaves the profile uncertain beyond the accuracy (every length
                        ///< carries it)
  inlet_fit = 1u << 29,     ///< inlet angle set by the end fit: a cubic and a quartic over its span disagree
  outlet_fit = 1u << 30,    ///< the same at the TE
  registration = 1u << 31,  ///< a view merged into the input was registered but not confirmed (slice --view)
  thickness_measured = CheckBits(1) << 32,  ///< the thickest circle touches a hole in the data
  /// the section is no airfoil (thicker than half its chord, or flat faces about as wide as
  /// it is thick at both ends): the plane cuts a platform, a root or shroud, a fixture
  airfoil = CheckBits(1) << 33,
  /// a hole in the data along the profile: the area and centroid include the fit's bridge
  area_measured = CheckBits(1) << 34,
  /// a plain profile's LE moves with the point it starts at: fitted from its other end, the
  /// curve between its points there gives another edge point, radius or angle
  le_start = CheckBits(1) << 35,
  te_start = CheckBits(1) << 36,  ///< the same at the TE
  /// a cavity's thinnest wall (the walls table; or its thinnest to a side, in that side's
  /// flags) rests on a stretch of the profile or the cavity without measured points: the
  /// wall there is the fits' bridge
  wall_measured = CheckBits(1) << 37,
  /// the points' noise leaves the chord uncertain beyond its tolerance: the end directions'
  /// standard errors turn the edge points about the end circles (ValueSigmas::chord)
  chord_noise = CheckBits(1) << 38,
  thickness_noise = CheckBits(1) << 39,  ///< the same for the maximum thickness (its two contacts)
  inlet_noise = CheckBits(1) << 40,      ///< the same for the inlet angle (the camber line's end fit)
  outlet_noise = CheckBits(1) << 41,     ///< the same for the outlet angle
};

/// How many checks there are: a flags mask is below 2^check_count.
inline constexpr int check_count = 42;

/// A check's name (the word the issues use) and the params columns whose values it flags
/// (`wall`: the walls table's, docs/FORMAT.md). An
/// edge whose circle is doubtful flags its metal angle too: the camber line is extended to
/// that edge's point along its circle, so its end direction rests on the same points; one
/// whose point is doubtful (not circular, not measured) flags the chord and stagger it ends,
/// and what is measured along the camber line from it: the camber line, its length, the
/// place of the maximum thickness and the thickness table's stations.
struct CheckName {
  Check check;
  const char* name;
  const char* columns;  ///< the params columns it flags, space-separated (and `wall`)
};
inline constexpr CheckName check_names[] = {
    {Check::le_radius, "le_radius", "le_radius le_center inlet_angle camber_angle"},
    {Check::te_radius, "te_radius", "te_radius te_center outlet_angle camber_angle"},
    {Check::le_circle, "le_circle",
     "le_radius le_center le_point inlet_angle camber_angle chord stagger camber_line camber_length "
     "max_thickness_pos thickness"},
    {Check::te_circle, "te_circle",
     "te_radius te_center te_point outlet_angle camber_angle chord stagger camber_line camber_length "
     "max_thickness_pos thickness"},
    {Check::le_measured, "le_measured",
     "le_radius le_center le_point inlet_angle camber_angle chord stagger camber_line caliper_chord "
     "caliper_stagger camber_length max_thickness_pos thickness area centroid"},
    {Check::te_measured, "te_measured",
     "te_radius te_center te_point outlet_angle camber_angle chord stagger camber_line caliper_chord "
     "caliper_stagger camber_length max_thickness_pos thickness area centroid"},
    {Check::le_point, "le_point",
     "le_point chord stagger camber_line camber_length max_thickness_pos thickness"},
    {Check::te_point, "te_point",
     "te_point chord stagger camber_line camber_length max_thickness_pos thickness"},
    {Check::chord, "chord",
     "chord stagger le_point te_point camber_line camber_length max_thickness max_thickness_pos inlet_angle "
     "outlet_angle camber_angle thickness"},
    {Check::caliper, "caliper", "caliper_chord caliper_stagger"},
    {Check::inlet_angle, "inlet_angle", "inlet_angle camber_angle"},
    {Check::outlet_angle, "outlet_angle", "outlet_angle camber_angle"},
    {Check::le_choice, "le_choice", "every column that depends on which end is the LE"},
    {Check::off_axis, "off_axis", "camber_length max_thickness max_thickness_pos"},
    {Check::jump_chord, "jump_chord", "chord"},
    {Check::jump_thickness, "jump_thickness", "max_thickness"},
    {Check::jump_stagger, "jump_stagger", "stagger"},
    {Check::jump_inlet, "jump_inlet", "inlet_angle"},
    {Check::jump_outlet, "jump_outlet", "outlet_angle"},
    {Check::jump_camber, "jump_camber", "camber_angle"},
    {Check::jump_le_radius, "jump_le_radius", "le_radius"},
    {Check::jump_te_radius, "jump_te_radius", "te_radius"},
    {Check::units, "units", "every length column (and, through the defaults, every value)"},
    {Check::registration, "registration", "every value (a view's points may lie slid and turned)"},
    {Check::layers, "layers",
     "max_thickness max_thickness_pos thickness camber_line le_radius le_center te_radius te_center le_point "
     "te_point chord stagger caliper_chord camber_length inlet_angle outlet_angle camber_angle wall"},
    {Check::le_vertex, "le_vertex",
     "le_point chord stagger camber_line camber_length inlet_angle camber_angle max_thickness_pos thickness"},
    {Check::te_vertex, "te_vertex",
     "te_point chord stagger camber_line camber_length outlet_angle camber_angle max_thickness_pos "
     "thickness"},
    {Check::le_sharp, "le_sharp", "le_radius le_center"},
    {Check::te_sharp, "te_sharp", "te_radius te_center"},
    {Check::noise, "noise",
     "max_thickness max_thickness_pos thickness le_radius le_center te_radius te_center le_point te_point "
     "chord stagger caliper_chord camber_line camber_length inlet_angle outlet_angle camber_angle wall"},
    {Check::inlet_fit, "inlet_fit",
     "inlet_angle camber_angle le_point chord stagger camber_line camber_length max_thickness_pos thickness"},
    {Check::outlet_fit, "outlet_fit",
     "outlet_angle camber_angle te_point chord stagger camber_line camber_length max_thickness_pos "
     "thickness"},
    {Check::thickness_measured, "thickness_measured", "max_thickness max_thickness_pos"},
    {Check::airfoil, "airfoil", "every column (what was measured is no blade section)"},
    {Check::area_measured, "area_measured", "area centroid"},
    {Check::le_start, "le_start",
     "le_radius le_center le_point inlet_angle camber_angle chord stagger camber_line camber_length "
     "max_thickness_pos thickness"},
    {Check::te_start, "te_start",
     "te_radius te_center te_point outlet_angle camber_angle chord stagger camber_line camber_length "
     "max_thickness_pos thickness"},
    {Check::wall_measured, "wall_measured", "wall"},
    {Check::chord_noise, "chord_noise", "chord stagger le_point te_point"},
    {Check::thickness_noise, "thickness_noise", "max_thickness"},
    {Check::inlet_noise, "inlet_noise", "inlet_angle camber_angle"},
    {Check::outlet_noise, "outlet_noise", "outlet_angle camber_angle"},
};

/// The bit of a check in a flags mask.
constexpr CheckBits bit(Check c) {
  return static_cast<CheckBits>(c);
}

/// The name of a check ("le_radius", ...).
const char* check_name(Check check);

/// The check bits a flags column's value holds: 0 for a value that is no mask (negative,
/// fractional parts dropped as a cast would, 2^check_count or more, not a number).
CheckBits flags_mask(double value);

/// The names of the checks in `flags` ("le_radius", ...), in bit order, joined by
/// `separator`; "" for none.
std::string check_names_text(CheckBits flags, const char* separator = ", ");

/// The bits of `flags` (a params row's) whose checks flag the params column `column` (or
/// the walls table's `wall`): each check the columns check_names lists for it, units,
/// registration and airfoil every column, le_choice every column that is not the same
/// whichever end is the LE (all but chord, camber_length, max_thickness, area,
/// caliper_chord, centroid and wall). 0 when none does.
CheckBits checks_flagging(CheckBits flags, const char* column);

/// Options of check_section (lengths in the profile's units, angles in degrees).
struct CheckOptions {
  double noise = 0;  ///< rms of the measured points about the profile (0 = unknown)
  double points_noise =
      0;              ///< the points' own scatter (points_noise(), or a dense fit's rms; 0 = unknown) ...
  double points = 0;  ///< ... over this many independent points (0: the check is not made)
  /// ... at these profile parameters (PointsNoise::params; empty: the thickness is not checked
  /// apart): the thickest circle's contacts, each where its spans hold few of the points.
  std::vector<double> point_params;
  double accuracy = 1.5e-4;  ///< fraction of the profile's size: a profile uncertain by more flags its values
  double noise_factor = 4;   ///< a distance is off beyond this many noise rms ...
  double floor = 1e-5;       ///< ... plus this fraction of the profile's size
  double tangent_length = 0.05;  ///< camber-length fraction over which the end directions are taken
  double angle_floor = 1;        ///< degrees: least angle tolerance
  double fit_model = 0.25;       ///< degrees: most an end direction may change from a cubic to a quartic fit
  double vertex_reach = 0.02;    ///< camber-length fraction over which a sharp edge's wedge is taken
  double arc_shortfall = 40;  ///< degrees: a round edge's arc may fall this far short of its flanks' turning
  /// Fractions of a round edge's radius: the most twice its spread may be (the standard
  /// error of the circle fitted on the measured points, taken or not, else, where its arc
  /// holds under 8 of them, the larger of the noise and the arc's rms about the circle times
  /// their arc_spread), so that the radius stands within them about 19 times in 20 (0 = not
  /// checked).
  double le_radius_tolerance = 0.03;
  double te_radius_tolerance = 0.10;  ///< the same at the TE
  /// An airfoil is at most this thick over its chord (the thickest blades, roots of
  /// impulse turbines, about 0.3; a platform's or root block's section 0.5-1) ...
  double airfoil_thickness = 0.5;
  /// ... and does not end in flat faces wider than this fraction of its thickness at both
  /// ends (a cut-off trailing edge is a fraction of it; a plate's or block's ends are as
  /// wide as it is thick).
  double airfoil_face = 0.5;
  /// A value is flagged (chord_noise, thickness_noise, inlet_noise, outlet_noise) where this
  /// many of its standard errors (ValueSigmas) exceed its tolerance: about 369 times in 370
  /// the value then stands within it of what the scan's surface gives (0 = not checked).
  double value_sigmas = 3;
  double chord_tolerance = 2.5e-4;       ///< fraction of the chord (10 um on a 40 mm chord)
  double thickness_tolerance = 1.25e-4;  ///< fraction of the chord (5 um on a 40 mm chord)
  double angle_tolerance = 0.5;          ///< degrees, inlet and outlet angles
  /// Knot spans of the fit over which its error at two places is taken as correlated
  /// (falling linearly to none): what ties the camber line's centres' errors together.
  double noise_correlation = 1.5;
};

/// Standard errors of a section's values through the points' noise (CheckOptions's
/// points_noise over its points, each place of the profile averaging the points its knot
/// spans hold): how far a new scan of the same surface would move them. All 0 when the
/// noise is unknown.
struct ValueSigmas {
  double chord = 0;          ///< its edge points' moves along it, the end directions' turning them
  double max_thickness = 0;  ///< its two contacts' moves
  double inlet_angle = 0;    ///< degrees: the camber line's end fit over its centres' moves
  double outlet_angle = 0;   ///< degrees
};

/// One failed check: what was measured and the most it may be (same unit).
struct Finding {
  Check check = Check::le_radius;
  double value = 0;  ///< the measured discrepancy (see check_section)
  double limit = 0;  ///< the most it may be
  /// le_radius/te_radius: failed by the radius's spread (value = twice it, limit = the
  /// tolerance's share of the radius), not by its circle's fit to the profile.
  bool spread = false;
};

/// The checks a section failed.
struct SectionCheck {
  CheckBits flags = 0;            ///< bits of the failed checks
  std::vector<Finding> findings;  ///< one per failed check, in bit order
  ValueSigmas sigmas;             ///< the values' standard errors the *_noise checks judge
};

/// Checks a section's parameters against its profile (docs/CAMBER.md, "Checks"); sets the
/// bits le_radius/te_radius, le_point/te_point, chord, caliper, inlet_angle/outlet_angle:
/// - round edge: value = how far its circle passes the profile (radius minus the centre's
///   distance to the profile; radius plus it when the centre lies outside), limit =
///   noise_factor x max(noise, fit rms) + floor x size; or, with the noise known, the
///   largest distance of the edge arc from the circle, limit 2 x noise_factor x
///   max(noise, 1e-4 R); or value = twice the radius's spread (Edge::radius_sigma where
///   its circle was refitted on the measured points, else Edge::points_sigma of the circle
///   fitted on them and not taken, else, where the arc holds under 8 of them, the larger
///   of the noise and the arc's rms about the circle times Edge::arc_spread: a circle
///   resting on the fitted curve through a handful of points), limit =
///   le_radius_tolerance (or te_radius_tolerance) x R: the points cannot fix the radius
///   that closely (Finding::spread);
/// - edge point: its distance to the profile, limit noise_factor x noise + floor x size;
///   a sharp edge's vertex (le_vertex/te_vertex): that limit / sin(a), a the wedge's half
///   angle over vertex_reach x the camber length (how far the noise moves the vertex along
///   the edge), limit twice that limit (flagged below a 60 deg wedge);
/// - chord: the profile's extent along the chord line minus the chord, limit
///   sum of R (1 - cos a) over both edges (a: the end tangent against the chord line) +
///   the distance limit; also flagged when negative beyond that limit, and when the chord
///   differs from its edge points' distance by more than the distance limit (a params row
///   edited or made elsewhere; NaN);
/// - caliper: |caliper chord - the profile's extent along the caliper line|, the distance limit;
/// - angles: |end tangent - the end direction extrapolated from the camber line's two
///   chords of tangent_length x camber length from the edge|, limit max(angle_floor, the
///   turning between those chords) + the angle noise x noise / length subtends.
SectionCheck check_section(const BSpline& profile, const CamberResult& camber, const SectionParams& params,
                           const CheckOptions& options = {});

/// The scatter (rms, along the normal) of measured points about a smooth curve, from the
/// points themselves: each point against the quadratic through its two neighbours either
/// side along `profile` (the points ordered by their place on it), that residual divided by
/// its standard deviation in noise units, robust (1.4826 x the median). Unlike a fit's
/// rms it does not shrink when the fit follows the points (as many coefficients as points).
/// Points much closer than half the mean spacing count once (`points`: those counted).
/// 0 with fewer than 12 points.
struct PointsNoise {
  double rms = 0;              ///< the scatter, in the points' unit
  double points = 0;           ///< the points it rests on (independent ones)
  std::vector<double> params;  ///< their parameters on the profile, ascending
};
PointsNoise points_noise(const BSpline& profile, const std::vector<Eigen::Vector2d>& points);

/// A section of a blade as check_blade sees it.
struct BladeSection {
  double height = 0;     ///< position along the blade (the plane's offset along the mean normal)
  SectionParams params;  ///< its parameters (chord, max thickness, radii, angles read)
  CheckBits flags = 0;   ///< the checks its own values failed (the params' flags)
};

/// Options of check_blade: the least jump flagged per kind of value.
struct BladeCheckOptions {
  double angle = 2;         ///< degrees (stagger, inlet, outlet, camber angle)
  double length = 0.02;     ///< fraction of the chord (chord, max thickness: of the max thickness)
  double radius = 0.25;     ///< fraction of the edge radius
  double thickness = 0.05;  ///< fraction of the max thickness
  double spread = 6;        ///< ... or this many robust sigmas of the blade's own residuals, if more
  int min_sections = 3;     ///< fewer sections: nothing is checked
};

/// A value that jumps from its neighbours.
struct Jump {
  std::size_t index = 0;  ///< into the sections given
  Check check = Check::jump_chord;
  double value = 0;     ///< the section's value
  double expected = 0;  ///< from its neighbours (interpolated by height, or extrapolated at an end)
  double limit = 0;     ///< the least jump flagged
};

/// The values that jump from their neighbours across the sections of one blade (any
/// order; sorted by height): a value is compared with the line through its two neighbours
/// (the two nearest at an end, where the limit doubles, followed no farther out than twice
/// their spacing; a length is expected at 0 or more) and flagged when it departs by more
/// than the limit and more than its neighbours do. Of the values beyond their limits, one
/// its own section's checks flag already goes first: as a neighbour it would make the
/// right values beside it jump.
std::vector<Jump> check_blade(const std::vector<BladeSection>& sections,
                              const BladeCheckOptions& options = {});

}  // namespace section

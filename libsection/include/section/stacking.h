// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// @file stacking.h
/// The whole blade from its measured sections (docs/BLADE.md): the stacking line (the
/// sections' centroids, LE and TE points in 3D, each fitted as a smooth curve along the
/// span), twist, lean, bow, sweep, and the chord and thickness along the span. Each value
/// that rests on a flagged params value, or that the sections cannot define (too few,
/// out of order), is flagged, never given bare.
#include "section/bspline.h"
#include "section/checks.h"
#include "section/frame.h"
#include "section/params.h"

#include <Eigen/Core>
#include <cstdint>
#include <vector>

namespace section {

/// The blade's checks, one bit each in the blade table's `flags` column (docs/BLADE.md).
enum class StackCheck : std::uint32_t {
  twist = 1u << 0,  ///< the section's or the reference's stagger is flagged by camber
  position =
      1u << 1,      ///< the section's or the reference's centroid is doubtful (an edge not measured, units)
  le = 1u << 2,     ///< the LE point is flagged
  te = 1u << 3,     ///< the TE point is flagged
  chord = 1u << 4,  ///< the chord is flagged
  thickness = 1u << 5,  ///< the max thickness is flagged
  bow = 1u << 6,        ///< bow undefined (fewer than 3 sections) or an end section's position doubtful
  order = 1u << 7,      ///< the ids are not in span order, or two sections share a span
  curve = 1u << 8,      ///< the stacking line is a straight line (2 sections) or the section lies off it
};

/// A blade check's name, why it fails and the blade columns it flags.
struct StackCheckName {
  StackCheck check;
  const char* name;
  const char* why;      ///< in the issue's words
  const char* columns;  ///< space-separated
};
inline constexpr StackCheckName stack_check_names[] = {
    {StackCheck::twist, "twist", "camber flagged the stagger here or at the reference section",
     "stagger twist"},
    {StackCheck::position, "position",
     "the centroid here or at the reference section is doubtful (an edge not measured, or the units)",
     "centroid lean sweep bow axial_bow off_line"},
    {StackCheck::le, "le", "camber flagged the LE point", "le"},
    {StackCheck::te, "te", "camber flagged the TE point", "te"},
    {StackCheck::chord, "chord", "camber flagged the chord", "chord"},
    {StackCheck::thickness, "thickness", "camber flagged the max thickness", "max_thickness"},
    {StackCheck::bow, "bow", "fewer than 3 sections, or a doubtful hub or tip centroid", "bow axial_bow"},
    {StackCheck::order, "order", "the section ids are not in span order, or two sections share a span",
     "span bow axial_bow off_line"},
    {StackCheck::curve, "curve", "the stacking line is straight (2 sections) or the centroid lies off it",
     "off_line"},
};

/// One measured section as the stacking sees it.
struct StackedSection {
  int id = 0;            ///< the section id
  Frame frame;           ///< maps its (u, v) to 3D (to_world)
  SectionParams params;  ///< centroid, le_point, te_point, chord, max_thickness, stagger read
  CheckBits flags = 0;   ///< camber's checks it failed (section/checks.h bits)
};

/// How the blade is measured. Directions need not be unit length.
struct StackingOptions {
  int reference = -1;  ///< section id whose twist, lean and sweep are 0; -1 = the first by span (the hub)
  /// false: a planar stack: span s = the frames' mean normal, axial a = the reference
  /// frame's u made normal to s, tangential t = s x a. true: a rotor about the axis below:
  /// a = axis_direction, s = the radial direction at each point, t = s x a; the span
  /// coordinate is the radius and tangential distances are radius x angle.
  bool rotor = false;
  Eigen::Vector3d axis_point = Eigen::Vector3d::Zero();       ///< a point of the machine axis (rotor)
  Eigen::Vector3d axis_direction = Eigen::Vector3d::UnitX();  ///< its direction (rotor)
  int control_points = 0;  ///< of each fitted line; 0 = min(sections, 4 + sections / 4)
  int samples = 41;        ///< points of each fitted line in the result (>= 2)
  double off_line = 0.01;  ///< length: a centroid farther than this from its fitted line sets `curve`
};

/// The blade's values at one section (lengths in the sections' unit, angles in degrees).
struct StackedValues {
  int id = 0;
  double span = 0;       ///< span coordinate: the centroid's offset along s (rotor: its radius)
  double fraction = 0;   ///< (span - hub span) / (tip span - hub span)
  double stagger = 0;    ///< angle of TE - LE in (a, t) from a, (-180, 180]
  double twist = 0;      ///< stagger - the reference's, wrapped to (-180, 180]
  double lean = 0;       ///< tangential coordinate of the centroid - the reference's
  double sweep = 0;      ///< axial coordinate of the centroid - the reference's
  double bow = 0;        ///< tangential departure from the line through the hub and tip centroids
  double axial_bow = 0;  ///< axial departure from that line
  double off_line = 0;   ///< distance of the centroid from its fitted stacking line at its span
  Eigen::Vector3d centroid{0, 0, 0}, le{0, 0, 0}, te{0, 0, 0};  ///< in 3D (frame.to_world)
  double chord = 0, max_thickness = 0;                          ///< the params'
  bool reference = false;                                       ///< the reference section
  std::uint32_t flags = 0;                                      ///< StackCheck bits
};

/// A point of the fitted lines, at one span coordinate.
struct StackSample {
  double span = 0, fraction = 0;
  Eigen::Vector3d centroid{0, 0, 0}, le{0, 0, 0}, te{0, 0, 0};  ///< the three lines there
  double lean = 0, sweep = 0;                                   ///< of the centroid line there
};

/// The whole blade.
struct StackingResult {
  std::vector<StackedValues> sections;  ///< in span order, hub first
  int reference = 0;                    ///< the reference section's id
  /// The fitted lines as curves of the (axial, tangential) coordinates with the span
  /// coordinate as their parameter (open B-splines of degree min(3, sections - 1)).
  BSpline centroid_line, le_line, te_line;
  std::vector<StackSample> samples;  ///< `samples` points of the lines from hub to tip
  /// Planar stack: the directions (a, t, s); rotor: a = the axis, t and s at the reference centroid.
  Eigen::Vector3d axial{1, 0, 0}, tangential{0, 1, 0}, span_direction{0, 0, 1};
};

/// The blade measured from its sections (any order; at least 2). Throws section::Error
/// (`stacking: ...`) with fewer than 2 sections, two with one id, a reference that is not
/// among them, a non-finite value, all sections at one span, or (rotor) a centroid on the axis.
StackingResult stacking(const std::vector<StackedSection>& sections, const StackingOptions& options = {});

/// The name of a blade check ("twist", ...).
const char* stack_check_name(StackCheck check);

/// Whether camber's `flags` (section/checks.h bits) flag the params value `column`
/// ("stagger", "chord", "max_thickness", "le_point", "te_point", "centroid"): a check
/// listing the column, le_choice for the values that depend on which end is the LE, units
/// for every value, le_measured and te_measured for the centroid too (the area centroid
/// rests on the whole profile, and an edge bridging a hole moves it).
bool params_flagged(CheckBits flags, const char* column);

}  // namespace section

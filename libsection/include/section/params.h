// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// @file params.h
/// Blade section parameters measured on a profile and its mean-camber line: chord,
/// thickness, edge radii, angles, area, caliper chord, thickness stations and the two
/// sides split at the edges.
#include "section/bspline.h"
#include "section/camber.h"

#include <Eigen/Core>
#include <vector>

namespace section {

/// Parameters of one section. Lengths in the profile's units, angles in degrees measured
/// counterclockwise from the +u axis, in (-180, 180].
struct SectionParams {
  double chord = 0;                     ///< |TE point - LE point|
  double camber_length = 0;             ///< camber line length, LE point to TE point
  double max_thickness = 0;             ///< largest inscribed diameter
  double max_thickness_pos = 0;         ///< its position along the camber line, 0 at LE, 1 at TE
  double le_radius = 0, te_radius = 0;  ///< radii of the circles fitted to the edge arcs
  double le_curvature_radius = 0, te_curvature_radius = 0;  ///< 1 / curvature at the edge points
  double stagger = 0;                                       ///< angle of the chord line, LE to TE
  double inlet_angle = 0;                                   ///< camber tangent (toward the TE) at the LE
  double outlet_angle = 0;                                  ///< camber tangent (toward the TE) at the TE
  double camber_angle = 0;                         ///< inlet_angle - outlet_angle (the turning), wrapped
  double area = 0;                                 ///< enclosed area
  Eigen::Vector2d centroid{0, 0};                  ///< area centroid
  Eigen::Vector2d le_point{0, 0}, te_point{0, 0};  ///< edge points
  /// Caliper laid against the pressure side: the line touching the profile at both ends
  /// of the concave side (its bitangent); the chord is the profile's extent along it.
  double caliper_chord = 0;
  double caliper_stagger = 0;                          ///< angle of that line, oriented LE to TE
  Eigen::Vector2d caliper_le{0, 0}, caliper_te{0, 0};  ///< its two touching points
  bool caliper_found = false;  ///< false when the pressure side is not concave (caliper = chord line)
};

/// Section parameters of `profile` from its camber line.
SectionParams section_params(const BSpline& profile, const CamberResult& camber);

/// Thickness at one station of the camber line.
struct ThicknessStation {
  double fraction = 0;          ///< station: arc length from the LE point / camber length
  double s = 0;                 ///< arc length from the LE point
  Eigen::Vector2d point{0, 0};  ///< camber point (the inscribed circle's centre)
  double thickness = 0;         ///< inscribed diameter (on an extension: width across the camber normal)
  Eigen::Vector2d pressure{0, 0}, suction{0, 0};  ///< contact points on each side
  double pressure_t = 0, suction_t = 0;           ///< their parameters on the profile
};

/// Thickness at `fractions` of the camber length (values outside [0, 1] are an error; at 0
/// and 1, the edge points, it is 0). Throws section::Error for a profile check_spline
/// refuses or a camber line not from camber_line.
std::vector<ThicknessStation> thickness_stations(const BSpline& profile, const CamberResult& camber,
                                                 const std::vector<double>& fractions);

/// The two sides of the profile split at the LE and TE points, each sampled from LE to
/// TE with `count` points evenly in curve parameter (ends included).
struct Sides {
  std::vector<Eigen::Vector2d> pressure;  ///< concave side
  std::vector<Eigen::Vector2d> suction;   ///< convex side
};
/// The two sides of `profile` split at the LE and TE points of `camber` (see Sides).
Sides split_sides(const BSpline& profile, const CamberResult& camber, int count = 201);

/// Enclosed area and area centroid of a closed curve (Green's theorem, exact quadrature
/// per knot span); the area is signed, positive counterclockwise.
double enclosed_area(const BSpline& curve, Eigen::Vector2d* centroid = nullptr);

}  // namespace section

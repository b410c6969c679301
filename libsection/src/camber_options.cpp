// SPDX-License-Identifier: GPL-3.0-or-later
// The ranges of camber_line's options, checked where a caller hands them in.
#include "detail/camber_line.h"
#include "section/error.h"

#include <cstdio>
#include <string>

namespace section {

namespace detail {

namespace {

// Throws "camber: NAME is V, not in RANGE" unless lo <= v <= hi (a NaN is never in range).
void in_range(const char* name, double v, double lo, double hi, const char* range) {
  if (v >= lo && v <= hi) return;
  char text[200];
  std::snprintf(text, sizeof text, "camber: %s is %.6g, not in %s", name, v, range);
  throw Error(text);
}

}  // namespace

void check_options(const MedialAxisOptions& o) {
  in_range("medial.samples", o.samples, 16, 1e6, "16..1000000");
  in_range("medial.stations", o.stations, 0, 1e5, "0..100000");
  in_range("medial.iterations", o.iterations, 0, 100, "0..100");
  in_range("medial.tolerance", o.tolerance, 1e-14, 1e-2, "[1e-14, 0.01] (relative to the profile's size)");
  for (const auto& p : o.seed)
    if (!p.allFinite()) throw Error("camber: a point of medial.seed is not finite");
}

void check_profile_degree(const BSpline& profile) {
  if (profile.degree < 2)
    throw Error("camber: the profile is of degree " + std::to_string(profile.degree) +
                ", 2 or more is needed (a polygon's corners moved a leading edge point by 6.7 mm)");
}

void check_options(const CamberOptions& o) {
  check_options(o.medial);
  const double big = 1e300;
  in_range("edge_arc", o.edge_arc, 0, 360, "[0, 360] degrees");
  in_range("edge_core", o.edge_core, 1e-3, 90, "(0, 90] degrees");
  in_range("edge_residual", o.edge_residual, 1e-6, big, "(0, inf)");
  in_range("edge_noise_residual", o.edge_noise_residual, 0, big, "[0, inf)");
  in_range("profile_noise", o.profile_noise, 0, big, "[0, inf)");
  in_range("edge_circularity", o.edge_circularity, 1e-6, big, "(0, inf)");
  in_range("edge_hole", o.edge_hole, 0, big, "[0, inf)");
  in_range("edge_hole_reach", o.edge_hole_reach, 0, big, "[0, inf)");
  in_range("edge_bridge", o.edge_bridge, 0, big, "[0, inf)");
  in_range("thickness_hole", o.thickness_hole, 0, 1, "[0, 1]");
  in_range("end_hole", o.end_hole, 0, 1, "[0, 1]");
  in_range("thickness_hole_spacings", o.thickness_hole_spacings, 0, big, "[0, inf)");
  in_range("off_axis", o.off_axis, 0, big, "[0, inf)");
  in_range("edge_point_gap", o.edge_point_gap, 0, 1, "[0, 1]");
  in_range("edge_point_sigma", o.edge_point_sigma, 0, big, "[0, inf)");
  in_range("edge_max_arc", o.edge_max_arc, 1e-3, 360, "(0, 360] degrees");
  in_range("tangent_span", o.tangent_span, 0, 0.9, "[0, 0.9]");
  in_range("edge_prune", o.edge_prune, 0, 45, "[0, 45] degrees");
  in_range("blunt_flatness", o.blunt_flatness, 0, big, "[0, inf)");
  in_range("blunt_rms", o.blunt_rms, 0, big, "[0, inf)");
  in_range("blunt_face", o.blunt_face, 0, 1, "[0, 1]");
  in_range("sharp_ratio", o.sharp_ratio, 0, 1, "[0, 1]");
  in_range("min_slenderness", o.min_slenderness, 0, big, "[0, inf)");
  in_range("le_bluntness", o.le_bluntness, 0, big, "[0, inf)");
  in_range("le_thickness_margin", o.le_thickness_margin, 0, 0.5, "[0, 0.5]");
  in_range("samples", o.samples, 2, 1e6, "2..1000000");
  in_range("side_samples", o.side_samples, 2, 1e6, "2..1000000");
  in_range("wall_stations", o.wall_stations, 0, 1e6, "0..1000000");
  if (!o.le_direction.allFinite() || !o.le_direction_3d.allFinite())
    throw Error("camber: le_direction is not finite");
  for (double f : o.stations) in_range("a station", f, 0, 1, "[0, 1]");
}

}  // namespace detail

}  // namespace section

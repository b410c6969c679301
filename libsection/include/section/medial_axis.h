// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// @file medial_axis.h
/// Medial axis of a closed blade profile: the main branch of the locus of the centres of
/// the circles inscribed in it, seeded by a Delaunay triangulation and refined on the
/// exact spline (docs/CAMBER.md, method steps 1-3). The camber line is built on it.
#include "section/bspline.h"

#include <Eigen/Core>
#include <vector>

namespace section {

/// A circle inside the profile touching it on both sides.
struct InscribedCircle {
  Eigen::Vector2d center{0, 0};    ///< camber point
  double radius = 0;               ///< half the local thickness
  Eigen::Vector2d left{0, 0};      ///< contact on the side left of the camber direction
  Eigen::Vector2d right{0, 0};     ///< contact on the side right of the camber direction
  double t_left = 0, t_right = 0;  ///< profile parameters of the contacts
  /// Weight in the end directions' fits (camber_line with measured points): below 1 where a
  /// contact lies in a hole in them, 0 where the circle rests on the fit's bridge over a
  /// long one (CamberOptions::end_hole).
  double fit_weight = 1;
};

/// Options of medial_axis.
struct MedialAxisOptions {
  int samples = 1000;       ///< profile samples triangulated for the seed (more for thin edges)
  int stations = 120;       ///< inscribed circles solved along the axis (denser at the ends)
  int iterations = 3;       ///< most refinement passes (stations placed again on the refined axis)
  double tolerance = 1e-9;  ///< relative to the profile size: Newton and end-search accuracy
  /// Optional seed (e.g. the stream's morphological skeleton), ordered end to end; empty =
  /// the Delaunay medial axis of the profile samples.
  std::vector<Eigen::Vector2d> seed;
};

/// The refined main branch of the medial axis of a closed profile.
struct MedialAxis {
  std::vector<InscribedCircle> circles;  ///< from one end to the other, the ends included
  BSpline curve;                         ///< open cubic through the centres (light fairness)
  int seed_points = 0;                   ///< points of the seed branch
  int iterations = 0;                    ///< refinement passes done
  double change = 0;                     ///< largest move of an end in the last pass
};

/// Main branch of the medial axis of the closed curve `profile` (either orientation):
/// seeded from the Delaunay triangulation of `samples` curve samples (Voronoi vertices of
/// the inside triangles, longest path) or from `options.seed`, then refined: each
/// station's circle is solved on the axis normal so that it touches both sides (equal
/// distance, both contacts foot points, Newton on the exact spline), and the branch ends
/// where the inscribed circles degenerate (the circle osculates the profile or its two
/// contacts merge), located by bisection. Throws section::Error when no branch exists.
MedialAxis medial_axis(const BSpline& profile, const MedialAxisOptions& options = {});

/// The circle inscribed in `profile` whose centre lies on the line through `point` along
/// `normal`, touching the profile near the parameters `t_left` and `t_right` (Newton on
/// equal distance and both foot-point conditions). False when it does not converge.
bool inscribed_circle(const BSpline& profile, const Eigen::Vector2d& point, const Eigen::Vector2d& normal,
                      double t_left, double t_right, InscribedCircle& circle);

}  // namespace section

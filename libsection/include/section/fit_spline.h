// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// @file fit_spline.h
/// The `fitspline` stage (Li et al. 2014, section 2.4): a closed cubic B-spline fitted by
/// least squares to the smoothed profile, then refined by squared-distance minimisation
/// (Wang, Pottmann and Liu 2006) against the measured points, with knots inserted where
/// the curve misses the data (blade edges).
#include "section/bspline.h"

#include <Eigen/Core>
#include <map>
#include <utility>
#include <vector>

namespace section {

/// Options of fit_spline and fit_spline_stream (lengths in mm; scale them for other
/// units). What each does in the method: docs/FITSPLINE.md.
struct FitSplineOptions {
  int degree = 3;                    ///< spline degree
  int control_points = 0;            ///< control points per loop; 0 = adaptive to `tolerance`
  double tolerance = 0.00025;        ///< mm, adaptive: systematic RMS deviation a span may keep
  double initial_span = 2.0;         ///< mm, adaptive: knot spacing of the first curve (merged where sparse)
  double min_span = 0.04;            ///< mm, adaptive: shortest span (half of it on a gross misfit)
  double min_span_points = 2;        ///< adaptive: fewest measured points per knot span
  double exact_min_span_points = 4;  ///< adaptive: the same on near-exact data (noise below exact_noise)
  double exact_noise = 0.001;        ///< mm: noise sigma below which the data count as near-exact
  int max_control_points = 1500;     ///< adaptive: cap on control points per loop
  int max_rounds = 12;               ///< adaptive: knot insertion rounds
  int max_iterations = 30;           ///< distance-minimisation iterations per round
  int first_iterations = 4;  ///< adaptive: iterations of the first curve, whose curvature places the knots
  /// adaptive: holes longer than this many median spacings keep only the knots their bridge
  /// needs (4 = the stable candidate, docs/FITSPLINE.md); 0 = off
  double bridge_factor = 0;
  double convergence = 1e-2;       ///< stop iterating when the RMS changes by less than this fraction
  double fairness = 1e-5;          ///< weight of the control polygon's second differences
  double smoothing_length = 0.15;  ///< mm: strength of the change-of-curvature penalty; 0 = off
  double outlier_distance = 0;     ///< mm: isolated points farther off are ignored; 0 = automatic
  double outlier_floor = 0.02;     ///< mm: least automatic outlier distance (6 noise sigmas otherwise)
  int samples = 0;                 ///< stream stage: points per loop in the "samples" table (0 = none)
  double sample_spacing = 0;       ///< mm, stream stage: spacing of "samples" (0 = use `samples`)
  double gap_factor = 10;          ///< a stretch without points longer than this many spacings is a hole
  double layer_ratio = 1.6;        ///< residual spread (noise sigmas) marking two layers; 0 = off
  double layer_separation = 2;     ///< noise sigmas: least separation of two layers reported
  int threads = 0;                 ///< stream stage: worker threads over the loops; 0 = all cores
  /// The most samples a loop gets (`samples`, or its length over `sample_spacing`): beyond, an error.
  static constexpr int max_samples = 1000000;
};

/// What fit_spline returns: the fitted curve and its fit diagnostics.
struct FitSplineResult {
  BSpline spline;            ///< the fitted closed curve
  double rms = 0;            ///< mm, RMS distance measured points -> curve (outliers excluded)
  double max = 0;            ///< mm, largest such distance
  double p95 = 0;            ///< mm, 95th percentile of such distances
  double noise = 0;          ///< mm, noise sigma estimated from the residuals
  int iterations = 0;        ///< distance-minimisation iterations over all rounds
  int rounds = 0;            ///< knot insertion rounds done (adaptive mode)
  int control_points = 0;    ///< control points of the result
  int points = 0;            ///< measured points used
  int outliers = 0;          ///< measured points ignored as outliers
  double max_gap = 0;        ///< mm, longest stretch of the curve without a measured point (bridged: a guess)
  double gap_start = 0;      ///< curve parameter where that stretch begins
  double gap_end = 0;        ///< curve parameter where it ends (below gap_start when it wraps past t_max)
  double spacing = 0;        ///< mm, median distance along the curve between consecutive measured points
  double layers = 0;         ///< mm, separation of two layers of points (misregistered views); 0 = none
  double layers_length = 0;  ///< mm, length of profile over which they were found
  /// Holes: stretches between consecutive measured points longer than `gap_factor`
  /// spacings, longest first (parameters as gap_start/gap_end, length in mm along the curve).
  struct Gap {
    double start = 0, end = 0, length = 0;
  };
  std::vector<Gap> gaps;
};

/// Fits a closed B-spline to one loop. `profile` is the ordered loop the first curve is
/// fitted to (smoothed points, or the ordered measured points); `measured` are the points
/// the curve is refined against (any order). Lengths in mm (any unit works if the
/// length options are scaled alike). Throws section::Error (`fit_spline: ...`) on too few
/// points, a degenerate loop (all points on a line), or a fitted curve that folds or
/// crosses itself.
FitSplineResult fit_spline(const std::vector<Eigen::Vector2d>& profile,
                           const std::vector<Eigen::Vector2d>& measured,
                           const FitSplineOptions& options = {});

/// The points of a closed loop (ordered along it) from a canonical start, the same way
/// round: counterclockwise, from the point farthest from the points' centroid (ties to the
/// least x, then y): on a blade section, the tip of an edge, mostly the thinner one.
/// fit_spline's curve depends on where its profile starts and which way it runs (the first
/// curve's spans begin at the first point, and the later knots follow that curve's
/// curvature): on a profile whose edges hold few points, its chord by up to 0.2 mm and its
/// edge radii by a fifth. A loop given from any start, either way round, gives one curve
/// from this order, and the first curve gets a knot at the edge's tip, where a thin edge
/// needs one most (started mid-flank instead, a T-Blade3 tip section's 10 um trailing edge
/// came out sharp and 0.65 mm off). Fewer than 3 points are returned as they are.
std::vector<Eigen::Vector2d> canonical_loop(std::vector<Eigen::Vector2d> loop);

/// True when the closed curve crosses itself, has a cusp, or doubles back alongside itself
/// (a finger: two opposite hairpin turns close together), tested on a dense polyline.
bool self_intersects(const BSpline& curve);

/// True when curve parameter t lies in the gap (which may wrap past the curve's end).
bool in_gap(const BSpline& curve, const FitSplineResult::Gap& gap, double t);

}  // namespace section

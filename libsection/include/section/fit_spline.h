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

/// Options of fit_spline and fit_spline_stream (lengths in mm; scale them for other units).
struct FitSplineOptions {
  int degree = 3;                 ///< spline degree
  int control_points = 0;         ///< control points per loop; 0 = adaptive to `tolerance`
  double tolerance = 0.00025;     ///< mm, adaptive mode: largest systematic (non-noise) RMS deviation allowed in a knot span before it is split
  double initial_span = 2.0;      ///< mm, adaptive mode: knot spacing (along the profile) of the first curve
  double min_span = 0.04;         ///< mm, adaptive mode: spans are not split below this length
  double min_span_points = 2;     ///< 1, adaptive mode: fewest measured points per knot span (the change-of-curvature penalty keeps sparse spans from fitting the noise)
  double exact_min_span_points = 4;  ///< 1, adaptive mode: the same floor on near-exact data (noise sigma below exact_noise), where the change-of-curvature penalty does not act
  double exact_noise = 0.001;     ///< mm: estimated noise sigma below which the data count as near-exact
  int max_control_points = 1500;  ///< adaptive mode: cap on control points per loop
  int max_rounds = 12;            ///< adaptive mode: knot insertion rounds
  int max_iterations = 30;        ///< distance-minimisation iterations per round
  double convergence = 1e-2;      ///< 1: stop iterating when the RMS changes by less than this fraction
  double fairness = 1e-5;         ///< 1: weight of the control-polygon second differences, relative to the data term (keeps holes well posed)
  double smoothing_length = 0.15; ///< mm: weight of the change-of-curvature penalty (normal component of C''', zero on lines and circular arcs), as the length over which it balances data of mean density at 5 um noise (the weight scales with the noise variance); cubic curves only; 0 = off (docs/FITSPLINE.md)
  double outlier_distance = 0;    ///< mm: isolated measured points farther than this from the curve are ignored; 0 = automatic (6 noise sigmas, at least `outlier_floor`)
  double outlier_floor = 0.02;    ///< mm: least automatic outlier distance
  int samples = 0;                ///< stream stage: points per loop written to the "samples" table (0 = none unless sample_spacing)
  double sample_spacing = 0;      ///< mm, stream stage: arc-length spacing of the "samples" table (0 = use `samples`)
  double gap_factor = 10;         ///< 1: a stretch of the curve without measured points longer than this many median spacings is listed as a hole (FitSplineResult::gaps, table "gaps")
  double layer_ratio = 1.6;       ///< 1: a stretch where the residuals spread more than this many noise sigmas is a second layer of points (misregistered views; FitSplineResult::layers); 0 = not looked for
  double layer_separation = 2;    ///< 1: ... and reported when the layers lie at least this many noise sigmas apart (noise alone spreads a few windows too)
  int threads = 0;                ///< stream stage: worker threads over the loops (output identical for any count); 0 = all cores
};

/// What fit_spline returns: the fitted curve and its fit diagnostics.
struct FitSplineResult {
  BSpline spline;                 ///< the fitted closed curve
  double rms = 0;                 ///< mm, RMS distance measured points -> curve (outliers excluded)
  double max = 0;                 ///< mm, largest such distance
  double p95 = 0;                 ///< mm, 95th percentile of such distances
  double noise = 0;               ///< mm, noise sigma estimated from the residuals
  int iterations = 0;             ///< distance-minimisation iterations over all rounds
  int rounds = 0;                 ///< knot insertion rounds done (adaptive mode)
  int control_points = 0;         ///< control points of the result
  int points = 0;                 ///< measured points used
  int outliers = 0;               ///< measured points ignored as outliers
  double max_gap = 0;             ///< mm, longest stretch of the curve (along it) without a measured point: a bridged hole, where the curve is a guess
  double gap_start = 0;           ///< curve parameter where that stretch begins
  double gap_end = 0;             ///< curve parameter where it ends (may be below gap_start: it wraps past t_max)
  double spacing = 0;             ///< mm, median distance along the curve between consecutive measured points
  double layers = 0;              ///< mm, separation of two layers of measured points found along the profile (views merged with a misregistration: the curve runs between them); 0 = none
  double layers_length = 0;       ///< mm, length of profile over which they were found
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

/// True when the closed curve crosses itself, has a cusp, or doubles back alongside itself
/// (a finger: two opposite hairpin turns close together), tested on a dense polyline.
bool self_intersects(const BSpline& curve);

/// True when curve parameter t lies in the gap (which may wrap past the curve's end).
bool in_gap(const BSpline& curve, const FitSplineResult::Gap& gap, double t);

}  // namespace section

// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// @file extras/score.h
/// Errors of measured results against the exact truth of a generated section
/// (generate.h): the scores of the accuracy tests, bench/evaluate_pipeline and
/// docs/ACCURACY.md, computed in one place.
#include "section/bspline.h"
#include "section/extras/generate.h"
#include "section/io/stream.h"

#include <Eigen/Core>

#include <string>
#include <vector>

namespace section {

/// How a fitted curve is scored.
struct FitScoreOptions {
  int samples = 20000;  ///< curve samples (even in parameter) at which the distance to the truth is taken
  /// mm: a sample is "near data" when a measured point lies within this distance of it along
  /// the true profile (across a thin edge the other side's points are close but say nothing of the tip)
  double near = 0.3;
};

/// Distances of a fitted curve to the true profile (lengths in mm).
struct FitScore {
  double rms = 0;        ///< RMS over the whole curve
  double rms_near = 0;   ///< RMS over the samples near data
  double max_near = 0;   ///< largest distance near data
  double gap = 0;        ///< largest distance elsewhere: where the curve bridges a hole
  double where_max = 0;  ///< arc length along the true profile (from the LE point) of max_near
  double where_gap = 0;  ///< the same for gap
};

/// Scores `curve` against `truth`; `measured` are the section's measured points (in-plane).
FitScore score_fit(const BSpline& curve, const std::vector<Eigen::Vector2d>& measured,
                   const SectionTruth& truth, const FitScoreOptions& options = {});

/// Errors of one section's camber results; signed ones are measured - true.
struct CamberScore {
  double camber_rms = 0, camber_max = 0;     ///< distance of the camber samples to the true camber line
  double chord = 0;                          ///< signed
  double max_thickness = 0;                  ///< signed
  double le_radius = 0, te_radius = 0;       ///< signed, relative (0.01 = 1 %)
  double inlet_angle = 0, outlet_angle = 0;  ///< signed, degrees in (-180, 180]
  double le_point = 0, te_point = 0;         ///< distances of the edge points from the true ones
  /// The params' standard errors of the radii (lengths; 0: none reported)
  double le_radius_sigma = 0, te_radius_sigma = 0;
  /// ... and of the chord, the maximum thickness (lengths) and the end angles (degrees)
  double chord_sigma = 0, max_thickness_sigma = 0, inlet_angle_sigma = 0, outlet_angle_sigma = 0;
};

/// Scores section `section` of a stream that holds camber's tables (camber, params).
/// Throws section::Error when the stream has no params row for the section.
CamberScore score_camber(const Stream& stream, int section, const SectionTruth& truth);

/// How errors compare with the standard errors reported with them, from |error| / sigma of
/// each value: a normal error gives a median of 0.67, a 90th percentile of 1.64, a 99th of
/// 2.58, 4.6 % beyond 2 and 0.27 % beyond 3.
struct Calibration {
  std::size_t count = 0;                ///< values
  double median = 0, p90 = 0, p99 = 0;  ///< percentiles of |error| / sigma
  double beyond2 = 0, beyond3 = 0;      ///< fractions beyond 2 and 3 sigma
};

/// The calibration of `ratios` (|error| / sigma each); all zero when empty.
Calibration calibration(std::vector<double> ratios);

/// `calibration(ratios)` in words: "median 0.67, 90 % 1.64, 99 % 2.58, 0.3 % beyond 3 (N)".
std::string calibration_text(const std::vector<double>& ratios);

/// Angle wrapped to (-180, 180] degrees.
double wrap_degrees(double angle);

}  // namespace section

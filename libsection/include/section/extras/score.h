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
};

/// Scores section `section` of a stream that holds camber's tables (camber, params).
/// Throws section::Error when the stream has no params row for the section.
CamberScore score_camber(const Stream& stream, int section, const SectionTruth& truth);

/// Angle wrapped to (-180, 180] degrees.
double wrap_degrees(double angle);

}  // namespace section

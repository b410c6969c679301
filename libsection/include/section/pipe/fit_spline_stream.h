// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// @file pipe/fit_spline_stream.h
/// The fitspline stage on the stream: tables "points" (and "smoothed") -> "splines",
/// "spline_knots", "spline_ctrl", "gaps", "samples"; and the splines and holes read back.
#include "section/fit_spline.h"
#include "section/io/stream.h"

#include <map>
#include <utility>
#include <vector>

namespace section {

/// Stream stage: fits every (section, loop) of the "points" table (first curve from the
/// "smoothed" table when present) and writes the tables "splines", "spline_knots",
/// "spline_ctrl", "gaps" and, when samples are requested, "samples" (docs/FORMAT.md). A loop
/// that cannot be fitted is recorded in stream.issues (stage "fitspline"), the others go
/// on. Throws section::Error when the "points" table is missing or lacks a column.
void fit_spline_stream(Stream& stream, const FitSplineOptions& options = {});

/// The holes of a stream written by fit_spline_stream (table "gaps"), by (section, loop),
/// longest first; empty when the stream has no such table (written before it existed).
std::map<std::pair<int, int>, std::vector<FitSplineResult::Gap>> gaps(const Stream& stream);

/// The splines of a stream written by fit_spline_stream, by (section, loop). Throws
/// section::Error when the tables are missing or inconsistent.
std::map<std::pair<int, int>, BSpline> splines(const Stream& stream);

}  // namespace section

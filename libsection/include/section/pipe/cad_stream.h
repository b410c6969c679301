// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// @file pipe/cad_stream.h
/// The curves of a stream for the CAD writers (io/cad.h): each fitted loop's spline with
/// its section's frame.
#include "section/io/cad.h"
#include "section/io/stream.h"

#include <vector>

namespace section {

/// The splines of a stream written by fitspline (tables "splines", "spline_knots",
/// "spline_ctrl"), each with its section's frame (table "frames"; the identity when the
/// stream has none, as for a plain profile), by section and loop; only loop 0 of each
/// section unless `all_loops`. Throws section::Error when the tables are missing or
/// inconsistent.
std::vector<CadCurve> cad_curves(const Stream& stream, bool all_loops = true);

}  // namespace section

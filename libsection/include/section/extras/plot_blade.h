// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// @file extras/plot_blade.h
/// The whole blade (stacking.h) drawn: twist, lean and bow, sweep, chord and thickness
/// against the span, one panel each, and the blade seen along the span (`blade --plot`).
#include "section/stacking.h"

#include <string>

namespace section {

/// A standalone SVG document: four panels side by side sharing the span axis (up): twist
/// (deg); lean and bow; sweep; chord and max thickness (lengths in `units`). Each section
/// is a dot (a flagged value: a hollow red ring, class `flagged`), the fitted centroid line
/// a curve on the lean and sweep panels (class `line`); a fifth, square panel shows the
/// blade seen along the span (class `top-view`): each section's chord line and centroid,
/// axial right and tangential up at one scale, with the fitted centroid line.
std::string plot_blade_svg(const StackingResult& blade, const std::string& units = "mm");

}  // namespace section

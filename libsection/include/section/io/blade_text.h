// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// @file io/blade_text.h
/// The whole blade (stacking.h) as a table for people: `blade --format table`.
#include "section/stacking.h"

#include <string>

namespace section {

/// The blade's values one line per section from hub to tip, each line at most 120 columns:
/// lengths with 4 decimals, angles with 3, fraction with 3; a flagged value is followed by
/// '!' and the row ends with the names of its failed checks (docs/BLADE.md). `units` names
/// the length unit in the heading.
std::string format_blade_text(const StackingResult& blade, const std::string& units = "mm");

}  // namespace section

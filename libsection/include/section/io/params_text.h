// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// @file io/params_text.h
/// The params table as text for people (camber on a terminal): one block per section,
/// chosen digits per quantity, shapes, sides and checks in words. The stream and the CSV
/// files keep full precision; this is for reading only (docs/FORMAT.md, "For people").
#include "section/io/stream.h"

#include <string>

namespace section {

/// Options of format_params_text.
struct ParamsTextOptions {
  int width = 120;     ///< columns no line is longer than (issues are shortened to fit)
  int max_issues = 4;  ///< issue lines per section; more are counted in one line
};

/// The `params` table of `stream` (with its `frames` table, when present, for each
/// section's plane, and its issues) as aligned text: a header line with the units (lengths
/// in mm to 4 decimals, i.e. 0.1 um; angles in degrees to 3 decimals; positions as a
/// fraction of the camber length to 3 decimals), then per section: its id and plane offset
/// along the plane's normal; chord, caliper chord, camber length; maximum thickness and its
/// position; LE and TE radius with the edge's shape in words (edge_shape_names); stagger,
/// inlet, outlet and camber angles; the pressure side; the failed checks by name
/// (check_names, from the `flags` bits); a hollow blade's cavities (the `walls` table, when
/// present), a line each with its thinnest wall and area; the section's issues, shortened
/// to the width.
/// Lengths in another unit (`# units`) are converted to mm. A section with issues and no
/// params row gets a block of its issues. A value that is not finite, or a column the table
/// lacks, prints as "-". Throws section::Error when the stream has no `params` table.
std::string format_params_text(const Stream& stream, const ParamsTextOptions& options = {});

}  // namespace section

// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// @file pipe/smooth_stream.h
/// The smooth stage on the stream: tables "points" -> "smoothed", "smooth_stats".
#include "section/io/stream.h"
#include "section/smooth.h"

#include <string>
#include <utility>
#include <vector>

namespace section {

/// Stream stage: smooths every (section, loop) of the "points" table (closed loops) and
/// writes the tables "smoothed" and "smooth_stats" (columns: pipe/schema.h, docs/FORMAT.md).
/// Sections already failed at an earlier stage are skipped; a loop that cannot be smoothed
/// is recorded in stream.issues (stage "smooth") and the others go on. Throws
/// section::Error when the "points" table is missing or lacks a column.
void smooth_stream(Stream& stream, const SmoothOptions& options = {});

/// The columns of its input smooth_stream never reads, only passes on (StageRun::unread):
/// the points' normals and offsets, the skeleton's points and radii.
const std::vector<std::pair<std::string, std::string>>& smooth_unread_columns();

}  // namespace section

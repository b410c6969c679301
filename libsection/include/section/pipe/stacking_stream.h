// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// @file pipe/stacking_stream.h
/// The stacking stage on the stream (docs/BLADE.md): the params and frames of every
/// section of a camber stream -> tables "blade" and "stacking".
#include "section/io/stream.h"
#include "section/stacking.h"

#include <vector>

namespace section {

/// The sections of a camber stream as the stacking takes them: each params row with its
/// frame (table "frames"; without one, the identity). Throws section::Error when the params
/// table is missing, lacks a column, or a row has no frame.
std::vector<StackedSection> stacked_sections(const Stream& stream);

/// Stream stage: converts the stream to mm, measures the blade from every section that has
/// params (stacking.h; a section whose centroid, edge points, stagger, chord or thickness
/// is not finite is left out with an issue) and puts the tables "blade" and "stacking"; each section whose
/// values are flagged gets an issue (stage "blade") naming the checks and why. Returns the
/// result. Throws section::Error as stacking() does (fewer than 2 sections, ...).
StackingResult stacking_stream(Stream& stream, const StackingOptions& options = {});

/// The issue text of a blade row's flags: `its values fail blade checks twist (stagger flagged
/// by camber here or at the reference), ...`; "" when none.
std::string stack_flags_text(std::uint32_t flags);

}  // namespace section

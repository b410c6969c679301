// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// @file pipe/slice_stream.h
/// The stream written by slice.
#include "section/io/stream.h"
#include "section/slice.h"

#include <string>

namespace section {

/// The pipe stream of a slice: tables frames, loops, points, skeleton (docs/FORMAT.md) and
/// the notes `# band`, `# fill`, `# loops`, `# row`; failed sections as issues. `command`
/// goes into the history.
Stream to_stream(const SliceResult& result, const std::string& command, const std::string& units = "mm");

/// The stream's note on what the points are (`sampling kind=K spacing=S normal_spacing=N
/// slab=D rows=R row_gap=G`, docs/FORMAT.md), without its `# `.
std::string sampling_note(const Sampling& sampling);

}  // namespace section

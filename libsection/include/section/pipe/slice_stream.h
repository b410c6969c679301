#pragma once
/// @file pipe/slice_stream.h
/// The stream written by slice.
#include "section/io/stream.h"
#include "section/slice.h"

#include <string>

namespace section {

/// The pipe stream of a slice: tables frames, loops, points, skeleton (docs/FORMAT.md) and
/// the notes `# band`, `# fill`, `# loops`; failed sections as issues. `command` goes into
/// the history.
Stream to_stream(const SliceResult& result, const std::string& command, const std::string& units = "mm");

}  // namespace section

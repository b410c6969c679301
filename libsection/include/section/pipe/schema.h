#pragma once
/// @file pipe/schema.h
/// The stream's tables and their columns (docs/FORMAT.md).
#include "section/frame.h"
#include "section/io/stream.h"

#include <map>

namespace section {

/// Section frames of a stream (table "frames"), by section id.
std::map<int, Frame> frames(const Stream& stream);

/// Adds or replaces the "frames" table from frames by section id.
void put_frames(Stream& stream, const std::map<int, Frame>& frames);

}  // namespace section

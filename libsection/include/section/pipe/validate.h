// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// @file pipe/validate.h
/// The stream held to its schema (pipe/schema.h) once read: what the parser, which knows no
/// table, cannot check.
#include "section/io/stream.h"

#include <string>

namespace section {

/// Checks every table of `stream` the schema knows (docs/FORMAT.md): no two rows with the
/// same ids (section, loop, side, index: those it has; two params rows for one section
/// are refused), counts that are whole numbers of 0 or more, flags that are 0 or 1.
/// Tables it does not know are left as they are. Throws section::Error
/// `pipe: SOURCE: table 'T' ...` naming the rows and their ids. (The parser checks the rest
/// as it reads: every id an integer of 0 or more, a part holding its own section only, no
/// column twice in a header.) run_stage calls it on every part or whole stream it reads.
void validate_stream(const Stream& stream, const std::string& source);

}  // namespace section

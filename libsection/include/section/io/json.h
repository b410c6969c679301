// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// @file io/json.h
/// Stream tables as JSON for scripts (`tocad`, `camber`, `compare --format json`): numbers at full precision,
/// grouped by section. docs/EXPORT.md shows the layout.
#include "section/io/stream.h"

#include <string>
#include <vector>

namespace section {

/// The tables `tables` (of `stream`, e.g. got with schema.h's `params.get(stream)`) as one
/// JSON document with the stream's units, history and issues:
/// `{"libsection": 1, "units": "mm", "history": [...], "issues": [{"section", "loop",
/// "stage", "message"}...], "sections": [{"section": S, TABLE: ...}...]}`, a section for each
/// id found in those tables, ascending. A table with an `index` column (thickness, camber,
/// sides) is given per section as one array per column (`{"fraction": [...], ...}`); a table
/// with a `loop`, `zone` or `item` column and no `index` (splines; compare's zones and
/// compared) as an array of row objects; any other
/// (params, frames) as one object of its row. Numbers are written in the shortest form that
/// reads back to the same double; a number that is not finite is `null`. Throws
/// section::Error when a table of the last kind has two rows for one section, or a table
/// has no `section` column.
std::string format_json(const Stream& stream, const std::vector<const Table*>& tables);

}  // namespace section

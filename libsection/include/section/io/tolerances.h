// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// @file io/tolerances.h
/// The tolerance file of compare (docs/COMPARE.md): a CSV table with the columns item
/// (required), section, low, high and on, one row per toleranced value.
#include "section/compare.h"

#include <string>
#include <string_view>
#include <vector>

namespace section {

/// Parses a tolerance file: `#` lines and blank lines skipped; the first remaining line is
/// the header; each row names an item of `items`, a section id (empty, `*` or `all`: every
/// section), the lowest and highest value allowed (empty: unbounded on that side, not
/// both), and what they bound (`on`: `deviation`, the default, or `value`). Throws
/// section::Error `tolerances: SOURCE:LINE: ...` on an unknown column or item, a bad
/// number, low above high, or a second row for the same item and section.
std::vector<Tolerance> parse_tolerances(std::string_view text, const std::string& source,
                                        const std::vector<std::string>& items);

/// Reads and parses a tolerance file ("-" = standard input).
std::vector<Tolerance> read_tolerances(const std::string& path, const std::vector<std::string>& items);

}  // namespace section

// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// @file io/csv.h
/// Plain text tables outside the stream: CSV tables, ordered 2D profiles, section planes.
#include "section/io/stream.h"
#include "section/slice.h"

#include <Eigen/Core>
#include <string>
#include <string_view>
#include <vector>

namespace section {

/// Parses a plain CSV table (not a stream): `#` lines and blank lines skipped, the first
/// remaining line is the header of column names, then numeric rows with as many values,
/// separated by commas or blanks. The table is named after `source`. Throws section::Error
/// naming `source` and the line.
Table parse_csv(std::string_view text, const std::string& source);

/// Parses a plain ordered 2D profile: one point a line, x and y in the first two columns
/// (comma or blank separated; further columns ignored), or in the columns a header line
/// names `x` and `y` (`y,x` reads the second column as x); leading title lines and `#`
/// lines are skipped, as in airfoil .dat files. An exact copy of a point read before counts
/// once (a closing point repeated). Throws section::Error naming `source` and the line.
std::vector<Eigen::Vector2d> parse_profile(std::string_view text, const std::string& source);

/// Formats one table as a plain CSV file (header row, then the rows; no `#` lines), for
/// tools that also write a table on its own (camber --params, smooth --report); a value
/// that is not a number is written `nan`. Throws section::Error for values that are not
/// whole rows of the columns.
std::string format_csv(const Table& table);
/// Planes from a CSV table with columns origin_x, origin_y, origin_z, normal_x, normal_y,
/// normal_z (extra columns ignored). `source` names it in error messages.
std::vector<Plane> parse_planes(std::string_view csv, const std::string& source);

}  // namespace section

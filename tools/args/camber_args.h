// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// camber's command line: its options and help text (tools/camber.cpp runs them).
#include "common/tool.h"

#include "section/camber.h"

#include <string>
#include <vector>

namespace section::tool {

struct CamberArgs {
  static constexpr const char* name = "camber";
  static const char* const description;
  Common common;
  CamberOptions options;       ///< every other flag; --stations, --le-direction, --edge and
                               ///< --edge-on-spline are read into it once parsed
  std::string params_file;     ///< --params: the params table (CSV) to this file
  std::string thickness_file;  ///< --thickness: the thickness table (CSV) to this file
  std::string walls_file;      ///< --walls: the walls table (CSV) to this file
  std::string wall_map_file;   ///< --wall-map: the wall_map table (CSV) to this file
  std::string stations, le_direction, edge = "round";  ///< those flags as given
  bool edge_on_spline = false;
  bool allow_partial = false;  ///< --allow-partial: exit 0 when some sections have no params
  /// --format: what goes to the output: "stream" (the pipe stream), "table" (params for
  /// people), "csv" (the params table), "json" (params and issues); "" = table when the
  /// output is a terminal, else stream.
  std::string format;
  std::string units;  ///< --units: a plain profile's length unit ("" = mm, or m by its extent)
  /// Declares the options on `app`, bound to these fields.
  void declare(CLI::App& app);
};

/// "a,b,c" -> finite numbers, parsed like the pipe parses (std::from_chars: no locale, the
/// whole item, a leading '+' allowed); throws CLI::ValidationError naming the flag.
std::vector<double> numbers(const std::string& text, const std::string& flag);

/// Accepts a direction for `flag`: two numbers u,v or three x,y,z, not all 0 (--le-direction,
/// compare's --direction).
CLI::Validator direction_check(const std::string& flag);

}  // namespace section::tool

// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// tocad's command line: its options and help text (tools/tocad.cpp runs them).
#include "common/tool.h"

#include <string>
#include <vector>

namespace section::tool {

struct TocadArgs {
  static constexpr const char* name = "tocad";
  static const char* const description;
  Common common;
  std::string format;                 ///< dxf, iges or json: --format, else from -o's extension
  double polyline_tolerance = 0.001;  ///< --polyline-tolerance (mm; DXF), 0 = splines only
  bool profiles_only = false;         ///< --profiles-only: loop 0 of each section
  std::vector<std::string> tables = {"params", "thickness"};  ///< --tables (JSON)
  bool tables_given = false;  ///< --tables given: without it, a stream's walls table joins the default
  /// Declares the options on `app`, bound to these fields.
  void declare(CLI::App& app);
};

/// The format an output file's name asks for ("dxf" for .dxf, "iges" for .igs or .iges,
/// "json" for .json, any case), or "" for another name.
std::string format_of(const std::string& output);

}  // namespace section::tool

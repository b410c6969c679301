// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// blade's command line: its options and help text (tools/blade.cpp runs them).
#include "common/tool.h"

#include "section/stacking.h"

#include <string>

namespace section::tool {

struct BladeArgs {
  static constexpr const char* name = "blade";
  static const char* const description;
  Common common;
  StackingOptions options;  ///< --reference, --axis, --control-points, --samples, --off-line
  std::string axis;         ///< --axis as given: px,py,pz,dx,dy,dz
  std::string plot_file;    ///< --plot: an SVG of the stacking line and the distributions
  std::string lines_file;   ///< --lines: the 'stacking' table (CSV) to this file
  /// --format: "table" (for people), "csv" (the blade table), "json" (blade rows and issues
  /// per section), "stream" (the input stream with the tables blade and stacking); "" =
  /// table when the output is a terminal, else csv.
  std::string format;
  bool allow_partial = false;  ///< --allow-partial: exit 0 when some sections have no params
  /// Declares the options on `app`, bound to these fields.
  void declare(CLI::App& app);
};

}  // namespace section::tool

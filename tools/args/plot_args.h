// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// plot's command line: its options and help text (tools/plot.cpp runs them).
#include "common/tool.h"

#include "section/extras/plot.h"

namespace section::tool {

struct PlotArgs {
  static constexpr const char* name = "plot";
  static const char* const description;
  Common common;
  PlotOptions
      options;  ///< --width, --inset, --inset-radii; --no-points, --no-stations, --no-insets, --no-dimensions
  int only = -1;      ///< --section N
  bool one = false;   ///< --section was given
  bool html = false;  ///< --html, or an output ending in .html without --section
  bool no_points = false, no_insets = false, no_stations = false, no_dimensions = false;
  /// Declares the options on `app`, bound to these fields.
  void declare(CLI::App& app);
};

}  // namespace section::tool

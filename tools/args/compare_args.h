// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// compare's command line: its options and help text (tools/compare.cpp runs them).
#include "common/tool.h"

#include "section/pipe/compare_stream.h"

#include <string>

namespace section::tool {

/// compare's exit codes beside 0 (every toleranced value passed), 1 and 2 (tool.h).
inline constexpr int exit_failed = 4;        ///< a value failed its tolerance
inline constexpr int exit_not_measured = 5;  ///< none failed, and a value was not measured
inline constexpr int exit_uncertain = 6;     ///< none failed or was not measured, and one was uncertain

struct CompareArgs {
  static constexpr const char* name = "compare";
  static const char* const description;
  Common common;
  CompareStreamOptions options;  ///< every other flag, read into it once parsed
  std::string nominal;           ///< --nominal: a mesh, a stream or a CSV of section points
  std::string nominal_units;  ///< --nominal-units: the nominal mesh's or points' unit ("" = from its extent)
  std::string tolerances;     ///< --tolerances: the tolerance file (CSV)
  std::string report;         ///< --report: the verdicts as text to FILE ("-" = standard error)
  /// --format: what goes to the output: "stream", "table" (the report) or "json" (verdicts,
  /// zones, compared values and issues per section); "" = table at a terminal, else stream.
  std::string format;
  std::string method = "least-squares", freedom = "all";  ///< --fit, --freedom as given
  std::string decision = "guarded";                       ///< --decision-rule as given
  std::string direction, center, weights, le_direction;   ///< those flags as given
  bool keep_outliers = false;
  /// Declares the options on `app`, bound to these fields.
  void declare(CLI::App& app);
};

}  // namespace section::tool

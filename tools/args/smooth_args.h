// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// smooth's command line: its options and help text (tools/smooth.cpp runs them).
#include "common/tool.h"

#include "section/smooth.h"

#include <string>

namespace section::tool {

struct SmoothArgs {
  static constexpr const char* name = "smooth";
  static const char* const description;
  Common common;
  /// --length, --spacings, --a, --b, --solver, --max-iterations, --move-tolerance, --threads
  SmoothOptions options;
  std::string solver = "cholmod";  ///< --solver as given (options.solver is set from it)
  std::string report;              ///< --report: the per-loop statistics (CSV) to this file
  /// Declares the options on `app`, bound to these fields.
  void declare(CLI::App& app);
};

}  // namespace section::tool

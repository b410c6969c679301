// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// fitspline's command line: its options and help text (tools/fitspline.cpp runs them).
#include "common/tool.h"

#include "section/fit_spline.h"

namespace section::tool {

struct FitsplineArgs {
  static constexpr const char* name = "fitspline";
  static const char* const description;
  Common common;
  FitSplineOptions options;  ///< every other flag
  /// Declares the options on `app`, bound to these fields.
  void declare(CLI::App& app);
};

}  // namespace section::tool

#pragma once
// bladegen's command line: its options and help text (tools/bladegen.cpp runs them).
#include "common/tool.h"

#include "section/extras/generate.h"

#include <string>
#include <vector>

namespace section::tool {

struct BladegenArgs {
  static constexpr const char* name = "bladegen";
  static const char* const description;
  std::string output;                 ///< -o: the scan or mesh
  std::string kind = "turbine";       ///< --kind: the blade preset
  std::string truth;                  ///< --truth: the true section parameters (CSV) to this file
  std::string second_view;            ///< --second-view: the second view's points to this file
  bool points = false, mesh = false;  ///< --points, --mesh
  ScanOptions scan;                   ///< the scanner's options
  int profile_points = 400;           ///< --profile-points (mesh)
  int layers = 60;                    ///< --layers (mesh)
  std::vector<double> at;             ///< --at: heights of the --truth sections
  /// Declares the options on `app`, bound to these fields.
  void declare(CLI::App& app);
};

}  // namespace section::tool

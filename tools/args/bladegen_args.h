// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// bladegen's command line: its options and help text (tools/bladegen.cpp runs them).
#include "common/tool.h"

#include "section/extras/generate.h"
#include "section/extras/generate_rotor.h"

#include <string>
#include <vector>

namespace section::tool {

/// The blade presets by name (--kind).
struct BladePreset {
  const char* name;
  BladeDesign (*blade)();
};
inline constexpr BladePreset blade_presets[] = {{"turbine", turbine_blade},
                                                {"compressor", compressor_blade},
                                                {"sharp-te", sharp_te_blade},
                                                {"impulse", impulse_blade},
                                                {"thick-root", thick_root_blade}};

/// Millimetres per unit of --units (the scale the coordinates are written in).
double mm_per_unit(const std::string& unit);

struct BladegenArgs {
  static constexpr const char* name = "bladegen";
  static const char* const description;
  std::string output;                  ///< -o: the scan, mesh, grid or rows
  std::string kind = "turbine";        ///< --kind: the blade preset
  std::string truth;                   ///< --truth: the true section parameters (CSV) to this file
  std::string second_view;             ///< --second-view: the second view's points to this file
  std::string units = "mm";            ///< --units: the unit the coordinates are written in
  double span = 0;                     ///< --span: blade height, mm; 0 = the preset's (60)
  StackingLaw stacking;                ///< --lean, --sweep, --bow: the sections' moves along the span (mm)
  bool points = false, mesh = false;   ///< --points, --mesh
  std::string grid;                    ///< --grid chordwise|spanwise: a structured surface grid
  int rows = 0;                        ///< --rows N: sparse rows (0 = none)
  ScanOptions scan;                    ///< the scanner's options (--noise, --seed, --z-min, --z-max shared)
  GridOptions grid_options;            ///< --clustering, --repeat-seam
  int lines = 200, line_points = 200;  ///< --lines, --line-points (grid)
  RowsOptions rows_options;            ///< --row-pitch, --first-row, --hub-radius
  bool spacing_given = false;          ///< --spacing given (rows default to 1 mm)
  int profile_points = 400;            ///< --profile-points (mesh)
  int layers = 60;                     ///< --layers (mesh)
  std::vector<double> at;              ///< --at: heights of the --truth sections
  std::string rotor;                   ///< --rotor cylinder|cone: the sections on surfaces of revolution
  RotorDesign rotor_options;           ///< --rotor-radius, --cone-angle, --unroll
  /// Declares the options on `app`, bound to these fields.
  void declare(CLI::App& app);
  /// The blade of --kind and --span.
  BladeDesign blade() const;
  /// The grid's options from the shared and grid flags (chordwise: --lines heights of
  /// --line-points places; spanwise: --lines places of --line-points heights).
  GridOptions grid_settings() const;
  /// The rotor of --rotor (its blade: blade()).
  RotorDesign rotor_design() const;
  /// The rows' options from the shared and rows flags.
  RowsOptions rows_settings() const;
};

}  // namespace section::tool

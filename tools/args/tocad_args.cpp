// SPDX-License-Identifier: GPL-3.0-or-later
#include "args/tocad_args.h"

#include "section/pipe/schema.h"

#include <algorithm>
#include <cctype>

namespace section::tool {

const char* const TocadArgs::description =
    "tocad: write the sections of a pipe stream as CAD curves (DXF, IGES) or as JSON.\n\n"
    "Reads a stream written by fitspline (or camber after it; docs/FORMAT.md) and writes:\n"
    "  dxf   each loop's B-spline as a SPLINE entity (degree, knots, control points) in 3D on\n"
    "        its section's plane, on the layer section_S, and a 3D POLYLINE within\n"
    "        --polyline-tolerance of it (AutoCAD 2000 DXF, units mm)\n"
    "  iges  each loop's B-spline as an IGES entity 126 (rational B-spline curve, weights 1),\n"
    "        in 3D on its section's plane (IGES 5.3, units mm)\n"
    "  json  the tables --tables (default params and thickness, written by camber, and walls\n"
    "        when the stream has it: a hollow blade's cavities) by section,\n"
    "        numbers at full precision, with the stream's units, history and issues\n"
    "The format is --format, or the output's extension (.dxf, .igs, .iges, .json).\n"
    "Sections that failed (issues in the stream) have no curve and are named on stderr.\n\n"
    "Example: slice blade.ply --count 9 | smooth | fitspline | tocad -o blade.dxf";

std::string format_of(const std::string& output) {
  const std::size_t dot = output.rfind('.');
  if (dot == std::string::npos || output.find('/', dot) != std::string::npos) return "";
  std::string ext = output.substr(dot + 1);
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  if (ext == "dxf" || ext == "json") return ext;
  if (ext == "igs" || ext == "iges") return "iges";
  return "";
}

void TocadArgs::declare(CLI::App& app) {
  add_common(app, common);
  app.add_option("-f,--format", format, "dxf, iges or json; default: from the output's extension")
      ->check(CLI::IsMember({"dxf", "iges", "json"}));
  add_checked(app, "--polyline-tolerance", polyline_tolerance,
              "DXF: also a 3D polyline per curve within this distance of it, mm; 0 = splines only",
              CLI::NonNegativeNumber);
  app.add_flag("--profiles-only", profiles_only, "Only each section's profile (loop 0), not its other loops");
  app.add_option("--tables", tables, "JSON: the tables to write, by name")
      ->delimiter(',')
      ->capture_default_str();
  app.callback([this, &app] {
    tables_given = app.count("--tables") > 0;
    for (const auto& t : tables) {
      const auto known = section::schema::tables();
      if (std::none_of(known.begin(), known.end(), [&](const auto& d) { return t == d.name; }))
        throw CLI::ValidationError("--tables", "there is no table '" + t + "' (docs/FORMAT.md lists them)");
    }
    if (format.empty()) format = format_of(common.output);
    if (format.empty())
      throw CLI::ValidationError("--format",
                                 "give --format dxf|iges|json, or an output file ending in .dxf, "
                                 ".igs, .iges or .json");
  });
}

}  // namespace section::tool

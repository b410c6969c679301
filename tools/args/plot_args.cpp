// SPDX-License-Identifier: GPL-3.0-or-later
#include "args/plot_args.h"

#include <algorithm>
#include <string>

namespace section::tool {

const char* const PlotArgs::description =
    "plot: draw the sections of a pipe stream to scale (SVG or HTML).\n\n"
    "Reads a stream from any stage (docs/FORMAT.md) and draws, per section, what it holds:\n"
    "measured points, fitted curve, mean-camber line, inscribed circles at the thickness\n"
    "stations with their thickness, LE and TE circles, chord line, dimension lines (chord,\n"
    "maximum thickness, edge radii), parameter table, scale bar and a magnified inset of\n"
    "each edge; v points up, both axes at one scale. Sections are named by their plane\n"
    "(z = 12 mm). The HTML page pans and zooms (wheel, drag; double click: whole) without\n"
    "fetching anything; points and curves are thinned to the screen (docs/PLOT.md).\n\n"
    "Output:\n"
    "  --section N -o file.svg   one section as SVG (-o - = standard output)\n"
    "  --html -o page.html       one HTML page with every section (implied by .html)\n"
    "  -o file.svg               the SVG of the only section\n"
    "  -o DIR                    DIR/section-N.svg for every section (DIR is created)\n"
    "  (default)                 the SVG of the only section on standard output\n\n"
    "Example: slice blade.ply --count 5 | smooth | fitspline | camber | plot --html -o blade.html";

void PlotArgs::declare(CLI::App& app) {
  add_common(app, common);
  auto* section_flag = app.add_option("--section", only, "Draw only section N (SVG)");
  app.add_flag("--html", html, "Write one HTML page holding every section")->excludes("--section");
  add_checked(app, "--width", options.width, "Drawing width, px", CLI::Range(300.0, 20000.0));
  auto* inset_flag = add_checked(app, "--inset", options.inset_size,
                                 "Edge inset side, px (0 = no insets; at most half of --width, less 20)",
                                 CLI::Range(0.0, 10000.0));
  add_checked(app, "--inset-radii", options.inset_radii, "Inset half-width in edge radii",
              CLI::Range(1.05, 100.0));
  app.add_flag("--no-points", no_points, "Do not draw the measured points");
  app.add_flag("--no-stations", no_stations, "Do not draw the thickness-station circles");
  app.add_flag("--no-insets", no_insets, "Do not draw the edge insets");
  app.add_flag("--no-dimensions", no_dimensions, "Do not draw the dimension lines");
  app.callback([this, section_flag, inset_flag] {
    options.points = !no_points;
    options.stations = !no_stations;
    if (no_insets) options.inset_size = 0;
    const double widest = options.width / 2 - 20;  // the library's bound, said with the flags' names
    if (inset_flag->count() == 0)
      options.inset_size = std::min(options.inset_size, widest);  // a narrow --width
    if (options.inset_size != 0 && !(options.inset_size >= 80 && options.inset_size <= widest))
      throw CLI::ValidationError("--inset", "0 (none) or 80 to " + std::to_string(static_cast<int>(widest)) +
                                                " px (half of --width, less 20)");
    options.dimensions = !no_dimensions;
    one = section_flag->count() > 0;
    if (!one && ends_with(common.output, ".html")) html = true;
  });
}

}  // namespace section::tool

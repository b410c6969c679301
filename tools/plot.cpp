// plot: SVG drawings of the sections of a pipe stream, or one HTML page of them all.
#include "common/tool.h"

#include "section/error.h"
#include "section/io/stream.h"
#include "section/io/file.h"
#include "section/extras/plot.h"

#include <filesystem>
#include <iostream>

namespace {

const char* const description =
    "plot: draw the sections of a pipe stream to scale (SVG or HTML).\n\n"
    "Reads a stream from any stage (docs/FORMAT.md) and draws, per section, what it holds:\n"
    "measured points, fitted curve, mean-camber line, inscribed circles at the thickness\n"
    "stations, LE and TE circles, chord line, parameter table, scale bar and a magnified\n"
    "inset of each edge; v points up, both axes at one scale.\n\n"
    "Output:\n"
    "  --section N -o file.svg   one section as SVG (-o - = standard output)\n"
    "  --html -o page.html       one HTML page with every section (implied by .html)\n"
    "  -o file.svg               the SVG of the only section\n"
    "  -o DIR                    DIR/section-N.svg for every section (DIR is created)\n"
    "  (default)                 the SVG of the only section on standard output\n\n"
    "Example: slice blade.ply --count 5 | smooth | fitspline | camber | plot --html -o blade.html";

}  // namespace

int main(int argc, char** argv) {
  section::tool::Common common;
  section::PlotOptions options;
  int only = -1;
  CLI::Option* section_flag = nullptr;
  bool html = false, no_points = false, no_insets = false, no_stations = false;
  return section::tool::run_tool(
      "plot", description, argc, argv,
      [&](CLI::App& app) {
        section::tool::add_common(app, common);
        section_flag = app.add_option("--section", only, "Draw only section N (SVG)");
        app.add_flag("--html", html, "Write one HTML page holding every section")->excludes("--section");
        app.add_option("--width", options.width, "Drawing width, px")->check(CLI::Range(300.0, 20000.0))
            ->capture_default_str();
        app.add_option("--inset", options.inset_size, "Edge inset side, px (0 = no insets)")
            ->check(CLI::Range(0.0, 10000.0))->capture_default_str();
        app.add_option("--inset-radii", options.inset_radii, "Inset half-width in edge radii")
            ->check(CLI::Range(1.05, 100.0))->capture_default_str();
        app.add_flag("--no-points", no_points, "Do not draw the measured points");
        app.add_flag("--no-stations", no_stations, "Do not draw the thickness-station circles");
        app.add_flag("--no-insets", no_insets, "Do not draw the edge insets");
      },
      [&] {
        options.points = !no_points;
        options.stations = !no_stations;
        if (no_insets) options.inset_size = 0;
        const auto ends_with = [&](const std::string& tail) {
          const std::string& o = common.output;
          return o.size() >= tail.size() && o.compare(o.size() - tail.size(), tail.size(), tail) == 0;
        };
        if (ends_with(".html") && section_flag->count() == 0) html = true;
        const section::Stream stream = section::read_stream(common.input);
        if (html) {
          section::write_file(common.output, section::plot_html(stream, options));
          return;
        }
        const auto ids = section::plot_sections(stream);
        const bool one = section_flag->count() > 0;
        if (one || common.output == "-" || ends_with(".svg")) {
          if (!one && ids.size() != 1)
            throw section::Error("the stream holds " + std::to_string(ids.size()) +
                                 " sections: give --section N, --html, or -o DIR");
          section::write_file(common.output, section::plot_svg(stream, one ? only : ids.front(), options));
          return;
        }
        std::filesystem::create_directories(common.output);
        int written = 0;
        for (int id : ids) {
          try {
            const std::string path = common.output + "/section-" + std::to_string(id) + ".svg";
            section::write_file(path, section::plot_svg(stream, id, options));
            ++written;
          } catch (const section::Error& e) {
            std::cerr << "plot: warning: section " << id << ": " << e.what() << "\n";
          }
        }
        if (written == 0) throw section::Error("no section could be drawn");
      });
}

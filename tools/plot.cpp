// SPDX-License-Identifier: GPL-3.0-or-later
// plot: SVG drawings of the sections of a pipe stream, or one HTML page of them all.
#include "args/plot_args.h"

#include "section/error.h"
#include "section/io/stream.h"
#include "section/io/file.h"
#include "section/extras/plot.h"
#include "section/pipe/validate.h"

#include <filesystem>
#include <iostream>

namespace {

using section::tool::PlotArgs;

// DIR/section-N.svg for every section that can be drawn.
void plot_each(const section::Stream& stream, const std::vector<int>& ids, const PlotArgs& a) {
  std::filesystem::create_directories(a.common.output);
  int written = 0;
  for (int id : ids) {
    try {
      const std::string path = a.common.output + "/section-" + std::to_string(id) + ".svg";
      section::write_file(path, section::plot_svg(stream, id, a.options));
      ++written;
    } catch (const section::Error& e) {
      std::cerr << "plot: warning: section " << id << ": " << e.what() << "\n";
    }
  }
  if (written == 0) throw section::Error("no section could be drawn");
}

void run_plot(const PlotArgs& a) {
  const std::string& out = a.common.output;
  const section::Stream stream = section::read_stream(a.common.input);
  section::validate_stream(stream, section::tool::input_name(a.common.input));
  if (a.html) {
    section::write_file(out, section::plot_html(stream, a.options));
    return;
  }
  const auto ids = section::plot_sections(stream);
  if (a.one || out == "-" || section::tool::ends_with(out, ".svg")) {
    if (!a.one && ids.size() != 1)
      throw section::Error("the stream holds " + std::to_string(ids.size()) +
                           " sections: give --section N, --html, or -o DIR");
    section::write_file(out, section::plot_svg(stream, a.one ? a.only : ids.front(), a.options));
    return;
  }
  plot_each(stream, ids, a);
}

}  // namespace

int main(int argc, char** argv) {
  return section::tool::run<PlotArgs>(argc, argv, run_plot);
}

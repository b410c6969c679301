// SPDX-License-Identifier: GPL-3.0-or-later
// fitspline: fit a closed cubic B-spline to every section loop of a pipe stream.
#include "args/fitspline_args.h"

#include "section/error.h"
#include "section/io/stream.h"
#include "section/pipe/run_stage.h"
#include "section/pipe/fit_spline_stream.h"
#include "section/pipe/schema.h"
#include "section/units.h"

#include <iostream>

namespace {

using section::tool::FitsplineArgs;

// Points in two layers along a loop: views merged with a misregistration, or a slab so wide
// that the profile moves across it (a twisted or tapered blade)?
void warn_layers(const section::Table& splines) {
  namespace col = section::schema::col;
  const std::size_t cs = splines.column(col::section), cl = splines.column(col::loop),
                    cy = splines.column(col::layers), cyl = splines.column(col::layers_length);
  for (std::size_t r = 0; r < splines.rows(); ++r) {
    const double layers = splines.at(r, cy);
    if (!(layers > 0)) continue;
    std::cerr
        << "fitspline: warning: section " << splines.at(r, cs) << " loop " << splines.at(r, cl)
        << ": the points lie in two layers about " << section::format_length(layers) << " apart over "
        << section::format_length(splines.at(r, cyl))
        << " of the profile, and the curve runs between them: views merged with a misregistration "
           "(register them: slice --view, docs/REGISTRATION.md), or a slab so wide that the profile moves "
           "across it (a narrower slice --slab)?\n";
  }
}

void run_fitspline(const FitsplineArgs& a, const std::string& history) {
  section::tool::refuse_terminal_output(a.common, "camber");
  std::size_t fitted = 0, measured = 0;
  section::StageRun run = section::tool::stage_run(a.common, history, a.options, section::fit_spline_stream);
  run.written = [&](const section::Stream& stream) {
    section::tool::warn_issues("fitspline", stream, true);
    if (const section::Table* splines = section::schema::splines.find(stream)) {
      warn_layers(*splines);
      fitted += splines->rows();
    }
    if (const section::Table* points = section::schema::points.find(stream)) measured += points->rows();
  };
  run.before_end = [&] {
    if (fitted == 0 && measured > 0)
      throw section::Error(section::tool::input_name(a.common.input) +
                           ": no loop could be fitted (see the warnings above)");
  };
  section::run_stage(run);
}

}  // namespace

int main(int argc, char** argv) {
  return section::tool::run<FitsplineArgs>(argc, argv, [&](const FitsplineArgs& args) {
    run_fitspline(args, section::tool::command_line(argc, argv));
  });
}

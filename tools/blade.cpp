// SPDX-License-Identifier: GPL-3.0-or-later
// blade: the whole blade from the sections of a camber stream: stacking line, twist, lean, bow, sweep.
#include "args/blade_args.h"

#include "section/extras/plot_blade.h"
#include "section/io/blade_text.h"
#include "section/io/csv.h"
#include "section/io/file.h"
#include "section/io/json.h"
#include "section/io/stream.h"
#include "section/pipe/schema.h"
#include "section/pipe/stacking_stream.h"
#include "section/pipe/validate.h"

#include <iostream>

namespace {

using section::tool::BladeArgs;

void run_blade(const BladeArgs& a, const std::string& history) {
  const std::string format = !a.format.empty()                                    ? a.format
                             : section::tool::output_is_terminal(a.common.output) ? "table"
                                                                                  : "csv";
  section::Stream stream;
  section::StackingResult blade;
  section::tool::with_input(a.common.input, [&] {
    stream = section::read_stream(a.common.input);
    section::validate_stream(stream, section::tool::input_name(a.common.input));
    blade = section::stacking_stream(stream, a.options);
  });
  section::tool::warn_issues("blade", stream, false);
  section::tool::SectionTally tally("params", "blade");
  tally.add(stream);
  const section::Table& table = section::schema::blade.get(stream);
  if (!a.lines_file.empty())
    section::write_file(a.lines_file, section::format_csv(section::schema::stacking.get(stream)));
  if (!a.plot_file.empty()) section::write_file(a.plot_file, section::plot_blade_svg(blade, stream.units));
  if (format == "stream") {
    stream.history.push_back(history);
    section::write_stream(a.common.output, stream);
  } else if (format == "csv") {
    section::write_file(a.common.output, section::format_csv(table));
  } else if (format == "json") {
    section::write_file(a.common.output, section::format_json(stream, {&table}));
  } else {
    section::write_file(a.common.output, section::format_blade_text(blade, stream.units));
  }
  tally.check(a.allow_partial);
}

}  // namespace

int main(int argc, char** argv) {
  return section::tool::run<BladeArgs>(
      argc, argv, [&](const BladeArgs& args) { run_blade(args, section::tool::command_line(argc, argv)); });
}

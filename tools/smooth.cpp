// SPDX-License-Identifier: GPL-3.0-or-later
// smooth: energy-minimising smoothing of every section loop of a pipe stream.
#include "args/smooth_args.h"

#include "section/io/stream.h"
#include "section/io/csv.h"
#include "section/io/file.h"
#include "section/pipe/run_stage.h"
#include "section/pipe/schema.h"
#include "section/pipe/smooth_stream.h"

#include <iostream>

namespace {

using section::tool::SmoothArgs;

void run_smooth(const SmoothArgs& a, const std::string& history) {
  section::tool::refuse_terminal_output(a.common, "fitspline");
  section::Table stats;
  section::StageRun run = section::tool::stage_run(a.common, history, a.options, section::smooth_stream);
  run.unread = section::smooth_unread_columns();
  run.written = [&](const section::Stream& part) {
    section::tool::warn_issues("smooth", part, true);
    section::append_rows(stats, section::schema::smooth_stats.get(part));
  };
  section::run_stage(run);
  if (!a.report.empty()) section::write_file(a.report, section::format_csv(stats));
}

}  // namespace

int main(int argc, char** argv) {
  return section::tool::run<SmoothArgs>(
      argc, argv, [&](const SmoothArgs& args) { run_smooth(args, section::tool::command_line(argc, argv)); });
}

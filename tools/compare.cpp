// SPDX-License-Identifier: GPL-3.0-or-later
// compare: the measured sections of a pipe stream against their nominal, with tolerances.
#include "args/compare_args.h"

#include "section/error.h"
#include "section/extras/report.h"
#include "section/io/file.h"
#include "section/io/json.h"
#include "section/pipe/nominal_file.h"
#include "section/io/stream.h"
#include "section/io/tolerances.h"
#include "section/pipe/compare_stream.h"
#include "section/pipe/run_stage.h"
#include "section/pipe/schema.h"

#include <iostream>

namespace {

using section::tool::CompareArgs;

// The nominal (mesh, stream or points), its unit's doubt said on standard error.
section::NominalFile read_nominal(const std::string& path, const std::string& units) {
  section::NominalFile n = section::read_nominal(path, units);
  if (!n.units.warning.empty()) std::cerr << "compare: warning: " << path << ": " << n.units.warning << "\n";
  return n;
}

int run_compare(const CompareArgs& a, const std::string& history) {
  CompareArgs args = a;
  if (!a.tolerances.empty())
    args.options.tolerances = section::read_tolerances(a.tolerances, section::tolerance_items());
  const section::NominalFile nominal = read_nominal(a.nominal, a.nominal_units);
  const section::NominalSource source = nominal.source();
  const section::CompareStreamOptions& o = args.options;
  // Errors name the file they come from: the nominal's or the measured stream's.
  auto stage = [&](section::Stream& s, int threads) {
    section::CompareStreamOptions part = o;
    part.threads = threads;
    std::map<int, section::Frame> frames;
    section::Stream n;
    section::tool::with_input(a.common.input, [&] {
      if (section::schema::frames.find(s)) frames = section::frames(s);
    });
    section::tool::with_input(a.nominal, [&] { n = section::nominal_stream(source, frames, part); });
    section::tool::with_input(a.common.input, [&] { section::compare_stream(s, n, part); });
  };
  const std::string format = !a.format.empty()                                    ? a.format
                             : section::tool::output_is_terminal(a.common.output) ? "table"
                                                                                  : "stream";
  const std::string output = format == "stream" ? a.common.output : "/dev/null";  // or the table, json
  section::Stream all;  // the verdicts, zones and compared values, gathered over the parts
  auto gather = [&](const section::Stream& s) {
    section::tool::warn_issues("compare", s, false);
    all.units = s.units;
    all.issues.insert(all.issues.end(), s.issues.begin(), s.issues.end());
    for (const char* name : {"verdicts", "zones", "compared"}) {
      if (!all.find(name)) all.put(section::Table(name, {}));
      section::append_rows(*all.find(name), s.get(name, "compare"));
    }
  };
  if (o.whole) {
    // One motion for every section: the stream read, compared and written whole.
    section::Stream s = section::read_stream(a.common.input);
    stage(s, o.threads);
    s.history.push_back(history);
    gather(s);
    section::write_stream(output, s);
  } else {
    section::StageRun run;
    run.input = a.common.input;
    run.output = output;
    run.history = history;
    run.threads = o.threads;
    run.stage = stage;
    run.written = gather;
    section::run_stage(run);
  }
  // A tolerance naming a section the stream does not have judges nothing: said, and not measured.
  const std::size_t issues = all.issues.size();
  section::judge_absent_sections(all, o);
  section::Stream absent;  // the new issues alone, said as the parts' were
  absent.issues.assign(all.issues.begin() + static_cast<std::ptrdiff_t>(issues), all.issues.end());
  section::tool::warn_issues("compare", absent, false);
  if (!a.report.empty()) {
    const std::string text = section::compare_report(all);
    if (a.report == "-")
      std::cerr << text;
    else
      section::write_file(a.report, text);
  }
  if (format == "table") section::write_file(a.common.output, section::compare_report(all));
  if (format == "json")
    section::write_file(a.common.output, section::format_json(all, {all.find("verdicts"), all.find("zones"),
                                                                    all.find("compared")}));
  const int verdict = section::stream_verdict(all);
  return verdict == 1   ? section::tool::exit_failed
         : verdict == 2 ? section::tool::exit_not_measured
         : verdict == 3 ? section::tool::exit_uncertain
                        : 0;
}

}  // namespace

int main(int argc, char** argv) {
  int verdict = 0;
  const int code = section::tool::run<CompareArgs>(argc, argv, [&](const CompareArgs& args) {
    verdict = run_compare(args, section::tool::command_line(argc, argv));
  });
  return code != 0 ? code : verdict;
}

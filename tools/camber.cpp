// SPDX-License-Identifier: GPL-3.0-or-later
// camber: mean-camber line and blade section parameters of every section of a pipe stream.
#include "args/camber_args.h"

#include "section/camber.h"
#include "section/io/stream.h"
#include "section/io/csv.h"
#include "section/io/file.h"
#include "section/io/json.h"
#include "section/io/params_text.h"
#include "section/pipe/run_stage.h"
#include "section/pipe/camber_stream.h"
#include "section/pipe/plain_profile.h"
#include "section/pipe/schema.h"
#include "section/units.h"

#include <Eigen/Geometry>

#include <future>
#include <iostream>
#include <string>
#include <vector>

namespace {

using section::tool::CamberArgs;

// The params (and the issues, frames and units) of every section, as --format asks for
// them instead of the stream: table, csv or json (with the walls of a hollow blade's
// cavities, when it has any, and in json their wall maps too).
std::string params_output(const std::string& format, section::Stream summary, section::Table params,
                          const section::Table& walls, const section::Table& wall_map) {
  if (params.columns.empty()) params = section::Table("params", {"section"});  // no section measured
  if (format == "csv") return section::format_csv(params);
  summary.put(params);
  std::vector<std::string> tables = {"params"};
  if (walls.rows() > 0) summary.put(walls), tables.push_back("walls");  // a hollow blade's cavities
  if (format != "json") return section::format_params_text(summary);
  if (walls.rows() > 0 && wall_map.rows() > 0) summary.put(wall_map), tables.push_back("wall_map");
  std::vector<const section::Table*> found;  // taken once every table is in: put may move them
  for (const std::string& name : tables) found.push_back(summary.find(name));
  return section::format_json(summary, found);
}

void run_camber(const CamberArgs& a, const std::string& history) {
  section::Table params, thickness, walls, wall_map, frames;
  const std::string format = !a.format.empty()                                    ? a.format
                             : section::tool::output_is_terminal(a.common.output) ? "table"
                                                                                  : "stream";
  // Parts are checked across the blade in the hold step below, not each by itself.
  section::CamberOptions per_part = a.options;
  per_part.across_sections = false;
  section::StageRun run = section::tool::stage_run(a.common, history, per_part, section::camber_stream);
  run.unread = section::camber_unread_columns();
  if (format != "stream") run.output = "/dev/null";  // the stream's place takes the params
  section::Stream summary;  // units and issues of every section, for the params output
  // A plain profile (x y per line): its spline is fitted to its points, and its values are
  // checked against the same points fitted from its other end (in the hold step), which
  // are fitted and measured beside it.
  std::future<section::Stream> other_end;
  run.other_input = [&](const std::string& text, const std::string& source) {
    auto points = section::parse_profile(text, source);
    Eigen::AlignedBox2d box;
    for (const auto& p : points) box.extend(p);
    const section::InputUnits units = section::input_units(a.units, box.sizes().maxCoeff());
    for (auto& p : points) p *= units.mm;
    other_end = section::other_end_stream_async(points, per_part);
    section::Stream stream;
    section::tool::with_input(a.common.input, [&] { stream = section::plain_profile_stream(points); });
    if (!units.warning.empty()) std::cerr << "camber: warning: " << units.warning << "\n";
    if (!units.note.empty()) stream.notes.push_back(units.note);
    return stream;
  };
  // A doubtful unit (slice's or the plain profile's note) or a view registered unconfirmed (slice's note)
  // flags every row.
  bool doubtful_units = false, unconfirmed = false;
  run.preamble = [&](const section::Stream& head) {
    doubtful_units = section::units_doubtful(head);
    unconfirmed = section::registration_unconfirmed(head);
    summary.units = head.units;
    summary.history = head.history;
    summary.history.push_back(history);
  };
  // The check across the blade needs every section: the parts are held until all are measured.
  run.hold = [&](const std::vector<section::Stream*>& parts) {
    if (other_end.valid() && parts.size() == 1) section::flag_start_dependence(*parts[0], other_end.get());
    section::check_blade_stream(parts);
    section::flag_scan_layers(parts);
    section::flag_swapped_ends(parts);
    if (doubtful_units)
      for (section::Stream* part : parts) section::flag_doubtful_units(*part);
    if (unconfirmed)
      for (section::Stream* part : parts) section::flag_unconfirmed_registration(*part);
  };
  section::tool::SectionTally tally("splines", "params");
  run.written = [&](const section::Stream& stream) {
    section::tool::warn_issues("camber", stream, false);
    tally.add(stream);
    section::append_rows(params, section::schema::params.get(stream));
    section::append_rows(thickness, section::schema::thickness.get(stream));
    if (const section::Table* w = section::schema::walls.find(stream)) section::append_rows(walls, *w);
    if (const section::Table* m = section::schema::wall_map.find(stream)) section::append_rows(wall_map, *m);
    if (const section::Table* f = stream.find("frames")) section::append_rows(frames, *f);
    summary.issues.insert(summary.issues.end(), stream.issues.begin(), stream.issues.end());
  };
  section::run_stage(run);
  if (!a.params_file.empty()) section::write_file(a.params_file, section::format_csv(params));
  if (!a.thickness_file.empty()) section::write_file(a.thickness_file, section::format_csv(thickness));
  if (!a.walls_file.empty()) {
    if (walls.columns.empty()) walls = section::schema::walls.table();  // no cavity: the header alone
    section::write_file(a.walls_file, section::format_csv(walls));
  }
  if (!a.wall_map_file.empty()) {
    if (wall_map.columns.empty())
      wall_map = section::schema::wall_map.table();  // no cavity: the header alone
    section::write_file(a.wall_map_file, section::format_csv(wall_map));
  }
  if (format != "stream") {
    if (!frames.columns.empty()) summary.put(frames);
    section::write_file(a.common.output, params_output(format, summary, params, walls, wall_map));
  }
  tally.check(a.allow_partial);
}

}  // namespace

int main(int argc, char** argv) {
  return section::tool::run<CamberArgs>(
      argc, argv, [&](const CamberArgs& args) { run_camber(args, section::tool::command_line(argc, argv)); });
}

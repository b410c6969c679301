// SPDX-License-Identifier: GPL-3.0-or-later
// slice: cut a blade scan (point cloud or mesh) by section planes into ordered profiles.
#include "args/slice_args.h"

#include "section/cloud.h"
#include "section/error.h"
#include "section/mesh.h"
#include "section/io/stream.h"
#include "section/io/csv.h"
#include "section/io/file.h"
#include "section/io/cloud_io.h"
#include "section/io/mesh_io.h"
#include "section/io/slice_file.h"
#include "section/pipe/slice_stream.h"
#include "section/register_views.h"
#include "section/revolution.h"
#include "section/slice.h"
#include "section/units.h"

#include <algorithm>
#include <cstdio>
#include <iostream>
#include <optional>
#include <utility>
#include <vector>

namespace {

using section::tool::SliceArgs;

// Writes each section as a part of the stream once it and those before it are done (the
// next tool starts on it meanwhile). Nothing is written before a section has been sliced:
// failed sections wait until then, and when all fail, the output stays empty.
class SectionWriter {
public:
  SectionWriter(const SliceArgs& args, std::string history) : args_(args), history_(std::move(history)) {}
  std::vector<std::string> notes;  ///< of the whole stream (registered views), written before the first part
  std::string warning;             ///< about the whole input, said once a section has been sliced

  void operator()(const section::SectionSlice& s) {
    section::SliceResult one;
    one.sections = {s};
    section::Stream part = section::to_stream(one, history_, "mm");
    section::tool::warn_issues("slice", part, false);
    if (s.error.empty() && s.open_polylines > 0)
      std::cerr << "slice: warning: section " << s.id << ": " << s.open_polylines
                << " open intersection polyline(s): the mesh is not closed around this plane; its cut points "
                   "were ordered as a scan's, the loop bridging up to "
                << s.bridged
                << " mm without a cut point (a hole in the mesh): camber flags what rests on it\n";
    ++sections_;
    if (!s.error.empty()) ++failed_;
    if (!writer_ && !s.error.empty()) {
      waiting_.emplace_back(s.id, std::move(part));
      return;
    }
    if (!writer_) {
      // The input's unit is worth a word once a section of it has been sliced.
      if (!warning.empty()) std::cerr << "slice: warning: " << warning << "\n";
      section::Stream head;
      head.units = "mm";
      head.history = {history_};
      head.notes = notes;
      writer_.emplace(args_.common.output, head);
      for (const auto& [id, earlier] : waiting_) writer_->part(std::to_string(id), earlier);
      waiting_.clear();
    }
    writer_->part(std::to_string(s.id), part);
  }

  // Closes the stream; throws when no section could be sliced.
  void finish() {
    const std::string hint = normal_hint();
    if (failed_ == sections_)
      throw section::Error(section::tool::input_name(args_.common.input) +
                           ": no section could be sliced (see the warnings above)" +
                           (hint.empty() ? "" : "; " + hint));
    if (!hint.empty()) std::cerr << "slice: warning: " << hint << "\n";
    writer_->finish();
  }

private:
  // Most planes of one normal giving no profile: they may run along the part, as planes
  // normal to z do through a blade scanned with its span along x (open sheets, points that
  // close into no loop, each section's own message saying only that).
  std::string normal_hint() const {
    if (!args_.axis.empty() || !args_.planes_file.empty() || args_.by_rows() || sections_ < 2 ||
        2 * failed_ <= sections_)
      return "";
    char text[400];
    std::snprintf(
        text, sizeof text,
        "%zu of %zu planes gave no profile: if they run along the part rather than across its span, "
        "give --normal along the span (now %g,%g,%g), or cut a rotor on surfaces of revolution (--axis)",
        failed_, sections_, args_.normal[0], args_.normal[1], args_.normal[2]);
    return text;
  }

  const SliceArgs& args_;
  std::string history_;
  std::optional<section::StreamWriter> writer_;
  std::vector<std::pair<int, section::Stream>> waiting_;
  std::size_t failed_ = 0, sections_ = 0;
};

// A cloud file as read (in its own unit): a plain 2D profile (two columns) at z = 0.
section::Cloud read_points(const std::string& name) {
  if (auto profile = section::read_profile_cloud(name)) return std::move(*profile);
  return section::read_cloud(name);
}

// The clouds of the input and its views, as read (in their own unit).
std::vector<section::Cloud> read_views(const SliceArgs& a) {
  std::vector<std::string> names{a.common.input};
  names.insert(names.end(), a.views.begin(), a.views.end());
  std::vector<section::Cloud> clouds;
  for (const auto& name : names) {
    if (section::is_mesh_file(name)) throw section::Error(name + ": --view takes point clouds, not meshes");
    clouds.push_back(read_points(name));
  }
  return clouds;
}

// What the points are, said in the stream and, unless a dense scan, on standard error.
void say_sampling(const section::Sampling& sampling, SectionWriter& out) {
  if (sampling.kind == section::SamplingKind::dense) return;
  out.notes.push_back(section::sampling_note(sampling));
  std::cerr << "slice: the points are " << sampling.describe() << "\n";
}

// Views apart: held in memory, registered onto the input, merged, then sliced.
section::Cloud merged_views(const SliceArgs& a, const std::vector<section::Cloud>& clouds,
                            SectionWriter& out) {
  section::RegisterResult reg;
  try {
    reg = section::register_views(clouds, a.register_options);
  } catch (const section::Error& e) {
    std::string what = e.what();
    for (std::size_t k = 1; k < clouds.size(); ++k)
      if (what.find("view " + std::to_string(k) + " ") != std::string::npos)
        what += " (view " + std::to_string(k) + ": " + a.views[k - 1] + ")";
    throw section::Error(what);
  }
  for (std::size_t k = 1; k < clouds.size(); ++k) {
    out.notes.push_back(section::describe(reg.views[k], a.views[k - 1]));
    if (!reg.views[k].caution.empty())
      std::cerr << "slice: warning: register_views: view " << k << " (" << a.views[k - 1]
                << "): " << reg.views[k].caution << "\n";
  }
  return section::merge_views(clouds, reg);
}

// Planes spread over a part whose extent left points out: where they lie, and what to do.
void warn_strays(const section::PartExtent& e, int count) {
  if (e.strays == 0) return;
  std::cerr << "slice: warning: " << e.strays << " point" << (e.strays == 1 ? " lies" : "s lie")
            << " far beyond the rest along the normal (offsets " << section::format_length(e.lowest) << " to "
            << section::format_length(e.highest) << "; the rest " << section::format_length(e.lo) << " to "
            << section::format_length(e.hi) << "): the " << count
            << " planes are spread over the rest (strays: a reflection, dust, a fixture; crop them from "
               "the scan, or give the planes)\n";
}

// The input's unit (given, or guessed from its extent), said on standard error and in the stream
// once the input has been read.
section::InputUnits units_of(const SliceArgs& a, double extent, SectionWriter& out) {
  const section::InputUnits units = section::input_units(a.units, extent);
  out.warning = units.warning;
  if (!units.note.empty()) out.notes.push_back(units.note);
  return units;
}

void run_slice(const SliceArgs& given, const std::string& history) {
  section::tool::refuse_terminal_output(given.common, "smooth");
  const std::string& input = given.common.input;
  SectionWriter out(given, history);
  // Held in memory (views, standard input, a mesh): the extent from all the points; a cloud
  // file: from points spread over it. Everything is converted to mm before it is sliced.
  std::vector<section::Cloud> clouds;
  std::optional<section::Mesh> mesh;
  double extent = 0;
  const bool is_mesh = section::is_mesh_file(input);
  if (is_mesh && given.by_rows())
    throw section::Error(input + ": a mesh is cut by planes: give --at, --count or --planes");
  if (is_mesh) {
    mesh = section::read_mesh(input);
    extent = section::points_extent(mesh->vertices);
  } else if (!given.views.empty() || input == "-" || given.by_rows() || !given.axis.empty() ||
             section::read_profile_cloud(input)) {
    clouds = read_views(given);
    extent = section::points_extent(clouds[0].points);
  } else {
    extent = section::sample_extent(input);
  }
  const section::InputUnits units = units_of(given, extent, out);
  const SliceArgs a = given.in_mm(units.mm);
  const Eigen::Vector3d n(a.normal[0], a.normal[1], a.normal[2]);
  std::vector<section::Plane> planes;
  if (!a.planes_file.empty()) {
    planes = section::parse_planes(section::read_file(a.planes_file), a.planes_file);
    for (auto& p : planes) p.origin *= units.mm;
  } else if (!a.at.empty()) {
    planes = section::planes_at(n, a.at);
  }
  for (auto& c : clouds)
    for (auto& p : c.points) p *= units.mm;
  if (mesh)
    for (auto& v : mesh->vertices) v *= units.mm;
  // Each section is written as soon as it is done (the next tool starts on it meanwhile),
  // the sampling said before the first.
  const auto said = [&](const section::Sampling& sampling) { say_sampling(sampling, out); };
  if (!clouds.empty()) {
    const section::Cloud merged = a.views.empty() ? std::move(clouds[0]) : merged_views(a, clouds, out);
    if (a.count > 0 && a.axis.empty()) {
      const section::PartExtent extent = section::extent_along(merged.points, n);
      warn_strays(extent, a.count);
      planes = section::planes_across(extent, n, a.count);
    }
    section::tool::with_input(input, [&] {
      if (!a.axis.empty()) {
        section::slice(merged, a.surfaces(merged.points, units.mm), a.options, std::ref(out), said);
      } else if (a.by_rows()) {
        section::slice_by_rows(merged, n, a.options, a.rows, std::ref(out), said);
      } else {
        section::slice(merged, planes, a.options, std::ref(out), said);
      }
    });
  } else if (mesh) {
    if (a.count > 0 && a.axis.empty()) {
      const section::PartExtent extent = section::extent_along(mesh->vertices, n);
      warn_strays(extent, a.count);
      planes = section::planes_across(extent, n, a.count);
    }
    section::tool::with_input(input, [&] {
      if (a.axis.empty())
        section::slice(*mesh, planes, a.options, std::ref(out));
      else
        section::slice(*mesh, a.surfaces(mesh->vertices, units.mm), a.options, std::ref(out));
    });
  } else {
    // Streamed: only the slab points are held, not the cloud, and each section is written
    // as it comes. Read errors name the file already, so with_input leaves them as they are.
    section::CloudReadOptions read;
    read.scale = units.mm;
    section::tool::with_input(input, [&] {
      const section::SliceResult r = section::slice_file(input, section::PlaneSpec{planes, n, a.count},
                                                         a.options, read, std::ref(out), said);
      warn_strays(r.extent, a.count);
    });
  }
  out.finish();
}

}  // namespace

int main(int argc, char** argv) {
  return section::tool::run<SliceArgs>(
      argc, argv, [&](const SliceArgs& args) { run_slice(args, section::tool::command_line(argc, argv)); });
}

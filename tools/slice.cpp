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
#include "section/slice.h"

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

  void operator()(const section::SectionSlice& s) {
    section::SliceResult one;
    one.sections = {s};
    section::Stream part = section::to_stream(one, history_, args_.units);
    section::tool::warn_issues("slice", part, false);
    ++sections_;
    if (!s.error.empty()) ++failed_;
    if (!writer_ && !s.error.empty()) {
      waiting_.emplace_back(s.id, std::move(part));
      return;
    }
    if (!writer_) {
      section::Stream head;
      head.units = args_.units;
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
    if (failed_ == sections_)
      throw section::Error(section::tool::input_name(args_.common.input) +
                           ": no section could be sliced (see the warnings above)");
    writer_->finish();
  }

private:
  const SliceArgs& args_;
  std::string history_;
  std::optional<section::StreamWriter> writer_;
  std::vector<std::pair<int, section::Stream>> waiting_;
  std::size_t failed_ = 0, sections_ = 0;
};

// Views apart: held in memory, registered onto the input, merged, then sliced.
section::Cloud merged_views(const SliceArgs& a, SectionWriter& out) {
  std::vector<std::string> names{a.common.input};
  names.insert(names.end(), a.views.begin(), a.views.end());
  std::vector<section::Cloud> clouds;
  for (const auto& name : names) {
    if (section::is_mesh_file(name)) throw section::Error(name + ": --view takes point clouds, not meshes");
    clouds.push_back(section::read_cloud(name));
  }
  section::RegisterResult reg;
  try {
    reg = section::register_views(clouds, a.register_options);
  } catch (const section::Error& e) {
    std::string what = e.what();
    for (std::size_t k = 1; k < names.size(); ++k)
      if (what.find("view " + std::to_string(k) + " ") != std::string::npos)
        what += " (view " + std::to_string(k) + ": " + names[k] + ")";
    throw section::Error(what);
  }
  for (std::size_t k = 1; k < names.size(); ++k)
    out.notes.push_back(section::describe(reg.views[k], names[k]));
  return section::merge_views(clouds, reg);
}

void run_slice(const SliceArgs& a, const std::string& history) {
  const Eigen::Vector3d n(a.normal[0], a.normal[1], a.normal[2]);
  std::vector<section::Plane> planes;
  if (!a.planes_file.empty())
    planes = section::parse_planes(section::read_file(a.planes_file), a.planes_file);
  else if (!a.at.empty())
    planes = section::planes_at(n, a.at);
  SectionWriter out(a, history);
  const std::string& input = a.common.input;
  section::SliceResult result;
  if (!a.views.empty()) {
    const section::Cloud merged = merged_views(a, out);
    if (a.count > 0) planes = section::planes_across(merged.points, n, a.count);
    section::tool::with_input(input, [&] { result = section::slice(merged, planes, a.options); });
  } else if (section::is_mesh_file(input)) {
    const section::Mesh mesh = section::read_mesh(input);
    if (a.count > 0) planes = section::planes_across(mesh.vertices, n, a.count);
    section::tool::with_input(input, [&] { result = section::slice(mesh, planes, a.options); });
  } else {
    // Streamed: only the slab points are held, not the cloud, and each section is written
    // as it comes. Read errors name the file already, so with_input leaves them as they are.
    section::tool::with_input(input, [&] {
      section::slice_file(input, section::PlaneSpec{planes, n, a.count}, a.options, {}, std::ref(out));
    });
  }
  for (const auto& s : result.sections) out(s);
  out.finish();
}

}  // namespace

int main(int argc, char** argv) {
  return section::tool::run<SliceArgs>(
      argc, argv, [&](const SliceArgs& args) { run_slice(args, section::tool::command_line(argc, argv)); });
}

// slice: cut a blade scan (point cloud or mesh) by section planes into ordered profiles.
#include "common/tool.h"

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

#include <iostream>
#include <optional>
#include <utility>
#include <vector>

namespace {

const char* const description =
    "slice: cut a blade scan by section planes into ordered section profiles.\n\n"
    "Reads a point cloud (.xyz .asc .txt .csv .ply; '-' = stdin, XYZ or PLY) or a mesh\n"
    "(.stl .obj .off, or .ply with faces) and writes the pipe stream (docs/FORMAT.md) with,\n"
    "per section: the plane frame, the measured points of the slab projected onto the plane\n"
    "and ordered along each closed loop with outward normals, and the skeleton of the\n"
    "filled profile. Loop 0 is the profile (largest area).\n\n"
    "Gaps: where the slab leaves a gap longer than --fill-gap slab widths (a hole, a sparse\n"
    "thin edge), scan points up to --fill-reach from the plane are carried onto it along the\n"
    "surface (the section's drift with height is fitted beside the gap) and fill it; the\n"
    "stream notes how many per section ('# fill ...'). --no-fill keeps the slab points alone.\n"
    "Band: where the slab is sparse, points up to --band-max slab widths from the plane join\n"
    "it, each carried onto the plane along the section's drift (lean, sweep, twist, taper and\n"
    "a camber or thickness changing with height, fitted over the section) rather than\n"
    "projected straight, until the profile holds about one point per --band-spacing ('# band\n"
    "...' in the stream); --band-sparse-max widens it beside sparse stretches of the profile.\n"
    "--band-spacing 0 keeps the slab.\n"
    "Meshes are cut exactly and need neither.\n\n"
    "Views: a part scanned in several views, each in its own file: the input is the first,\n"
    "--view adds each other one. Each is registered onto the first (rigid ICP to the surface\n"
    "they share; the views must be aligned to within --view-reach already) before\n"
    "slicing, and the stream notes how it moved ('# register ...'). A view misregistered by a\n"
    "few micrometres otherwise shifts every section it alone covers by that much.\n\n"
    "Planes: --normal with --at offsets or --count planes spread over the part, or --planes FILE\n"
    "(CSV with origin_x,origin_y,origin_z,normal_x,normal_y,normal_z).\n\n"
    "Example: slice blade.ply --normal 0,0,1 --at 12,20,28 | smooth | fitspline | camber";

std::vector<double> triple(const std::vector<double>& v, const char* what) {
  if (v.size() != 3) throw CLI::ValidationError(std::string(what) + " takes three comma-separated numbers");
  return v;
}

}  // namespace

int main(int argc, char** argv) {
  section::tool::Common common;
  std::vector<double> normal{0, 0, 1};
  std::vector<double> at;
  int count = 0;
  std::string planes_file;
  std::vector<std::string> views;
  section::RegisterOptions register_options;
  section::SliceOptions options;
  std::string units = "mm";
  return section::tool::run_tool(
      "slice", description, argc, argv,
      [&](CLI::App& app) {
        section::tool::add_common(app, common);
        app.add_option("--normal", normal, "Plane normal x,y,z")->delimiter(',')->capture_default_str();
        auto* o_at = app.add_option("--at", at, "Plane offsets along the normal, comma-separated")->delimiter(',');
        auto* o_count = app.add_option("--count", count, "Number of planes spread evenly over the part")
                            ->check(CLI::Range(1, 100000));
        auto* o_planes = app.add_option("--planes", planes_file, "CSV file of planes (origin and normal)");
        o_at->excludes(o_count)->excludes(o_planes);
        o_count->excludes(o_planes);
        app.add_option("--slab", options.slab, "Slab width d; 0 = the estimated point spacing")
            ->check(CLI::NonNegativeNumber)->capture_default_str();
        app.add_option("--cell", options.morphology.cell, "Raster cell h; 0 = the estimated spacing in the section")
            ->check(CLI::NonNegativeNumber)->capture_default_str();
        app.add_option("--band-spacing", options.band_spacing,
                       "Widen the slab into a drift-corrected band until the profile holds one point per this "
                       "length; 0 = the slab alone")
            ->check(CLI::NonNegativeNumber)
            ->capture_default_str();
        app.add_option("--band-max", options.band_max, "Largest half width of the band, in slab widths (>= 0.5)")
            ->check(CLI::Range(0.5, 1e6))
            ->capture_default_str();
        app.add_option("--band-sparse-max", options.band_sparse_max,
                       "Widen the band beside a sparse stretch of the profile up to this half width, in slab "
                       "widths; 0 = off")
            ->check(CLI::Range(0.0, 1e6))
            ->capture_default_str();
        app.add_flag("--no-fill", [&](std::int64_t) { options.fill_gaps = false; },
                     "Do not fill the slab's gaps from points beside the plane");
        app.add_option("--fill-reach", options.fill.reach,
                       "Farthest distance from the plane of the points that fill gaps; 0 = 12 slab widths")
            ->check(CLI::NonNegativeNumber);
        app.add_option("--fill-gap", options.fill.min_gap, "Fill gaps longer than this many slab widths")
            ->check(section::tool::positive)
            ->capture_default_str();
        app.add_option("--view", views, "Another view of the same part (a point cloud), registered onto the input "
                                        "before slicing; repeat for more views");
        app.add_option("--view-reach", register_options.reach,
                       "Views: pairs are sought within this distance; 0 = 3 x the input's point spacing")
            ->check(CLI::NonNegativeNumber)
            ->capture_default_str();
        app.add_option("--threads", options.threads, "Worker threads; 0 = all cores")->check(CLI::NonNegativeNumber);
        app.add_option("--units", units, "Length unit recorded in the stream")->capture_default_str();
        app.callback([&] {
          triple(normal, "--normal");
          if (at.empty() && count == 0 && planes_file.empty())
            throw CLI::RequiredError("one of --at, --count or --planes");
        });
      },
      [&] {
        const Eigen::Vector3d n(normal[0], normal[1], normal[2]);
        std::vector<section::Plane> planes;
        if (!planes_file.empty()) planes = section::parse_planes(section::read_file(planes_file), planes_file);
        else if (!at.empty()) planes = section::planes_at(n, at);
        section::SliceResult result;
        std::vector<std::string> notes;
        // Each section is written as a part of the stream once it and those before it are
        // done (the next tool starts on it meanwhile). Nothing is written before a section
        // has been sliced: failed sections wait until then, and when all fail, the output
        // stays empty.
        std::optional<section::StreamWriter> writer;
        std::vector<std::pair<int, section::Stream>> waiting;
        std::size_t failed = 0, sections = 0;
        const std::string history = section::tool::command_line(argc, argv);
        const section::SectionSink write_section = [&](const section::SectionSlice& s) {
          section::SliceResult one;
          one.sections = {s};
          section::Stream part = section::to_stream(one, history, units);
          for (const auto& issue : part.issues)
            std::cerr << "slice: warning: section " << issue.section << ": " << issue.message << "\n";
          ++sections;
          if (!s.error.empty()) ++failed;
          if (!writer && !s.error.empty()) {
            waiting.emplace_back(s.id, std::move(part));
            return;
          }
          if (!writer) {
            section::Stream head;
            head.units = units;
            head.history = {history};
            head.notes = notes;
            writer.emplace(common.output, head);
            for (const auto& [id, earlier] : waiting) writer->part(std::to_string(id), earlier);
            waiting.clear();
          }
          writer->part(std::to_string(s.id), part);
        };
        if (!views.empty()) {
          // Views apart: held in memory, registered, merged, then sliced.
          std::vector<std::string> names{common.input};
          names.insert(names.end(), views.begin(), views.end());
          std::vector<section::Cloud> clouds;
          for (const auto& name : names) {
            if (name != "-" && section::is_mesh_file(name))
              throw section::Error(name + ": --view takes point clouds, not meshes");
            clouds.push_back(section::read_cloud(name));
          }
          section::RegisterResult reg;
          try {
            reg = section::register_views(clouds, register_options);
          } catch (const section::Error& e) {
            std::string what = e.what();
            for (std::size_t k = 1; k < names.size(); ++k)
              if (what.find("view " + std::to_string(k) + " ") != std::string::npos)
                what += " (view " + std::to_string(k) + ": " + names[k] + ")";
            throw section::Error(what);
          }
          for (std::size_t k = 1; k < names.size(); ++k) notes.push_back(section::describe(reg.views[k], names[k]));
          const section::Cloud merged = section::merge_views(clouds, reg);
          clouds = {};  // the views apart are no longer needed
          if (count > 0) planes = section::planes_across(merged.points, n, count);
          section::tool::with_input(common.input, [&] { result = section::slice(merged, planes, options); });
          for (const auto& s : result.sections) write_section(s);
        } else if (common.input != "-" && section::is_mesh_file(common.input)) {
          const section::Mesh mesh = section::read_mesh(common.input);
          if (count > 0) planes = section::planes_across(mesh.vertices, n, count);
          section::tool::with_input(common.input, [&] { result = section::slice(mesh, planes, options); });
          for (const auto& s : result.sections) write_section(s);
        } else {
          // Streamed: only the slab points are held, not the cloud. Read errors name the file
          // already, so with_input leaves them as they are.
          section::tool::with_input(common.input, [&] {
            result = section::slice_file(common.input, section::PlaneSpec{planes, n, count}, options, {}, write_section);
          });
        }
        if (failed == sections)
          throw section::Error((common.input == "-" ? std::string("<stdin>") : common.input) +
                               ": no section could be sliced (see the warnings above)");
        writer->finish();
      });
}

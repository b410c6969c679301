// bladegen: synthetic blade scans and meshes with exact ground truth.
#include "common/tool.h"

#include "section/cloud.h"
#include "section/error.h"
#include "section/extras/generate.h"
#include "section/mesh.h"
#include "section/io/cloud_io.h"
#include "section/io/mesh_io.h"

#include <charconv>
#include <cstdio>
#include <string>
#include <vector>

namespace {

const char* const description =
    "bladegen: make a synthetic blade (scan or mesh) whose true sections are known exactly.\n\n"
    "A section is the envelope of circles r(s) along a camber curve c(s), closed by the\n"
    "edge circles; the blade stacks sections along z (hub z = 0, tip z = span = 60 mm),\n"
    "blending the design smoothly. --points samples the side surface like a scanner (noise\n"
    "along the normal, holes, varying density, two misregistered views, outliers);\n"
    "--mesh writes a closed triangle mesh. The format follows the extension of -o\n"
    "(.ply binary / .xyz text for points; .stl .obj .off .ply for meshes).\n\n"
    "--truth FILE --at Z1,Z2,... writes the exact section parameters at those heights as\n"
    "CSV, one row per height, columns (mm, degrees):\n"
    "  z, chord (|TE point - LE point|), stagger, inlet_angle, outlet_angle (camber\n"
    "  tangents at LE and TE), camber_length (LE point to TE point), max_thickness,\n"
    "  max_thickness_pos (arc-length fraction along the camber), le_radius, te_radius,\n"
    "  le_x, le_y, te_x, te_y (edge points), le_center_x, le_center_y, te_center_x,\n"
    "  te_center_y (edge circle centres), area, centroid_x, centroid_y, perimeter.\n\n"
    "Example: bladegen --kind turbine --points --noise 0.005 --holes 5 -o blade.ply \\\n"
    "           --truth truth.csv --at 12,20,28";

std::string number(double v) {
  char b[32];
  const auto r = std::to_chars(b, b + sizeof b, v);
  return std::string(b, r.ptr);
}

void write_truth(const std::string& path, const section::BladeDesign& blade, const std::vector<double>& at) {
  std::string out =
      "z,chord,stagger,inlet_angle,outlet_angle,camber_length,max_thickness,max_thickness_pos,"
      "le_radius,te_radius,le_x,le_y,te_x,te_y,le_center_x,le_center_y,te_center_x,te_center_y,"
      "area,centroid_x,centroid_y,perimeter\n";
  for (double z : at) {
    if (z < 0 || z > blade.span)
      throw section::Error("bladegen: --at " + number(z) + " is outside the span [0, " + number(blade.span) + "]");
    const section::SectionTruth t = section::section_truth(blade.at(z));
    const double v[] = {z, t.chord, t.stagger, t.inlet_angle, t.outlet_angle, t.camber_length,
                        t.max_thickness, t.max_thickness_pos, t.le_radius, t.te_radius,
                        t.le_point.x(), t.le_point.y(), t.te_point.x(), t.te_point.y(),
                        t.le_center.x(), t.le_center.y(), t.te_center.x(), t.te_center.y(),
                        t.area, t.centroid.x(), t.centroid.y(), t.perimeter};
    for (std::size_t i = 0; i < std::size(v); ++i) out += (i ? "," : "") + number(v[i]);
    out += '\n';
  }
  std::FILE* f = std::fopen(path.c_str(), "wb");
  if (!f) throw section::Error("bladegen: " + path + ": cannot open for writing");
  const bool ok = std::fwrite(out.data(), 1, out.size(), f) == out.size();
  if (std::fclose(f) != 0 || !ok) throw section::Error("bladegen: " + path + ": write error");
}

}  // namespace

int main(int argc, char** argv) {
  std::string output, kind = "turbine", truth, second_view;
  bool points = false, mesh = false;
  section::ScanOptions scan;
  int profile_points = 400, layers = 60;
  std::vector<double> at;
  return section::tool::run_tool(
      "bladegen", description, argc, argv,
      [&](CLI::App& app) {
        app.add_option("--kind", kind, "Blade preset")->check(CLI::IsMember({"turbine", "compressor"}))->capture_default_str();
        auto* o_points = app.add_flag("--points", points, "Write a scanned point cloud");
        auto* o_mesh = app.add_flag("--mesh", mesh, "Write a closed triangle mesh");
        o_points->excludes(o_mesh);
        app.add_option("-o,--output", output, "Output file (.ply .xyz; .stl .obj .off .ply for --mesh), - = stdout (points)");
        app.add_option("--spacing", scan.spacing, "Scan point spacing, mm")->check(section::tool::positive)->capture_default_str();
        app.add_option("--noise", scan.noise, "Noise sigma along the surface normal, mm")->check(CLI::NonNegativeNumber)->capture_default_str();
        app.add_option("--holes", scan.holes, "Number of unscanned patches (0.5-2 mm across)")->check(CLI::NonNegativeNumber)->capture_default_str();
        app.add_option("--density-min", scan.density_min, "Lowest relative local density, (0, 1]")->check(CLI::Range(1e-6, 1.0))->capture_default_str();
        app.add_option("--misregistration", scan.misregistration, "Offset of the second view, mm")->check(CLI::NonNegativeNumber)->capture_default_str();
        app.add_option("--outliers", scan.outlier_fraction, "Fraction of points replaced by outliers")->check(CLI::Range(0.0, 0.999))->capture_default_str();
        app.add_option("--seed", scan.seed, "Random seed")->capture_default_str();
        app.add_option("--z-min", scan.z_min, "Lowest scanned height, mm")->capture_default_str();
        app.add_option("--z-max", scan.z_max, "Highest scanned height, mm; below --z-min = the whole span")->capture_default_str();
        app.add_option("--profile-points", profile_points, "Mesh: points per section ring")->check(CLI::Range(16, 1000000))->capture_default_str();
        app.add_option("--layers", layers, "Mesh: number of section rings along the span")->check(CLI::Range(2, 100000))->capture_default_str();
        app.add_option("--second-view", second_view,
                       "Points: write the second view's points to this file and only the first view's to -o "
                       "(the views apart, as a scanner delivers them; slice --view registers them)");
        auto* o_truth = app.add_option("--truth", truth, "Write the true section parameters (CSV) to this file");
        app.add_option("--at", at, "Heights of the --truth sections, comma-separated, mm")->delimiter(',')->needs(o_truth);
        app.callback([&] {
          if ((points || mesh) && output.empty()) throw CLI::RequiredError("-o/--output");
          if (!points && !mesh && truth.empty()) throw CLI::RequiredError("one of --points, --mesh or --truth");
          if (!truth.empty() && at.empty()) throw CLI::RequiredError("--at (with --truth)");
          if (!output.empty() && !points && !mesh) throw CLI::ValidationError("-o needs --points or --mesh");
          if (!second_view.empty() && !points) throw CLI::ValidationError("--second-view needs --points");
        });
      },
      [&] {
        const section::BladeDesign blade = kind == "turbine" ? section::turbine_blade() : section::compressor_blade();
        if (points && second_view.empty()) section::write_cloud(output, section::generate_scan(blade, scan).cloud);
        if (points && !second_view.empty()) {
          const std::vector<section::Cloud> views = section::views_of(section::generate_scan(blade, scan));
          section::write_cloud(output, views[0]);
          section::write_cloud(second_view, views[1]);
        }
        if (mesh) section::write_mesh(output, section::generate_mesh(blade, profile_points, layers));
        if (!truth.empty()) write_truth(truth, blade, at);
      });
}

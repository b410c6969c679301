#include "args/bladegen_args.h"

namespace section::tool {

const char* const BladegenArgs::description =
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

namespace {

// The scanner: spacing, noise, holes, density, views, outliers, seed, heights.
void declare_scan(CLI::App& app, ScanOptions& scan) {
  add_checked(app, "--spacing", scan.spacing, "Scan point spacing, mm", positive);
  add_checked(app, "--noise", scan.noise, "Noise sigma along the surface normal, mm", CLI::NonNegativeNumber);
  add_checked(app, "--holes", scan.holes, "Number of unscanned patches (0.5-2 mm across)",
              CLI::NonNegativeNumber);
  add_checked(app, "--density-min", scan.density_min, "Lowest relative local density, (0, 1]",
              CLI::Range(1e-6, 1.0));
  add_checked(app, "--misregistration", scan.misregistration, "Offset of the second view, mm",
              CLI::NonNegativeNumber);
  add_checked(app, "--outliers", scan.outlier_fraction, "Fraction of points replaced by outliers",
              CLI::Range(0.0, 0.999));
  app.add_option("--seed", scan.seed, "Random seed")->capture_default_str();
  app.add_option("--z-min", scan.z_min, "Lowest scanned height, mm")->capture_default_str();
  app.add_option("--z-max", scan.z_max, "Highest scanned height, mm; below --z-min = the whole span")
      ->capture_default_str();
}

}  // namespace

void BladegenArgs::declare(CLI::App& app) {
  add_checked(app, "--kind", kind, "Blade preset", CLI::IsMember({"turbine", "compressor"}));
  auto* o_points = app.add_flag("--points", points, "Write a scanned point cloud");
  auto* o_mesh = app.add_flag("--mesh", mesh, "Write a closed triangle mesh");
  o_points->excludes(o_mesh);
  app.add_option("-o,--output", output,
                 "Output file (.ply .xyz; .stl .obj .off .ply for --mesh), - = stdout (points)");
  declare_scan(app, scan);
  add_checked(app, "--profile-points", profile_points, "Mesh: points per section ring",
              CLI::Range(16, 1000000));
  add_checked(app, "--layers", layers, "Mesh: number of section rings along the span", CLI::Range(2, 100000));
  app.add_option("--second-view", second_view,
                 "Points: write the second view's points to this file and only the first view's to -o "
                 "(the views apart, as a scanner delivers them; slice --view registers them)");
  auto* o_truth = app.add_option("--truth", truth, "Write the true section parameters (CSV) to this file");
  app.add_option("--at", at, "Heights of the --truth sections, comma-separated, mm")
      ->delimiter(',')
      ->needs(o_truth);
  app.callback([this] {
    if ((points || mesh) && output.empty()) throw CLI::RequiredError("-o/--output");
    if (!points && !mesh && truth.empty()) throw CLI::RequiredError("one of --points, --mesh or --truth");
    if (!truth.empty() && at.empty()) throw CLI::RequiredError("--at (with --truth)");
    if (!output.empty() && !points && !mesh) throw CLI::ValidationError("-o needs --points or --mesh");
    if (!second_view.empty() && !points) throw CLI::ValidationError("--second-view needs --points");
  });
}

}  // namespace section::tool

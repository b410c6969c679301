// SPDX-License-Identifier: GPL-3.0-or-later
#include "args/bladegen_args.h"

#include <map>

#include <stdexcept>

namespace section::tool {

const char* const BladegenArgs::description =
    "bladegen: make a synthetic blade (scan, mesh, grid or rows) whose true sections are\n"
    "known exactly.\n\n"
    "A section is the envelope of circles r(s) along a camber curve c(s), closed by the\n"
    "edge circles; the blade stacks sections along z (hub z = 0, tip z = span = 60 mm),\n"
    "blending the design smoothly. --kind: turbine, compressor, sharp-te (TE radius 0: the\n"
    "sides meet at one vertex), impulse (mirror-symmetric: the LE cannot be told from the\n"
    "thickness; its LE lies towards -x), thick-root (28 % thick at the hub, TE 0.2 mm).\n"
    "What is written (the format follows the extension of -o: .ply binary / .xyz text):\n"
    "  --points  a scan of the side surface (noise along the normal, holes, varying density,\n"
    "            two misregistered views, outliers);\n"
    "  --mesh    a closed triangle mesh (.stl .obj .off .ply);\n"
    "  --grid chordwise|spanwise  a CFD-like structured surface grid, no noise by default:\n"
    "            --lines lines of --line-points points, each line at one height around the\n"
    "            profile (chordwise) or at one place on the profile from hub to tip\n"
    "            (spanwise); places denser at the edges (--clustering);\n"
    "  --rows N  N sparse rows (a CMM, a layered scanner): --row-pitch apart, points\n"
    "            --spacing (default 1 mm) apart along each, at constant height or, with\n"
    "            --hub-radius R, at constant radius about the machine axis (the x axis\n"
    "            moved to z = -R: the rows lie on cylinders of radius R + z_row).\n"
    "--lean L, --sweep S, --bow B (mm) move each section at t = z / span by S t along +x and\n"
    "L t + 4 B t (1 - t) along +y (docs/BLADE.md); twist comes from the hub and tip stagger.\n"
    "--units m|in|um writes the coordinates in that unit (scaled from mm); the --at\n"
    "heights, the other options and the truth file stay in mm.\n\n"
    "--rotor cylinder|cone lays each section on a surface of revolution about the x axis (a\n"
    "rotor: docs/REVOLUTION.md): the section of height z on the cylinder of radius\n"
    "--rotor-radius + z, or on the cone through it at --cone-angle, its design (u, v) the\n"
    "surface's unrolled coordinates (--unroll); the truth is then that of the unrolled section.\n\n"
    "--truth FILE --at Z1,Z2,... writes the exact section parameters at those heights (mm;\n"
    "with --rows, --at defaults to the rows' heights) as CSV, one row per height, columns\n"
    "(mm, degrees, whatever --units):\n"
    "  z, chord (|TE point - LE point|), stagger, inlet_angle, outlet_angle (camber\n"
    "  tangents at LE and TE), camber_length (LE point to TE point), max_thickness,\n"
    "  max_thickness_pos (arc-length fraction along the camber), le_radius, te_radius\n"
    "  (0: a sharp edge, its point the vertex), le_x, le_y, te_x, te_y (edge points),\n"
    "  le_center_x, le_center_y, te_center_x, te_center_y (edge circle centres), area,\n"
    "  centroid_x, centroid_y, perimeter.\n\n"
    "Example: bladegen --kind turbine --points --noise 0.005 --holes 5 -o blade.ply \\\n"
    "           --truth truth.csv --at 12,20,28\n"
    "         bladegen --kind compressor --rows 5 --row-pitch 12 --units m -o rows.xyz \\\n"
    "           --truth truth.csv";

double mm_per_unit(const std::string& unit) {
  if (unit == "mm") return 1;
  if (unit == "m") return 1000;
  if (unit == "in") return 25.4;
  if (unit == "um") return 0.001;
  throw std::invalid_argument("bladegen: unknown unit '" + unit + "'");
}

namespace {

// The scanner: spacing, noise, holes, density, views, outliers, seed, heights.
void declare_scan(CLI::App& app, ScanOptions& scan) {
  add_checked(app, "--spacing", scan.spacing, "Scan point spacing, mm (--rows: along a row, default 1)",
              positive);
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

// The structured grid and the sparse rows: their own flags, each needing its mode.
void declare_grid_rows(CLI::App& app, BladegenArgs& a) {
  auto* o_grid =
      add_checked(app, "--grid", a.grid, "Write a structured surface grid: lines chordwise or spanwise",
                  CLI::IsMember({"chordwise", "spanwise"}));
  add_checked(app, "--lines", a.lines, "Grid: number of lines", CLI::Range(2, 1000000))->needs(o_grid);
  add_checked(app, "--line-points", a.line_points, "Grid: points a line", CLI::Range(2, 1000000))
      ->needs(o_grid);
  add_checked(app, "--clustering", a.grid_options.clustering,
              "Grid: 0 = even spacing around the profile, 1 = cosine (dense at the edges)",
              CLI::Range(0.0, 1.0))
      ->needs(o_grid);
  app.add_flag("--repeat-seam", a.grid_options.repeat_seam,
               "Grid: write the first place around the profile again at each line's end (an O-grid's seam)")
      ->needs(o_grid);
  auto* o_rows =
      add_checked(app, "--rows", a.rows, "Write this many sparse rows of points", CLI::Range(1, 10000));
  add_checked(app, "--row-pitch", a.rows_options.pitch, "Rows: distance between rows, mm", positive)
      ->needs(o_rows);
  app.add_option("--first-row", a.rows_options.first, "Rows: height of the first row, mm; < 0 = centred")
      ->capture_default_str()
      ->needs(o_rows);
  add_checked(
      app, "--hub-radius", a.rows_options.hub_radius,
      "Rows: > 0 = rows at constant radius about the x axis moved to z = -this, mm; 0 = constant height",
      CLI::NonNegativeNumber)
      ->needs(o_rows);
}

// --rotor and its surfaces.
void declare_rotor(CLI::App& app, BladegenArgs& a) {
  auto* o_rotor =
      add_checked(app, "--rotor", a.rotor,
                  "A rotor: each section designed on a cylinder (cylinder) or a cone (cone) about "
                  "the x axis, in its unrolled coordinates (docs/REVOLUTION.md); --points, --mesh, "
                  "--grid and --rows are carried onto the surfaces (rows: on their cylinders)",
                  CLI::IsMember({"cylinder", "cone"}));
  add_checked(app, "--rotor-radius", a.rotor_options.hub_radius,
              "Rotor: radius of the section z = 0 at axial position 0, mm (the section z at this + z)",
              positive)
      ->needs(o_rotor);
  add_checked(app, "--cone-angle", a.rotor_options.cone_angle,
              "Rotor cone: the meridians' slope against the axis, degrees", CLI::Range(-80.0, 80.0))
      ->needs(o_rotor);
  app.add_option(
         "--unroll", a.rotor_options.unrolling,
         "Rotor: how the designs lie on the surfaces: cylinder (r theta, axial), conformal (r_ref m', "
         "r_ref theta) or arclength (m, r_ref theta); default cylinder on cylinders, conformal on cones")
      ->transform(
          CLI::CheckedTransformer(std::map<std::string, Unrolling>{{"cylinder", Unrolling::cylinder},
                                                                   {"conformal", Unrolling::conformal},
                                                                   {"arclength", Unrolling::arclength}}))
      ->needs(o_rotor);
}

}  // namespace

void BladegenArgs::declare(CLI::App& app) {
  std::vector<std::string> kinds;
  for (const auto& p : blade_presets) kinds.emplace_back(p.name);
  add_checked(app, "--kind", kind, "Blade preset", CLI::IsMember(kinds));
  add_checked(app, "--span", span, "Blade height, mm; 0 = the preset's (60)", CLI::NonNegativeNumber);
  app.add_option("--lean", stacking.lean,
                 "Stacking: tangential (+y) move of the tip section, mm, linear in z")
      ->capture_default_str();
  app.add_option("--sweep", stacking.sweep, "Stacking: axial (+x) move of the tip section, mm, linear in z")
      ->capture_default_str();
  app.add_option("--bow", stacking.bow,
                 "Stacking: tangential move at mid-span, mm, parabolic (0 at hub and tip)")
      ->capture_default_str();
  add_checked(app, "--units", units, "Unit of the written coordinates",
              CLI::IsMember({"mm", "m", "in", "um"}));
  auto* o_points = app.add_flag("--points", points, "Write a scanned point cloud");
  auto* o_mesh = app.add_flag("--mesh", mesh, "Write a closed triangle mesh");
  o_points->excludes(o_mesh);
  app.add_option("-o,--output", output,
                 "Output file (.ply .xyz; .stl .obj .off .ply for --mesh), - = stdout (points)");
  declare_scan(app, scan);
  declare_grid_rows(app, *this);
  declare_rotor(app, *this);
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
  app.callback([this, &app] {
    spacing_given = app.count("--spacing") > 0;
    const int modes = int(points) + int(mesh) + int(!grid.empty()) + int(rows > 0);
    if (modes > 1) throw CLI::ValidationError("write one of --points, --mesh, --grid or --rows");
    if (modes == 1 && output.empty()) throw CLI::RequiredError("-o/--output");
    if (modes == 0 && truth.empty())
      throw CLI::RequiredError("one of --points, --mesh, --grid, --rows or --truth");
    if (!truth.empty() && at.empty() && rows == 0) throw CLI::RequiredError("--at (with --truth)");
    if (!output.empty() && modes == 0)
      throw CLI::ValidationError("-o needs --points, --mesh, --grid or --rows");
    if (!second_view.empty() && !points) throw CLI::ValidationError("--second-view needs --points");
    if (!grid.empty() || rows > 0)
      for (const char* scan_only : {"--holes", "--density-min", "--misregistration", "--outliers"})
        if (app.count(scan_only) > 0)
          throw CLI::ValidationError(std::string(scan_only) + " applies to --points only");
    if (rows > 0)
      for (const char* range : {"--z-min", "--z-max"})
        if (app.count(range) > 0)
          throw CLI::ValidationError(std::string(range) +
                                     " does not apply to --rows (--first-row, --row-pitch)");
    if (!rotor.empty() && rows_options.hub_radius > 0)
      throw CLI::ValidationError("--hub-radius (a planar blade's rows on cylinders) excludes --rotor");
    if (rotor == "cone" && app.count("--unroll") == 0) rotor_options.unrolling = Unrolling::conformal;
    if (rotor == "cylinder")
      rotor_options.cone_angle = 0;
    else if (rotor == "cone" && app.count("--cone-angle") == 0)
      rotor_options.cone_angle = 20;
    if (!grid.empty() && spacing_given)
      throw CLI::ValidationError("--spacing does not apply to --grid (--lines, --line-points)");
  });
}

BladeDesign BladegenArgs::blade() const {
  BladeDesign b = turbine_blade();
  for (const auto& p : blade_presets)
    if (kind == p.name) b = p.blade();
  if (span > 0) b.span = span;
  b.stacking = stacking;
  return b;
}

RotorDesign BladegenArgs::rotor_design() const {
  RotorDesign r = rotor_options;
  r.blade = blade();
  return r;
}

GridOptions BladegenArgs::grid_settings() const {
  GridOptions g = grid_options;
  const bool chordwise = grid != "spanwise";
  g.lines = chordwise ? GridOptions::Lines::chordwise : GridOptions::Lines::spanwise;
  g.heights = chordwise ? lines : line_points;
  g.around = chordwise ? line_points : lines;
  g.noise = scan.noise;
  g.z_min = scan.z_min;
  g.z_max = scan.z_max;
  g.seed = scan.seed;
  return g;
}

RowsOptions BladegenArgs::rows_settings() const {
  RowsOptions r = rows_options;
  r.rows = rows;
  r.spacing = spacing_given ? scan.spacing : 1.0;
  r.noise = scan.noise;
  r.seed = scan.seed;
  return r;
}

}  // namespace section::tool

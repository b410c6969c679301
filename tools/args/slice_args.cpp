// SPDX-License-Identifier: GPL-3.0-or-later
#include "args/slice_args.h"

#include "section/error.h"
#include "section/io/csv.h"
#include "section/io/file.h"

#include <algorithm>
#include <utility>

namespace section::tool {

const char* const SliceArgs::description =
    "slice: cut a blade scan by section planes into ordered section profiles.\n\n"
    "Reads a point cloud (.xyz .asc .txt .pts .csv .ply .pcd .las .laz .e57, T-Blade3's .dat;\n"
    "'-' = stdin: XYZ, PLY, LAS or PCD) or a mesh (.stl .obj .off, or .ply with faces) and\n"
    "writes the pipe stream (docs/FORMAT.md) with, per section: the plane frame, the\n"
    "measured points of the slab projected onto the plane and ordered along each closed loop\n"
    "with outward normals, and the skeleton of the filled profile. Loop 0 is the profile\n"
    "(largest area).\n\n"
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
    "Planes: --normal with --at offsets or --count planes spread over the part (a few stray\n"
    "points far off it left out, and said), or --planes FILE\n"
    "(CSV with origin_x,origin_y,origin_z,normal_x,normal_y,normal_z).\n\n"
    "Surfaces of revolution (docs/REVOLUTION.md): --axis PX,PY,PZ,DX,DY,DZ (a point of the\n"
    "machine axis and its direction) with cylinders (--radius R,R,... or --count N over the\n"
    "part's radii), cones (--cone A0,R0,A1,R1: two (axial, radius) points; repeat or give\n"
    "4 numbers per cone) or meridional streamlines (--streamline FILE of axial radius rows;\n"
    "repeat). With --axis alone, rows of points at constant radius (a CMM's passes) are each\n"
    "cut on their cylinder. A cloud's points within a shell around the surface (the slab's\n"
    "width) are taken, a mesh is cut exactly; each section is unrolled (--unroll: cylinder\n"
    "(r theta, axial), conformal (r_ref m', r_ref theta), arclength (m, r_ref theta)) and the\n"
    "frames table carries the surface, so samples, camber and params map back onto it in 3D.\n\n"
    "Sampling (docs/SAMPLING.md): with no --slab the points tell it. A dense scan: the slab is\n"
    "its point spacing. Lines of points close together (a structured surface grid): their\n"
    "spacing along the normal. Sparse rows, each a section's worth (a CMM pass, a scanner\n"
    "layer, one 2D profile, also at a constant radius if nearly planar): a plane through a row\n"
    "takes it as it lies, a plane between rows is reported with the rows beside it. With no\n"
    "planes, or --rows, each row is a section in its own best plane. A file of two columns\n"
    "(x y) is one profile at z = 0 and needs no planes. The stream notes what was found\n"
    "('# sampling ...', '# row ...').\n\n"
    "Example: slice blade.ply --normal 0,0,1 --at 12,20,28 | smooth | fitspline | camber\n"
    "         slice rotor.xyz --axis 0,0,0,1,0,0 --radius 210,230,250 | smooth | fitspline | camber\n"
    "         slice profile.xy | smooth | fitspline | camber";

namespace {

// The options that are lengths, by flag (given in the input's unit).
std::vector<std::pair<const char*, double*>> length_options(SliceArgs& a) {
  return {{"--slab", &a.options.slab},
          {"--cell", &a.options.morphology.cell},
          {"--band-spacing", &a.options.band_spacing},
          {"--fill-reach", &a.options.fill.reach},
          {"--view-reach", &a.register_options.reach},
          {"--r-ref", &a.r_ref}};
}

// --axis and the surfaces of revolution about it.
void declare_surfaces(CLI::App& app, SliceArgs& a) {
  app.add_option("--axis", a.axis,
                 "Machine axis PX,PY,PZ,DX,DY,DZ: cut by surfaces of revolution about it (cylinders "
                 "by --radius or --count, --cone, --streamline; alone: rows at constant radius)")
      ->delimiter(',');
  app.add_option("--radius", a.radii, "Cylinder radii about --axis, comma-separated")->delimiter(',');
  app.add_option("--cone", a.cones,
                 "Cones about --axis through two (axial, radius) points A0,R0,A1,R1 each (repeat, or 4 "
                 "numbers per cone)")
      ->delimiter(',');
  app.add_option("--streamline", a.streamlines,
                 "File of a meridional streamline about --axis, one (axial radius) point a line; repeat");
  app.add_option("--unroll", a.unroll,
                 "Unrolling of the surfaces: cylinder (r theta, axial), conformal (r_ref m', r_ref theta) "
                 "or arclength (m, r_ref theta); default cylinder for cylinders, conformal for the others")
      ->check(CLI::IsMember({"cylinder", "conformal", "arclength"}));
  add_checked(app, "--r-ref", a.r_ref,
              "Reference radius of the unrolled plane; 0 = the cylinder's radius, or the mean radius of "
              "the points nearest to the surface",
              CLI::NonNegativeNumber);
}

// The surface options' consistency (CLI11 cannot say it).
void check_surfaces(const SliceArgs& a) {
  if (a.axis.empty()) {
    if (!a.radii.empty() || !a.cones.empty() || !a.streamlines.empty() || !a.unroll.empty())
      throw CLI::ValidationError("--radius, --cone, --streamline and --unroll need --axis");
    return;
  }
  if (a.axis.size() != 6) throw CLI::ValidationError("--axis takes six comma-separated numbers");
  if (a.axis[3] == 0 && a.axis[4] == 0 && a.axis[5] == 0)
    throw CLI::ValidationError("--axis", "its direction must not be 0,0,0");
  if (a.cones.size() % 4 != 0) throw CLI::ValidationError("--cone takes four numbers per cone: A0,R0,A1,R1");
  if (!a.at.empty() || !a.planes_file.empty() || a.rows)
    throw CLI::ValidationError("--axis cuts by surfaces: it excludes --at, --planes and --rows");
  for (double r : a.radii)
    if (!(r > 0)) throw CLI::ValidationError("--radius", "radii must be positive");
}

// --normal, --at, --count, --planes: the planes.
void declare_planes(CLI::App& app, SliceArgs& a) {
  app.add_option("--normal", a.normal, "Plane normal x,y,z")->delimiter(',')->capture_default_str();
  auto* o_at =
      app.add_option("--at", a.at, "Plane offsets along the normal, comma-separated")->delimiter(',');
  auto* o_count = app.add_option("--count", a.count, "Number of planes spread evenly over the part")
                      ->check(CLI::Range(1, 100000));
  auto* o_planes = app.add_option("--planes", a.planes_file, "CSV file of planes (origin and normal)");
  auto* o_rows = app.add_flag("--rows", a.rows,
                              "Each row of points across the normal a section as it lies, in its best plane "
                              "(the default with no planes)");
  o_at->excludes(o_count)->excludes(o_planes)->excludes(o_rows);
  o_count->excludes(o_planes)->excludes(o_rows);
  o_planes->excludes(o_rows);
}

// --slab, --cell and the band's and the gap fill's options.
void declare_slab(CLI::App& app, SliceOptions& options) {
  add_checked(app, "--slab", options.slab,
              "Slab width d; 0 = from the points: a dense scan's spacing, lines' spacing along the normal, "
              "sparse rows as they lie",
              CLI::NonNegativeNumber);
  add_checked(app, "--cell", options.morphology.cell,
              "Raster cell h; 0 = the estimated spacing in the section", CLI::NonNegativeNumber);
  add_checked(app, "--band-spacing", options.band_spacing,
              "Widen the slab into a drift-corrected band until the profile holds one point per this "
              "length; 0 = the slab alone",
              CLI::NonNegativeNumber);
  add_checked(app, "--band-max", options.band_max, "Largest half width of the band, in slab widths (>= 0.5)",
              CLI::Range(0.5, 1e6));
  add_checked(app, "--band-sparse-max", options.band_sparse_max,
              "Widen the band beside a sparse stretch of the profile up to this half width, in slab "
              "widths; 0 = off",
              CLI::Range(0.0, 1e6));
  app.add_flag(
      "--no-fill", [&options](std::int64_t) { options.fill_gaps = false; },
      "Do not fill the slab's gaps from points beside the plane");
  app.add_option("--fill-reach", options.fill.reach,
                 "Farthest distance from the plane of the points that fill gaps; 0 = 12 slab widths")
      ->check(CLI::NonNegativeNumber);
  add_checked(app, "--fill-gap", options.fill.min_gap, "Fill gaps longer than this many slab widths",
              positive);
}

}  // namespace

void SliceArgs::declare(CLI::App& app) {
  add_common(app, common);
  declare_planes(app, *this);
  declare_surfaces(app, *this);
  declare_slab(app, options);
  app.add_option("--view", views,
                 "Another view of the same part (a point cloud), registered onto the input "
                 "before slicing; repeat for more views");
  add_checked(app, "--view-reach", register_options.reach,
              "Views: pairs are sought within this distance; 0 = 3 x the input's point spacing",
              CLI::NonNegativeNumber);
  app.add_option("--threads", options.threads, "Worker threads; 0 = all cores")
      ->check(CLI::NonNegativeNumber);
  app.add_option("--units", units,
                 "Length unit of the input (" + length_unit_names() +
                     "): its coordinates and the lengths given here are converted to mm, the stream's "
                     "unit; default mm, or m for an input under 1 across (with a warning)")
      ->check(length_unit);
  app.callback([this, &app] {
    lengths_given.clear();
    for (const auto& [flag, value] : length_options(*this))
      if (app.count(flag) > 0) lengths_given.push_back(flag);
    if (normal.size() != 3) throw CLI::ValidationError("--normal takes three comma-separated numbers");
    if (normal[0] == 0 && normal[1] == 0 && normal[2] == 0)
      throw CLI::ValidationError("--normal", "must not be 0,0,0 (a plane needs a direction)");
    const Eigen::Vector3d n = usable_normal({normal[0], normal[1], normal[2]});
    normal = {n.x(), n.y(), n.z()};
    check_surfaces(*this);
    options.sampling.threads = options.threads;  // --threads 1: no thread in the sampling either
  });
}

SliceArgs SliceArgs::in_mm(double mm) const {
  SliceArgs a = *this;
  for (const auto& [flag, value] : length_options(a))
    if (std::find(lengths_given.begin(), lengths_given.end(), flag) != lengths_given.end()) *value *= mm;
  for (double& at : a.at) at *= mm;
  for (double& r : a.radii) r *= mm;
  for (double& c : a.cones) c *= mm;
  for (std::size_t k = 0; k < 3 && k < a.axis.size(); ++k) a.axis[k] *= mm;
  return a;
}

std::vector<Revolution> SliceArgs::surfaces(const std::vector<Eigen::Vector3d>& points, double mm) const {
  const Eigen::Vector3d p(axis[0], axis[1], axis[2]), d(axis[3], axis[4], axis[5]);
  std::vector<double> r = radii;
  if (r.empty() && count > 0) {
    const Eigen::Vector2d range = radius_range(points, p, d);
    for (int k = 0; k < count; ++k) r.push_back(range.x() + (range.y() - range.x()) * (k + 1) / (count + 1));
  }
  if (r.empty() && cones.empty() && streamlines.empty()) r = row_radii(points, p, d, options.sampling);
  std::vector<Revolution> out;
  for (double radius : r) out.push_back(cylinder_surface(p, d, radius));
  for (std::size_t k = 0; k + 3 < cones.size(); k += 4)
    out.push_back(cone_surface(p, d, {cones[k], cones[k + 1]}, {cones[k + 2], cones[k + 3]}));
  for (const auto& file : streamlines) {
    std::vector<Eigen::Vector2d> meridian = parse_profile(read_file(file), file);
    for (auto& q : meridian) q *= mm;
    try {
      out.push_back(streamline_surface(p, d, std::move(meridian)));
      Revolution checked = out.back();  // its r_ref is chosen when slicing
      checked.r_ref = 1;
      check_surface(checked);
    } catch (const Error& e) {
      throw Error(file + ": " + e.what());
    }
  }
  const Eigen::Vector3d reference = reference_of(points, p, d);
  for (auto& s : out) {
    if (!unroll.empty()) s.unrolling = unrolling_named(unroll);
    if (r_ref > 0) s.r_ref = r_ref;
    s.reference = reference;
  }
  return out;
}

}  // namespace section::tool

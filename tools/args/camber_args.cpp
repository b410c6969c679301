// SPDX-License-Identifier: GPL-3.0-or-later
#include "args/camber_args.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <string_view>

namespace section::tool {

const char* const CamberArgs::description =
    "camber: mean-camber line and section parameters (docs/CAMBER.md).\n\n"
    "Reads the stream written by fitspline (docs/FORMAT.md) or a plain ordered 2D profile\n"
    "(x y per line, an airfoil .dat or CMM section; a title line is skipped, exact copies of\n"
    "a point count once; its points are checked as a scan's; any point may come first,\n"
    "either way round: the same values), and for the profile (loop 0) of every section\n"
    "computes the mean-camber line (the locus of the inscribed circles' centres, extended\n"
    "along its end tangents to the LE and TE points) and the section parameters. Adds the\n"
    "tables 'camber', 'params', 'thickness' and 'sides' to the stream; sections that fail\n"
    "are recorded as issues.\n\n"
    "A hollow blade's section (a CT scan's, with cooling channels) holds loops inside its\n"
    "profile: its cavities. The profile is measured as any other, and each cavity's thinnest\n"
    "wall to it, and its thinnest to the pressure and to the suction side (a shifted core\n"
    "thins one and thickens the other), go to the table 'walls' (--walls FILE), each flagged\n"
    "(check wall_measured) where a hole in the data lies under its thin stretch; the wall\n"
    "along each cavity, at --wall-stations stations evenly around it, goes to the table\n"
    "'wall_map' (--wall-map FILE). A loop beside the profile, across it or within a cavity\n"
    "leaves the section unmeasured.\n\n"
    "Every params row is checked before it is written (edge circles inside the blade, edge\n"
    "points on the profile, chord against the profile's extent, metal angles against the\n"
    "camber line, values against the neighbouring sections, and the chord's, max thickness's\n"
    "and end angles' standard errors through the points' noise, given as chord_sigma,\n"
    "max_thickness_sigma, inlet_angle_sigma and outlet_angle_sigma, against 10 and 5 um on a\n"
    "40 mm chord and 0.5 deg at 3 of them): a value that fails a check is flagged in the\n"
    "row's 'flags' column and by an issue (docs/CAMBER.md, \"Checks\").\n\n"
    "Exit status: 0 every section has params (flags or not), 1 bad data, 2 bad usage,\n"
    "3 the stream is written but some sections have no params (see their issues; exit 0\n"
    "with --allow-partial).\n\n"
    "On a terminal (no -o, no --format) camber prints the params as a table for people\n"
    "instead of the stream; --format chooses (stream, table, csv, json).\n\n"
    "Example: slice blade.ply --count 9 | smooth | fitspline | camber --params params.csv";

std::vector<double> numbers(const std::string& text, const std::string& flag) {
  std::vector<double> out;
  std::string_view rest = text;
  for (;;) {
    const std::size_t comma = rest.find(',');
    std::string_view item = rest.substr(0, comma);
    while (!item.empty() && (item.front() == ' ' || item.front() == '\t')) item.remove_prefix(1);
    while (!item.empty() && (item.back() == ' ' || item.back() == '\t')) item.remove_suffix(1);
    std::string_view digits = item;
    if (!digits.empty() && digits.front() == '+') digits.remove_prefix(1);
    double value = 0;
    const auto r = std::from_chars(digits.data(), digits.data() + digits.size(), value);
    if (digits.empty() || r.ec != std::errc() || r.ptr != digits.data() + digits.size() ||
        !std::isfinite(value))
      throw CLI::ValidationError(flag,
                                 "expected numbers separated by commas, found '" + std::string(item) + "'");
    out.push_back(value);
    if (comma == std::string_view::npos) break;
    rest.remove_prefix(comma + 1);
  }
  return out;
}

namespace {

// A check that `text` holds numbers (numbers()) and that `ok` accepts them: "" or why not.
CLI::Validator numbers_check(const std::string& flag, std::string (*ok)(const std::vector<double>&)) {
  return CLI::Validator(
      [flag, ok](std::string& text) {
        try {
          return ok(numbers(text, flag));
        } catch (const CLI::ValidationError& e) {
          return std::string(e.what());
        }
      },
      "");
}

std::string stations_ok(const std::vector<double>& v) {
  for (double f : v)  // at 0 and 1, the edge points, the camber normal runs along the profile
    if (!(f > 0 && f < 1))
      return "stations must lie between 0 and 1 (the edge points, where there is no thickness)";
  return "";
}

std::string direction_ok(const std::vector<double>& v) {
  if ((v.size() != 2 && v.size() != 3) || std::all_of(v.begin(), v.end(), [](double x) { return x == 0; }))
    return "expected two numbers u,v or three x,y,z, not all 0";
  return "";
}

}  // namespace

CLI::Validator direction_check(const std::string& flag) {
  return numbers_check(flag, direction_ok);
}

namespace {

// The edge model and the edge circles' fit.
void declare_edges(CLI::App& app, CamberArgs& a) {
  CamberOptions& o = a.options;
  add_checked(app, "--edge", a.edge,
              "Edge model: round (circle fitted to every edge) or auto "
              "(blunt and sharp edges get radius 0)",
              CLI::IsMember({"round", "auto"}));
  add_checked(app, "--edge-arc", o.edge_arc,
              "Degrees of a fixed edge arc the edge circle is fitted to (0 = grown geometrically)",
              CLI::Range(0.0, 270.0));
  add_checked(app, "--edge-core", o.edge_core,
              "Grown arc: half-angle in degrees of the core arc around the edge point that starts the growth",
              CLI::Range(5.0, 90.0));
  add_checked(app, "--edge-residual", o.edge_residual,
              "Grown arc: the arc grows while the profile stays within this many core-fit rms of the circle",
              CLI::Range(0.5, 100.0));
  add_checked(app, "--edge-noise-residual", o.edge_noise_residual,
              "Grown arc: that noise level is at least this many times the points' rms distance to the "
              "profile (the spline's noise ripples over the arc; 0 = off)",
              CLI::Range(0.0, 100.0));
  add_checked(app, "--edge-hole", o.edge_hole,
              "Edge radii: a stretch without measured points this long, beginning within --edge-hole-reach "
              "radii of the edge point, makes the edge 'partly not measured' (an issue)",
              positive);
  add_checked(app, "--edge-hole-reach", o.edge_hole_reach,
              "Edge radii along the profile from the edge point within which such a stretch must begin",
              CLI::NonNegativeNumber);
  add_checked(app, "--edge-bridge", o.edge_bridge,
              "Share of its bend: a shorter such stretch whose bridging curve bends from a straight line so "
              "far that this share of the bend (how far such a bridge strays from the blade) exceeds 1.5e-4 "
              "of the profile's size makes the edge 'partly not measured' too (0 = off)",
              CLI::NonNegativeNumber);
  add_checked(app, "--thickness-hole", o.thickness_hole,
              "Chord fraction: the thickest circle touching the profile within a stretch without measured "
              "points this long (and --thickness-hole-spacings times the points' mean distance there) "
              "flags the max thickness (check thickness_measured), and a thickness station whose circle "
              "touches one its row (0 = not checked)",
              CLI::Range(0.0, 1.0));
  add_checked(app, "--end-hole", o.end_hole,
              "Medial-axis-length fraction: an inscribed circle near an end touching the profile within a "
              "stretch without measured points this long (and twice --thickness-hole-spacings times the "
              "points' mean distance there) counts less in the end directions' fits, nothing from twice "
              "that length: it rests on the fit's bridge (0 = every circle counts fully)",
              CLI::Range(0.0, 1.0));
  add_checked(app, "--thickness-hole-spacings", o.thickness_hole_spacings,
              "The points' mean distances such a stretch must exceed (evenly sparse points are no hole)",
              CLI::NonNegativeNumber);
  app.add_flag(
      "--edge-on-spline", a.edge_on_spline,
      "Fit the edge circles to the spline's edge arcs alone (default: refitted to the measured points "
      "on the arcs, when the stream has them)");
}

}  // namespace

void CamberArgs::declare(CLI::App& app) {
  add_common(app, common);
  app.add_option("--params", params_file, "Also write the 'params' table to FILE (CSV)");
  app.add_option("--thickness", thickness_file, "Also write the 'thickness' table to FILE (CSV)");
  app.add_option(
      "--walls", walls_file,
      "Also write the 'walls' table to FILE (CSV): each cavity's thinnest wall, and to each side (a "
      "hollow blade's)");
  app.add_option(
      "--wall-map", wall_map_file,
      "Also write the 'wall_map' table to FILE (CSV): the wall along each cavity, station by station");
  app.add_option("--wall-stations", options.wall_stations,
                 "Stations of each cavity's wall map, evenly along it (0 = no map)")
      ->check(CLI::Range(0, 1000000));
  app.add_option(
         "--stations", stations,
         "Thickness stations, fractions of the camber length between 0 and 1 (default 0.05,0.1,...,0.95)")
      ->check(numbers_check("--stations", stations_ok));
  app.add_option("--le-direction", le_direction,
                 "u,v (in each section's plane) or x,y,z (in 3D, e.g. upstream along the machine "
                 "axis; projected onto each section's plane): the leading edge is the end lying "
                 "farther along this direction (default: the end nearer the maximum thickness, which "
                 "is wrong on blades thickest aft of mid-chord, e.g. transonic compressor rotors: "
                 "give it when known)")
      ->check(direction_check("--le-direction"));
  declare_edges(app, *this);
  add_checked(app, "--tangent-span", options.tangent_span,
              "Fraction of the medial axis over which the end tangents are fitted (0 = spline end slope)",
              CLI::Range(0.0, 0.5));
  app.add_option("--units", units,
                 "Length unit of a plain profile (" + length_unit_names() +
                     "): converted to mm, the stream's unit; default mm, or m for a profile under 1 "
                     "across (with a warning). A stream says its own unit.")
      ->check(length_unit);
  app.add_option("--format", format,
                 "What to write to the output: stream (the pipe stream, docs/FORMAT.md), table (the "
                 "params for people: mm to 4 decimals, degrees to 3, words for shapes and checks), csv "
                 "(the params table, full precision) or json (params and issues per section, with a hollow "
                 "section's walls and wall map, full precision); default table when the output is a "
                 "terminal, else stream")
      ->check(CLI::IsMember({"stream", "table", "csv", "json"}));
  add_allow_partial(app, allow_partial);
  app.add_option("--threads", options.threads, "Worker threads; 0 = all cores")
      ->check(CLI::NonNegativeNumber);
  app.callback([this] {
    if (!stations.empty()) options.stations = numbers(stations, "--stations");
    if (!le_direction.empty()) {
      const auto v = numbers(le_direction, "--le-direction");
      if (v.size() == 3)
        options.le_direction_3d = {v[0], v[1], v[2]};
      else
        options.le_direction = {v[0], v[1]};
    }
    options.edge = edge == "auto" ? EdgeModel::automatic : EdgeModel::round;
    options.edge_on_points = !edge_on_spline;
  });
}

}  // namespace section::tool

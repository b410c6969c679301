// SPDX-License-Identifier: GPL-3.0-or-later
#include "args/compare_args.h"

#include "args/camber_args.h"

#include <cmath>

namespace section::tool {

const char* const CompareArgs::description =
    "compare: the measured sections against their nominal, with tolerances (docs/COMPARE.md).\n\n"
    "Reads the stream written by camber (docs/FORMAT.md) and the nominal: a mesh (.stl .obj\n"
    ".off .ply, sliced on each measured section's plane), a stream (the pipe run on a nominal\n"
    "mesh or point set: sections matched by plane) or a CSV of points along each section's\n"
    "profile (columns section,u,v or x,y,z). The nominal gets its spline, camber line and\n"
    "params from the same code as the measurement. Per section: a best fit of the measured\n"
    "points onto the nominal (--fit, --freedom; --whole-blade: one motion for all sections),\n"
    "each point's signed deviation along the nominal's outward normal (positive = material\n"
    "outside), the zones (leading and trailing edge: --edge-zone of the chord from each edge\n"
    "point; pressure side; suction side; whole) with their extremes, form and holes, and\n"
    "every params value's deviation. Adds the tables 'fits', 'deviations', 'zones',\n"
    "'compared' and 'verdicts'. With --tolerances, each toleranced value passes, fails, is\n"
    "not measured (a hole over its zone is never a pass) or is uncertain: camber flagged it,\n"
    "or a limit lies within its uncertainty (the edge radii's standard errors, times\n"
    "--coverage-factor; --decision-rule).\n\n"
    "Exit status: 0 every toleranced value passed (or none is toleranced), 1 bad data,\n"
    "2 bad usage, 4 a value failed its tolerance, 5 none failed but a value was not measured,\n"
    "6 none failed or was not measured but a value was uncertain.\n\n"
    "Example: slice scan.ply --at 12,20,28 | smooth | fitspline | camber |\n"
    "         compare --nominal blade.stl --tolerances tolerances.csv --report -";

namespace {

CLI::Validator count_check(const std::string& flag, std::size_t a, std::size_t b) {
  return CLI::Validator(
      [flag, a, b](std::string& text) {
        try {
          const auto v = numbers(text, flag);
          return v.size() == a || v.size() == b ? std::string()
                                                : "expected " + std::to_string(a) + " or " +
                                                      std::to_string(b) + " numbers separated by commas";
        } catch (const CLI::ValidationError& e) {
          return std::string(e.what());
        }
      },
      "");
}

// "le=W,te=W,pressure=W,suction=W" into the zone weights.
void read_weights(const std::string& text, std::array<double, zone_count>& w) {
  std::size_t start = 0;
  while (start <= text.size()) {
    const std::size_t comma = std::min(text.find(',', start), text.size());
    const std::string item = text.substr(start, comma - start);
    const std::size_t eq = item.find('=');
    int zone = -1;
    for (int z = 1; z < zone_count && eq != std::string::npos; ++z)
      if (item.substr(0, eq) == zone_name(static_cast<Zone>(z))) zone = z;
    if (zone < 0)
      throw CLI::ValidationError(
          "--weights", "expected ZONE=WEIGHT items (zones le, te, pressure, suction), found '" + item + "'");
    const auto v = numbers(item.substr(eq + 1), "--weights");
    if (v.size() != 1 || v[0] < 0)
      throw CLI::ValidationError("--weights", "a weight is one number, not negative");
    w[zone] = v[0];
    start = comma + 1;
  }
}

void read_fit(CompareArgs& a) {
  FitOptions& f = a.options.compare.fit;
  f.method = a.method == "minimum-zone" ? FitMethod::minimum_zone
             : a.method == "weighted"   ? FitMethod::weighted
                                        : FitMethod::least_squares;
  f.freedom = a.freedom == "none"          ? FitFreedom::none
              : a.freedom == "translation" ? FitFreedom::translation
              : a.freedom == "along"       ? FitFreedom::translation_along
              : a.freedom == "rotation"    ? FitFreedom::rotation
                                           : FitFreedom::all;
  const bool whole = a.options.whole;
  const std::size_t dims = whole ? 3 : 2;
  for (auto [text, flag] : {std::pair{&a.direction, "--direction"}, std::pair{&a.center, "--center"}}) {
    if (text->empty()) continue;
    const auto v = numbers(*text, flag);
    if (v.size() != dims)
      throw CLI::ValidationError(flag, whole ? "with --whole-blade: three numbers x,y,z"
                                             : "two numbers u,v (x,y,z with --whole-blade)");
    if (std::string(flag) == "--direction") {
      f.direction = {v[0], v[1]};
      if (whole) f.direction_3d = {v[0], v[1], v[2]};
    } else {
      f.center = {v[0], v[1]};
      if (whole) f.center_3d = {v[0], v[1], v[2]};
    }
  }
  if (f.freedom == FitFreedom::translation_along && a.direction.empty())
    throw CLI::ValidationError("--freedom", "'along' needs --direction");
  if (!a.weights.empty()) read_weights(a.weights, f.weights);
}

}  // namespace

void CompareArgs::declare(CLI::App& app) {
  add_common(app, common);
  app.add_option("--nominal", nominal, "The nominal: a mesh, a stream, or a CSV of section points")
      ->required();
  app.add_option("--nominal-units", nominal_units,
                 "Length unit of a nominal mesh or CSV of points (" + length_unit_names() +
                     "): converted to mm, the stream's unit; default mm, or m for a nominal under 1 across "
                     "(with a warning). A stream says its own unit.")
      ->check(length_unit);
  app.add_option("--tolerances", tolerances,
                 "Tolerance file (CSV: item,section,low,high,on; docs/COMPARE.md)");
  app.add_option("--report", report, "Write the verdicts as text to FILE (- = standard error)");
  app.add_option("--format", format,
                 "What to write to the output: stream (the pipe stream, docs/FORMAT.md), table (the "
                 "report, as --report writes it) or json (verdicts, zones, compared values and issues per "
                 "section, full precision); default table when the output is a terminal, else stream")
      ->check(CLI::IsMember({"stream", "table", "json"}));
  add_checked(app, "--fit", method, "Best fit: least-squares, minimum-zone or weighted",
              CLI::IsMember({"least-squares", "minimum-zone", "weighted"}));
  add_checked(app, "--freedom", freedom,
              "The fit's freedom: none, translation, along (--direction), rotation "
              "(about --center) or all",
              CLI::IsMember({"none", "translation", "along", "rotation", "all"}));
  app.add_option("--direction", direction, "u,v: the direction of --freedom along (x,y,z with --whole-blade)")
      ->check(direction_check("--direction"));
  app.add_option(
         "--center", center,
         "u,v: the centre of --freedom rotation (x,y,z with --whole-blade); default the nominal's centroid")
      ->check(count_check("--center", 2, 3));
  app.add_option("--weights", weights,
                 "--fit weighted: ZONE=W,... for the zones le, te, pressure, suction (default 1)");
  add_checked(app, "--decision-rule", decision,
              "guarded: a value passes (fails) only when it lies inside (outside) its limits by more than "
              "its uncertainty, else it is uncertain (ISO 14253-1); simple: by the value alone",
              CLI::IsMember({"guarded", "simple"}));
  add_checked(app, "--coverage-factor", options.coverage,
              "The expanded uncertainty: this many standard errors (2: about 95 %)", positive);
  app.add_flag("--whole-blade", options.whole, "One rigid motion for all sections (parallel planes)");
  add_checked(app, "--edge-zone", options.compare.edge_zone,
              "The edge zones: the profile from each edge point to this fraction of the chord",
              CLI::Range(0.001, 0.45));
  add_checked(app, "--hole", options.compare.hole,
              "A stretch of nominal this long without a measured point is a hole (0 = 10 median spacings)",
              CLI::NonNegativeNumber);
  add_checked(app, "--outlier-distance", options.compare.outlier_distance,
              "Isolated points farther from the nominal are left out (0 = 6 noise sigmas, at least 0.02)",
              CLI::NonNegativeNumber);
  app.add_flag("--keep-outliers", keep_outliers, "Leave no point out");
  app.add_option("--le-direction", le_direction, "The nominal's camber: as camber --le-direction")
      ->check(direction_check("--le-direction"));
  add_checked(app, "--plane-tolerance", options.plane_tolerance,
              "A nominal section or point this near a measured plane lies on it", positive);
  app.add_option("--threads", options.threads, "Worker threads; 0 = all cores")
      ->check(CLI::NonNegativeNumber);
  app.callback([this] {
    read_fit(*this);
    options.decision = decision == "simple" ? DecisionRule::simple : DecisionRule::guarded;
    if (keep_outliers) options.compare.outlier_distance = -1;
    if (!le_direction.empty()) {
      const auto v = numbers(le_direction, "--le-direction");
      if (v.size() == 3)
        options.camber.le_direction_3d = {v[0], v[1], v[2]};
      else
        options.camber.le_direction = {v[0], v[1]};
    }
  });
}

}  // namespace section::tool

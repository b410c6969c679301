// camber: mean-camber line and blade section parameters of every section of a pipe stream.
#include "common/tool.h"

#include "section/camber.h"
#include "section/error.h"
#include "section/fit_spline.h"
#include "section/io/stream.h"
#include "section/io/csv.h"
#include "section/io/file.h"
#include "section/pipe/run_stage.h"
#include "section/pipe/camber_stream.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <iostream>
#include <memory>
#include <string_view>

namespace {

const char* const description =
    "camber: mean-camber line and section parameters (docs/CAMBER.md).\n\n"
    "Reads the stream written by fitspline (docs/FORMAT.md) or a plain ordered 2D profile\n"
    "(x y per line, an airfoil .dat or CMM section; a title line is skipped), and for the\n"
    "profile (loop 0) of every section computes the mean-camber line (the locus of the\n"
    "inscribed circles' centres, extended along its end tangents to the LE and TE points)\n"
    "and the section parameters. Adds the tables 'camber', 'params', 'thickness' and\n"
    "'sides' to the stream; sections that fail are recorded as issues.\n\n"
    "Example: slice blade.ply --count 9 | smooth | fitspline | camber --params params.csv";

// "a,b,c" -> finite numbers, parsed like the pipe parses (std::from_chars: no locale, the
// whole item, a leading '+' allowed); throws CLI::ValidationError naming the flag.
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
    if (digits.empty() || r.ec != std::errc() || r.ptr != digits.data() + digits.size() || !std::isfinite(value))
      throw CLI::ValidationError(flag, "expected numbers separated by commas, found '" + std::string(item) + "'");
    out.push_back(value);
    if (comma == std::string_view::npos) break;
    rest.remove_prefix(comma + 1);
  }
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  section::tool::Common common;
  section::CamberOptions options;
  std::string params_file, thickness_file, stations, le_direction, edge = "round";
  bool edge_on_spline = false;
  return section::tool::run_tool(
      "camber", description, argc, argv,
      [&](CLI::App& app) {
        section::tool::add_common(app, common);
        app.add_option("--params", params_file, "Also write the 'params' table to FILE (CSV)");
        app.add_option("--thickness", thickness_file, "Also write the 'thickness' table to FILE (CSV)");
        app.add_option("--stations", stations,
                       "Thickness stations, fractions of the camber length (default 0.05,0.1,...,0.95)")
            ->check([](const std::string& s) {
              try {
                for (double f : numbers(s, "--stations"))
                  if (!(f >= 0 && f <= 1)) return std::string("stations must lie in [0, 1]");
              } catch (const CLI::ValidationError& e) {
                return std::string(e.what());
              }
              return std::string();
            });
        app.add_option("--le-direction", le_direction,
                       "u,v (in each section's plane) or x,y,z (in 3D, e.g. upstream along the machine "
                       "axis; projected onto each section's plane): the leading edge is the end lying "
                       "farther along this direction (default: the end nearer the maximum thickness, which "
                       "is wrong on blades thickest aft of mid-chord, e.g. transonic compressor rotors: "
                       "give it when known)")
            ->check([](const std::string& s) {
              try {
                const auto v = numbers(s, "--le-direction");
                if ((v.size() != 2 && v.size() != 3) || std::all_of(v.begin(), v.end(), [](double x) { return x == 0; }))
                  return std::string("expected two numbers u,v or three x,y,z, not all 0");
              } catch (const CLI::ValidationError& e) {
                return std::string(e.what());
              }
              return std::string();
            });
        app.add_option("--edge", edge, "Edge model: round (circle fitted to every edge) or auto "
                                       "(blunt and sharp edges get radius 0)")
            ->check(CLI::IsMember({"round", "auto"}))->capture_default_str();
        app.add_option("--edge-arc", options.edge_arc, "Degrees of a fixed edge arc the edge circle is fitted to (0 = grown geometrically)")
            ->check(CLI::Range(0.0, 270.0))->capture_default_str();
        app.add_option("--edge-core", options.edge_core,
                       "Grown arc: half-angle in degrees of the core arc around the edge point that starts the growth")
            ->check(CLI::Range(5.0, 90.0))->capture_default_str();
        app.add_option("--edge-residual", options.edge_residual,
                       "Grown arc: the arc grows while the profile stays within this many core-fit rms of the circle")
            ->check(CLI::Range(0.5, 100.0))->capture_default_str();
        app.add_option("--edge-noise-residual", options.edge_noise_residual,
                       "Grown arc: that noise level is at least this many times the points' rms distance to the "
                       "profile (the spline's noise ripples over the arc; 0 = off)")
            ->check(CLI::Range(0.0, 100.0))->capture_default_str();
        app.add_option("--edge-hole", options.edge_hole,
                       "Edge radii: a stretch without measured points this long, beginning within --edge-hole-reach "
                       "radii of the edge point, makes the edge 'partly not measured' (an issue)")
            ->check(section::tool::positive)->capture_default_str();
        app.add_option("--edge-hole-reach", options.edge_hole_reach,
                       "Edge radii along the profile from the edge point within which such a stretch must begin")
            ->check(CLI::NonNegativeNumber)->capture_default_str();
        app.add_flag("--edge-on-spline", edge_on_spline,
                     "Fit the edge circles to the spline's edge arcs alone (default: refitted to the measured points "
                     "on the arcs, when the stream has them)");
        app.add_option("--tangent-span", options.tangent_span,
                       "Fraction of the medial axis over which the end tangents are fitted (0 = spline end slope)")
            ->check(CLI::Range(0.0, 0.5))->capture_default_str();
        app.add_option("--threads", options.threads, "Worker threads; 0 = all cores")->check(CLI::NonNegativeNumber);
      },
      [&] {
        if (!stations.empty()) options.stations = numbers(stations, "--stations");
        if (!le_direction.empty()) {
          const auto v = numbers(le_direction, "--le-direction");
          if (v.size() == 3)
            options.le_direction_3d = {v[0], v[1], v[2]};
          else
            options.le_direction = {v[0], v[1]};
        }
        options.edge = edge == "auto" ? section::EdgeModel::automatic : section::EdgeModel::round;
        options.edge_on_points = !edge_on_spline;
        section::Table params, thickness;
        section::StageRun run =
            section::tool::stage_run(common, argc, argv, options.threads, [&](section::Stream& part, int threads) {
              section::CamberOptions o = options;
              o.threads = threads;
              section::camber_stream(part, o);
            });
        run.other_input = [&](const std::string& text, const std::string& source) {
          const auto points = section::parse_profile(text, source);
          section::Stream stream;
          section::tool::with_input(common.input, [&] {
            const section::FitSplineResult fit = section::fit_spline(points, points);
            stream = section::profile_stream(fit.spline, fit.rms);
          });
          return stream;
        };
        run.written = [&](const section::Stream& stream) {
          for (const auto& issue : stream.issues)
            if (issue.stage == "camber")
              std::cerr << "camber: warning: section " << issue.section << ": " << issue.message << "\n";
          section::append_rows(params, stream.get("params", "camber"));
          section::append_rows(thickness, stream.get("thickness", "camber"));
        };
        section::run_stage(run);
        if (!params_file.empty()) section::write_file(params_file, section::format_csv(params));
        if (!thickness_file.empty()) section::write_file(thickness_file, section::format_csv(thickness));
      });
}

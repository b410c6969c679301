// SPDX-License-Identifier: GPL-3.0-or-later
#include "args/smooth_args.h"

namespace section::tool {

const char* const SmoothArgs::description =
    "smooth: smooth the ordered section points of a pipe stream (docs/SMOOTH.md).\n\n"
    "Reads the stream written by slice (docs/FORMAT.md) and, for every section loop of the\n"
    "'points' table, minimises E = a E_C + b E_S (curvature energy plus squared distance to\n"
    "the measured points; Li et al. 2014). Writes the tables 'smoothed' (section, loop,\n"
    "index, u, v) and 'smooth_stats' (per loop: energies, iterations, moves, merged\n"
    "duplicates); loops that fail are recorded as issues and the others go on.\n\n"
    "Strength: --length L (stream units) keeps half the amplitude of wiggles of wavelength L;\n"
    "by default L = 6 mean point spacings (0.48 mm for a 0.08 mm scan), which about halves\n"
    "the RMS of the scan noise. Curved parts of radius R shrink by about (L / 2 pi)^4 / R^3.\n"
    "--a sets the paper's weight directly (it depends on the units and the spacing).\n\n"
    "Example: slice blade.ply --count 9 | smooth | fitspline | camber";

void SmoothArgs::declare(CLI::App& app) {
  add_common(app, common);
  add_checked(app, "--length", options.smoothing_length,
              "Smoothing length L (stream units); 0 = from --a or --spacings", CLI::NonNegativeNumber);
  add_checked(app, "--spacings", options.relative_length,
              "Smoothing length in mean point spacings, used when --length and --a are 0",
              CLI::NonNegativeNumber);
  add_checked(app, "--a", options.a, "Explicit curvature weight a (units^3 with b = 1); 0 = not used",
              CLI::NonNegativeNumber);
  add_checked(app, "--b", options.b, "Closeness weight b", positive);
  add_checked(app, "--solver", solver, "Linear solver: cholmod or gauss-seidel",
              CLI::IsMember({"cholmod", "gauss-seidel", "gauss_seidel"}));
  add_checked(app, "--max-iterations", options.max_iterations, "Cap on outer iterations",
              CLI::Range(1, 100000));
  add_checked(app, "--move-tolerance", options.move_tolerance,
              "Stop when no point moved farther across the curve (mean spacings); 0 = run to the cap",
              CLI::NonNegativeNumber);
  app.add_option("--report", report, "Write the per-loop statistics (CSV) to FILE");
  app.add_option("--threads", options.threads, "Worker threads; 0 = all cores")
      ->check(CLI::NonNegativeNumber);
  app.callback([this] { options.solver = parse_smooth_solver(solver); });
}

}  // namespace section::tool

// SPDX-License-Identifier: GPL-3.0-or-later
#include "args/fitspline_args.h"

namespace section::tool {

const char* const FitsplineArgs::description =
    "fitspline: fit a closed cubic B-spline to every loop of a section stream.\n\n"
    "Reads the pipe stream (docs/FORMAT.md) written by slice (and optionally smooth): a first\n"
    "curve is fitted by least squares to the 'smoothed' profile (or the ordered 'points'),\n"
    "then refined by squared-distance minimisation against the measured 'points', with\n"
    "knots inserted where the curve misses the data (blade edges). Writes the tables\n"
    "'splines' (fit statistics), 'spline_knots', 'spline_ctrl' and, with --samples or\n"
    "--spacing, 'samples' (points, normals and curvature along the curve, also in 3D).\n"
    "A loop that cannot be fitted is reported as an issue; the other loops go on. Points\n"
    "lying in two layers (views merged with a misregistration) are reported on stderr and\n"
    "in the splines table (columns layers, layers_length).\n\n"
    "Example: slice blade.ply --count 9 | smooth | fitspline --spacing 0.1 | camber";

namespace {

// --control-points, --tolerance, --samples, --spacing: how many control points and samples.
void declare_counts(CLI::App& app, FitSplineOptions& options) {
  auto* ctrl = app.add_option("--control-points", options.control_points,
                              "Control points per loop (fixed); default: adaptive to --tolerance")
                   ->check(CLI::Range(4, 100000));
  auto* tol = add_checked(app, "--tolerance", options.tolerance,
                          "Systematic deviation allowed per knot span before a knot is inserted", positive);
  ctrl->excludes(tol);
  auto* n = app.add_option("--samples", options.samples, "Write N curve samples per loop")
                ->check(CLI::Range(3, FitSplineOptions::max_samples));
  auto* d = app.add_option("--spacing", options.sample_spacing,
                           "Write curve samples every D length units along the curve")
                ->check(positive);
  n->excludes(d);
}

}  // namespace

void FitsplineArgs::declare(CLI::App& app) {
  add_common(app, common);
  declare_counts(app, options);
  add_checked(app, "--max-iterations", options.max_iterations,
              "Distance-minimisation iterations per refinement round", CLI::Range(1, 10000));
  add_checked(app, "--first-iterations", options.first_iterations,
              "Adaptive knots: iterations of the first curve, whose curvature places the knots (12 with "
              "--bridge-factor 4: curves stable to the last bits of the input, for about a quarter more "
              "time, but edge radii not yet as sure; docs/FITSPLINE.md, Stability)",
              CLI::Range(0, 10000));
  add_checked(app, "--bridge-factor", options.bridge_factor,
              "Adaptive knots: a stretch without points longer than this many median spacings keeps only the "
              "knots its bridge needs; 0 = off",
              CLI::NonNegativeNumber);
  add_checked(app, "--max-control-points", options.max_control_points,
              "Cap on control points per loop in adaptive mode", CLI::Range(8, 1000000));
  add_checked(app, "--fairness", options.fairness, "Relative weight of the fairness term",
              CLI::NonNegativeNumber);
  add_checked(app, "--smoothing-length", options.smoothing_length,
              "mm: change-of-curvature penalty, zero on lines and circular arcs (0 = off; docs/FITSPLINE.md)",
              CLI::NonNegativeNumber);
  add_checked(app, "--min-span-points", options.min_span_points,
              "Adaptive knots: fewest measured points per knot span (on noisy data)",
              CLI::Range(1.0, 1000.0));
  add_checked(app, "--outlier-distance", options.outlier_distance,
              "Ignore isolated points farther than this from the curve; 0 = automatic",
              CLI::NonNegativeNumber);
  add_checked(app, "--gap-factor", options.gap_factor,
              "List as a hole (table gaps) any stretch without measured points longer than this many median "
              "spacings",
              positive);
  add_checked(app, "--layer-ratio", options.layer_ratio,
              "Report two layers of points where their spread about the curve exceeds this many noise "
              "sigmas over two overlapping windows of 48 points; 0 = off",
              CLI::NonNegativeNumber);
  app.add_option("--threads", options.threads, "Worker threads; 0 = all cores")
      ->check(CLI::NonNegativeNumber);
}

}  // namespace section::tool

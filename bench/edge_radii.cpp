// SPDX-License-Identifier: GPL-3.0-or-later
// edge_radii: how far the edge radii of noisy profiles fall from the truth, over many seeds
// (docs/CAMBER.md, "Noisy profiles"). Each design of design_family() but the turbine (as
// tests/test_edge.cpp), exact points every `--spacing` mm moved by Gaussian noise (sigma
// `--noise` mm) along the exact normal, fit_spline, camber_line measured two ways: the
// noise unknown and the spline alone, and the noise and the measured points given (as the
// pipe does). Prints, per way and edge, the rms, 90th percentile and worst relative error
// and how many fits pass 3 % (LE) / 10 % (TE), how the errors of the circles refitted on
// the points compare with their standard errors (Edge::radius_sigma), then each fit beyond
// a limit.
// Usage: edge_radii [--seeds N] [--spacing MM] [--noise MM] [--first-iterations N]
//                   [--bridge-factor F]
#include "section/camber.h"
#include "section/extras/generate.h"
#include "section/extras/score.h"
#include "section/fit_spline.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

using namespace section;

namespace {

struct Options {
  int seeds = 40;
  double spacing = 0.04, noise = 0.005;
  FitSplineOptions fit;
};

struct Errors {
  std::vector<double> le, te;
  std::vector<double> le_z, te_z;  // |error| / standard error, edges refitted on the points
};

void print_calibration(const char* edge, const std::vector<double>& ratios) {
  const Calibration c = calibration(ratios);
  if (c.count == 0) return;
  std::printf(
      "  %s |error| / standard error (%zu edges): median %.2f, 90 %% %.2f, 99 %% %.2f, beyond 2 sigma "
      "%.1f %%, beyond 3 sigma %.1f %%\n",
      edge, c.count, c.median, c.p90, c.p99, 100 * c.beyond2, 100 * c.beyond3);
}

void summary(const char* way, const char* edge, std::vector<double> v, double limit) {
  std::sort(v.begin(), v.end());
  double s2 = 0;
  for (double x : v) s2 += x * x;
  const long over = std::count_if(v.begin(), v.end(), [&](double x) { return x > limit; });
  std::printf("%-24s %s  fits %3zu  rms %5.2f %%  p90 %5.2f %%  worst %5.2f %%  over %2.0f %%: %ld\n", way,
              edge, v.size(), 100 * std::sqrt(s2 / double(v.size())), 100 * v[v.size() * 9 / 10],
              100 * v.back(), 100 * limit, over);
}

}  // namespace

int main(int argc, char** argv) {
  Options opt;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    const bool more = i + 1 < argc;
    if (a == "--seeds" && more)
      opt.seeds = std::atoi(argv[++i]);
    else if (a == "--spacing" && more)
      opt.spacing = std::atof(argv[++i]);
    else if (a == "--noise" && more)
      opt.noise = std::atof(argv[++i]);
    else if (a == "--first-iterations" && more)
      opt.fit.first_iterations = std::atoi(argv[++i]);
    else if (a == "--bridge-factor" && more)
      opt.fit.bridge_factor = std::atof(argv[++i]);
    else {
      std::fprintf(stderr,
                   "usage: edge_radii [--seeds N] [--spacing MM] [--noise MM] [--first-iterations N] "
                   "[--bridge-factor F]\n");
      return 2;
    }
  }
  if (opt.seeds < 1 || !(opt.spacing > 0) || !(opt.noise >= 0)) {
    std::fprintf(stderr, "edge_radii: --seeds must be at least 1, --spacing above 0, --noise at least 0\n");
    return 2;
  }
  const char* ways[2] = {"noise unknown, spline", "noise and points given"};
  Errors errors[2];
  std::vector<std::string> beyond;
  std::vector<SectionDesign> designs = design_family();
  designs.erase(designs.begin() + 1);
  for (std::size_t k = 0; k < designs.size(); ++k) {
    const SectionTruth truth = section_truth(designs[k], 20000);
    for (int seed = 1; seed <= opt.seeds; ++seed) {
      const auto pts = noisy_profile(truth, opt.spacing, opt.noise, std::uint64_t(seed) * 7919 + k);
      const BSpline spline = fit_spline(pts, pts, opt.fit).spline;
      CamberOptions given;
      given.profile_noise = opt.noise;
      const CamberResult c[2] = {camber_line(spline), camber_line(spline, given, pts)};
      for (int w = 0; w < 2; ++w) {
        const double dle = std::abs(c[w].le.radius - truth.le_radius),
                     dte = std::abs(c[w].te.radius - truth.te_radius);
        const double le = dle / truth.le_radius, te = dte / truth.te_radius;
        errors[w].le.push_back(le);
        errors[w].te.push_back(te);
        if (c[w].le.radius_sigma > 0) errors[w].le_z.push_back(dle / c[w].le.radius_sigma);
        if (c[w].te.radius_sigma > 0) errors[w].te_z.push_back(dte / c[w].te.radius_sigma);
        if (le > 0.03 || te > 0.10) {
          char line[160];
          std::snprintf(line, sizeof line,
                        "  %s: design %zu seed %d  LE %.2f %% (R %.3f)  TE %.2f %% (R %.3f)", ways[w], k,
                        seed, 100 * le, truth.le_radius, 100 * te, truth.te_radius);
          beyond.push_back(line);
        }
      }
    }
  }
  std::printf("%zu designs x %d seeds, a point every %g mm, noise sigma %g mm\n", designs.size(), opt.seeds,
              opt.spacing, opt.noise);
  for (int w = 0; w < 2; ++w) {
    summary(ways[w], "LE", errors[w].le, 0.03);
    summary(ways[w], "TE", errors[w].te, 0.10);
  }
  print_calibration("LE", errors[1].le_z);
  print_calibration("TE", errors[1].te_z);
  std::printf("beyond 3 %% (LE) or 10 %% (TE):%s\n", beyond.empty() ? " none" : "");
  for (const auto& line : beyond) std::printf("%s\n", line.c_str());
  return 0;
}

// SPDX-License-Identifier: GPL-3.0-or-later
// bench_smooth: time per section of smooth() with CHOLMOD and with Gauss-Seidel.
#include "common/tool.h"

#include "section/smooth.h"

#include <ctime>
#include <cmath>
#include <cstdio>
#include <random>

namespace {

const char* const description =
    "bench_smooth: time smooth() on noisy closed sections of 1e3, 1e4, 1e5 points\n"
    "(0.08 mm spacing, 5 um noise; CPU seconds per section) with the CHOLMOD solve and with Gauss-Seidel run "
    "to the\n"
    "same energy (the loosest sweep tolerance whose final E is within --match of CHOLMOD's).\n\n"
    "Example: bench_smooth --sizes 1000,10000 --length 0.5";

/// A wavy ellipse (4:1.6 axes plus a 5-lobe ripple) with n points ~0.08 mm apart.
std::vector<Eigen::Vector2d> section_of(int n, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> noise(0, 0.005);
  const double pi = 3.14159265358979323846, scale = n * 0.08 / (2 * pi * 3.0);
  std::vector<Eigen::Vector2d> p;
  for (int i = 0; i < n; ++i) {
    const double t = 2 * pi * i / n;
    const double r = 1 + 0.05 * std::cos(5 * t);
    const Eigen::Vector2d x(scale * 4 * r * std::cos(t), scale * 1.6 * r * std::sin(t));
    const Eigen::Vector2d d(-4 * std::sin(t), 1.6 * std::cos(t));
    p.push_back(x + noise(rng) * Eigen::Vector2d(d.y(), -d.x()).normalized());
  }
  return p;
}

/// CPU seconds per call (both solvers are single-threaded; wall time on a shared machine
/// would measure the neighbours).
double seconds(const std::function<void()>& f, int repeat) {
  const std::clock_t t0 = std::clock();
  for (int k = 0; k < repeat; ++k) f();
  return double(std::clock() - t0) / CLOCKS_PER_SEC / repeat;
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<int> sizes{1000, 10000, 100000};
  section::SmoothOptions options;
  double match = 1e-8;
  return section::tool::run_tool(
      "bench_smooth", description, argc, argv,
      [&](CLI::App& app) {
        app.add_option("--sizes", sizes, "Points per section")->delimiter(',')->capture_default_str();
        app.add_option("--a", options.a, "Curvature weight a")->capture_default_str();
        app.add_option("--length", options.smoothing_length, "Smoothing length (mm), overrides --a")
            ->capture_default_str();
        app.add_option("--match", match, "Relative energy difference that counts as the same")
            ->capture_default_str();
      },
      [&] {
        std::printf("%8s %10s %6s %12s %12s %6s %10s %12s %8s\n", "points", "a", "iters", "cholmod_s", "gs_s",
                    "gs_it", "gs_sweeps", "gs_rel_dE", "ratio");
        for (int n : sizes) {
          const auto p = section_of(n, 1);
          section::SmoothOptions o = options;
          section::SmoothResult c;
          const int repeat = n <= 10000 ? 5 : 1;
          const double tc = seconds([&] { c = section::smooth(p, o); }, repeat);
          o.solver = section::SmoothSolver::gauss_seidel;
          section::SmoothResult g;
          double tg = 0, rel = 0;
          for (double tol = 1e-5; tol >= 1e-13; tol /= 10) {
            o.sweep_tolerance = tol;
            tg = seconds([&] { g = section::smooth(p, o); }, 1);
            rel = std::abs(g.energy_after - c.energy_after) / c.energy_after;
            if (rel <= match) break;
          }
          std::printf("%8d %10.3g %6d %12.4g %12.4g %6d %10d %12.2g %8.1f\n", n, c.a, c.iterations, tc, tg,
                      g.iterations, g.sweeps, rel, tg / tc);
          std::fflush(stdout);
        }
      });
}

// SPDX-License-Identifier: GPL-3.0-or-later
// Two views that overlap all along the profile, merged with a misregistration: the points
// of both interleave everywhere, so no window of them stands out from the rest (the noise
// from consecutive differences takes the layers in), yet the curve runs between them.
#include "section/fit_spline.h"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

using Eigen::Vector2d;

namespace {

constexpr double pi = 3.14159265358979323846;

// A circle of radius r scanned all around, points every 0.04 mm with `noise` along the
// normal, in angular order from -pi.
std::vector<Vector2d> scanned_circle(double r, double noise, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> g(0, 1);
  std::vector<Vector2d> p;
  const int m = static_cast<int>(2 * pi * r / 0.04);
  for (int i = 0; i < m; ++i) {
    const double a = -pi + 2 * pi * (i + 0.5) / m;
    const Vector2d n(std::cos(a), std::sin(a));
    p.push_back((r + noise * g(rng)) * n);
  }
  return p;
}

}  // namespace

TEST_CASE("fit_spline: two views overlapping all along are reported as two layers", "[fit_spline]") {
  // Two full views of a 12 mm circle, the second `apart` outside the first, with 5 um of
  // noise, merged in angular order: two layers apart everywhere, interleaved.
  for (const double apart : {0.015, 0.025, 0.0}) {
    for (unsigned seed : {1u, 2u, 3u}) {
      std::vector<Vector2d> p = scanned_circle(12, 0.005, seed);
      const std::vector<Vector2d> second = scanned_circle(12 + apart, 0.005, seed + 100);
      p.insert(p.end(), second.begin(), second.end());
      std::sort(p.begin(), p.end(), [](const Vector2d& a, const Vector2d& b) {
        return std::atan2(a.y(), a.x()) < std::atan2(b.y(), b.x());
      });
      const auto res = section::fit_spline(p, p);
      INFO("apart " << apart << " seed " << seed << ": layers " << res.layers << " over " << res.layers_length
                    << ", noise " << res.noise << ", rms " << res.rms);
      if (apart > 0) {
        CHECK(res.layers > 0.7 * apart);
        CHECK(res.layers < 1.3 * apart);
        CHECK(res.layers_length > 0.9 * 2 * pi * 12);
      } else {
        CHECK(res.layers == 0);
      }
    }
  }
}

TEST_CASE("fit_spline: coordinates rounded to a coarse step are no two layers", "[fit_spline]") {
  // An ellipse 40 x 6 mm along x (flanks like a blade's, their normals near y), points
  // every 0.04 mm at 0, 1 and 2 um of noise, coordinates rounded to 0.02 mm (a coarse
  // digitiser's step): along the flanks the rounding spreads the residuals as flat as two
  // layers 10 um apart (a uniform's kurtosis is 1.8), but without a dip between them.
  for (const double noise : {0.0, 0.001, 0.002}) {
    for (unsigned seed : {1u, 2u}) {
      std::mt19937 rng(seed);
      std::normal_distribution<double> g(0, noise > 0 ? noise : 1);
      std::vector<Vector2d> p;
      for (int i = 0; i < 2600; ++i) {
        const double a = -pi + 2 * pi * (i + 0.5) / 2600;
        const Vector2d n = Vector2d(3 * std::cos(a), 20 * std::sin(a)).normalized();
        const Vector2d q = Vector2d(20 * std::cos(a), 3 * std::sin(a)) + (noise > 0 ? g(rng) : 0.0) * n;
        p.push_back((q * 50).array().round() / 50);
      }
      const auto res = section::fit_spline(p, p);
      INFO("noise " << noise << " seed " << seed << ": layers " << res.layers << ", rms " << res.rms);
      CHECK(res.layers == 0);
    }
  }
}

#include "section/fit_spline.h"
#include "section/error.h"
#include "section/pipe.h"

#include <catch2/catch.hpp>

#include <cmath>
#include <random>

using Eigen::Vector2d;
using section::FitSplineOptions;

namespace {

const double pi = std::acos(-1.0);

// Points of the closed curve f(a), a in [0, 2 pi), counterclockwise, with normal noise.
template <class F>
std::vector<Vector2d> curve_points(F f, int m, double noise, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> g(0, noise > 0 ? noise : 1);
  std::vector<Vector2d> p;
  for (int i = 0; i < m; ++i) {
    const double a = 2 * pi * (i + 0.37) / m;
    const double h = 1e-6;
    const Vector2d d = (f(a + h) - f(a - h)).normalized();
    const Vector2d n(d.y(), -d.x());
    p.push_back(f(a) + (noise > 0 ? g(rng) : 0.0) * n);
  }
  return p;
}

// Largest and RMS distance of the fitted curve to a circle.
std::pair<double, double> circle_error(const section::BSpline& c, Vector2d centre, double r) {
  double worst = 0, ss = 0;
  const auto s = section::sample(c, 5000);
  for (const auto& p : s) {
    const double e = std::abs((p - centre).norm() - r);
    worst = std::max(worst, e);
    ss += e * e;
  }
  return {worst, std::sqrt(ss / s.size())};
}

// Distance to the ellipse x^2/a^2 + y^2/b^2 = 1 by Newton on the foot angle.
double ellipse_distance(Vector2d p, double a, double b) {
  double best = 1e300;
  for (int k = 0; k < 64; ++k) {
    double th = 2 * pi * k / 64;
    for (int it = 0; it < 30; ++it) {
      const Vector2d e(a * std::cos(th), b * std::sin(th));
      const Vector2d d1(-a * std::sin(th), b * std::cos(th));
      const Vector2d d2(-a * std::cos(th), -b * std::sin(th));
      const double g = (e - p).dot(d1), h = d1.squaredNorm() + (e - p).dot(d2);
      th -= g / (h > 0 ? h : d1.squaredNorm());
    }
    best = std::min(best, (Vector2d(a * std::cos(th), b * std::sin(th)) - p).norm());
  }
  return best;
}

}  // namespace

TEST_CASE("fit_spline: exact circle points give a curve within 1 um", "[fit_spline]") {
  for (double r : {1.0, 20.0}) {
    const Vector2d centre(5, -3);
    auto f = [&](double a) { return Vector2d(centre + r * Vector2d(std::cos(a), std::sin(a))); };
    const auto p = curve_points(f, static_cast<int>(2 * pi * r / 0.08), 0, 1);
    const auto res = section::fit_spline(p, p);
    const auto [worst, rms] = circle_error(res.spline, centre, r);
    INFO("r " << r << " worst " << worst << " rms " << rms << " ctrl " << res.control_points
              << " it " << res.iterations << " rounds " << res.rounds);
    REQUIRE(worst < 1e-3);
    REQUIRE(res.rms < 1e-3);
    REQUIRE(res.outliers == 0);
  }
}

TEST_CASE("fit_spline: thin ellipse with 0.2 mm end radius within 1 um", "[fit_spline]") {
  const double a = 20, b = 2;  // end radius b^2 / a = 0.2 mm
  auto f = [&](double t) { return Vector2d(a * std::cos(t), b * std::sin(t)); };
  const auto p = curve_points(f, 1500, 0, 2);
  const auto res = section::fit_spline(p, p);
  double worst = 0;
  for (const auto& s : section::sample(res.spline, 4000)) worst = std::max(worst, ellipse_distance(s, a, b));
  INFO("worst " << worst << " ctrl " << res.control_points << " rounds " << res.rounds << " rms "
                << res.rms << " max " << res.max);
  REQUIRE(worst < 1e-3);
  REQUIRE(res.max < 1e-3);
}

TEST_CASE("fit_spline: noisy circle (sigma 5 um) is within 2 um RMS of the truth", "[fit_spline]") {
  for (unsigned seed : {3u, 4u, 5u}) {
    const double r = 12;
    const Vector2d centre(0, 0);
    auto f = [&](double a) { return Vector2d(r * std::cos(a), r * std::sin(a)); };
    const auto p = curve_points(f, static_cast<int>(2 * pi * r / 0.04), 0.005, seed);
    const auto res = section::fit_spline(p, p);
    const auto [worst, rms] = circle_error(res.spline, centre, r);
    INFO("seed " << seed << " worst " << worst << " rms " << rms << " ctrl " << res.control_points
                 << " noise " << res.noise << " fit rms " << res.rms);
    REQUIRE(rms < 0.002);
    REQUIRE(res.rms == Approx(0.005).epsilon(0.15));
    REQUIRE(res.noise == Approx(0.005).epsilon(0.2));
  }
}

// SPDX-License-Identifier: GPL-3.0-or-later
// Tests of the generator's data kinds (generate.h): sharp trailing edges, the symmetric
// impulse blade, the thick root, structured grids and sparse rows, each against the exact
// truth: the points lie on the true surface, the lines and rows where they should be.
#include "section/error.h"
#include "section/extras/generate.h"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <vector>

using Eigen::Vector2d;
using Eigen::Vector3d;
using section::BladeDesign;
using section::SectionTruth;

namespace {

constexpr double pi = 3.14159265358979323846;

// Largest distance of the points to the true section at each point's own height.
double worst_distance(const BladeDesign& b, const std::vector<Vector3d>& pts, std::size_t step = 1) {
  double worst = 0;
  for (std::size_t i = 0; i < pts.size(); i += step) {
    const SectionTruth t = section::section_truth(b.at(pts[i].z()), 4000);
    worst = std::max(worst, section::locate(t, pts[i].head<2>()).distance);
  }
  return worst;
}

// The profile point at arc length s along the truth (wrapped), by its dense samples.
Vector2d at_arc(const SectionTruth& t, double s) {
  s -= t.perimeter * std::floor(s / t.perimeter);
  const auto it = std::upper_bound(t.profile_s.begin(), t.profile_s.end(), s);
  return t.profile[std::size_t(std::max<long>(0, long(it - t.profile_s.begin()) - 1))];
}

// A grid of `heights` x `around` points (chordwise lines, the whole span).
section::GridOptions grid_of(int heights, int around) {
  section::GridOptions g;
  g.heights = heights;
  g.around = around;
  return g;
}

// Rows: `rows` of them `pitch` apart (centred), at constant radius when hub_radius > 0.
section::RowsOptions rows_of(int rows, double pitch, double hub_radius = 0) {
  section::RowsOptions r;
  r.rows = rows;
  r.pitch = pitch;
  r.hub_radius = hub_radius;
  return r;
}

}  // namespace

TEST_CASE("generate kinds: a sharp trailing edge closes at one vertex with a finite wedge", "[generate]") {
  const BladeDesign b = section::sharp_te_blade();
  for (double z : {0.0, 25.0, 60.0}) {
    const SectionTruth t = section::section_truth(b.at(z), 20000);
    CHECK(t.te_radius == 0);
    CHECK((t.te_point - t.te_center).norm() == 0);
    CHECK(t.le_radius > 0);
    CHECK(section::locate(t, t.te_point).distance < 1e-9);
    // both sides run straight into the vertex: 0.2 and 0.4 mm before it, the directions to
    // it agree (no arc), and the two sides' directions open a wedge of 8-30 degrees (12 by design)
    auto towards_te = [&](double ds) { return (t.te_point - at_arc(t, t.te_s + ds)).normalized(); };
    const Vector2d a1 = towards_te(-0.2), a2 = towards_te(-0.4), b1 = towards_te(0.2), b2 = towards_te(0.4);
    CHECK(a1.dot(a2) > std::cos(1.0 * pi / 180));
    CHECK(b1.dot(b2) > std::cos(1.0 * pi / 180));
    const double wedge = std::acos(std::clamp(a1.dot(b1), -1.0, 1.0)) * 180 / pi;
    CHECK(wedge > 8);
    CHECK(wedge < 30);
    // the vertex is the profile's: the nearest dense sample is within one step of it
    double nearest = 1e300;
    for (const Vector2d& p : t.profile) nearest = std::min(nearest, (p - t.te_point).norm());
    CHECK(nearest <= t.perimeter / 20000);
    // the camber line ends at the vertex, with no extension past c(1)
    CHECK((t.camber.back() - t.te_point).norm() < 1e-12);
    CHECK(t.camber_end >= t.camber.size() - 1);
  }
  // a scan of it lies on the surface
  section::ScanOptions o;
  o.z_min = 20, o.z_max = 21, o.spacing = 0.1;
  const auto scan = section::generate_scan(b, o);
  CHECK(worst_distance(b, scan.cloud.points, 97) < 1e-9);
}

TEST_CASE("generate kinds: the impulse blade is mirror-symmetric, front and back alike", "[generate]") {
  const BladeDesign b = section::impulse_blade();
  for (double z : {0.0, 17.0, 60.0}) {
    const SectionTruth t = section::section_truth(b.at(z), 8000);
    CHECK(t.le_radius == t.te_radius);
    CHECK(t.max_thickness_pos == Approx(0.5).margin(1e-9));
    CHECK(t.inlet_angle - t.stagger == Approx(t.stagger - t.outlet_angle).margin(1e-9));
    // the mirror across the chord's perpendicular bisector maps the profile onto itself
    const Vector2d mid = 0.5 * (t.le_point + t.te_point), ax = (t.te_point - t.le_point).normalized();
    double worst = 0;
    for (std::size_t i = 0; i < t.profile.size(); i += 13) {
      const Vector2d p = t.profile[i];
      const Vector2d m = p - 2 * (p - mid).dot(ax) * ax;
      worst = std::max(worst, section::locate(t, m).distance);
    }
    CHECK(worst < 1e-9);
    CHECK(t.le_point.x() < t.te_point.x());  // its LE lies towards -x (camber --le-direction -1,0,0)
  }
}

TEST_CASE("generate kinds: the thick root has a tiny trailing edge", "[generate]") {
  const BladeDesign b = section::thick_root_blade();
  const SectionTruth hub = section::section_truth(b.at(0)), tip = section::section_truth(b.at(b.span));
  CHECK(hub.max_thickness / hub.chord > 0.25);
  CHECK(hub.max_thickness / hub.chord < 0.30);
  CHECK(hub.te_radius < 0.3);
  CHECK(tip.te_radius < hub.te_radius);
  CHECK(tip.max_thickness / tip.chord < 0.15);
}

TEST_CASE("generate kinds: zero edge radii are allowed, negative ones refused", "[generate]") {
  section::SectionDesign d;
  d.te_radius = 0;
  CHECK_NOTHROW(section::section_truth(d));
  d.le_radius = 0;
  CHECK(section::section_truth(d).le_radius == 0);
  d.te_radius = -0.1;
  CHECK_THROWS_WITH(section::section_truth(d), Catch::Contains("zero (a sharp edge) or positive"));
}

TEST_CASE("generate kinds: a chordwise grid's lines lie at their heights on the true section", "[generate]") {
  const BladeDesign b = section::compressor_blade();
  section::GridOptions g = grid_of(31, 120);
  g.z_min = 10;
  g.z_max = 40;
  const auto grid = section::generate_grid(b, g).points;
  REQUIRE(grid.size() == 31 * 120);
  CHECK(worst_distance(b, grid, 7) < 1e-9);
  for (int j = 0; j < 31; ++j) {
    const double z = 10 + j;  // 30 mm over 30 steps, ends included
    for (int i = 0; i < 120; ++i) REQUIRE(grid[std::size_t(j * 120 + i)].z() == Approx(z).margin(1e-12));
  }
  // line 15 (z = 25): starts at the LE point, reaches the TE point half way, is dense at
  // both edges (cosine-like clustering) and about pi/2 times the mean spacing mid-side
  const SectionTruth t = section::section_truth(b.at(25));
  const Vector3d* line = &grid[15 * 120];
  CHECK((line[0].head<2>() - t.le_point).norm() < 1e-9);
  CHECK((line[60].head<2>() - t.te_point).norm() < 1e-9);
  auto step = [&](int i) { return (line[(i + 1) % 120] - line[i]).norm(); };
  const double mean = t.perimeter / 120;
  CHECK(step(0) < 0.3 * mean);
  CHECK(step(59) < 0.3 * mean);
  CHECK(step(60) < 0.3 * mean);
  CHECK(step(30) > 1.2 * mean);
  CHECK(step(90) > 1.2 * mean);
  // even spacing with clustering 0: every step close to the mean
  g.clustering = 0;
  const auto even = section::generate_grid(b, g).points;
  for (int i = 0; i < 120; ++i)
    CHECK((even[15 * 120 + std::size_t((i + 1) % 120)] - even[15 * 120 + std::size_t(i)]).norm() ==
          Approx(mean).epsilon(0.25));
}

TEST_CASE("generate kinds: a spanwise grid is the same surface, line by line along the span", "[generate]") {
  const BladeDesign b = section::turbine_blade();
  section::GridOptions g = grid_of(20, 40);
  const auto chordwise = section::generate_grid(b, g).points;
  g.lines = section::GridOptions::Lines::spanwise;
  g.repeat_seam = true;
  const auto spanwise = section::generate_grid(b, g).points;
  REQUIRE(spanwise.size() == 41 * 20);  // 40 places + the seam again, 20 heights each
  for (std::size_t i = 0; i < 40; ++i)
    for (std::size_t j = 0; j < 20; ++j) REQUIRE(spanwise[i * 20 + j] == chordwise[j * 40 + i]);
  for (std::size_t j = 0; j < 20; ++j) CHECK(spanwise[40 * 20 + j] == spanwise[j]);  // the seam line
  // each spanwise line runs from hub to tip
  CHECK(spanwise[0].z() == 0);
  CHECK(spanwise[19].z() == Approx(b.span));
}

TEST_CASE("generate kinds: grid and row noise has the requested sigma along the in-plane normal",
          "[generate]") {
  BladeDesign b = section::compressor_blade();
  b.tip = b.hub;  // prismatic: one truth
  const SectionTruth t = section::section_truth(b.hub);
  section::GridOptions g = grid_of(40, 200);
  g.noise = 0.01;
  g.seed = 4;
  const auto grid = section::generate_grid(b, g).points;
  section::RowsOptions r;
  r.spacing = 0.2;
  r.noise = 0.01;
  const auto rows = section::generate_rows(b, r).points;
  for (const auto* pts : {&grid, &rows}) {
    double sum2 = 0;
    for (const Vector3d& p : *pts) sum2 += std::pow(section::locate(t, p.head<2>()).distance, 2);
    CHECK(std::sqrt(sum2 / double(pts->size())) == Approx(0.01).epsilon(0.1));
  }
  // the heights stay those of the lines: the noise is in the plane
  for (const Vector3d& p : rows) CHECK(std::abs(p.z() - std::round(p.z())) < 1e-12);
}

TEST_CASE("generate kinds: rows lie at their heights, about `spacing` apart", "[generate]") {
  const BladeDesign b = section::compressor_blade();
  section::RowsOptions r = rows_of(4, 15);
  const std::vector<double> zs = section::row_heights(b, r);
  REQUIRE(zs.size() == 4);
  CHECK(zs[0] == Approx(7.5));  // centred on the 60 mm span
  CHECK(zs[3] == Approx(52.5));
  const auto pts = section::generate_rows(b, r).points;
  CHECK(worst_distance(b, pts) < 1e-9);
  std::size_t begin = 0;
  for (double z : zs) {
    std::size_t end = begin;
    while (end < pts.size() && pts[end].z() == z) ++end;
    const SectionTruth t = section::section_truth(b.at(z));
    const double count = double(end - begin);
    CHECK(count == Approx(t.perimeter / r.spacing).margin(1));
    // even in arc length along the true profile (the table's chords: within 1 %)
    const double spacing = t.perimeter / count;
    for (std::size_t i = begin; i + 1 < end; ++i) {
      double ds = section::locate(t, pts[i + 1].head<2>()).s - section::locate(t, pts[i].head<2>()).s;
      ds -= t.perimeter * std::floor(ds / t.perimeter);
      CHECK(ds == Approx(spacing).epsilon(0.01));
    }
    begin = end;
  }
  CHECK(begin == pts.size());
  r.rows = 6;  // 75 mm of rows on a 60 mm span
  CHECK_THROWS_WITH(section::generate_rows(b, r), Catch::Contains("outside the span"));
}

TEST_CASE("generate kinds: rotor rows lie at constant radius about the machine axis", "[generate]") {
  const BladeDesign b = section::turbine_blade();
  section::RowsOptions r = rows_of(3, 20, 150);
  const std::vector<double> zs = section::row_heights(b, r);
  const auto pts = section::generate_rows(b, r).points;
  CHECK(worst_distance(b, pts) < 1e-9);  // each point on the section at its own height
  double worst_radius = 0, lowest = 1e300;
  std::size_t k = 0;
  for (std::size_t i = 0; i < pts.size(); ++i) {
    if (i > 0 && pts[i].z() - pts[i - 1].z() > 5) ++k;  // the next row
    const double radius = std::hypot(pts[i].y(), pts[i].z() + r.hub_radius);
    worst_radius = std::max(worst_radius, std::abs(radius - (r.hub_radius + zs[k])));
    lowest = std::min(lowest, pts[i].z() - zs[k]);
    CHECK(pts[i].z() <= zs[k] + 1e-12);  // the cylinder falls away from the axis plane y = 0
  }
  CHECK(k == 2);
  CHECK(worst_radius < 1e-9);
  CHECK(lowest < -0.05);  // |y| up to ~15 mm: z drops by y^2 / 2R ~ 0.7 mm
  r.hub_radius = 5;       // the cylinder misses the section
  CHECK_THROWS_AS(section::generate_rows(b, r), section::Error);
}

TEST_CASE("generate kinds: grids and rows are deterministic and check their options", "[generate]") {
  const BladeDesign b = section::turbine_blade();
  section::GridOptions g = grid_of(5, 16);
  g.noise = 0.003;
  CHECK(section::generate_grid(b, g).points == section::generate_grid(b, g).points);
  g.around = 4;
  CHECK_THROWS_AS(section::generate_grid(b, g), section::Error);
  g.around = 16;
  g.z_min = 50, g.z_max = 70;
  CHECK_THROWS_WITH(section::generate_grid(b, g), Catch::Contains("part of the span"));
  section::RowsOptions r;
  r.noise = 0.003;
  CHECK(section::generate_rows(b, r).points == section::generate_rows(b, r).points);
  r.spacing = 0;
  CHECK_THROWS_AS(section::generate_rows(b, r), section::Error);
}

// SPDX-License-Identifier: GPL-3.0-or-later
// CFD-like structured grids and sparse rows of a generated blade (generate.h): points
// placed exactly on the section at their height through an arc-length table.
#include "generate_sample.h"
#include "generate_section.h"
#include "section/error.h"

#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

namespace section {

using namespace detail::gen;
using Eigen::Vector3d;

namespace {

void check_noise(double noise, const std::string& who) {
  if (!(noise >= 0) || !std::isfinite(noise)) throw Error(who + ": noise must be zero or positive");
}

// Arc lengths of `around` places on a profile of perimeter P whose TE point lies at te_s:
// half from the LE point to the TE point, the rest back, each side clustered at its ends.
std::vector<double> grid_places(int around, double clustering, double P, double te_s) {
  const int m0 = around / 2, m1 = around - m0;
  auto fraction = [clustering](int i, int m) {
    const double t = double(i) / m;
    return (1 - clustering) * t + clustering * 0.5 * (1 - std::cos(pi * t));
  };
  std::vector<double> a;
  a.reserve(std::size_t(around));
  for (int i = 0; i < m0; ++i) a.push_back(fraction(i, m0) * te_s);
  for (int i = 0; i < m1; ++i) a.push_back(te_s + fraction(i, m1) * (P - te_s));
  return a;
}

void check_grid(const GridOptions& o, const std::string& who) {
  if (o.heights < 2)
    throw Error(who + ": a grid needs at least 2 heights (got " + std::to_string(o.heights) +
                "; chordwise: --lines, spanwise: --line-points)");
  if (o.around < 8)
    throw Error(who + ": a grid needs at least 8 places around the profile (got " + std::to_string(o.around) +
                "; chordwise: --line-points, spanwise: --lines)");
  if (!(o.clustering >= 0 && o.clustering <= 1)) throw Error(who + ": clustering must be in [0, 1]");
  check_noise(o.noise, who);
  if (double(o.heights) * double(o.around) > 4e8)
    throw Error(who + ": " + num(double(o.heights) * double(o.around)) + " points requested; at most 4e8");
}

}  // namespace

Cloud generate_grid(const BladeDesign& blade, const GridOptions& o) {
  const std::string who = "generate_grid";
  check_grid(o, who);
  const auto [z_lo, z_hi] = checked_span_range(blade, o.z_min, o.z_max, who);
  const auto n = std::size_t(o.around);
  // grid[j * n + i]: height j, place i; the noise drawn in this order whatever the lines.
  std::vector<Vector3d> grid;
  grid.reserve(std::size_t(o.heights) * n);
  for (int j = 0; j < o.heights; ++j) {
    const double z = z_lo + (z_hi - z_lo) * j / (o.heights - 1);
    const ArcTable table(blade.at(z));
    Rng rng(o.seed * 0x9e3779b97f4a7c15ULL + std::uint64_t(j) * 0x2545f4914f6cdd1dULL + 7);
    for (double a : grid_places(o.around, o.clustering, table.perimeter, table.te_s)) {
      const PieceEval e = table.eval(a, table.sec);
      const double u1 = rng.uniform(), u2 = rng.uniform();
      const Vector2d p = e.p + (o.noise > 0 ? o.noise * Rng::normal(u1, u2) : 0.0) * e.normal;
      grid.emplace_back(p.x(), p.y(), z);
    }
  }
  Cloud cloud;
  const auto heights = std::size_t(o.heights);
  cloud.points.reserve(grid.size() + (o.repeat_seam ? heights : 0));
  if (o.lines == GridOptions::Lines::chordwise) {
    for (std::size_t j = 0; j < heights; ++j) {
      cloud.points.insert(cloud.points.end(), grid.begin() + long(j * n), grid.begin() + long((j + 1) * n));
      if (o.repeat_seam) cloud.points.push_back(grid[j * n]);
    }
  } else {
    for (std::size_t i = 0; i < n + (o.repeat_seam ? 1 : 0); ++i)
      for (std::size_t j = 0; j < heights; ++j) cloud.points.push_back(grid[j * n + i % n]);
  }
  return cloud;
}

std::vector<double> row_heights(const BladeDesign& blade, const RowsOptions& o) {
  const std::string who = "generate_rows";
  if (o.rows < 1) throw Error(who + ": rows must be at least 1");
  if (!(o.pitch > 0) || !std::isfinite(o.pitch)) throw Error(who + ": the row pitch must be positive");
  if (!std::isfinite(o.first)) throw Error(who + ": the first row's height must be finite");
  if (!(blade.span > 0)) throw Error(who + ": the blade span must be positive");
  const double first = o.first >= 0 ? o.first : 0.5 * blade.span - 0.5 * (o.rows - 1) * o.pitch;
  std::vector<double> zs;
  for (int k = 0; k < o.rows; ++k) {
    const double z = first + k * o.pitch;
    if (z < 0 || z > blade.span)
      throw Error(who + ": row " + std::to_string(k) + " at z = " + num(z) + " lies outside the span [0, " +
                  num(blade.span) + "]: fewer rows, a smaller pitch or another first height");
    zs.push_back(z);
  }
  return zs;
}

namespace {

// The point at arc length a of `table`'s row on the cylinder of radius R about the axis
// (parallel to x through (0, 0, -hub)): the height z where the section's point there lies
// at radius R, by fixed-point iteration (the section moves little with z, so it contracts
// fast); z returned through `z`.
PieceEval on_cylinder(const BladeDesign& blade, const ArcTable& table, double a, double hub, double R,
                      double& z, const std::string& who) {
  PieceEval e = table.eval(a, table.sec);
  for (int it = 0; it < 50; ++it) {
    const double y = e.p.y();
    if (std::abs(y) >= R)
      throw Error(who + ": the row of radius " + num(R) + " misses the section (|y| = " + num(std::abs(y)) +
                  "): a larger hub radius");
    const double next = std::sqrt(R * R - y * y) - hub;
    if (next < 0) throw Error(who + ": the row of radius " + num(R) + " leaves the span below the hub");
    const bool done = std::abs(next - z) < 1e-13 * (1 + R);
    z = next;
    const Section sec = make_section(blade.at(z));
    e = table.eval(a, sec);
    if (done) break;
  }
  return e;
}

}  // namespace

Cloud generate_rows(const BladeDesign& blade, const RowsOptions& o) {
  const std::string who = "generate_rows";
  if (!(o.spacing > 0) || !std::isfinite(o.spacing)) throw Error(who + ": spacing must be positive");
  check_noise(o.noise, who);
  if (!(o.hub_radius >= 0) || !std::isfinite(o.hub_radius))
    throw Error(who + ": the hub radius must be zero (rows at constant height) or positive");
  const std::vector<double> zs = row_heights(blade, o);
  Cloud cloud;
  for (std::size_t k = 0; k < zs.size(); ++k) {
    check_design(blade.at(zs[k]), who);
    const ArcTable table(blade.at(zs[k]));
    const int n = std::max(8, int(std::lround(table.perimeter / o.spacing)));
    if (double(n) * double(zs.size()) > 4e8) throw Error(who + ": too many points; increase the spacing");
    const double da = table.perimeter / n;
    Rng rng(o.seed * 0x100000001b3ULL + std::uint64_t(k) * 0x9e3779b97f4a7c15ULL + 29);
    const double phase = rng.uniform() * da;
    for (int i = 0; i < n; ++i) {
      const double a = phase + i * da;
      double z = zs[k];
      const PieceEval e = o.hub_radius > 0
                              ? on_cylinder(blade, table, a, o.hub_radius, o.hub_radius + zs[k], z, who)
                              : table.eval(a, table.sec);
      const double u1 = rng.uniform(), u2 = rng.uniform();
      const Vector2d p = e.p + (o.noise > 0 ? o.noise * Rng::normal(u1, u2) : 0.0) * e.normal;
      cloud.points.emplace_back(p.x(), p.y(), z);
    }
  }
  return cloud;
}

}  // namespace section

// SPDX-License-Identifier: GPL-3.0-or-later
// Tests of the morphology step (ordering unordered section points into closed loops).
// Shapes are analytic closed curves sampled as a scanner would (random spacing, varying
// density, holes, noise, a misregistered half, outliers) with exact ground truth.
#include "detail/kept_ordering.h"
#include "point_grid.h"
#include "section/error.h"
#include "section/morphology.h"

#include <catch2/catch.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numeric>
#include <optional>
#include <random>
#include <vector>

namespace {

using section::MorphologyOptions;
using section::MorphologyResult;
using section::order_section;
using Vec = Eigen::Vector2d;
using Points = std::vector<Vec>;
constexpr double pi = 3.14159265358979323846;

/// A closed counterclockwise curve as a dense polyline with arc lengths.
struct Curve {
  Points p;
  std::vector<double> s;  // arc length at each vertex
  double perimeter = 0;

  explicit Curve(Points pts) : p(std::move(pts)) {
    s.assign(p.size(), 0);
    for (std::size_t i = 1; i < p.size(); ++i) s[i] = s[i - 1] + (p[i] - p[i - 1]).norm();
    perimeter = s.back() + (p.front() - p.back()).norm();
  }
  struct Where {
    double distance, s;
    Vec normal;
  };
  /// Nearest foot on the polyline (brute force: test sizes are small).
  Where locate(const Vec& q) const {
    Where best{1e300, 0, Vec(0, 0)};
    for (std::size_t i = 0; i < p.size(); ++i) {
      const Vec& a = p[i];
      const Vec& b = p[(i + 1) % p.size()];
      const Vec e = b - a;
      const double t = std::clamp((q - a).dot(e) / e.squaredNorm(), 0.0, 1.0);
      const double d = (a + t * e - q).norm();
      if (d < best.distance) best = {d, s[i] + t * e.norm(), Vec(e.y(), -e.x()).normalized()};
    }
    return best;
  }
  /// Point and outward normal at arc length t.
  std::pair<Vec, Vec> at(double t) const {
    t = std::fmod(std::fmod(t, perimeter) + perimeter, perimeter);
    const std::size_t i = std::upper_bound(s.begin(), s.end(), t) - s.begin() - 1;
    const Vec& a = p[i];
    const Vec& b = p[(i + 1) % p.size()];
    const double l = (b - a).norm();
    const Vec e = (b - a) / l;
    return {a + (t - s[i]) * e, Vec(e.y(), -e.x())};
  }
};

Curve ellipse(Vec c, double a, double b, int n = 4000) {
  Points p;
  for (int i = 0; i < n; ++i) {
    const double t = 2 * pi * i / n;
    p.push_back(c + Vec(a * std::cos(t), b * std::sin(t)));
  }
  return Curve(p);
}

/// A thin cambered airfoil: chord 40 mm along +x from `origin`, half thickness
/// r0 + (r1 - r0) x / L + bump sin^2(pi x / L) around a circular-arc camber line, closed by
/// round edges of radius r0 (leading) and r1 (trailing).
Curve airfoil(Vec origin, double r0 = 0.2, double r1 = 0.2, double thickness = 3.0, double camber = 2.0,
              int n = 2500) {
  const double L = 40;
  const auto centre = [&](double x) -> Vec { return origin + Vec(x, 4 * camber * x * (L - x) / (L * L)); };
  const auto normal = [&](double x) -> Vec {
    const Vec t(1, 4 * camber * (L - 2 * x) / (L * L));
    return Vec(-t.y(), t.x()).normalized();
  };
  const auto half = [&](double x) {
    const double sn = std::sin(pi * x / L);
    return r0 + (r1 - r0) * x / L + (thickness / 2 - (r0 + r1) / 2) * sn * sn;
  };
  Points p;
  for (int i = 0; i <= n; ++i) {  // lower side, leading to trailing edge
    const double x = L * (1 - std::cos(pi * i / n)) / 2;
    p.push_back(centre(x) - half(x) * normal(x));
  }
  const Vec nt = normal(L);
  for (int i = 1; i < 200; ++i) {  // trailing-edge arc
    const double a = -pi / 2 + pi * i / 200;
    const Vec t(nt.y(), -nt.x());
    p.push_back(centre(L) + r1 * (std::cos(a) * t + std::sin(a) * nt));
  }
  for (int i = n; i >= 0; --i) {  // upper side, trailing to leading edge
    const double x = L * (1 - std::cos(pi * i / n)) / 2;
    p.push_back(centre(x) + half(x) * normal(x));
  }
  const Vec n0 = normal(0);
  for (int i = 1; i < 200; ++i) {  // leading-edge arc
    const double a = pi / 2 + pi * i / 200;
    const Vec t(n0.y(), -n0.x());
    p.push_back(centre(0) + r0 * (std::cos(a) * t + std::sin(a) * n0));
  }
  // Drop consecutive duplicates.
  Points q;
  for (const Vec& v : p)
    if (q.empty() || (v - q.back()).norm() > 1e-9) q.push_back(v);
  return Curve(q);
}

struct ScanSpec {
  double spacing = 0.08;           // mm, mean distance along the curve at full density
  double noise = 0.005;            // mm, sigma along the normal
  double density_min = 0.25;       // lowest relative density
  int holes = 3;                   // gaps 0.5-2 mm long
  double misregistration = 0.015;  // mm, offset of the points whose normal has x > 0
  double outliers = 0.0002;        // fraction of outlier points
  unsigned seed = 1;
};

struct Scan {
  Points points;
  std::vector<int> outlier;
};

Scan scan(const Curve& c, const ScanSpec& spec) {
  std::mt19937_64 rng(spec.seed);
  std::uniform_real_distribution<double> u01(0, 1);
  std::normal_distribution<double> gauss(0, 1);
  std::vector<std::pair<double, double>> holes;
  for (int k = 0; k < spec.holes; ++k) {
    const double a = u01(rng) * c.perimeter;
    holes.emplace_back(a, a + 0.5 + 1.5 * u01(rng));
  }
  const double phase = u01(rng) * 2 * pi;
  Scan out;
  const Vec shift = spec.misregistration * Vec(std::cos(phase), std::sin(phase));
  for (double t = u01(rng) * spec.spacing; t < c.perimeter;) {
    bool in_hole = false;
    for (auto [a, b] : holes)
      if ((t >= a && t <= b) || (t + c.perimeter >= a && t + c.perimeter <= b)) in_hole = true;
    if (!in_hole) {
      auto [p, n] = c.at(t);
      p += spec.noise * gauss(rng) * n;
      if (n.x() > 0) p += shift;
      out.points.push_back(p);
      out.outlier.push_back(0);
    }
    // Density varies smoothly along the curve between density_min and 1.
    const double dens = spec.density_min +
                        (1 - spec.density_min) * (0.5 + 0.5 * std::sin(2 * pi * 3 * t / c.perimeter + phase));
    t += spec.spacing / dens * (0.5 + u01(rng));
  }
  // Outliers anywhere in the box grown by 3 mm (at least one).
  Vec lo = c.p[0], hi = lo;
  for (const Vec& v : c.p) {
    lo = lo.cwiseMin(v);
    hi = hi.cwiseMax(v);
  }
  const std::size_t count = std::max<std::size_t>(1, std::size_t(spec.outliers * out.points.size() + 0.5));
  for (std::size_t k = 0; k < count && spec.outliers > 0; ++k) {
    const Vec p(lo.x() - 3 + u01(rng) * (hi.x() - lo.x() + 6), lo.y() - 3 + u01(rng) * (hi.y() - lo.y() + 6));
    const std::size_t at = std::size_t(u01(rng) * out.points.size());
    out.points.insert(out.points.begin() + at, p);
    out.outlier.insert(out.outlier.begin() + at, 1);
  }
  return out;
}

/// The points of scans of two curves (no outliers: topology only), the second's with seed
/// `seed_b`, after the first's.
Points two_scans(const Curve& a, const Curve& b, unsigned seed_b) {
  ScanSpec spec;
  spec.outliers = 0;
  Points points = scan(a, spec).points;
  spec.seed = seed_b;
  const Scan sb = scan(b, spec);
  points.insert(points.end(), sb.points.begin(), sb.points.end());
  return points;
}

/// Facts about one loop against its true curve.
struct LoopCheck {
  double near_fraction = 0;    // kept points within 30 um of the truth
  double worst_backstep = 0;   // mm, largest step backwards in truth arc length
  double winding = 0;          // sum of steps / perimeter (1 = once around, counterclockwise)
  double normal_fraction = 0;  // normals with dot > 0.9 against the truth
  std::size_t far_kept = 0;    // kept points farther than 0.2 mm from the truth
};

LoopCheck check_loop(const section::Loop& loop, const Curve& c) {
  LoopCheck r;
  std::vector<double> s;
  std::size_t near = 0, normal_ok = 0;
  for (std::size_t i = 0; i < loop.points.size(); ++i) {
    const auto w = c.locate(loop.points[i]);
    s.push_back(w.s);
    near += w.distance <= 0.030;
    r.far_kept += w.distance > 0.2;
    normal_ok += loop.normals[i].dot(w.normal) > 0.9;
  }
  double total = 0;
  for (std::size_t i = 0; i < s.size(); ++i) {
    double d = s[(i + 1) % s.size()] - s[i];
    d -= c.perimeter * std::round(d / c.perimeter);  // wrapped into [-P/2, P/2]
    total += d;
    r.worst_backstep = std::max(r.worst_backstep, -d);
  }
  r.winding = total / c.perimeter;
  r.near_fraction = double(near) / double(s.size());
  r.normal_fraction = double(normal_ok) / double(s.size());
  return r;
}

/// Outliers farther than `far` from the truth that some loop kept.
std::size_t kept_far_outliers(const MorphologyResult& m, const Scan& sc, const Curve& c, double far) {
  std::size_t kept = 0;
  for (const auto& loop : m.loops)
    for (std::size_t k : loop.index)
      if (sc.outlier[k] && c.locate(sc.points[k]).distance > far) ++kept;
  return kept;
}

}  // namespace

TEST_CASE("morphology: clean dense circle gives one ordered loop with radial normals", "[morphology]") {
  const Curve c = ellipse({3, -2}, 10, 10);
  ScanSpec spec;  // exact: no noise, holes, density changes, misregistration or outliers
  spec.noise = spec.misregistration = spec.outliers = 0;
  spec.holes = 0;
  spec.density_min = 1;
  const Scan sc = scan(c, spec);
  const MorphologyResult m = order_section(sc.points);
  REQUIRE(m.loops.size() == 1);
  const auto& loop = m.loops[0];
  CHECK(loop.points.size() == sc.points.size());
  CHECK(m.dropped == 0);
  const LoopCheck r = check_loop(loop, c);
  CHECK(r.winding == Approx(1).margin(1e-9));
  CHECK(r.worst_backstep < 0.02);
  CHECK(r.normal_fraction == 1.0);
  // The traced boundary follows the circle to a fraction of a cell.
  double worst = 0;
  for (const Vec& b : loop.boundary) worst = std::max(worst, std::abs((b - Vec(3, -2)).norm() - 10));
  CHECK(worst < 0.75 * m.cell);  // sub-cell: the raster alone is good to half a cell
  CHECK(loop.area == Approx(pi * 100).epsilon(0.01));
  CHECK(loop.length == Approx(2 * pi * 10).epsilon(0.01));
  for (std::size_t i = 0; i < loop.points.size(); ++i) {
    const Vec radial = (loop.points[i] - Vec(3, -2)).normalized();
    CHECK(loop.normals[i].dot(radial) > 0.98);  // 11 degrees
  }
}

TEST_CASE("morphology: noisy ellipses and thin airfoils are ordered like their true profile",
          "[morphology]") {
  struct Case {
    const char* name;
    Curve curve;
  };
  const std::vector<Case> cases = {
      {"ellipse 15 x 5", ellipse({0, 0}, 15, 5)},
      {"airfoil, 0.2 mm edges", airfoil({-20, 0}, 0.2, 0.2, 3.0, 2.0)},
      {"airfoil, 0.3 mm edges, thin", airfoil({5, 7}, 0.3, 0.25, 1.6, 4.0)},
  };
  for (const auto& cs : cases)
    for (unsigned seed = 1; seed <= 4; ++seed) {
      ScanSpec spec;
      spec.seed = seed;
      spec.outliers = 0.002;  // ten times the nominal rate, so each scan has some
      const Scan sc = scan(cs.curve, spec);
      const MorphologyResult m = order_section(sc.points);
      INFO(cs.name << ", seed " << seed << ", cell " << m.cell << ", dilation " << m.dilation);
      REQUIRE(m.loops.size() == 1);
      const LoopCheck r = check_loop(m.loops[0], cs.curve);
      CHECK(r.winding == Approx(1).margin(1e-9));
      CHECK(r.worst_backstep < 0.1);
      CHECK(r.near_fraction >= 0.995);
      CHECK(r.normal_fraction >= 0.99);
      // Outliers beyond the default outlier distance (2.5 cells) plus the boundary's error.
      CHECK(kept_far_outliers(m, sc, cs.curve, std::max(0.2, 2.5 * m.cell + 0.03)) == 0);
      CHECK(m.loops[0].points.size() + m.dropped == sc.points.size());
    }
}

TEST_CASE("morphology: two separate blades give two loops, largest first", "[morphology]") {
  const Curve big = airfoil({0, 0}, 0.2, 0.2, 3.0, 2.0);
  const Curve small = ellipse({20, 20}, 6, 2.5);
  const MorphologyResult m = order_section(two_scans(big, small, 7));
  REQUIRE(m.loops.size() == 2);
  CHECK(m.loops[0].area > m.loops[1].area);
  for (const Vec& p : m.loops[0].points) CHECK(big.locate(p).distance < 0.1);
  for (const Vec& p : m.loops[1].points) CHECK(small.locate(p).distance < 0.1);
  CHECK(check_loop(m.loops[0], big).worst_backstep < 0.1);
  CHECK(check_loop(m.loops[1], small).worst_backstep < 0.1);
}

TEST_CASE("morphology: points scattered off the surface make no loop of their own", "[morphology]") {
  // A laser's mixed pixels: a point every 0.3-0.9 mm along the profile moved 0.1-0.25 mm off
  // it, out or in. Those farther than the outlier distance closed, on their own pass, into
  // loops along the profile, and the section was refused for its "other objects". A dense
  // scan of a second object as near (a cooling channel 0.5 mm inside the wall) stays a loop.
  const Curve blade = airfoil({0, 0}, 0.5, 0.3, 6.0, 2.0);
  for (const unsigned seed : {1u, 2u, 3u}) {
    ScanSpec spec;
    spec.spacing = 0.04, spec.holes = 0, spec.outliers = 0, spec.misregistration = 0, spec.seed = seed;
    Points points = scan(blade, spec).points;
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> u01(0, 1);
    std::size_t strays = 0;
    for (double t = 0; t < blade.perimeter; t += 0.3 + 0.6 * u01(rng), ++strays) {
      const auto [p, n] = blade.at(t);
      points.push_back(p + (u01(rng) < 0.5 ? -1 : 1) * (0.1 + 0.15 * u01(rng)) * n);
    }
    const MorphologyResult m = order_section(points);
    INFO("seed " << seed << ": " << strays << " strays, " << m.loops.size() << " loops, dropped "
                 << m.dropped);
    CHECK(m.loops.size() == 1);
    CHECK(check_loop(m.loops[0], blade).worst_backstep < 0.1);
  }
  const Curve wall = ellipse({0, 0}, 12, 4);
  const Curve channel = ellipse({0, 0}, 11.5, 3.5);
  const MorphologyResult m = order_section(two_scans(wall, channel, 5));
  CHECK(m.loops.size() == 2);
}

TEST_CASE("morphology: an annulus (cooling channel) gives an outer and an inner loop", "[morphology]") {
  const Curve outer = ellipse({0, 0}, 12, 6);
  const Curve inner = ellipse({1, 0.5}, 3, 1.5);
  const MorphologyResult m = order_section(two_scans(outer, inner, 3));
  REQUIRE(m.loops.size() == 2);
  const LoopCheck ro = check_loop(m.loops[0], outer);
  const LoopCheck ri = check_loop(m.loops[1], inner);
  CHECK(ro.far_kept == 0);
  CHECK(ri.far_kept == 0);
  CHECK(ro.worst_backstep < 0.1);
  CHECK(ri.worst_backstep < 0.1);
  CHECK(m.loops[1].area == Approx(pi * 3 * 1.5).epsilon(0.05));
}

TEST_CASE("morphology: bad input throws a clear error", "[morphology]") {
  CHECK_THROWS_WITH(order_section({}), Catch::Contains("morphology: no points"));
  CHECK_THROWS_WITH(order_section({{0, 0}, {1, 0}, {0, 1}}), Catch::Contains("at least"));
  Points nan_points(20, Vec(1, 2));
  nan_points[4] = Vec(std::nan(""), 0);
  CHECK_THROWS_WITH(order_section(nan_points), Catch::Contains("not finite"));
  // An open arc never encloses anything.
  Points arc;
  for (int i = 0; i < 500; ++i) arc.emplace_back(10 * std::cos(i * 0.005), 10 * std::sin(i * 0.005));
  CHECK_THROWS_WITH(order_section(arc), Catch::Contains("do not close"));
  // It names no option a user cannot give (max_dilation) or that would not help (the cell).
  CHECK_THROWS_WITH(order_section(arc), !Catch::Contains("max_dilation") && !Catch::Contains("cell or"));
  // A raster beyond max_cells is refused before it is allocated; a larger cell helps there.
  MorphologyOptions o;
  o.cell = 1e-4;
  const Scan sc = scan(ellipse({0, 0}, 10, 10), ScanSpec{});
  CHECK_THROWS_WITH(order_section(sc.points, o),
                    Catch::Contains("max_cells") && Catch::Contains("slice --cell"));
}

TEST_CASE("morphology: skeleton of a stadium lies on its axis with the true radius", "[morphology]") {
  // Stadium: segment from (-10, 0) to (10, 0) grown by 2 mm.
  Points p;
  const int n = 2000;
  for (int i = 0; i < n; ++i) {
    const double t = 2 * pi * i / n;
    p.emplace_back(10 * (std::cos(t) > 0 ? 1 : -1) + 2 * std::cos(t), 2 * std::sin(t));
  }
  const Curve c(p);
  ScanSpec spec;
  spec.seed = 5;
  const Scan sc = scan(c, spec);
  const MorphologyResult m = order_section(sc.points);
  REQUIRE(m.loops.size() == 1);
  REQUIRE(m.skeleton.size() > 10);
  REQUIRE(m.skeleton.size() == m.skeleton_radius.size());
  std::size_t middle = 0;
  for (std::size_t i = 0; i < m.skeleton.size(); ++i) {
    const Vec& q = m.skeleton[i];
    if (std::abs(q.x()) > 6) continue;  // the ends branch toward the caps
    ++middle;
    CHECK(std::abs(q.y()) < 2 * m.cell);
    CHECK(m.skeleton_radius[i] == Approx(2).margin(0.2));  // 10%: a seed for the camber stage
  }
  CHECK(middle * m.cell > 10);                                           // covers the middle of the axis
  CHECK(std::abs(m.skeleton.front().x() - m.skeleton.back().x()) > 18);  // from cap to cap
}

TEST_CASE("morphology: skeleton_if leaves the skeleton out and the loops as they are", "[morphology]") {
  // Stadium of half length 10 grown by 2 mm: the skeleton, when asked for, is its axis.
  Points p;
  for (int i = 0; i < 1500; ++i) {
    const double t = 2 * pi * i / 1500;
    p.emplace_back(10 * (std::cos(t) > 0 ? 1 : -1) + 2 * std::cos(t), 2 * std::sin(t));
  }
  ScanSpec spec;
  spec.seed = 9;
  const Scan sc = scan(Curve(p), spec);
  const MorphologyResult all = order_section(sc.points);
  REQUIRE(all.skeleton.size() > 10);
  for (const bool wanted : {false, true}) {
    MorphologyOptions opt;
    std::size_t asked = 0;
    opt.skeleton_if = [&](const MorphologyResult& m) {
      ++asked;
      CHECK(m.loops.size() == 1);  // asked with the loops made
      return wanted;
    };
    const MorphologyResult m = order_section(sc.points, opt);
    CHECK(asked == 1);
    REQUIRE(m.loops.size() == all.loops.size());
    CHECK(m.loops[0].index == all.loops[0].index);
    CHECK(m.loops[0].normals == all.loops[0].normals);
    CHECK(m.skeleton.size() == (wanted ? all.skeleton.size() : 0));
    if (wanted) CHECK(m.skeleton_radius == all.skeleton_radius);  // g deep inside made again
    for (std::size_t i = 0; wanted && i < m.skeleton.size(); ++i) {
      CHECK(std::abs(m.skeleton[i].y()) < 2 * m.cell + 1e-9 + (std::abs(m.skeleton[i].x()) > 6 ? 2 : 0));
      CHECK(m.skeleton[i] == all.skeleton[i]);
    }
  }
}

TEST_CASE("morphology: denser points beside a kept ordering are ordered on its loops", "[morphology]") {
  // slice's band: the slab's sparse points are ordered, then a denser scan of the same
  // profile is ordered on the loops they made, without a raster of its own.
  const std::vector<Curve> curves = {ellipse({0, 0}, 15, 5), airfoil({-20, 0}, 0.2, 0.2, 3.0, 2.0)};
  for (std::size_t ci = 0; ci < curves.size(); ++ci)
    for (unsigned seed = 1; seed <= 3; ++seed) {
      INFO("curve " << ci << ", seed " << seed);
      ScanSpec sparse;
      sparse.seed = seed;
      sparse.spacing = 0.1;
      sparse.holes = 0;
      sparse.outliers = 0;
      ScanSpec dense = sparse;
      dense.seed = seed + 100;
      dense.spacing = 0.05;
      MorphologyOptions no_skeleton;
      no_skeleton.skeleton_if = [](const MorphologyResult&) { return false; };
      const section::detail::OrderedKept slab =
          section::detail::order_section_kept(scan(curves[ci], sparse).points, no_skeleton);
      REQUIRE(slab.result.skeleton.empty());
      const Scan band = scan(curves[ci], dense);
      const std::optional<MorphologyResult> m = section::detail::order_beside(*slab.kept, band.points, {});
      REQUIRE(m);
      REQUIRE(m->loops.size() == 1);
      CHECK(m->dropped == 0);
      CHECK(m->loops[0].points.size() == band.points.size());
      const LoopCheck r = check_loop(m->loops[0], curves[ci]);
      CHECK(r.winding == Approx(1).margin(1e-9));
      CHECK(r.worst_backstep < 0.1);
      CHECK(r.near_fraction >= 0.995);
      CHECK(r.normal_fraction >= 0.99);  // from the slab's fill
      // The skeleton is the slab's own: the same as made afresh from it.
      MorphologyResult with = slab.result;
      section::detail::add_skeleton(*slab.kept, with);
      REQUIRE(with.skeleton.size() > 10);
      CHECK(m->skeleton == with.skeleton);
      // Points off the kept loops (the profile moved by 1 mm) are not ordered on them.
      Points moved = band.points;
      for (Vec& q : moved) q.x() += 1.0;
      CHECK_FALSE(section::detail::order_beside(*slab.kept, moved, {}));
    }
}

TEST_CASE("morphology: the median spacing with a floor is the larger of the two", "[morphology]") {
  // 2000 points evenly on a circle of radius 10: each one chord 20 sin(pi / 2000) from the next.
  Points points;
  for (int i = 0; i < 2000; ++i) {
    const double a = 2 * M_PI * i / 2000;
    points.emplace_back(10 * std::cos(a), 10 * std::sin(a));
  }
  std::vector<std::size_t> all(points.size());
  std::iota(all.begin(), all.end(), std::size_t(0));
  const double chord = 20 * std::sin(M_PI / 2000);
  const double median = section::morph::median_spacing(points, all, 20000);
  CHECK(median == Approx(chord).epsilon(1e-9));
  CHECK(section::morph::median_spacing(points, all, 20000, 0.5 * chord) == median);
  CHECK(section::morph::median_spacing(points, all, 20000, 3 * chord) == 3 * chord);
}

TEST_CASE("morphology: 1e5 dense points give one loop (time reported, not asserted)", "[morphology][speed]") {
  const Curve c = airfoil({0, 0}, 0.2, 0.25, 3.0, 3.0);
  ScanSpec spec;
  spec.spacing = 87.0 / 1e5;  // about 1e5 points around the profile
  spec.holes = 2;
  spec.density_min = 1;
  const Scan sc = scan(c, spec);
  const auto t0 = std::chrono::steady_clock::now();
  const MorphologyResult m = order_section(sc.points);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  WARN("morphology: " << sc.points.size() << " points in " << seconds * 1e3
                      << " ms = " << sc.points.size() / seconds << " points/s (cell " << m.cell << " mm, "
                      << m.raster_cells << " cells)");
  REQUIRE(m.loops.size() == 1);
}

// ---------------------------------------------------------------------------------------
// Sections of generated blade scans (section/generate.h), both presets, several seeds.

#include "section/extras/generate.h"

namespace {

struct BladeSlab {
  section::SectionTruth truth;
  Points points;
  std::vector<int> outlier;
};

/// Scan points of a noisy scan within |z - z0| <= slab / 2, projected to (x, y).
BladeSlab blade_slab(const section::BladeDesign& blade, double z0, std::uint64_t seed, double slab = 0.08) {
  section::ScanOptions o = section::inspection_scan();
  o.holes = 6;
  o.misregistration = 0.015;
  o.z_min = z0 - 2;
  o.z_max = z0 + 2;
  o.seed = seed;
  const section::Scan scan = section::generate_scan(blade, o);
  BladeSlab s;
  s.truth = section::section_truth(blade.at(z0));
  for (std::size_t k = 0; k < scan.cloud.points.size(); ++k) {
    const Eigen::Vector3d& p = scan.cloud.points[k];
    if (std::abs(p.z() - z0) > slab / 2) continue;
    s.points.emplace_back(p.x(), p.y());
    s.outlier.push_back(scan.outlier[k]);
  }
  return s;
}

}  // namespace

TEST_CASE("morphology: generated turbine and compressor sections give one ordered loop", "[morphology]") {
  struct Preset {
    const char* name;
    section::BladeDesign blade;
  };
  const std::vector<Preset> presets = {{"turbine", section::turbine_blade()},
                                       {"compressor", section::compressor_blade()}};
  for (const auto& preset : presets)
    for (std::uint64_t seed = 1; seed <= 4; ++seed) {
      const double z0 = 10 + 12 * double(seed);
      const BladeSlab s = blade_slab(preset.blade, z0, seed);
      const MorphologyResult m = order_section(s.points);
      INFO(preset.name << ", seed " << seed << ", z " << z0 << ", " << s.points.size() << " points, cell "
                       << m.cell << ", dilation " << m.dilation << ", dropped " << m.dropped);
      REQUIRE(m.loops.size() == 1);
      const auto& loop = m.loops[0];
      const double P = s.truth.perimeter;
      std::size_t near = 0, normal_ok = 0, far_outliers_kept = 0;
      std::vector<double> sv;
      for (std::size_t i = 0; i < loop.points.size(); ++i) {
        const section::ProfileLocation w = section::locate(s.truth, loop.points[i]);
        sv.push_back(w.s);
        near += w.distance <= 0.030;
        // True outward normal: the profile runs counterclockwise, so the tangent turned clockwise.
        const std::size_t n = s.truth.profile.size();
        const double step = P / double(n);
        const std::size_t a = std::size_t(w.s / step) % n;
        const Vec t = s.truth.profile[(a + 1) % n] - s.truth.profile[(a + n - 1) % n];
        normal_ok += loop.normals[i].dot(Vec(t.y(), -t.x()).normalized()) > 0.9;
        far_outliers_kept += s.outlier[loop.index[i]] && w.distance > 0.2;
      }
      double total = 0, worst_back = 0;
      for (std::size_t i = 0; i < sv.size(); ++i) {
        double d = sv[(i + 1) % sv.size()] - sv[i];
        d -= P * std::round(d / P);
        total += d;
        worst_back = std::max(worst_back, -d);
      }
      CHECK(total / P == Approx(1).margin(1e-9));  // once around, counterclockwise
      CHECK(worst_back < 0.1);
      CHECK(double(near) / double(sv.size()) >= 0.995);
      CHECK(double(normal_ok) / double(sv.size()) >= 0.99);
      CHECK(far_outliers_kept == 0);
    }
}

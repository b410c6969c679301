// SPDX-License-Identifier: GPL-3.0-or-later
// What slice makes of each kind of sampling (docs/SAMPLING.md), on generated blades with
// exact truth: dense scans, structured surface grids (lines along the chord or along the
// span), sparse rows (at constant height, between planes, tilted, at a constant radius),
// single 2D profiles (ordered and shuffled) and exact copies of points.
#include "section/error.h"
#include "section/extras/generate.h"
#include "section/extras/score.h"
#include "section/fit_spline.h"
#include "section/io/slice_file.h"
#include "section/io/stream.h"
#include "section/pipe/slice_stream.h"
#include "section/sampling.h"
#include "section/slice.h"
#include "pipe_stages.h"
#include "detail/spacing_search.h"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <random>
#include <string>
#include <vector>

using namespace section;
using Vec3 = Eigen::Vector3d;

namespace {

// Points of the true profile at height z about `step` apart along it (vertices of the exact
// polyline, so on the curve), from `phase` of a step on: one row, or one chordwise grid line.
std::vector<Vec3> row_at(const BladeDesign& blade, double z, double step, double phase = 0) {
  const SectionTruth t = section_truth(blade.at(z), 8000);
  std::vector<Vec3> out;
  const std::size_t n = t.profile.size();
  for (double s = phase * step; s < t.perimeter - 0.5 * step; s += step) {
    const std::size_t k = std::min(n - 1, std::size_t(s / t.perimeter * double(n) + 0.5));
    out.emplace_back(t.profile[k].x(), t.profile[k].y(), z);
  }
  return out;
}

// Lines along the chord (rows of points `step` apart) every `gap` from z0 to z1: a
// structured CFD surface grid's chordwise lines.
Cloud chordwise_grid(const BladeDesign& blade, double z0, double z1, double gap, double step) {
  Cloud c;
  int k = 0;
  for (double z = z0; z <= z1 + 1e-9; z += gap, ++k) {
    const auto row = row_at(blade, z, step, 0.37 * (k % 3));  // lines not aligned along the chord
    c.points.insert(c.points.end(), row.begin(), row.end());
  }
  return c;
}

// Lines along the span: at `lines` fractions of the perimeter, points every `gap` in height.
Cloud spanwise_grid(const BladeDesign& blade, double z0, double z1, double gap, int lines) {
  Cloud c;
  for (double z = z0; z <= z1 + 1e-9; z += gap) {
    const SectionTruth t = section_truth(blade.at(z), 8000);
    for (int k = 0; k < lines; ++k) {
      const std::size_t i = std::size_t(double(k) / lines * double(t.profile.size()));
      c.points.emplace_back(t.profile[i].x(), t.profile[i].y(), z);
    }
  }
  return c;
}

// Sparse rows: the profile at each height, `step` apart along it.
Cloud rows_at(const BladeDesign& blade, const std::vector<double>& zs, double step) {
  Cloud c;
  for (double z : zs) {
    const auto row = row_at(blade, z, step);
    c.points.insert(c.points.end(), row.begin(), row.end());
  }
  return c;
}

// Largest distance of a section's loop-0 points from the true profile at height z (the
// section's frame must be u = x, v = y).
double worst_distance(const SectionSlice& s, const SectionTruth& truth) {
  double worst = 0;
  for (const auto& p : s.morphology.loops.at(0).points) worst = std::max(worst, locate(truth, p).distance);
  return worst;
}

// The pipe after slice (through the stream's text, as the tools pass it): each section's
// camber scores against the truth at its height; a section without params fails the test.
std::vector<CamberScore> camber_scores(const SliceResult& r, const std::vector<double>& zs,
                                       const BladeDesign& blade) {
  const Stream stream = test::after_slice(to_stream(r, "slice"));
  std::vector<CamberScore> out;
  for (std::size_t k = 0; k < zs.size(); ++k) {
    INFO("section " << k << " at z = " << zs[k]);
    REQUIRE(r.sections[k].error.empty());
    out.push_back(score_camber(stream, int(k), section_truth(blade.at(zs[k]), 8000)));
    const CamberScore& e = out.back();
    UNSCOPED_INFO("z " << zs[k] << ": camber rms " << e.camber_rms * 1e3 << " um, chord " << e.chord * 1e3
                       << " um, max thickness " << e.max_thickness * 1e3 << " um, LE radius "
                       << e.le_radius * 100 << " %, TE radius " << e.te_radius * 100 << " %, inlet "
                       << e.inlet_angle << " deg, outlet " << e.outlet_angle << " deg");
  }
  return out;
}

// The issues' targets where the data are dense (docs/ACCURACY.md).
void check_targets(const CamberScore& e) {
  CHECK(e.camber_rms <= 0.003);
  CHECK(std::abs(e.chord) <= 0.010);
  CHECK(std::abs(e.max_thickness) <= 0.005);
  CHECK(std::abs(e.le_radius) <= 0.03);
  CHECK(std::abs(e.te_radius) <= 0.10);
  CHECK(std::abs(e.inlet_angle) <= 0.5);
  CHECK(std::abs(e.outlet_angle) <= 0.5);
}

}  // namespace

TEST_CASE("sampling: a dense scan is dense, and its slab is the mean spacing as before", "[sampling]") {
  const BladeDesign blade = compressor_blade();
  ScanOptions so = inspection_scan();
  so.seed = 3;
  const Cloud cloud = scan_bands(blade, {30.0}, so, 1.0);
  const Sampling s = sampling_of(cloud.points, {0, 0, 1});
  INFO(s.describe());
  CHECK(s.kind == SamplingKind::dense);
  CHECK(s.spacing == Approx(0.08).epsilon(0.4));
  CHECK(s.normal_spacing < 2 * s.spacing);
  CHECK(s.duplicates == 0);
  const SliceResult r = slice(cloud, planes_at({0, 0, 1}, {30.0}));
  CHECK(r.slab == mean_spacing(cloud.points));
  CHECK(r.sampling.kind == SamplingKind::dense);
  REQUIRE(r.sections[0].error.empty());
}

TEST_CASE("sampling: lines along the chord are sliced between them", "[sampling]") {
  // A CFD-like surface grid: chordwise lines 0.4 mm apart in height, points 0.1 mm apart
  // along them (anisotropic: a slab of the nearest neighbour's spacing falls between lines).
  for (const BladeDesign& blade : {turbine_blade(), compressor_blade()}) {
    const Cloud grid = chordwise_grid(blade, 24, 36, 0.4, 0.1);
    const Sampling s = sampling_of(grid.points, {0, 0, 1});
    INFO(s.describe());
    REQUIRE(s.kind == SamplingKind::lines);
    CHECK(s.slab == Approx(0.4).epsilon(0.01));
    CHECK(s.rows.size() == 31);
    // Planes between lines and on one: each section interpolated between the lines beside it.
    const std::vector<double> zs = {28.2, 30.0, 33.3};
    const SliceResult r = slice(grid, planes_at({0, 0, 1}, zs));
    CHECK(r.slab == s.slab);
    for (std::size_t k = 0; k < zs.size(); ++k) {
      INFO("z " << zs[k]);
      REQUIRE(r.sections[k].error.empty());
      CHECK(worst_distance(r.sections[k], section_truth(blade.at(zs[k]), 8000)) < 0.003);
    }
    for (const CamberScore& e : camber_scores(r, zs, blade)) check_targets(e);
    // Beyond the lines there is nothing to interpolate.
    const SliceResult beyond = slice(grid, planes_at({0, 0, 1}, {40.0}));
    CHECK(beyond.sections[0].error.find("beyond the lines") != std::string::npos);
  }
}

TEST_CASE("sampling: grid lines closer in height than along them are lines, sliced between them",
          "[sampling]") {
  // A CFD grid of 100 chordwise lines 0.6 mm apart, 120 points a line (0.78 mm apart
  // mid-side): before, a dense scan for its spacings, cut by a slab with the band, whose
  // thin tip sections did not close and whose thickness came out 15 um off.
  for (const auto lines : {GridOptions::Lines::chordwise, GridOptions::Lines::spanwise}) {
    for (const BladeDesign& blade : {compressor_blade(), turbine_blade()}) {
      GridOptions g;
      g.lines = lines, g.heights = 100, g.around = 120;
      const Cloud grid = generate_grid(blade, g);
      const Sampling s = sampling_of(grid.points, {0, 0, 1});
      INFO(s.describe());
      REQUIRE(s.kind == SamplingKind::lines);
      CHECK(s.rows.size() == 100);
      CHECK(s.slab == Approx(blade.span / 99).epsilon(0.01));
      const std::vector<double> zs = {6.1, 30.0, 48.3, 54.0, 59.5};
      const SliceResult r = slice(grid, planes_at({0, 0, 1}, zs));
      for (std::size_t k = 0; k < zs.size(); ++k) {
        INFO("z " << zs[k]);
        REQUIRE(r.sections[k].error.empty());
        CHECK(worst_distance(r.sections[k], section_truth(blade.at(zs[k]), 8000)) < 0.003);
      }
    }
  }
}

TEST_CASE("sampling: a plane tilted to a grid's lines is cut where it crosses them", "[sampling]") {
  // The same grids cut by planes 1-4 degrees off their levels: the levels come apart along
  // their own normal, and each section point is where a step from a line to the next one's
  // curve crosses the plane. Before, the levels overlapped along the plane's normal: a
  // slab with the band, whose sections did not close (3 of 4) or came 3 mm short.
  // (Chordwise lines only: a spanwise grid is the same points in another order.)
  for (const BladeDesign& blade : {compressor_blade(), turbine_blade()}) {
    GridOptions g;
    g.heights = 100, g.around = 120;
    const Cloud grid = generate_grid(blade, g);
    {
      for (const Vec3& normal : {Vec3(0.02, 0, 1), Vec3(0.05, 0.05, 1)}) {
        const Sampling s = sampling_of(grid.points, normal);
        INFO(s.describe());
        REQUIRE(s.kind == SamplingKind::lines);
        CHECK(s.rows.size() == 100);
        const std::vector<double> zs = {10.0, 30.0, 50.0};
        const SliceResult r = slice(grid, planes_at(normal, zs));
        for (std::size_t k = 0; k < zs.size(); ++k) {
          INFO("plane " << zs[k]);
          REQUIRE(r.sections[k].error.empty());
          // Each point on the blade's surface: on the true section at its own height (within
          // 0.5-2 um; up to 5 um at the compressor's 0.2 mm edges, which move between lines:
          // a step between lines is second order in their spacing there).
          double worst = 0;
          const auto& points = r.sections[k].morphology.loops.at(0).points;
          for (std::size_t i = 0; i < points.size(); i += 3) {  // every third: a truth each
            const Vec3 w = r.sections[k].frame.to_world(points[i]);
            worst = std::max(worst, locate(section_truth(blade.at(w.z()), 2000), w.head<2>()).distance);
          }
          CHECK(worst < 0.006);
        }
        // A plane that leaves the lines (near the tip) would give part of its section: refused.
        const SliceResult tip = slice(grid, planes_at(normal, {59.8}));
        INFO("normal " << normal.transpose() << ": " << tip.sections[0].error);
        CHECK(tip.sections[0].error.find("leaves the lines of points") != std::string::npos);
      }
    }
  }
}

TEST_CASE("sampling: lines along the span, sparse in height, are lines too", "[sampling]") {
  // 600 spanwise lines (0.15 mm apart along a compressor profile), a point every 0.5 mm up.
  const BladeDesign blade = compressor_blade();
  const Cloud grid = spanwise_grid(blade, 26, 34, 0.5, 600);
  const Sampling s = sampling_of(grid.points, {0, 0, 1});
  INFO(s.describe());
  REQUIRE(s.kind == SamplingKind::lines);
  CHECK(s.slab == Approx(0.5).epsilon(0.01));
  const std::vector<double> zs = {29.75, 31.2};
  const SliceResult r = slice(grid, planes_at({0, 0, 1}, zs));
  for (std::size_t k = 0; k < zs.size(); ++k) {
    REQUIRE(r.sections[k].error.empty());
    CHECK(worst_distance(r.sections[k], section_truth(blade.at(zs[k]), 8000)) < 0.003);
  }
  for (const CamberScore& e : camber_scores(r, zs, blade)) check_targets(e);
}

TEST_CASE("sampling: sparse rows are sections as they lie; a plane between rows names them", "[sampling]") {
  // A CMM-like compressor rotor: 4 rows 15 mm apart, a point every 1 mm along each.
  const BladeDesign blade = compressor_blade();
  const std::vector<double> zs = {10, 25, 40, 55};
  const Cloud rows = rows_at(blade, zs, 1.0);
  const Sampling s = sampling_of(rows.points, {0, 0, 1});
  INFO(s.describe());
  REQUIRE(s.kind == SamplingKind::rows);
  REQUIRE(s.rows.size() == 4);
  CHECK(s.row_gap == Approx(15));
  for (const PointRow& row : s.rows) {
    CHECK(row.planar);
    CHECK(row.spread < 1e-9);
    CHECK(std::abs(row.normal.z()) == Approx(1));
  }
  // Each row a section in its own plane (u = x, v = y: the rows are level), its points
  // exactly on the true profile.
  const SliceResult all = slice_rows(rows, {0, 0, 1});
  REQUIRE(all.sections.size() == 4);
  for (std::size_t k = 0; k < zs.size(); ++k) {
    const SectionSlice& sec = all.sections[k];
    REQUIRE(sec.error.empty());
    CHECK(sec.row == int(k));
    CHECK(sec.frame.origin.z() == Approx(zs[k]));
    CHECK(sec.morphology.loops.size() == 1);
    CHECK(sec.morphology.loops[0].points.size() == s.rows[k].points.size());
    CHECK(worst_distance(sec, section_truth(blade.at(zs[k]), 8000)) < 1e-6);
  }
  // Measured, not held to the dense targets: 1 mm apart, the 0.2-0.35 mm edges hold a point
  // or two (docs/SAMPLING.md).
  camber_scores(all, zs, blade);
  // Planes through a row take it; a plane between rows says which rows lie beside it.
  const SliceResult r = slice(rows, planes_at({0, 0, 1}, {25.0, 30.0, 70.0}));
  REQUIRE(r.sections[0].error.empty());
  CHECK(r.sections[0].row == 1);
  CHECK(r.sections[0].slab_points == s.rows[1].points.size());
  CHECK(r.sections[1].error.find("falls between the rows at heights 25 and 40") != std::string::npos);
  CHECK(r.sections[1].error.find("--rows") != std::string::npos);
  CHECK(r.sections[2].error.find("above the highest row, at height 55") != std::string::npos);
}

TEST_CASE("sampling: with no planes, rows are the sections; other points say what to give", "[sampling]") {
  // slice_by_rows: what `slice` and ls.slice do given no planes.
  const BladeDesign blade = turbine_blade();
  std::vector<int> told;  // the sampling (-1), then each row as it is done
  const SliceResult rows = slice_by_rows(
      rows_at(blade, {10, 25, 40}, 1.0), {0, 0, 1}, {}, false,
      [&](const SectionSlice& s) { told.push_back(s.id); }, [&](const Sampling&) { told.push_back(-1); });
  CHECK(told == std::vector<int>{-1, 0, 1, 2});
  REQUIRE(rows.sections.size() == 3);
  CHECK(rows.sections[1].frame.origin.z() == Approx(25));
  const Cloud grid = chordwise_grid(blade, 29, 31, 0.4, 0.1);  // 6 lines 0.4 mm apart
  CHECK_THROWS_WITH(
      slice_by_rows(grid, {0, 0, 1}, {}, false),
      Catch::Contains("not sparse rows") && Catch::Contains("--rows to take each of its 6 lines"));
  CHECK(slice_by_rows(grid, {0, 0, 1}, {}, true).sections.size() == 6);
  ScanOptions so = inspection_scan();
  so.seed = 3;
  const Cloud dense = scan_bands(blade, {30.0}, so, 1.0);
  CHECK_THROWS_WITH(slice_by_rows(dense, {0, 0, 1}, {}, false), Catch::Contains("but a dense scan"));
  CHECK_THROWS_WITH(
      slice_by_rows(dense, {0, 0, 1}, {}, true),
      Catch::StartsWith("--rows: the points hold no rows or lines") && Catch::Contains("dense scan"));
  Cloud few;
  few.points = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}, {2, 2, 0}};
  CHECK_THROWS_WITH(slice_by_rows(few, {0, 0, 1}, {}, false), Catch::Contains("5 points make no row"));
}

TEST_CASE("sampling: a tilted row is taken in its best plane; a row curved around an axis is refused",
          "[sampling]") {
  const BladeDesign blade = turbine_blade();
  const std::vector<Vec3> flat = row_at(blade, 30, 0.5);
  const double tilt = 0.08;  // rad about x
  Cloud tilted, curved;
  for (double z : {10.0, 30.0, 50.0})
    for (const Vec3& p : flat)
      tilted.points.emplace_back(p.x(), p.y() * std::cos(tilt), z + p.y() * std::sin(tilt));
  // Rows on cylinders about the y axis (the chord, along x, wrapped round it), radii 100 and
  // 160 mm (a constant-radius CMM pass), and one warped (z + 0.03 x y: 4.5 mm at the corners).
  for (double r : {100.0, 160.0})
    for (const Vec3& p : flat)
      curved.points.emplace_back(r * std::sin(p.x() / r), p.y(), r * std::cos(p.x() / r));
  for (const Vec3& p : flat) curved.points.emplace_back(p.x(), p.y(), 200 + 0.03 * p.x() * p.y());
  const SliceResult t = slice_rows(tilted, {0, 0, 1});
  REQUIRE(t.sections.size() == 3);
  for (const SectionSlice& s : t.sections) {
    REQUIRE(s.error.empty());
    CHECK(s.row_spread < 1e-9);
    CHECK(std::acos(std::min(1.0, s.frame.n.z())) == Approx(tilt).margin(1e-9));
    // Taken as it lies: every point goes back to its place in 3D.
    for (const auto& p : s.morphology.loops[0].points) {
      const Vec3 q = s.frame.to_world(p);
      double nearest = INFINITY;
      for (const Vec3& o : tilted.points) nearest = std::min(nearest, (o - q).norm());
      CHECK(nearest < 1e-9);
    }
  }
  const SliceResult c = slice_rows(curved, {0, 0, 1});
  REQUIRE(c.sections.size() == 3);
  for (int k : {0, 1}) {
    INFO("row " << k << ": " << c.sections[std::size_t(k)].error);
    CHECK(c.sections[std::size_t(k)].error.empty());
    CHECK(c.sections[std::size_t(k)].row_spread > 0.3);
    CHECK(c.sections[std::size_t(k)].row_spread < 0.05 * 42);
  }
  INFO(c.sections[2].error << " spread " << c.sections[2].row_spread);
  CHECK(c.sections[2].error.find("is not planar") != std::string::npos);
}

TEST_CASE("sampling: a 2D profile, ordered or shuffled, is one section in its own plane", "[sampling]") {
  const BladeDesign blade = turbine_blade();
  const SectionTruth truth = section_truth(blade.at(20), 8000);
  std::string text = "# a turbine section\nx y\n";
  for (std::size_t k = 0; k < truth.profile.size(); k += 20)
    text += std::to_string(truth.profile[k].x()) + " " + std::to_string(truth.profile[k].y()) + "\n";
  const auto cloud = profile_cloud(text, "profile.xy");
  REQUIRE(cloud);
  REQUIRE(cloud->points.size() == 400);
  CHECK(!profile_cloud("1 2 3\n4 5 6\n", "cloud.xyz"));
  CHECK(!profile_cloud("241 21\n1 2 3\n4 5 6\n", "blade3d.dat"));  // a count header over rows of three
  CHECK(profile_cloud("NACA 4412\n1 0\n0.5 0.05\n0 0\n0.5 -0.02\n", "naca.dat")->points.size() == 4);
  CHECK(!profile_cloud("ply\nformat ascii 1.0\n", "cloud.ply"));
  for (const bool shuffled : {false, true}) {
    Cloud c = *cloud;
    if (shuffled) std::shuffle(c.points.begin(), c.points.end(), std::mt19937(7));
    const SliceResult r = slice_rows(c, {0, 0, 1});
    REQUIRE(r.sections.size() == 1);
    CHECK(r.sampling.kind == SamplingKind::rows);
    const SectionSlice& s = r.sections[0];
    REQUIRE(s.error.empty());
    CHECK((s.frame.u - Vec3::UnitX()).norm() < 1e-12);
    CHECK(s.frame.origin.norm() < 1e-12);
    CHECK(s.morphology.loops[0].points.size() == 400);
    CHECK(worst_distance(s, truth) < 2e-6);  // std::to_string's 6 decimals
    for (const CamberScore& e : camber_scores(r, {20}, blade)) check_targets(e);
  }
}

TEST_CASE("sampling: points along a line are no profile", "[sampling]") {
  // A row that is a straight line (or a slightly bent one) encloses nothing: no section,
  // said so, rather than a loop out and back of no area.
  for (const double bend : {0.0, 1e-4, 0.01}) {
    Cloud line;
    for (int i = 0; i < 500; ++i) line.points.emplace_back(0.1 * i, bend * (0.1 * i) * (0.1 * i), 0.0);
    const SliceResult r = slice_rows(line, {0, 0, 1});
    REQUIRE(r.sections.size() == 1);
    CHECK(r.sections[0].error.find("lie along one curve, not round a profile") != std::string::npos);
    CHECK(r.sections[0].morphology.loops.empty());
  }
}

TEST_CASE("sampling: exact copies of points do not shrink the spacing", "[sampling]") {
  const BladeDesign blade = compressor_blade();
  ScanOptions so = inspection_scan();
  so.seed = 5;
  const Cloud once = scan_bands(blade, {30.0}, so, 1.0);
  for (int copies : {2, 3}) {
    Cloud many;
    for (const Vec3& p : once.points)
      for (int k = 0; k < copies; ++k) many.points.push_back(p);
    const Sampling s = sampling_of(many.points, {0, 0, 1});
    CHECK(s.kind == SamplingKind::dense);
    CHECK(s.duplicates == s.measured);
    CHECK(s.spacing == Approx(sampling_of(once.points, {0, 0, 1}).spacing).epsilon(0.15));
    // The slab follows the distinct points; a section holds each point once.
    const SliceResult r = slice(many, planes_at({0, 0, 1}, {30.0}));
    CHECK(r.slab == Approx(mean_spacing(once.points)).epsilon(0.3));
    SliceOptions fixed;
    fixed.slab = 0.08;
    const SliceResult a = slice(once, planes_at({0, 0, 1}, {30.0}), fixed);
    const SliceResult b = slice(many, planes_at({0, 0, 1}, {30.0}), fixed);
    REQUIRE(b.sections[0].error.empty());
    CHECK(b.sections[0].slab_points == a.sections[0].slab_points);
    CHECK(b.sections[0].morphology.loops[0].points == a.sections[0].morphology.loops[0].points);
  }
  // A profile given with every point twice (as a stream made elsewhere may hold it): its
  // spacing is not zero, and its holes are those of the profile once.
  const auto loop = slice(once, planes_at({0, 0, 1}, {30.0})).sections[0].morphology.loops.at(0).points;
  std::vector<Eigen::Vector2d> twice;
  for (const auto& p : loop) twice.insert(twice.end(), {p, p});
  const FitSplineResult f1 = fit_spline(loop, loop), f2 = fit_spline(twice, twice);
  CHECK(f2.spacing == Approx(f1.spacing).epsilon(0.05));
  CHECK(f2.gaps.size() == f1.gaps.size());
}

TEST_CASE("sampling: a section that does not close names the option that helps", "[sampling]") {
  // A wavy ring cut by a slab thinner than its waves: two short arcs, which close nothing.
  Cloud ring;
  for (int i = 0; i < 2000; ++i) {
    const double a = 0.00314 * i;
    ring.points.emplace_back(10 * std::cos(a), 5 * std::sin(a), 0.5 + 0.01 * std::sin(a));
  }
  SliceOptions o;
  o.slab = 0.004;
  const SliceResult r = slice(ring, planes_at({0, 0, 1}, {0.5}), o);
  const std::string& e = r.sections[0].error;
  INFO(e);
  CHECK(e.find("morphology:") == 0);
  CHECK(e.find("a wider slab holds more points (--slab, now 0.004 mm)") != std::string::npos);
  CHECK(e.find("max_dilation") == std::string::npos);
}

TEST_CASE("sampling: a loop that leaves much of the section's points far off is refused", "[sampling]") {
  // A thin closed piece (an ellipse 8 x 0.8 mm) and, beside it, an open sheet cut across (a
  // single layer of sparse points along 20 mm, as a plane cuts a radial rotor's blade where
  // its surface runs nearly along the plane): before, the loop closed round the piece alone
  // and its params (chord 8 of a 30 mm cut) came out with no issue.
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> turn(0, 2 * M_PI), height(0, 10), along(-25, -5);
  Cloud piece;
  for (int k = 0; k < 20000; ++k) {
    const double t = turn(rng);
    piece.points.emplace_back(4 * std::cos(t), 0.4 * std::sin(t), height(rng));
  }
  Cloud cut = piece;
  for (int k = 0; k < 4000; ++k) {
    const double x = along(rng);
    cut.points.emplace_back(x, 0.05 * x + 0.3, height(rng));
  }
  const SliceResult r = slice(cut, planes_at({0, 0, 1}, {5.0}));
  INFO(r.sections[0].error);
  CHECK(r.sections[0].error.find("the loop holds only part of the section") != std::string::npos);
  // The piece alone, and with a few far outliers, is a profile.
  for (int outliers : {0, 5}) {
    Cloud c = piece;
    for (int k = 0; k < outliers; ++k) c.points.emplace_back(-10 - k, 3, 5.0);
    const SliceResult p = slice(c, planes_at({0, 0, 1}, {5.0}));
    INFO(p.sections[0].error);
    CHECK(p.sections[0].error.empty());
  }
}

TEST_CASE("sampling: mean_spacing from its searches is mean_spacing, bit for bit", "[sampling]") {
  // Sizes where sampling_of measures every point, every other one at steps that miss some
  // of mean_spacing's (10 460 points), every tenth, and over mean_spacing's subset (its own
  // tree then); exact copies of points; a grid, whose points lie at equal distances.
  const BladeDesign blade = turbine_blade();
  std::vector<std::vector<Vec3>> clouds;
  for (const double spacing : {2.0, 0.776, 0.56, 0.35}) {
    ScanOptions o;
    o.spacing = spacing;
    o.noise = 0.005;
    o.seed = 3;
    clouds.push_back(generate_scan(blade, o).cloud.points);
  }
  std::vector<Vec3> copies = clouds[1];
  for (std::size_t i = 0; i < copies.size(); i += 7) copies.push_back(copies[i]);
  clouds.push_back(copies);
  std::vector<Vec3> grid;
  for (int i = 0; i < 120; ++i)
    for (int j = 0; j < 90; ++j) grid.emplace_back(0.08 * i, 0.08 * j, 0.01 * ((i + j) % 3));
  clouds.push_back(grid);
  clouds.push_back({Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 0, 0)});
  for (const auto& points : clouds) {
    detail::SpacingSearch search;
    const Sampling s = detail::sampling_of(points, Vec3::UnitZ(), {}, search);
    CHECK(s.describe() == sampling_of(points, Vec3::UnitZ()).describe());
    CHECK(bool(search.tree) == (s.kind == SamplingKind::dense && points.size() <= 50'000));
    const double reused = detail::mean_spacing(points, search), own = mean_spacing(points);
    INFO(points.size() << " points, " << s.describe());
    CHECK(std::memcmp(&reused, &own, sizeof own) == 0);
  }
}

TEST_CASE("sampling: a point's k nearest are the first k of its K nearest, ties included", "[sampling]") {
  // What lets sampling_of search 17 neighbours, not 24, for a point without a copy, and
  // mean_spacing 2, not 3: lattices put many neighbours at equal distances, where an order
  // could differ.
  std::vector<std::vector<Vec3>> clouds(3);
  for (int i = 0; i < 60; ++i)
    for (int j = 0; j < 50; ++j) {
      clouds[0].emplace_back(0.08 * i, 0.08 * j, 0);
      clouds[1].emplace_back(0.3 * (i + 0.5 * (j % 2)), 0.3 * j * std::sqrt(0.75), 0.21 * (j % 3));
    }
  for (int i = 0; i < 15; ++i)
    for (int j = 0; j < 15; ++j)
      for (int k = 0; k < 15; ++k) clouds[2].emplace_back(0.1 * i, 0.1 * j, 0.1 * k);
  ScanOptions o;
  o.spacing = 1;
  o.noise = 0.005;
  clouds.push_back(generate_scan(turbine_blade(), o).cloud.points);
  for (const auto& points : clouds) {
    const detail::NearestPoints<3> tree(points);
    for (const auto [k, more] : {std::pair{17, 24}, std::pair{2, 3}}) {
      int differ = 0;
      for (const Vec3& p : points) {
        int ik[24], im[24];
        double dk[24], dm[24];
        tree.k_nearest(p, k, ik, dk);
        tree.k_nearest(p, more, im, dm);
        differ += !std::equal(ik, ik + k, im) || !std::equal(dk, dk + k, dm);
      }
      CHECK(differ == 0);
    }
  }
}

TEST_CASE("sampling: a quick look settles a plain dense scan alone, and nothing near a line", "[sampling]") {
  // Dense scans of both blades at three densities are settled measuring a fifth of the
  // first look's points; a grid on levels and a scan with exact copies go on to the first
  // look (or the whole one) and are what it says.
  for (const BladeDesign& blade : {turbine_blade(), compressor_blade()})
    for (const double spacing : {0.78, 0.35, 0.2}) {
      ScanOptions o;
      o.spacing = spacing;
      o.noise = 0.005;
      o.seed = 4;
      const std::vector<Vec3> points = generate_scan(blade, o).cloud.points;
      const Sampling s = sampling_of(points, Vec3::UnitZ());
      INFO(points.size() << " points, " << s.describe());
      CHECK(s.kind == SamplingKind::dense);
      REQUIRE(points.size() >= 5'000);
      CHECK(s.measured <= 2'000);  // a fifth of the first look's 5 000 to 10 000
    }
  const Cloud grid = chordwise_grid(turbine_blade(), 24, 36, 0.4, 0.1);
  const Sampling lines = sampling_of(grid.points, Vec3::UnitZ());
  CHECK(lines.kind == SamplingKind::lines);
  CHECK(lines.measured == grid.points.size());
  ScanOptions o;
  o.spacing = 0.35;
  o.seed = 4;
  std::vector<Vec3> copies = generate_scan(compressor_blade(), o).cloud.points;
  for (std::size_t i = 0, n = copies.size(); i < n; i += 50) copies.push_back(copies[i]);
  const Sampling copied = sampling_of(copies, Vec3::UnitZ());
  CHECK(copied.kind == SamplingKind::dense);
  CHECK(copied.duplicates > 0);
  CHECK(copied.measured >= 5'000);
}

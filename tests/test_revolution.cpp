// SPDX-License-Identifier: GPL-3.0-or-later
// Tests of surfaces of revolution: the exact maps both ways, and rotor blades designed on
// cylinders and cones cut on their own surfaces against the generator's exact sections.
#include "pipe_stages.h"

#include "args/slice_args.h"

#include "section/error.h"
#include "section/extras/generate_rotor.h"
#include "section/extras/score.h"
#include "section/pipe/schema.h"
#include "section/pipe/slice_stream.h"
#include "section/revolution.h"

#include <catch2/catch.hpp>

#include <cmath>
#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

using namespace section;

namespace {

// Random points near a surface, and their round trip through (u, v).
double worst_round_trip(const Revolution& s, double extent) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> uv(-extent, extent);
  double worst = 0;
  for (int k = 0; k < 2000; ++k) {
    const Eigen::Vector2d p(uv(rng), uv(rng));
    const Eigen::Vector3d x = surface_point(s, p);
    const SurfacePlace q = surface_place(s, x);
    REQUIRE(q.valid);
    worst = std::max({worst, (q.uv - p).norm(), std::abs(q.w)});
    // 3D -> (u, v) -> 3D for the point on the surface.
    worst = std::max(worst, (surface_point(s, q.uv) - x).norm());
  }
  return worst;
}

std::vector<Revolution> surfaces_of_every_kind() {
  const Eigen::Vector3d o(1, -2, 3), d(0.2, 1, 0.1);
  std::vector<Revolution> out;
  Revolution c = cylinder_surface(o, d, 150);
  out.push_back(c);
  for (Unrolling u : {Unrolling::conformal, Unrolling::arclength}) {
    Revolution k = cone_surface(o, d, {-10, 120}, {40, 160});
    k.unrolling = u;
    k.r_ref = 140;
    k.shift = {3, -4};
    out.push_back(k);
    Revolution s = streamline_surface(o, d, {{-50, 100}, {-10, 104}, {20, 115}, {45, 140}, {70, 170}});
    s.unrolling = u;
    s.r_ref = 120;
    out.push_back(s);
  }
  return out;
}

// Sections at these heights of a rotor, sliced on their own surfaces and measured.
Stream measured_rotor(const RotorDesign& rotor, const std::vector<double>& zs, const Cloud& cloud) {
  std::vector<Revolution> surfaces;
  for (double z : zs) surfaces.push_back(rotor.surface(z));
  SliceOptions options;
  options.slab = 0.08;
  return test::after_slice(to_stream(slice(cloud, surfaces, options), "slice"));
}

// Every section within the issue-5 targets (docs/ACCURACY.md).
void require_targets(const RotorDesign& rotor, const std::vector<double>& zs, const Stream& stream) {
  for (std::size_t k = 0; k < zs.size(); ++k) {
    const SectionTruth truth = section_truth(rotor.blade.at(zs[k]), 8000);
    const CamberScore e = score_camber(stream, int(k), truth);
    INFO("z " << zs[k] << ": camber rms " << e.camber_rms * 1e3 << " um, max " << e.camber_max * 1e3
              << " um, chord " << e.chord * 1e3 << " um, max thickness " << e.max_thickness * 1e3
              << " um, LE radius " << e.le_radius * 100 << " %, TE radius " << e.te_radius * 100
              << " %, inlet " << e.inlet_angle << ", outlet " << e.outlet_angle << " deg");
    const std::pair<double, double> error_bound[] = {
        {e.camber_rms, 0.003}, {e.camber_max, 0.015}, {e.chord, 0.010},     {e.max_thickness, 0.005},
        {e.le_radius, 0.03},   {e.te_radius, 0.10},   {e.inlet_angle, 0.5}, {e.outlet_angle, 0.5}};
    for (const auto& [error, bound] : error_bound) CHECK(std::abs(error) <= bound);
  }
}

}  // namespace

TEST_CASE("revolution: points on every kind of surface map to (u, v) and back exactly", "[revolution]") {
  for (const Revolution& s : surfaces_of_every_kind()) {
    INFO(surface_kind_name(s.kind) << " unrolled " << unrolling_name(s.unrolling));
    CHECK(worst_round_trip(s, 30) < 1e-9);
  }
}

TEST_CASE("revolution: a cylinder's unrolling is (r theta, axial) and w the radius' excess", "[revolution]") {
  Revolution c = cylinder_surface({0, 0, 0}, {0, 0, 1}, 100);
  c.reference = {1, 0, 0};
  const SurfacePlace q = surface_place(c, {0, 103, 7});  // theta = 90 degrees, r = 103
  CHECK_THAT(q.uv.x(), Catch::WithinAbs(100 * M_PI / 2, 1e-12));
  CHECK_THAT(q.uv.y(), Catch::WithinAbs(7, 1e-12));
  CHECK_THAT(q.w, Catch::WithinAbs(3, 1e-12));
}

TEST_CASE("revolution: the radius range of a part leaves its stray points out", "[revolution]") {
  // Cylinders spread over a part's radii (slice --axis --count): a point a metre off a
  // rotor ring of radii 200-230 (a reflection) took the range to 1 000; left out, it is the
  // ring's. A second ring holding more than 1 in 1 000 of the points stays.
  std::vector<Eigen::Vector3d> ring;
  for (int i = 0; i < 5000; ++i) {
    const double t = 0.001 * i, r = 200 + 30 * (i % 100) / 99.0;
    ring.emplace_back(10 * std::sin(7.0 * i), r * std::cos(t), r * std::sin(t));
  }
  const Eigen::Vector2d clean = section::radius_range(ring, {0, 0, 0}, {1, 0, 0});
  CHECK(clean.x() == Approx(200));
  CHECK(clean.y() == Approx(230));
  std::vector<Eigen::Vector3d> stray = ring;
  stray.emplace_back(0, 1000, 0);
  CHECK(section::radius_range(stray, {0, 0, 0}, {1, 0, 0}) == clean);
  for (int i = 0; i < 20; ++i) stray.emplace_back(0, 0, 1000 + i);
  CHECK(section::radius_range(stray, {0, 0, 0}, {1, 0, 0}).y() == Approx(1019));
}

TEST_CASE("revolution: the conformal unrolling of a cone keeps angles, m' = ln(r / r0) / sin(phi)",
          "[revolution]") {
  Revolution k = cone_surface({0, 0, 0}, {1, 0, 0}, {0, 100}, {100, 100 + 100 * std::tan(0.3)});
  k.r_ref = 100;
  k.reference = {0, 0, 1};
  const double m = 50;
  const double r = 100 + m * std::sin(0.3);
  const Eigen::Vector3d p(m * std::cos(0.3), 0, r);  // theta = 0
  CHECK_THAT(surface_place(k, p).uv.x(), Catch::WithinAbs(100 * std::log(r / 100) / std::sin(0.3), 1e-9));
  // A small step along m and the same unrolled step along theta are equally long in 3D.
  const Eigen::Vector2d at(20, 5);
  const double h = 1e-4;
  const double du = (surface_point(k, at + Eigen::Vector2d(h, 0)) - surface_point(k, at)).norm();
  const double dv = (surface_point(k, at + Eigen::Vector2d(0, h)) - surface_point(k, at)).norm();
  CHECK_THAT(du / dv, Catch::WithinAbs(1, 1e-6));
}

TEST_CASE("revolution: bad surfaces are refused with what is wrong", "[revolution]") {
  CHECK_THROWS_AS(cylinder_surface({0, 0, 0}, {0, 0, 0}, 10), Error);
  CHECK_THROWS_AS(cylinder_surface({0, 0, 0}, {0, 0, 1}, -1), Error);
  Revolution s = streamline_surface({0, 0, 0}, {0, 0, 1}, {{0, 10}, {0, 10}});
  s.r_ref = 10;
  CHECK_THROWS_AS(check_surface(s), Error);
  s.meridian = {{0, 0}, {10, 10}};  // the conformal map needs r > 0
  CHECK_THROWS_AS(check_surface(s), Error);
  s.unrolling = Unrolling::arclength;
  CHECK_NOTHROW(check_surface(s));
}

TEST_CASE("revolution: a rotor on cylinders cut on its cylinders meets the issue-5 targets",
          "[revolution][generated]") {
  const RotorDesign rotor = cylinder_rotor();
  ScanOptions so = inspection_scan();
  so.seed = 5;  // seed 3 at z = 30 misses the LE by 0.7 mm cut by a plane as well (a hole there)
  const std::vector<double> zs = {12, 30, 48};
  const Cloud cloud = rotor_cloud(rotor, scan_bands(rotor.blade, zs, so));
  require_targets(rotor, zs, measured_rotor(rotor, zs, cloud));
}

TEST_CASE("revolution: a rotor on cones cut on its cones meets the issue-5 targets",
          "[revolution][generated]") {
  for (Unrolling u : {Unrolling::conformal, Unrolling::arclength}) {
    INFO(unrolling_name(u));
    const RotorDesign rotor = cone_rotor(u);
    ScanOptions so = inspection_scan();
    so.seed = 4;
    const std::vector<double> zs = {15, 40};
    const Cloud cloud = rotor_cloud(rotor, scan_bands(rotor.blade, zs, so));
    require_targets(rotor, zs, measured_rotor(rotor, zs, cloud));
  }
}

TEST_CASE("revolution: camber points map back to 3D on the design surface and the true camber line",
          "[revolution][generated]") {
  // The default reference direction (theta = 0 from the points) and r_ref chosen from the
  // points: the stream's frames carry them, so the 3D camber is the design's whatever the
  // unrolled plane.
  const RotorDesign rotor = cone_rotor(Unrolling::conformal);
  const std::vector<double> zs = {25};
  ScanOptions so = inspection_scan();
  so.seed = 4;
  const Cloud cloud = rotor_cloud(rotor, scan_bands(rotor.blade, zs, so));
  Revolution cut = rotor.surface(zs[0]);
  cut.reference.setZero();
  cut.r_ref = 0;
  SliceOptions options;
  options.slab = 0.08;
  const Stream stream = test::after_slice(to_stream(slice(cloud, {cut}, options), "slice"));
  const auto frame = frames(stream).at(0);
  REQUIRE(frame.surface);
  CHECK(frame.surface->r_ref != rotor.surface(zs[0]).r_ref);
  const SectionTruth truth = section_truth(rotor.blade.at(zs[0]), 8000);
  const Table& camber = stream.get("camber", "camber");
  const std::size_t cu = camber.column("u"), cv = camber.column("v"), cx = camber.column("x");
  double worst_surface = 0, worst_camber = 0, worst_trip = 0;
  for (std::size_t r = 0; r < camber.rows(); ++r) {
    const Eigen::Vector3d x(camber.at(r, cx), camber.at(r, cx + 1), camber.at(r, cx + 2));
    const Eigen::Vector2d uv(camber.at(r, cu), camber.at(r, cv));
    const SurfacePlace design = surface_place(rotor.surface(zs[0]), x);
    worst_surface = std::max(worst_surface, std::abs(design.w));
    worst_camber = std::max(worst_camber, camber_distance(truth, design.uv));
    worst_trip = std::max(worst_trip, (frame.to_plane(frame.to_world(uv)) - uv).norm());
  }
  INFO("3D camber: " << worst_surface << " mm off the surface, " << worst_camber * 1e3
                     << " um off the true camber line; round trip " << worst_trip << " mm");
  CHECK(worst_surface < 1e-6);  // the stream's 7 significant digits of 3D coordinates
  CHECK(worst_camber < 0.015);
  CHECK(worst_trip < 1e-9);
}

TEST_CASE("revolution: sparse rows at constant radius are each cut on their cylinder",
          "[revolution][generated]") {
  const RotorDesign rotor = cylinder_rotor();
  RowsOptions ro;
  ro.rows = 4;
  ro.pitch = 12;
  ro.spacing = 0.05;
  const std::vector<double> zs = row_heights(rotor.blade, ro);
  const Cloud cloud = rotor_cloud(rotor, generate_rows(rotor.blade, ro));
  const std::vector<double> radii = row_radii(cloud.points, rotor.axis_point, rotor.axis);
  REQUIRE(radii.size() == zs.size());
  std::vector<Revolution> surfaces;
  for (std::size_t k = 0; k < zs.size(); ++k) {
    CHECK_THAT(radii[k], Catch::WithinAbs(rotor.hub_radius + zs[k], 1e-9));
    surfaces.push_back(cylinder_surface(rotor.axis_point, rotor.axis, radii[k]));
    surfaces.back().reference = rotor.reference;
  }
  const SliceResult result = slice(cloud, surfaces);  // slab 0: the rows as they lie
  CHECK(result.sampling.kind == SamplingKind::rows);
  for (const auto& s : result.sections) {
    CHECK(s.error.empty());
    CHECK(s.row >= 0);
  }
  const Stream stream = test::after_slice(to_stream(result, "slice"));
  for (std::size_t k = 0; k < zs.size(); ++k) {
    const CamberScore e = score_camber(stream, int(k), section_truth(rotor.blade.at(zs[k]), 8000));
    INFO("row " << k << ": camber max " << e.camber_max * 1e3 << " um, chord " << e.chord * 1e3 << " um");
    CHECK(e.camber_max < 0.015);
    CHECK(std::abs(e.chord) < 0.010);
  }
  // A cylinder between two rows takes neither, and says so.
  surfaces = {cylinder_surface(rotor.axis_point, rotor.axis, 0.5 * (radii[0] + radii[1]))};
  CHECK_FALSE(slice(cloud, surfaces).sections[0].error.empty());
}

TEST_CASE("revolution: a rotor's mesh is cut exactly on its surfaces", "[revolution][generated]") {
  for (const RotorDesign& rotor : {cylinder_rotor(), cone_rotor()}) {
    const Mesh mesh = rotor_mesh(rotor, 2000, 61);  // rings 1 mm apart
    const std::vector<double> zs = {20, 40.5};      // on a ring, and between two
    std::vector<Revolution> surfaces;
    for (double z : zs) surfaces.push_back(rotor.surface(z));
    const SliceResult result = slice(mesh, surfaces);
    for (std::size_t k = 0; k < zs.size(); ++k) {
      const auto& s = result.sections[k];
      REQUIRE(s.error.empty());
      REQUIRE(s.morphology.loops.size() == 1);
      const SectionTruth truth = section_truth(rotor.blade.at(zs[k]), 8000);
      double worst = 0;
      for (const auto& p : s.morphology.loops[0].points) {
        worst = std::max(worst, locate(truth, p).distance);
        CHECK(std::abs(surface_place(rotor.surface(zs[k]), s.frame.to_world(p)).w) < 1e-9);
      }
      INFO(surface_kind_name(rotor.surface(0).kind)
           << " z " << zs[k] << ": cut " << worst * 1e3 << " um from the design");
      CHECK(worst < (zs[k] == 20 ? 1e-6 : 0.002));
    }
  }
}

TEST_CASE("revolution: a rotor cut by a plane differs from its design section, and says how much",
          "[revolution][generated]") {
  // The plane z = hub + 30 through the blade against the cylinder r = hub + 30: the
  // planar section of a rotor is another curve (the reason for cutting on cylinders).
  const RotorDesign rotor = cylinder_rotor();
  const Mesh mesh = rotor_mesh(rotor, 1000, 61);
  const double z = 30;
  const SliceResult plane = slice(mesh, planes_at({0, 0, 1}, {rotor.hub_radius + z}));
  REQUIRE(plane.sections[0].error.empty());
  const SectionTruth truth = section_truth(rotor.blade.at(z), 8000);
  Revolution design = rotor.surface(z);
  double worst = 0;
  for (const auto& p : plane.sections[0].morphology.loops[0].points) {
    const SurfacePlace q = surface_place(design, plane.sections[0].frame.to_world(p));
    worst = std::max(worst, locate(truth, q.uv).distance + std::abs(q.w));
  }
  WARN("planar cut of the cylinder rotor at r = " << rotor.hub_radius + z << ": up to " << worst
                                                  << " mm from the design section");
  CHECK(worst > 0.05);
}

TEST_CASE("revolution: slice's --axis options make the surfaces, in mm", "[revolution][tools]") {
  const auto parsed = [](std::vector<std::string> words, tool::SliceArgs& args) {
    words.insert(words.begin(), "slice");
    std::vector<char*> argv;
    for (auto& w : words) argv.push_back(w.data());
    std::ostringstream out, err;
    return tool::parse(static_cast<int>(argv.size()), argv.data(), args, out, err);
  };
  tool::SliceArgs a;
  REQUIRE(parsed({"rotor.xyz", "--axis", "0,0,-0.2,1,0,0", "--radius", "0.21,0.23", "--cone",
                  "0,0.2,0.01,0.21", "--unroll", "arclength", "--units", "m"},
                 a) == -1);
  const tool::SliceArgs mm = a.in_mm(1000);
  const std::vector<Eigen::Vector3d> points = {{0, 0, 0.01}, {1, 0, 0.02}};
  const auto surfaces = mm.surfaces(points, 1000);
  REQUIRE(surfaces.size() == 3);
  CHECK(surfaces[0].kind == SurfaceKind::cylinder);
  CHECK_THAT(surfaces[1].meridian[0].y(), Catch::WithinAbs(230, 1e-9));
  CHECK(surfaces[2].kind == SurfaceKind::cone);
  CHECK_THAT(surfaces[2].meridian[1].x(), Catch::WithinAbs(10, 1e-9));
  CHECK_THAT(surfaces[0].axis_point.z(), Catch::WithinAbs(-200, 1e-9));
  for (const auto& s : surfaces) {
    CHECK(s.unrolling == Unrolling::arclength);
    CHECK((s.reference - Eigen::Vector3d::UnitZ()).norm() < 1e-12);  // the points' radial direction
  }
  tool::SliceArgs b;
  CHECK(parsed({"rotor.xyz", "--radius", "3"}, b) == 2);
  CHECK(parsed({"rotor.xyz", "--axis", "0,0,0,1,0,0", "--rows"}, b) == 2);
  CHECK(parsed({"rotor.xyz", "--axis", "0,0,0,1,0", "--radius", "3"}, b) == 2);
  CHECK(parsed({"rotor.xyz", "--axis", "0,0,0,1,0,0", "--unroll", "flat"}, b) == 2);
}

TEST_CASE("revolution: a long meridian's foot is the nearest point of every piece", "[revolution]") {
  // 300 pieces of a wavy meridian: the tree of boxes finds what looking at every piece finds.
  std::vector<Eigen::Vector2d> meridian;
  for (int k = 0; k <= 300; ++k) meridian.emplace_back(0.3 * k, 100 + 3 * std::sin(0.05 * k) + 0.01 * k);
  Revolution s = streamline_surface({0, 0, 0}, {0, 0, 1}, meridian);
  s.r_ref = 100;
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> a(-20, 110), r(90, 112), t(-1, 1);
  for (int i = 0; i < 3000; ++i) {
    const double ai = a(rng), ri = r(rng), ti = t(rng);
    const Eigen::Vector3d p =
        ri * std::cos(ti) * s.reference + ri * std::sin(ti) * s.axis.cross(s.reference) + ai * s.axis;
    double nearest = INFINITY;
    const std::size_t last = meridian.size() - 2;
    for (std::size_t k = 0; k <= last; ++k) {
      const Eigen::Vector2d q(ai, ri), d = meridian[k + 1] - meridian[k];
      double x = (q - meridian[k]).dot(d) / d.squaredNorm();
      if (k > 0) x = std::max(x, 0.0);
      if (k < last) x = std::min(x, 1.0);
      nearest = std::min(nearest, (q - meridian[k] - x * d).norm());
    }
    REQUIRE_THAT(std::abs(surface_place(s, p).w), Catch::WithinAbs(nearest, 1e-9));
  }
}

TEST_CASE("revolution: theta = 0 lies mid-blade, the branch cut between blades", "[revolution]") {
  const Eigen::Vector3d axis(0, 0, 1);
  const auto at = [](double degrees, double r) {
    const double t = degrees * M_PI / 180;
    return Eigen::Vector3d(r * std::cos(t), r * std::sin(t), 0.1 * degrees);
  };
  std::vector<Eigen::Vector3d> blade, rotor;
  for (double d = 165; d <= 195; d += 0.5) blade.push_back(at(d, 100 + 0.01 * d));  // across +-180
  REQUIRE(reference_of(blade, {0, 0, 0}, axis).isApprox(Eigen::Vector3d(-1, 0, 0), 1e-9));
  for (double centre : {20.0, 140.0, 260.0})
    for (double d = -10; d <= 10; d += 0.5) rotor.push_back(at(centre + d, 100));
  Revolution c = cylinder_surface({0, 0, 0}, axis, 100);
  c.reference = reference_of(rotor, {0, 0, 0}, axis);
  for (const auto& p : rotor)  // no blade runs across the cut: every point 25 degrees or more from it
    CHECK(std::abs(surface_place(c, p).uv.x()) / 100 < M_PI - 25 * M_PI / 180);
}

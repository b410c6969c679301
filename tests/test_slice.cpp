// SPDX-License-Identifier: GPL-3.0-or-later
#include "section/error.h"
#include "section/io/cloud_io.h"
#include "section/io/csv.h"
#include "section/slice.h"

#include "pipe_stages.h"
#include "section/checks.h"
#include "section/extras/generate.h"
#include "section/pipe/slice_stream.h"

#include <catch2/catch.hpp>

#include <cmath>

using namespace section;

TEST_CASE("slice: points exactly on a slab plane belong to the slab, the next double out does not",
          "[slice]") {
  // Plane z = 1 with slab 0.5: boundaries z = 0.75 and z = 1.25, both exact in binary.
  const auto planes = planes_at({0, 0, 1}, {1.0, 3.0});
  std::vector<Eigen::Vector3d> pts = {
      {0.3, 0.1, 0.75},                       // on the lower boundary: in
      {0.3, 0.1, 1.25},                       // on the upper boundary: in
      {0.3, 0.1, std::nextafter(0.75, 0.0)},  // just below: out
      {0.3, 0.1, std::nextafter(1.25, 2.0)},  // just above: out
      {-7.0, 1e6, 1.0},                       // far in the plane: in
      {0.0, 0.0, 2.75},                       // second plane's lower boundary: in there only
      {0.0, 0.0, 2.0},                        // between the slabs: nowhere
  };
  const auto slabs = slab_points(pts, planes, 0.5);
  REQUIRE(slabs.size() == 2);
  REQUIRE(slabs[0].size() == 3);
  CHECK(slabs[0][0] == Eigen::Vector2d(0.3, 0.1));
  CHECK(slabs[0][2] == Eigen::Vector2d(-7.0, 1e6));
  REQUIRE(slabs[1].size() == 1);
  // A tilted plane: points built on its boundary planes are decided exactly, and the
  // projection drops the normal component.
  const Eigen::Vector3d n = Eigen::Vector3d(1, 2, 2) / 3.0;
  const Frame f = make_frame(Eigen::Vector3d::Zero(), n);
  std::vector<Eigen::Vector3d> tilted;
  for (int i = 0; i < 50; ++i) {
    const Eigen::Vector3d in = f.origin + 0.01 * i * f.u - 0.02 * i * f.v + (0.1 - 0.004 * i) * f.n;
    tilted.push_back(in);
  }
  const auto ts = slab_points(tilted, {{Eigen::Vector3d::Zero(), n}}, 0.2);
  REQUIRE(ts[0].size() == 50);  // heights 0.1 .. -0.096: all within the closed slab
  CHECK(std::abs(ts[0][10].x() - 0.1) < 1e-12);
  CHECK(std::abs(ts[0][10].y() + 0.2) < 1e-12);
  REQUIRE_THROWS_AS(slab_points(pts, planes, -1.0), Error);
}

TEST_CASE("slice: a normal 1e308 or 1e-200 long is the direction it gives", "[slice]") {
  // Its squared length overflowed to infinity or underflowed to 0: 'the plane normal must be
  // finite and non-zero', or a frame without a normal.
  for (double length : {1e308, 1e-200, 1.0}) {
    INFO("length " << length);
    const auto planes = planes_at({0, 0, length}, {2.0});
    REQUIRE(planes.size() == 1);
    CHECK(planes[0].origin == Eigen::Vector3d(0, 0, 2));
    CHECK(planes[0].normal.normalized() == Eigen::Vector3d(0, 0, 1));
    const auto across = planes_across({{0, 0, 0}, {0, 0, 4}}, {0, 0, length}, 1);
    CHECK(across[0].origin == Eigen::Vector3d(0, 0, 2));
  }
  CHECK(usable_normal({1, 2, 2}) == Eigen::Vector3d(1, 2, 2));  // unchanged where the square is fine
  CHECK(usable_normal({3e200, 0, -4e200}) == Eigen::Vector3d(0.75, 0, -1));
}

TEST_CASE("slice: planes spread over a part leave its stray points out", "[slice]") {
  // A blade's band 20 mm high about z = 30 (a few thousand points), and three points far
  // off it (a reflection 900 mm up, dust 400 mm down, a fixture's corner beside it): the
  // planes spread over everything missed the blade but one. The strays are left out of
  // the extent, and it is said.
  ScanOptions band = inspection_scan();
  band.outlier_fraction = 0;
  band.z_min = 20;
  band.z_max = 40;
  band.seed = 3;
  const Scan scan = generate_scan(turbine_blade(), band);
  const PartExtent clean = extent_along(scan.cloud.points, {0, 0, 1});
  CHECK(clean.strays == 0);
  CHECK(clean.lo == clean.lowest);
  CHECK(clean.hi == clean.highest);
  std::vector<Eigen::Vector3d> strays = scan.cloud.points;
  for (const Eigen::Vector3d& p :
       {Eigen::Vector3d(0, 0, 900), Eigen::Vector3d(-3, 2, -400), Eigen::Vector3d(500, 20, 30)})
    strays.push_back(p);
  const PartExtent e = extent_along(strays, {0, 0, 1});
  CHECK(e.strays == 2);  // the fixture's corner lies within the blade's heights
  CHECK(e.lo == clean.lo);
  CHECK(e.hi == clean.hi);
  CHECK(e.lowest == -400);
  CHECK(e.highest == 900);
  const auto planes = planes_across(strays, {0, 0, 1}, 5),
             expected = planes_across(scan.cloud.points, {0, 0, 1}, 5);
  for (std::size_t k = 0; k < planes.size(); ++k) CHECK(planes[k].origin == expected[k].origin);
  // What is not a stray stays: rows 3 mm apart, each a twentieth of the points (a sparse
  // scan's), and a cloud of under 1 000 points (a profile's), whatever their gaps.
  std::vector<Eigen::Vector3d> rows;
  for (int r = 0; r < 20; ++r)
    for (int i = 0; i < 100; ++i) rows.emplace_back(std::cos(0.06 * i), std::sin(0.06 * i), 3.0 * r);
  CHECK(extent_along(rows, {0, 0, 1}).strays == 0);
  std::vector<Eigen::Vector3d> few(scan.cloud.points.begin(), scan.cloud.points.begin() + 900);
  few.emplace_back(0, 0, 900);
  CHECK(extent_along(few, {0, 0, 1}).hi == 900);
  // More than 1 in 1 000 points far off (a second part in the scan): kept, the planes over both.
  std::vector<Eigen::Vector3d> two = scan.cloud.points;
  for (std::size_t i = 0; i < 2 * two.size() / 1000 + 2; ++i) two.emplace_back(0, 0, 900 + 0.01 * double(i));
  CHECK(extent_along(two, {0, 0, 1}).strays == 0);
  // The units are guessed from the extent without them: a scan in metres with a point a
  // metre off it is still 0.05 across.
  std::vector<Eigen::Vector3d> metres;
  for (const auto& p : scan.cloud.points) metres.push_back(p / 1000);
  metres.emplace_back(0.9, 0.1, 0.5);
  CHECK(points_extent(metres) < 0.06);
}

TEST_CASE("slice: many planes in one pass give what each plane alone gives", "[slice]") {
  std::vector<Eigen::Vector3d> pts;
  for (int i = 0; i < 20000; ++i) pts.emplace_back(std::sin(i * 0.37), std::cos(i * 0.11), 0.001 * i);
  std::vector<double> at;
  for (int k = 0; k < 15; ++k) at.push_back(1.0 + 1.2 * k + 0.013 * k * k);
  const auto planes = planes_at({0, 0, 1}, at);
  const auto all = slab_points(pts, planes, 0.3);
  for (std::size_t k = 0; k < planes.size(); ++k) {
    const auto one = slab_points(pts, {planes[k]}, 0.3);
    REQUIRE(one[0] == all[k]);
    std::size_t brute = 0;
    // The boundary planes pass exactly through the doubles at -+ 0.15 (as rounded).
    const double lo = at[k] - 0.5 * 0.3, hi = at[k] + 0.5 * 0.3;
    for (const auto& p : pts) brute += (p.z() >= lo && p.z() <= hi) ? 1 : 0;
    CHECK(all[k].size() == brute);
  }
}

namespace {

// The octahedron |x| + |y| + |z| = 1.
Mesh octahedron() {
  Mesh m;
  m.vertices = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  m.triangles = {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4}, {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}};
  return m;
}

}  // namespace

TEST_CASE("slice: a mesh cut gives the analytic intersection within 1e-9", "[slice]") {
  const Mesh m = octahedron();
  const std::vector<Plane> planes = {
      {{0, 0, 0.3}, {0, 0, 1}}, {{0.05, -0.1, 0.2}, {0.2, 0.1, 1}}, {{0, 0, 3}, {0, 0, 1}}};
  const SliceResult r = slice(m, planes);
  REQUIRE(r.sections.size() == 3);
  for (int s = 0; s < 2; ++s) {
    const SectionSlice& sec = r.sections[s];
    REQUIRE(sec.error.empty());
    REQUIRE(sec.morphology.loops.size() == 1);
    const Loop& loop = sec.morphology.loops[0];
    REQUIRE(loop.points.size() >= 4);
    for (std::size_t i = 0; i < loop.points.size(); ++i) {
      const Eigen::Vector3d p = sec.frame.to_world(loop.points[i]);
      CHECK(std::abs(p.cwiseAbs().sum() - 1) < 1e-9);                                     // on the octahedron
      CHECK(std::abs((p - planes[s].origin).dot(planes[s].normal.normalized())) < 1e-9);  // on the plane
      CHECK(loop.normals[i].dot(loop.points[i] - sec.frame.to_plane(Eigen::Vector3d::Zero())) >
            0);  // outward
    }
  }
  // z = 0.3 cuts the square |x| + |y| = 0.7: area 2 * 0.7^2, counterclockwise.
  CHECK(std::abs(r.sections[0].morphology.loops[0].area - 2 * 0.49) < 1e-9);
  CHECK_FALSE(r.sections[2].error.empty());  // misses the part
}

TEST_CASE("slice: bad planes are refused", "[slice]") {
  Cloud c;
  c.points = {{0, 0, 0}, {1, 0, 0}};
  CHECK_THROWS_AS(slice(c, {}), Error);
  CHECK_THROWS_AS(slice(c, {{{0, 0, 0}, {0, 0, 0}}}), Error);
  CHECK_THROWS_WITH(parse_planes("origin_x,origin_y,origin_z,normal_x,normal_y\n0,0,0,0,1\n", "p.csv"),
                    Catch::Contains("normal_z"));
  const auto planes =
      parse_planes("origin_x,origin_y,origin_z,normal_x,normal_y,normal_z\n0,0,5,0,0,2\n", "p.csv");
  REQUIRE(planes.size() == 1);
  CHECK(planes[0].origin.z() == 5);
}

#include "section/extras/generate.h"

#include <algorithm>

namespace {

struct OrderCheck {
  double within_30um = 0;     // fraction of kept points within 30 um of the true profile
  double worst_backstep = 0;  // longest step against the true order, mm
  std::size_t far_outliers_kept = 0;
};

// Walks the loop and maps each point to its arc length on the true profile; the sequence
// must advance (cyclically) except for small back-steps.
OrderCheck check_loop(const Loop& loop, const SectionTruth& truth) {
  OrderCheck c;
  const double P = truth.perimeter;
  std::size_t within = 0;
  std::vector<double> s;
  for (const auto& p : loop.points) {
    const ProfileLocation at = locate(truth, p);
    if (at.distance <= 0.030) ++within;
    if (at.distance > 0.2) ++c.far_outliers_kept;
    s.push_back(at.s);
  }
  c.within_30um = double(within) / double(loop.points.size());
  // Running maximum of the unwrapped position: a point behind it by more than 0.1 mm is a fold.
  double unwrapped = s[0], ahead = s[0];
  for (std::size_t i = 1; i < s.size(); ++i) {
    double d = s[i] - s[i - 1];
    d -= P * std::round(d / P);
    unwrapped += d;
    ahead = std::max(ahead, unwrapped);
    c.worst_backstep = std::max(c.worst_backstep, ahead - unwrapped);
  }
  // One lap in all, counterclockwise like the truth.
  CHECK(std::abs((unwrapped - s[0]) - P) < 0.05 * P);
  return c;
}

}  // namespace

TEST_CASE("slice: a noisy blade scan gives one ordered closed loop per section", "[slice][generated]") {
  struct Case {
    const char* name;
    BladeDesign blade;
  };
  const Case cases[] = {{"turbine", turbine_blade()}, {"compressor", compressor_blade()}};
  for (const auto& c : cases) {
    for (const double z0 : {0.2 * c.blade.span, 0.5 * c.blade.span, 0.85 * c.blade.span}) {
      for (const std::uint64_t seed : {11u, 12u}) {
        ScanOptions so = section::inspection_scan();
        so.holes = 6;
        so.misregistration = 0.015;
        so.z_min = z0 - 1.0;
        so.z_max = z0 + 1.0;
        so.seed = seed;
        const Scan scan = generate_scan(c.blade, so);
        const SliceResult r = slice(scan.cloud, planes_at({0, 0, 1}, {z0}));
        INFO(c.name << " z0=" << z0 << " seed=" << seed);
        REQUIRE(r.sections.size() == 1);
        INFO("error: " << r.sections[0].error);
        REQUIRE(r.sections[0].error.empty());
        const MorphologyResult& m = r.sections[0].morphology;
        REQUIRE(m.loops.size() == 1);
        const SectionTruth truth = section_truth(c.blade.at(z0));
        const OrderCheck oc = check_loop(m.loops[0], truth);
        INFO("within 30 um " << oc.within_30um << ", worst back-step " << oc.worst_backstep << " mm, slab "
                             << r.slab);
        CHECK(oc.within_30um >= 0.995);
        CHECK(oc.worst_backstep <= 0.1);
        CHECK(oc.far_outliers_kept == 0);
        CHECK(m.loops[0].points.size() > 300);
      }
    }
  }
}

TEST_CASE("slice: a generated blade mesh cuts to the true section", "[slice][generated]") {
  const BladeDesign blade = compressor_blade();
  const Mesh mesh = generate_mesh(blade, 800, 31);
  const double z0 = 0.5 * blade.span;  // a mesh layer: the cut is exact there
  const SliceResult r = slice(mesh, planes_at({0, 0, 1}, {z0}));
  REQUIRE(r.sections[0].error.empty());
  REQUIRE(r.sections[0].morphology.loops.size() == 1);
  const SectionTruth truth = section_truth(blade.at(z0));
  double worst = 0;
  for (const auto& p : r.sections[0].morphology.loops[0].points)
    worst = std::max(worst, locate(truth, p).distance);
  CHECK(worst < 1e-6);
}

namespace {

// A generated blade's mesh (600 profile points, 61 layers) without the triangles within
// 1.5 mm of height z0 whose centroids `in_hole` takes: a hole in a scan's mesh.
template <class InHole>
Mesh mesh_with_hole(const BladeDesign& blade, double z0, const InHole& in_hole) {
  Mesh mesh = generate_mesh(blade, 600, 61);
  std::vector<std::array<int, 3>> kept;
  for (const auto& t : mesh.triangles) {
    const Eigen::Vector3d c = (mesh.vertices[t[0]] + mesh.vertices[t[1]] + mesh.vertices[t[2]]) / 3;
    if (!(std::abs(c.z() - z0) < 1.5 && in_hole(c))) kept.push_back(t);
  }
  REQUIRE(kept.size() < mesh.triangles.size());
  mesh.triangles = kept;
  return mesh;
}

// The flags of the params row the whole pipe gives `mesh`'s section at height z0.
CheckBits flags_through_pipe(const Mesh& mesh, double z0) {
  const Stream s =
      section::test::after_slice(to_stream(slice(mesh, planes_at({0, 0, 1}, {z0})), "test", "mm"));
  const Table* params = s.find("params");
  REQUIRE(params);
  REQUIRE(params->rows() == 1);
  return flags_mask(params->at(0, params->column("flags")));
}

}  // namespace

TEST_CASE("slice: a mesh with a hole at the plane is cut, its hole bridged as a scan's",
          "[slice][generated]") {
  // A scan's mesh often has holes: a plane through one cut it into open polylines, and the
  // section was refused. Its cut points are ordered as a cloud's slab instead; the loop
  // bridges the hole (2-3 mm of the suction side here) and lies on the true section.
  const BladeDesign blade = turbine_blade();
  const double z0 = 30;
  const Mesh mesh =
      mesh_with_hole(blade, z0, [](const Eigen::Vector3d& c) { return c.x() > 0 && c.x() < 3 && c.y() > 0; });
  const SliceResult r = slice(mesh, planes_at({0, 0, 1}, {z0}));
  const SectionSlice& s = r.sections[0];
  INFO(s.error);
  REQUIRE(s.error.empty());
  CHECK(s.open_polylines == 2);
  CHECK(s.bridged > 2);
  CHECK(s.bridged < 3.5);
  REQUIRE(s.morphology.loops.size() == 1);
  const SectionTruth truth = section_truth(blade.at(z0));
  double worst = 0;
  for (const auto& p : s.morphology.loops[0].points) worst = std::max(worst, locate(truth, p).distance);
  CHECK(worst < 0.01);  // the cut points, on the mesh's facets
  // The closed mesh's section is no open one.
  const SliceResult whole = slice(generate_mesh(blade, 600, 61), planes_at({0, 0, 1}, {z0}));
  CHECK(whole.sections[0].open_polylines == 0);
  CHECK(whole.sections[0].bridged == 0);
}

TEST_CASE("slice: a mesh's hole over the TE flags what rests on the bridge", "[slice][generated]") {
  // The TE's last 3 mm gone: the bridge closes at a corner taken as a sharp TE, and the
  // chord and caliper chord came out 2.8 mm short, the area 6.4 mm2 small, the caliper and
  // area unflagged. A sharp edge whose vertex lies in a hole is not measured (te_measured),
  // which flags them.
  const BladeDesign blade = turbine_blade();
  const double z0 = 30;
  const Mesh mesh = mesh_with_hole(blade, z0, [](const Eigen::Vector3d& c) { return c.x() > 17; });
  const CheckBits flags = flags_through_pipe(mesh, z0);
  INFO(check_names_text(flags));
  CHECK((flags & bit(Check::te_measured)) != 0);
  for (const char* column : {"chord", "caliper_chord", "area", "stagger", "camber_length"})
    CHECK(checks_flagging(flags, column) & bit(Check::te_measured));
}

TEST_CASE("slice: a mesh's flank hole over 5 % of the chord flags the area, a small one not",
          "[slice][generated]") {
  // The area integrates the fit's bridge over a hole: an 8 mm hole in a mesh's flank moved
  // it by 0.2-0.6 %, flagged by nothing. A stretch without points longer than 5 % of the
  // chord and 4 times their mean distance beside it anywhere along the profile now flags it
  // (area_measured), as it would the thickest circle touching it.
  const BladeDesign blade = turbine_blade();
  const double z0 = 30;
  const SectionTruth truth = section_truth(blade.at(z0));
  const Eigen::Vector2d flank = truth.profile[truth.profile.size() / 4];  // mid-flank
  for (const double across : {8.0, 1.0}) {
    const Mesh mesh = mesh_with_hole(
        blade, z0, [&](const Eigen::Vector3d& c) { return (c.head<2>() - flank).norm() < across / 2; });
    const CheckBits flags = flags_through_pipe(mesh, z0);
    INFO(across << " mm hole: " << check_names_text(flags));
    CHECK(((flags & bit(Check::area_measured)) != 0) == (across > 2));
    CHECK(checks_flagging(bit(Check::area_measured), "area") != 0);
    CHECK(checks_flagging(bit(Check::area_measured), "chord") == 0);
  }
}

TEST_CASE("slice: a band tried and not taken leaves the slab's ordering, skeleton and all", "[slice]") {
  // A stadium (axis from (-10, 0) to (10, 0), half width 2 mm) scanned in the plane z = 0
  // only: a band is tried (a tiny band spacing asks for the widest), but it holds nothing
  // beside the slab's points, so the slab's ordering stays, with the skeleton its first
  // ordering left out for the band.
  Cloud cloud;
  const double side = 20, cap = M_PI * 2, length = 2 * side + 2 * cap;
  for (int i = 0; i < 2000; ++i) {
    double s = length * i / 2000;  // arc length from (10, -2), counterclockwise
    Eigen::Vector3d p;
    if (s < cap) {
      p = {10 + 2 * std::sin(s / 2), -2 * std::cos(s / 2), 0};
    } else if ((s -= cap) < side) {
      p = {10 - s, 2, 0};
    } else if ((s -= side) < cap) {
      p = {-10 - 2 * std::sin(s / 2), 2 * std::cos(s / 2), 0};
    } else {
      p = {-10 + (s - cap), -2, 0};
    }
    cloud.points.push_back(p);
  }
  SliceOptions with_band;
  with_band.slab = 0.1;
  with_band.band_spacing = 1e-4;
  SliceOptions slab_alone = with_band;
  slab_alone.band_spacing = 0;
  const SliceResult a = slice(cloud, planes_at({0, 0, 1}, {0.0}), with_band);
  const SliceResult b = slice(cloud, planes_at({0, 0, 1}, {0.0}), slab_alone);
  REQUIRE(a.sections.size() == 1);
  INFO(a.sections[0].error);
  REQUIRE(a.sections[0].error.empty());
  CHECK(a.sections[0].band_points == 0);
  const MorphologyResult& m = a.sections[0].morphology;
  REQUIRE(m.skeleton.size() > 10);
  CHECK(m.skeleton == b.sections[0].morphology.skeleton);
  CHECK(m.loops[0].index == b.sections[0].morphology.loops[0].index);
  for (std::size_t i = 0; i < m.skeleton.size(); ++i)
    if (std::abs(m.skeleton[i].x()) < 6) CHECK(std::abs(m.skeleton[i].y()) < 2 * m.cell);  // on the axis
}

TEST_CASE("slice: exact copies of points change no section", "[slice][generated]") {
  ScanOptions so = section::inspection_scan();
  so.z_min = 29;
  so.z_max = 31;
  so.seed = 5;
  const Scan scan = generate_scan(turbine_blade(), so);
  Cloud copied = scan.cloud;
  // After the originals: each first instance is kept, in order (slab, band and fill).
  copied.points.insert(copied.points.end(), scan.cloud.points.begin(), scan.cloud.points.end());
  SliceOptions options;
  options.slab = 0.1;  // the spacing estimate would see the copies
  const std::vector<Plane> planes = planes_at({0, 0, 1}, {30});
  const SliceResult a = slice(scan.cloud, planes, options), b = slice(copied, planes, options);
  REQUIRE(a.sections.size() == 1);
  REQUIRE(b.sections.size() == 1);
  REQUIRE(a.sections[0].error.empty());
  CHECK(b.sections[0].slab_points == a.sections[0].slab_points);
  CHECK(b.sections[0].band_points == a.sections[0].band_points);
  const MorphologyResult &ma = a.sections[0].morphology, &mb = b.sections[0].morphology;
  REQUIRE(ma.loops.size() == mb.loops.size());
  for (std::size_t l = 0; l < ma.loops.size(); ++l) CHECK(ma.loops[l].points == mb.loops[l].points);
}

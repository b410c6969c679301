// SPDX-License-Identifier: GPL-3.0-or-later
// Tests of the synthetic blade generator: the ground truth is self-consistent and the
// scans and meshes agree with it.
#include "section/error.h"
#include "section/extras/generate.h"

#include <Eigen/Geometry>
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <map>
#include <random>
#include <utility>
#include <vector>

using Eigen::Vector2d;
using Eigen::Vector3d;
using section::SectionDesign;
using section::SectionTruth;

namespace {

double cross2(const Vector2d& a, const Vector2d& b) {
  return a.x() * b.y() - a.y() * b.x();
}

double shoelace(const std::vector<Vector2d>& p) {
  double a = 0;
  for (std::size_t i = 0; i < p.size(); ++i) a += cross2(p[i], p[(i + 1) % p.size()]);
  return 0.5 * a;
}

// Designs to check: both presets at hub, mid and tip, and varied designs around them.
std::vector<SectionDesign> designs() {
  std::vector<SectionDesign> out;
  for (const auto& b : {section::turbine_blade(), section::compressor_blade()})
    for (double z : {0.0, 0.5 * b.span, b.span}) out.push_back(b.at(z));
  std::mt19937_64 rng(7);
  auto u = [&](double a, double b) { return a + (b - a) * double(rng() >> 11) * 0x1.0p-53; };
  for (int i = 0; i < 4; ++i) {
    SectionDesign d;
    d.chord = u(20, 60);
    d.stagger = u(-30, 40);
    const double turning = u(10, 115);
    d.inlet_angle = d.stagger + turning / 2 + u(-5, 5);
    d.outlet_angle = d.stagger - turning / 2 + u(-5, 5);
    d.max_thickness = d.chord * u(0.05, 0.2);
    d.le_radius = d.max_thickness * u(0.08, 0.3);
    d.te_radius = d.max_thickness * u(0.05, 0.15);
    d.max_thickness_pos = u(0.25, 0.5);
    d.offset = Vector2d(u(-10, 10), u(-10, 10));
    out.push_back(d);
  }
  return out;
}

// Index of the profile point nearest to p (brute force).
std::size_t nearest_index(const std::vector<Vector2d>& pts, const Vector2d& p) {
  std::size_t best = 0;
  for (std::size_t i = 1; i < pts.size(); ++i)
    if ((pts[i] - p).squaredNorm() < (pts[best] - p).squaredNorm()) best = i;
  return best;
}

// Brute-force distance from p to the segments of pts[b..e] (indices mod n).
double polyline_distance(const std::vector<Vector2d>& pts, std::size_t b, std::size_t e, const Vector2d& p) {
  double best = 1e300;
  const std::size_t n = pts.size();
  for (std::size_t i = b; i < e; ++i) {
    const Vector2d& a = pts[i % n];
    const Vector2d ab = pts[(i + 1) % n] - a;
    const double t = std::clamp((p - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
    best = std::min(best, (a + t * ab - p).norm());
  }
  return best;
}

double circle_radius(const Vector2d& a, const Vector2d& b, const Vector2d& c) {
  const double ab = (b - a).norm(), bc = (c - b).norm(), ca = (a - c).norm();
  return ab * bc * ca / (2 * std::abs(cross2(b - a, c - a)));
}

}  // namespace

TEST_CASE("generate: profile is closed, counterclockwise and evenly sampled", "[generate]") {
  for (const SectionDesign& d : designs()) {
    const SectionTruth t = section::section_truth(d, 4000);
    REQUIRE(t.profile.size() == 4000);
    REQUIRE(t.profile_normal.size() == 4000);
    const double step = t.perimeter / 4000;
    for (std::size_t i = 0; i < t.profile.size(); ++i) {
      const double seg = (t.profile[(i + 1) % t.profile.size()] - t.profile[i]).norm();
      // chords of equal arcs: shorter than the arc by (step kappa)^2/24 at most
      REQUIRE(seg == Approx(step).epsilon(2e-3));
    }
    REQUIRE(shoelace(t.profile) > 0);
    REQUIRE(shoelace(t.profile) == Approx(t.area).epsilon(1e-4));
    REQUIRE((t.profile[0] - t.le_point).norm() < 1e-12);
    // outward normals: the normal points away from the interior, tangent turned clockwise
    for (std::size_t i = 0; i < t.profile.size(); i += 7) {
      const Vector2d tan = t.profile[(i + 1) % 4000] - t.profile[(i + 3999) % 4000];
      REQUIRE(std::abs(t.profile_normal[i].norm() - 1) < 1e-12);
      // central differences lag by ~ h (kappa jump) / 4 where pieces of different curvature meet
      REQUIRE(t.profile_normal[i].dot(Vector2d(tan.y(), -tan.x()).normalized()) > 0.998);
    }
  }
}

TEST_CASE("generate: area, perimeter and centroid are exact to 1e-9", "[generate]") {
  // Richardson on shoelace/polygon sums of the exactly placed profile points: their
  // errors go as h^2, so (4 F(2n) - F(n)) / 3 converges to the true value.
  for (const SectionDesign& d : designs()) {
    const SectionTruth t = section::section_truth(d);
    const SectionTruth h1 = section::section_truth(d, 16000), h2 = section::section_truth(d, 32000);
    auto poly = [](const std::vector<Vector2d>& p) {
      double len = 0, a = 0;
      Vector2d m(0, 0);
      for (std::size_t i = 0; i < p.size(); ++i) {
        const Vector2d& x = p[i];
        const Vector2d& y = p[(i + 1) % p.size()];
        len += (y - x).norm();
        const double c = cross2(x, y);
        a += 0.5 * c;
        m += c * (x + y) / 6;
      }
      return std::make_pair(std::make_pair(len, a), Vector2d(m / a));
    };
    const auto p1 = poly(h1.profile), p2 = poly(h2.profile);
    const double len = (4 * p2.first.first - p1.first.first) / 3;
    const double area = (4 * p2.first.second - p1.first.second) / 3;
    const Vector2d cen = (4 * p2.second - p1.second) / 3;
    CHECK(len == Approx(t.perimeter).epsilon(1e-9));
    CHECK(area == Approx(t.area).epsilon(1e-9));
    CHECK((cen - t.centroid).norm() < 1e-9 * t.chord);
    CHECK(t.perimeter == Approx(h1.perimeter).epsilon(1e-13));
    // chord, angles, thickness against the design
    CHECK(t.max_thickness == Approx(d.max_thickness).epsilon(1e-14));
    CHECK(t.inlet_angle == Approx(d.inlet_angle).epsilon(1e-12));
    CHECK(t.outlet_angle == Approx(d.outlet_angle).epsilon(1e-12));
    CHECK((t.le_center - d.offset).norm() < 1e-12);
    CHECK(t.chord > d.chord);
    CHECK(t.camber_length > t.chord);
  }
}

TEST_CASE("generate: camber is the medial axis: inscribed radius = distance to both sides", "[generate]") {
  for (const SectionDesign& d : designs()) {
    const SectionTruth t = section::section_truth(d, 20000);
    const std::size_t n = t.profile.size();
    const std::size_t te = nearest_index(t.profile, t.te_point);
    REQUIRE(t.profile_s[te] == Approx(t.te_s).epsilon(1e-4));
    REQUIRE(t.camber_begin > 0);
    REQUIRE(t.camber_end < t.camber.size());
    REQUIRE(t.camber_s.back() == Approx(t.camber_length).epsilon(1e-14));
    double worst = 0, worst_right = 0, worst_left = 0;
    for (std::size_t j = t.camber_begin; j < t.camber_end; j += 3) {
      const Vector2d& c = t.camber[j];
      const double r = t.camber_radius[j];
      worst = std::max(worst, std::abs(section::locate(t, c).distance - r));
      if (j % 60 == 0) {
        // the circle touches the right side (LE -> TE) and the left side (TE -> LE)
        worst_right = std::max(worst_right, std::abs(polyline_distance(t.profile, 0, te, c) - r));
        worst_left = std::max(worst_left, std::abs(polyline_distance(t.profile, te, n, c) - r));
      }
    }
    CHECK(worst < 1e-10);       // locate refines on the exact curve
    CHECK(worst_right < 1e-6);  // polyline: sagitta of the 20000-point profile
    CHECK(worst_left < 1e-6);
    // extension points: distance to the profile = edge radius - distance to the edge centre
    for (std::size_t j = 0; j < t.camber_begin; ++j)
      CHECK(section::locate(t, t.camber[j]).distance ==
            Approx(t.le_radius - (t.camber[j] - t.le_center).norm()).margin(1e-7));
    CHECK(section::camber_distance(t, t.le_point) < 1e-12);
    CHECK(section::camber_distance(t, t.camber[t.camber.size() / 3]) < 1e-12);
  }
}

TEST_CASE("generate: inscribed circles fit the local curvature of both sides", "[generate]") {
  // Where a side is convex, its radius of curvature (from three profile points) is at
  // least the inscribed radius there, bounded below by the distance to the camber. The
  // medial-axis test above checks maximality exactly; this is the local picture.
  for (const SectionDesign& d : designs()) {
    const SectionTruth t = section::section_truth(d, 20000);
    const std::size_t n = t.profile.size();
    int checked = 0;
    for (std::size_t i = 0; i < n; i += 10) {
      const Vector2d &a = t.profile[(i + n - 5) % n], &b = t.profile[i], &c = t.profile[(i + 5) % n];
      const double turn = cross2(b - a, c - b);  // > 0: convex
      // inscribed radius of the circle touching here: walk inwards along the normal
      const double r_touch = section::camber_distance(t, b);  // >= the inscribed radius
      if (turn > 0) {
        const double rho = circle_radius(a, b, c);
        CHECK(rho > 0.999 * std::min(r_touch, t.max_thickness / 2) - 1e-9);
        ++checked;
      }
    }
    CHECK(checked > 100);
  }
}

TEST_CASE("generate: edge points and radii", "[generate]") {
  for (const SectionDesign& d : designs()) {
    const SectionTruth t = section::section_truth(d, 20000);
    CHECK(section::locate(t, t.le_point).distance < 1e-12);
    CHECK(section::locate(t, t.te_point).distance < 1e-8);
    CHECK(t.le_radius == Approx(d.le_radius).epsilon(1e-15));
    CHECK(t.te_radius == Approx(d.te_radius).epsilon(1e-15));
    const std::size_t n = t.profile.size();
    const std::size_t te = nearest_index(t.profile, t.te_point);
    // edge arcs sampled at (perimeter/n); three points 3 steps apart give the radius
    CHECK(circle_radius(t.profile[n - 3], t.profile[0], t.profile[3]) == Approx(t.le_radius).epsilon(1e-6));
    CHECK(circle_radius(t.profile[te - 2], t.profile[te], t.profile[te + 2]) ==
          Approx(t.te_radius).epsilon(1e-6));
    CHECK((t.te_point - t.le_point).norm() == Approx(t.chord).epsilon(1e-15));
  }
}

TEST_CASE("generate: locate is exact on points moved along the true normal", "[generate]") {
  std::mt19937_64 rng(11);
  auto u = [&](double a, double b) { return a + (b - a) * double(rng() >> 11) * 0x1.0p-53; };
  for (const SectionDesign& d : designs()) {
    const SectionTruth t = section::section_truth(d);
    const double inside = 0.9 * std::min(t.le_radius, t.te_radius);
    double worst_d = 0, worst_s = 0;
    for (int k = 0; k < 4000; ++k) {
      const std::size_t i = std::size_t(u(0, double(t.profile.size()))) % t.profile.size();
      const double off = u(-inside, 1.0);
      const auto loc = section::locate(t, t.profile[i] + off * t.profile_normal[i]);
      worst_d = std::max(worst_d, std::abs(loc.distance - std::abs(off)));
      double ds = std::abs(loc.s - t.profile_s[i]);
      ds = std::min(ds, t.perimeter - ds);
      worst_s = std::max(worst_s, ds);
    }
    CHECK(worst_d < 1e-10);
    CHECK(worst_s < 1e-9);
    // random points anywhere: the tree search agrees with brute force on the polyline
    // (locate then refines the foot on the curve, by less than the polyline's sagitta)
    for (int k = 0; k < 300; ++k) {
      const Vector2d p = t.centroid + Vector2d(u(-30, 30), u(-30, 30));
      CHECK(section::locate(t, p).distance ==
            Approx(polyline_distance(t.profile, 0, t.profile.size(), p)).margin(2e-5));
    }
  }
}

TEST_CASE("generate: locate is fast", "[generate]") {
  const SectionTruth t = section::section_truth(section::turbine_blade().at(20));
  std::mt19937_64 rng(3);
  double sum = 0;
  for (int k = 0; k < 100000; ++k) {
    const std::size_t i = rng() % t.profile.size();
    sum += section::locate(t, t.profile[i] + 0.01 * t.profile_normal[i]).distance;
  }
  CHECK(sum == Approx(1000).epsilon(1e-6));
}

TEST_CASE("generate: invalid designs are refused", "[generate]") {
  SectionDesign d;
  d.le_radius = 3;  // above max_thickness / 2
  CHECK_THROWS_AS(section::section_truth(d), section::Error);
  d = SectionDesign{};
  d.chord = -1;
  CHECK_THROWS_AS(section::section_truth(d), section::Error);
  d = SectionDesign{};
  d.max_thickness = 30;  // thicker than the camber can carry: the right side folds
  d.inlet_angle = 80;
  d.outlet_angle = -40;
  CHECK_THROWS_WITH(section::section_truth(d), Catch::Contains("section_truth:"));
}

TEST_CASE("generate: blade designs blend smoothly from hub to tip", "[generate]") {
  const auto b = section::turbine_blade();
  CHECK(b.at(0).stagger == b.hub.stagger);
  CHECK(b.at(b.span).stagger == b.tip.stagger);
  CHECK(b.at(-5).chord == b.hub.chord);
  const double turning = b.hub.inlet_angle - b.hub.outlet_angle;
  CHECK(turning > 100);
  CHECK(turning < 120);
  const auto c = section::compressor_blade();
  CHECK(c.hub.inlet_angle - c.hub.outlet_angle == Approx(30).margin(5));
  CHECK(c.hub.le_radius >= 0.25);
  CHECK(c.hub.le_radius <= 0.35);
}

namespace {
section::ScanOptions small_scan() {
  section::ScanOptions o;
  o.z_min = 10;
  o.z_max = 12;
  o.spacing = 0.1;
  return o;
}
}  // namespace

TEST_CASE("generate: scans are deterministic per seed", "[generate]") {
  const auto b = section::turbine_blade();
  auto o = small_scan();
  o.noise = 0.01;
  o.holes = 5;
  o.density_min = 0.3;
  o.misregistration = 0.02;
  o.outlier_fraction = 0.001;
  const auto s1 = section::generate_scan(b, o), s2 = section::generate_scan(b, o);
  REQUIRE(s1.cloud.points.size() == s2.cloud.points.size());
  REQUIRE(s1.cloud.points.size() > 10000);
  CHECK(s1.cloud.points == s2.cloud.points);
  CHECK(s1.outlier == s2.outlier);
  CHECK(s1.view == s2.view);
  o.seed = 2;
  const auto s3 = section::generate_scan(b, o);
  CHECK(s3.cloud.points != s1.cloud.points);
  // both views present, z inside the range
  CHECK(std::count(s1.view.begin(), s1.view.end(), 1) > 1000);
  CHECK(std::count(s1.view.begin(), s1.view.end(), 0) > 1000);
  for (std::size_t i = 0; i < s1.cloud.points.size(); ++i)
    if (!s1.outlier[i]) REQUIRE((s1.cloud.points[i].z() >= 10 && s1.cloud.points[i].z() <= 12));
}

TEST_CASE("generate: clean scan points lie on the section at their height", "[generate]") {
  const auto b = section::compressor_blade();
  auto o = small_scan();
  const auto s = section::generate_scan(b, o);
  // spacing: nearest-neighbour distance ~ spacing
  for (std::size_t i = 0; i < s.cloud.points.size(); i += s.cloud.points.size() / 15) {
    const Vector3d& p = s.cloud.points[i];
    const SectionTruth t = section::section_truth(b.at(p.z()));
    CHECK(section::locate(t, p.head<2>()).distance < 1e-6);
  }
}

TEST_CASE("generate: scan noise has the requested sigma", "[generate]") {
  // A prismatic blade: one truth for all heights.
  auto b = section::turbine_blade();
  b.tip = b.hub;
  for (double sigma : {0.005, 0.02}) {
    auto o = small_scan();
    o.noise = sigma;
    o.seed = 5;
    const auto s = section::generate_scan(b, o);
    const SectionTruth t = section::section_truth(b.hub);
    double sum2 = 0;
    for (const Vector3d& p : s.cloud.points) sum2 += std::pow(section::locate(t, p.head<2>()).distance, 2);
    const double measured = std::sqrt(sum2 / double(s.cloud.points.size()));
    CHECK(measured == Approx(sigma).epsilon(0.1));
    // same seed without noise: the same points before the noise
    o.noise = 0;
    const auto clean = section::generate_scan(b, o);
    REQUIRE(clean.cloud.points.size() == s.cloud.points.size());
    double d2 = 0;
    for (std::size_t i = 0; i < s.cloud.points.size(); ++i)
      d2 += (s.cloud.points[i] - clean.cloud.points[i]).squaredNorm();
    CHECK(std::sqrt(d2 / double(s.cloud.points.size())) == Approx(sigma).epsilon(0.03));
  }
}

TEST_CASE("generate: outliers are at least 0.2 mm away, misregistration moves view 1", "[generate]") {
  auto b = section::compressor_blade();
  b.tip = b.hub;
  auto o = small_scan();
  o.outlier_fraction = 0.01;
  o.misregistration = 0.05;
  const auto s = section::generate_scan(b, o);
  const SectionTruth t = section::section_truth(b.hub);
  std::size_t outliers = 0;
  double view1 = 0, view0 = 0;
  std::size_t n1 = 0, n0 = 0;
  for (std::size_t i = 0; i < s.cloud.points.size(); ++i) {
    const double d = section::locate(t, s.cloud.points[i].head<2>()).distance;
    if (s.outlier[i]) {
      ++outliers;
      CHECK(d >= 0.2);
    } else if (s.view[i]) {
      view1 += d;
      ++n1;
    } else {
      view0 += d;
      ++n0;
    }
  }
  // on the twisted blade, each outlier against the exact section at its height
  {
    const auto tb = section::turbine_blade();
    auto ot = small_scan();
    ot.outlier_fraction = 0.002;
    const auto st = section::generate_scan(tb, ot);
    int checked = 0;
    for (std::size_t i = 0; i < st.cloud.points.size() && checked < 20; ++i)
      if (st.outlier[i]) {
        const Vector3d& p = st.cloud.points[i];
        const SectionTruth tz = section::section_truth(tb.at(std::clamp(p.z(), 0.0, tb.span)), 4000);
        CHECK(section::locate(tz, p.head<2>()).distance >= 0.2);
        CHECK((p.z() >= 8 && p.z() <= 14));
        ++checked;
      }
    CHECK(checked == 20);
  }
  const double frac = double(outliers) / double(s.cloud.points.size());
  CHECK(frac == Approx(0.01).epsilon(0.25));
  CHECK(view0 / double(n0) < 1e-6);
  // a fixed shift of 0.05 seen along the surface normal: between 0 and 0.05 on average,
  // close to 0.05 on the side it is normal to
  CHECK(view1 / double(n1) > 0.02);
  CHECK(view1 / double(n1) <= 0.05 + 1e-9);
}

TEST_CASE("generate: holes and density variation remove points", "[generate]") {
  const auto b = section::turbine_blade();
  auto o = small_scan();
  const auto full = section::generate_scan(b, o);
  o.density_min = 0.25;
  const auto sparse = section::generate_scan(b, o);
  const double ratio = double(sparse.cloud.points.size()) / double(full.cloud.points.size());
  CHECK(ratio > 0.3);
  CHECK(ratio < 0.95);
  o.density_min = 1;
  o.holes = 20;
  const auto holed = section::generate_scan(b, o);
  CHECK(holed.cloud.points.size() < full.cloud.points.size());
}

TEST_CASE("generate: mesh is closed, outward and cuts to the true profile", "[generate]") {
  const auto b = section::turbine_blade();
  const section::Mesh m = section::generate_mesh(b, 800, 31);
  // every directed edge once and its reverse once: closed and consistently oriented
  std::map<std::pair<int, int>, int> edges;
  for (const auto& t : m.triangles)
    for (int k = 0; k < 3; ++k) ++edges[{t[k], t[(k + 1) % 3]}];
  bool closed = true;
  for (const auto& [e, count] : edges)
    if (count != 1 || !edges.count({e.second, e.first})) closed = false;
  CHECK(closed);
  // positive volume ~ mean area * span (outward normals)
  double vol = 0;
  for (const auto& t : m.triangles) vol += m.vertices[t[0]].dot(m.vertices[t[1]].cross(m.vertices[t[2]])) / 6;
  const double area_mid = section::section_truth(b.at(30)).area;
  CHECK(vol == Approx(area_mid * b.span).epsilon(0.1));
  // cut at a layer height (z = 20) and between layers (z = 21)
  for (double z : {20.0, 21.0}) {
    const SectionTruth t = section::section_truth(b.at(z));
    double worst = 0;
    int crossings = 0;
    for (const auto& tri : m.triangles)
      for (int k = 0; k < 3; ++k) {
        const Vector3d& p = m.vertices[tri[k]];
        const Vector3d& q = m.vertices[tri[(k + 1) % 3]];
        if ((p.z() - z) * (q.z() - z) >= 0 || p.z() == q.z()) continue;
        const Vector3d x = p + (z - p.z()) / (q.z() - p.z()) * (q - p);
        worst = std::max(worst, section::locate(t, x.head<2>()).distance);
        ++crossings;
      }
    if (z == 20.0) {  // the layer's vertices are the exact profile
      for (const Vector3d& v : m.vertices)
        if (v.z() == z) worst = std::max(worst, section::locate(t, v.head<2>()).distance);
      CHECK(worst < 1e-6);
    } else {
      CHECK(crossings > 1000);
      // linear in z between layers 2 mm apart: smoothstep twist, a few um at most
      CHECK(worst < 5e-3);
    }
  }
}

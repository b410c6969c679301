// SPDX-License-Identifier: GPL-3.0-or-later
// Tests of compare (the stage): the fits recover known rigid moves, the deviations equal
// known changes made to generated sections (a thickened pressure side, a shortened chord,
// a blunted LE, a local dent) and zero elsewhere, minimum zone against least squares and
// brute force, holes, verdicts and the whole-blade fit.
#include "compare_fixtures.h"
#include "section/compare.h"
#include "section/error.h"
#include "section/frame.h"

#include <Eigen/LU>
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <thread>
#include <utility>
#include <vector>

using namespace compare_test;
using section::CompareOptions;
using section::FitFreedom;
using section::FitMethod;
using section::Zone;

namespace {

// The largest distance between where the fit puts each point of `pts` (moved by the
// motion degrees/shift from the truth) and where it was.
double recovery_error(const section::SectionComparison& c, const std::vector<Vector2d>& truth) {
  double worst = 0;
  for (std::size_t i = 0; i < truth.size(); ++i)
    worst = std::max(worst, (c.points[i].point - truth[i]).norm());
  return worst;
}

CompareOptions with(FitMethod m, FitFreedom f = FitFreedom::all) {
  CompareOptions o;
  o.fit.method = m;
  o.fit.freedom = f;
  return o;
}

const section::ZoneResult& zone(const section::SectionComparison& c, Zone z) {
  return c.zones[static_cast<int>(z)];
}

}  // namespace

TEST_CASE("compare: each fit recovers a rigid move on noise-free sections", "[compare]") {
  const auto designs = section::design_family();
  for (std::size_t d = 0; d < designs.size(); ++d) {
    const Case c = make_case(designs[d]);
    const std::vector<Vector2d> truth = profile_points(c.truth, 0.05);
    const double angle = 0.05 + 0.01 * d;
    const Vector2d shift(0.03, -0.02 + 0.01 * d);
    std::vector<Vector2d> pts;
    for (const auto& p : truth) pts.push_back(moved(p, angle, shift));
    for (FitMethod m : {FitMethod::least_squares, FitMethod::minimum_zone, FitMethod::weighted}) {
      CompareOptions o = with(m);
      o.fit.weights = {1, 5, 5, 1, 1};
      const auto r = section::compare_section(c.nominal, pts, o);
      INFO("design " << d << ", method " << static_cast<int>(m));
      CHECK(r.fit.converged);
      CHECK(std::abs(r.fit.motion.angle + angle) < 0.001);
      CHECK(recovery_error(r, truth) < 0.001);
      CHECK(r.fit.max_after < 0.001);
      CHECK(r.fit.max_before > 0.02);
      CHECK(r.outliers == 0);
    }
  }
}

TEST_CASE("compare: with 5 um of noise the move is recovered within the noise", "[compare]") {
  const auto designs = section::design_family();
  for (std::size_t d : {0u, 2u, 4u}) {
    const Case c = make_case(designs[d]);
    for (std::uint64_t seed : {1u, 2u}) {
      const std::vector<Vector2d> clean = profile_points(c.truth, 0.05);
      const std::vector<Vector2d> noisy = profile_points(c.truth, 0.05, 0.005, seed);
      std::vector<Vector2d> pts;
      for (const auto& p : noisy) pts.push_back(moved(p, -0.1, Vector2d(-0.05, 0.04)));
      for (FitMethod m : {FitMethod::least_squares, FitMethod::minimum_zone}) {
        const auto r = section::compare_section(c.nominal, pts, with(m));
        INFO("design " << d << ", seed " << seed << ", method " << static_cast<int>(m));
        // Where the fit puts the noise-free points: the noise's own part aside.
        double worst = 0;
        for (std::size_t i = 0; i < clean.size(); ++i) {
          const Vector2d back = r.fit.motion.apply(moved(clean[i], -0.1, Vector2d(-0.05, 0.04)));
          worst = std::max(worst, (back - clean[i]).norm());
        }
        // Least squares: far within the noise. Minimum zone: set by the few extreme points,
        // it may shift a thin section along its chord by a few sigma (docs/COMPARE.md), and
        // holds them at least as tight as the true move does.
        CHECK(worst < (m == FitMethod::least_squares ? 0.001 : 0.02));
        CHECK(r.fit.rms_after < 0.007);
        CHECK(r.fit.rms_after > 0.004);
        if (m == FitMethod::minimum_zone) {
          double at_truth = 0;
          for (std::size_t i = 0; i < clean.size(); ++i)
            at_truth = std::max(at_truth, std::abs(exact_deviation(c.truth, noisy[i])));
          CHECK(r.fit.max_after <= at_truth + 1e-6);
        }
      }
    }
  }
}

TEST_CASE("compare: the degrees of freedom limit the fit", "[compare]") {
  const Case c = make_case(section::design_family()[0]);
  const std::vector<Vector2d> truth = profile_points(c.truth, 0.05);
  SECTION("none: the deviations as measured") {
    std::vector<Vector2d> pts;
    for (const auto& p : truth) pts.push_back(p + Vector2d(0.01, 0));
    const auto r = section::compare_section(c.nominal, pts, with(FitMethod::least_squares, FitFreedom::none));
    CHECK(r.fit.motion.translation.norm() == 0);
    for (std::size_t i = 0; i < pts.size(); ++i) CHECK(r.points[i].after == r.points[i].before);
    CHECK(r.fit.max_after > 0.0099);
  }
  SECTION("translation: a shift is recovered, a rotation is not") {
    std::vector<Vector2d> shifted, turned;
    for (const auto& p : truth) {
      shifted.push_back(p + Vector2d(0.02, -0.03));
      turned.push_back(moved(p, 0.1, Vector2d(0, 0)));
    }
    auto o = with(FitMethod::least_squares, FitFreedom::translation);
    const auto a = section::compare_section(c.nominal, shifted, o);
    CHECK((a.fit.motion.translation - Vector2d(-0.02, 0.03)).norm() < 1e-6);
    CHECK(a.fit.motion.angle == 0);
    const auto b = section::compare_section(c.nominal, turned, o);
    CHECK(b.fit.motion.angle == 0);
    CHECK(b.fit.max_after > 0.005);
  }
  SECTION("translation along a direction: only its component") {
    std::vector<Vector2d> pts;
    for (const auto& p : truth) pts.push_back(p + Vector2d(0.02, 0.0));
    auto o = with(FitMethod::least_squares, FitFreedom::translation_along);
    o.fit.direction = Vector2d(1, 1);
    const auto r = section::compare_section(c.nominal, pts, o);
    const Vector2d t = r.fit.motion.translation;
    CHECK(std::abs(t.x() - t.y()) < 1e-12);
    CHECK(std::abs(t.x()) > 0);
  }
  SECTION("rotation about a point: a turn about it is recovered") {
    const Vector2d centre(10, 2);
    std::vector<Vector2d> pts;
    for (const auto& p : truth) pts.push_back(moved(p - centre, 0.2, centre));
    auto o = with(FitMethod::least_squares, FitFreedom::rotation);
    o.fit.center = centre;
    const auto r = section::compare_section(c.nominal, pts, o);
    CHECK(std::abs(r.fit.motion.angle + 0.2) < 1e-6);
    CHECK(recovery_error(r, truth) < 1e-4);
  }
}

TEST_CASE("compare: deviations equal known changes where made and zero elsewhere", "[compare]") {
  const auto designs = section::design_family();
  for (std::size_t d : {0u, 2u, 3u}) {
    const Case c = make_case(designs[d]);
    std::vector<Vector2d> normals;
    const std::vector<Vector2d> truth = profile_points(c.truth, 0.05, 0, 1, &normals);
    const auto fixed = with(FitMethod::least_squares, FitFreedom::none);
    INFO("design " << d);
    SECTION("a thickened pressure side") {
      std::vector<Vector2d> pts = truth;
      for (std::size_t i = 0; i < pts.size(); ++i)
        if (on_pressure_side(c, truth[i], normals[i], 0.2, 0.8)) pts[i] += 0.02 * normals[i];
      const auto r = section::compare_section(c.nominal, pts, fixed);
      for (std::size_t i = 0; i < pts.size(); ++i) {
        const bool thick = on_pressure_side(c, truth[i], normals[i], 0.2, 0.8);
        CHECK(std::abs(r.points[i].after - (thick ? 0.02 : 0.0)) < 0.0005);
        if (thick) CHECK(r.points[i].zone == Zone::pressure);
      }
      CHECK(zone(r, Zone::pressure).max == Approx(0.02).margin(0.0005));
      CHECK(std::abs(zone(r, Zone::suction).max) < 0.0005);
      CHECK(std::abs(zone(r, Zone::leading_edge).max) < 0.0005);
    }
    SECTION("a local dent") {
      std::vector<Vector2d> pts = truth;
      std::vector<double> depth(pts.size(), 0);
      // A cosine dent 0.03 deep and 2 mm wide at 40 % of the chord on the suction side.
      for (std::size_t i = 0; i < pts.size(); ++i) {
        if (on_pressure_side(c, truth[i], normals[i], 0, 1)) continue;
        const double x = (chord_fraction(c.truth, truth[i]) - 0.4) * c.truth.chord;
        if (std::abs(x) < 1) depth[i] = 0.015 * (1 + std::cos(pi * x));
        pts[i] -= depth[i] * normals[i];
      }
      const auto r = section::compare_section(c.nominal, pts, fixed);
      for (std::size_t i = 0; i < pts.size(); ++i) CHECK(std::abs(r.points[i].after + depth[i]) < 0.0005);
      CHECK(zone(r, Zone::suction).min == Approx(-0.03).margin(0.0005));
      CHECK(std::abs(zone(r, Zone::pressure).min) < 0.0005);
    }
    SECTION("a blunted leading edge and a shortened chord") {
      // The LE cut flat at 1 % of the chord, the TE cut back by 0.5 mm along the camber.
      Vector2d cut;
      double width = 0;
      const std::vector<Vector2d> te_cut = camber_test::cut_trailing_edge(c.truth, 0.5, cut, width);
      std::vector<Vector2d> pts;
      const Vector2d chord = (c.truth.te_point - c.truth.le_point).normalized();
      for (std::size_t i = 0; i < te_cut.size(); i += 25) {
        Vector2d p = te_cut[i];
        const double x = chord_fraction(c.truth, p);
        if (x < 0.01) p += (0.01 - x) * c.truth.chord * chord;
        pts.push_back(p);
      }
      const auto r = section::compare_section(c.nominal, pts, fixed);
      for (std::size_t i = 0; i < pts.size(); ++i) {
        const double exact = exact_deviation(c.truth, pts[i]);
        CHECK(std::abs(r.points[i].after - exact) < 0.0005);
        if (r.points[i].zone == Zone::pressure || r.points[i].zone == Zone::suction)
          CHECK(std::abs(r.points[i].after) < 0.0005);
      }
      CHECK(zone(r, Zone::leading_edge).min < -0.05);
      CHECK(zone(r, Zone::trailing_edge).min < -0.05);
    }
  }
}

TEST_CASE("compare: bad input is refused", "[compare]") {
  const Case c = make_case(section::design_family()[0]);
  const std::vector<Vector2d> pts = profile_points(c.truth, 0.5);
  CHECK_THROWS_AS(section::compare_section(c.nominal, {Vector2d(0, 0), Vector2d(1, 0)}), section::Error);
  std::vector<Vector2d> bad = pts;
  bad[3].x() = std::nan("");
  CHECK_THROWS_AS(section::compare_section(c.nominal, bad), section::Error);
  CompareOptions o;
  o.edge_zone = 0.6;
  CHECK_THROWS_AS(section::compare_section(c.nominal, pts, o), section::Error);
  o = CompareOptions{};
  o.fit.direction = Vector2d(0, 0);
  CHECK_THROWS_AS(section::compare_section(c.nominal, pts, o), section::Error);
  section::NominalSection open = c.nominal;
  open.curve.closed = false;
  CHECK_THROWS_AS(section::compare_section(open, pts), section::Error);
}

namespace {

// Signed distance of p to the counterclockwise curve (positive outside) and its outward
// normal, by a global closest-point search: the brute force's measure, independent of
// compare's feet.
double signed_distance(const section::BSpline& curve, const Vector2d& p, Vector2d* normal = nullptr) {
  const section::ClosestPoint f = section::closest_point(curve, p);
  const Vector2d d = curve.derivative(f.t, 1);
  const Vector2d n = Vector2d(d.y(), -d.x()).normalized();
  if (normal) *normal = n;
  return (p - f.point).dot(n);
}

// The motion x = (angle in radians about the origin, shift u, v) restricted by `free`
// (1 translation, 2 rotation, 3 all) from its k parameters.
Eigen::Vector3d full(const Eigen::VectorXd& x, int free) {
  if (free == 1) return {0, x(0), x(1)};
  if (free == 2) return {x(0), 0, 0};
  return x;
}

// Brute force over the active sets: the minimum zone of k motion parameters touches k + 1
// points at its optimum (as the linear Chebyshev fit does on points in general
// position), each at +z or -z. For every k + 1 points and signs, Newton solves those
// equalities; the smallest z whose motion keeps every point within it is the minimum.
double brute_force(const section::BSpline& curve, const std::vector<Vector2d>& pts, int free) {
  const int k = free == 3 ? 3 : (free == 1 ? 2 : 1), n = static_cast<int>(pts.size());
  double best = 1e300;
  for (int mask = 0; mask < (1 << n); ++mask) {
    std::vector<int> set;
    for (int i = 0; i < n; ++i)
      if (mask >> i & 1) set.push_back(i);
    if (static_cast<int>(set.size()) != k + 1) continue;
    for (int signs = 0; signs < (1 << (k + 1)); ++signs) {
      Eigen::VectorXd x = Eigen::VectorXd::Zero(k + 1);  // parameters, then z
      bool solved = false;
      for (int it = 0; it < 30 && !solved; ++it) {
        Eigen::MatrixXd jac(k + 1, k + 1);
        Eigen::VectorXd f(k + 1);
        const Eigen::Vector3d m = full(x.head(k), free);
        for (int r = 0; r <= k; ++r) {
          const Vector2d q = moved(pts[set[r]], m(0) * 180 / pi, m.tail<2>());
          Vector2d nrm;
          const double sign = (signs >> r & 1) ? 1.0 : -1.0;
          f(r) = signed_distance(curve, q, &nrm) - sign * x(k);
          const Eigen::Vector3d g(nrm.dot(Vector2d(-q.y(), q.x())), nrm.x(), nrm.y());
          const Eigen::Vector3d gk = free == 1 ? Eigen::Vector3d(g(1), g(2), 0) : g;
          for (int c = 0; c < k; ++c) jac(r, c) = gk(c);
          jac(r, k) = -sign;
        }
        const Eigen::FullPivLU<Eigen::MatrixXd> lu(jac);
        if (!lu.isInvertible()) break;
        const Eigen::VectorXd step = lu.solve(f);
        x -= step;
        solved = step.norm() < 1e-14;
      }
      if (!solved || x(k) < 0 || x(k) >= best) continue;
      const Eigen::Vector3d m = full(x.head(k), free);
      bool inside = true;
      for (const auto& p : pts)
        inside = inside &&
                 std::abs(signed_distance(curve, moved(p, m(0) * 180 / pi, m.tail<2>()))) <= x(k) + 1e-12;
      if (inside) best = x(k);
    }
  }
  return best;
}

}  // namespace

TEST_CASE("compare: minimum zone is no wider than least squares and equals a brute force on small cases",
          "[compare]") {
  const auto designs = section::design_family();
  for (std::size_t d : {0u, 3u}) {
    const SectionTruth t = section::section_truth(designs[d], 4000);
    section::NominalSection nominal;
    nominal.curve = camber_test::dense_spline(t.profile, 200);
    nominal.le_point = t.le_point;
    nominal.te_point = t.te_point;
    nominal.pressure_side = t.inlet_angle > t.outlet_angle ? -1 : 1;
    for (std::uint64_t seed : {3u, 4u}) {
      // 6 points around the profile, 10 um of noise.
      std::vector<Vector2d> pts = profile_points(t, t.perimeter / 6.1, 0.01, seed);
      const std::pair<FitFreedom, int> freedoms[] = {
          {FitFreedom::translation, 1}, {FitFreedom::rotation, 2}, {FitFreedom::all, 3}};
      for (const auto& [freedom, code] : freedoms) {
        auto ls = with(FitMethod::least_squares, freedom), mz = with(FitMethod::minimum_zone, freedom);
        ls.outlier_distance = mz.outlier_distance = -1;
        ls.fit.center = mz.fit.center = Vector2d(0, 0);
        const auto a = section::compare_section(nominal, pts, ls);
        const auto b = section::compare_section(nominal, pts, mz);
        INFO("design " << d << ", seed " << seed << ", freedom " << code);
        CHECK(b.fit.max_after <= a.fit.max_after + 1e-12);
        CHECK(b.fit.max_after == Approx(brute_force(nominal.curve, pts, code)).margin(1e-8));
      }
    }
  }
  // And on every fit of the tests above: a noisy section of each design.
  for (const auto& design : designs) {
    const Case c = make_case(design);
    const auto pts = profile_points(c.truth, 0.1, 0.005, 9);
    const auto a = section::compare_section(c.nominal, pts, with(FitMethod::least_squares));
    const auto b = section::compare_section(c.nominal, pts, with(FitMethod::minimum_zone));
    CHECK(b.fit.max_after <= a.fit.max_after + 1e-12);
  }
}

TEST_CASE("compare: a hole leaves its zone not measured, and verdicts follow the tolerances", "[compare]") {
  const Case c = make_case(section::design_family()[2]);
  std::vector<Vector2d> normals;
  const std::vector<Vector2d> all = profile_points(c.truth, 0.05, 0.005, 5, &normals);
  // A 2 mm hole over the leading edge; a 0.04 mm dent on the suction side.
  std::vector<Vector2d> pts;
  for (std::size_t i = 0; i < all.size(); ++i) {
    if ((all[i] - c.truth.le_point).norm() < 1) continue;
    Vector2d p = all[i];
    const double x = (chord_fraction(c.truth, p) - 0.5) * c.truth.chord;
    if (!on_pressure_side(c, p, normals[i], 0, 1) && std::abs(x) < 1)
      p -= 0.02 * (1 + std::cos(pi * x)) * normals[i];
    pts.push_back(p);
  }
  const auto r = section::compare_section(c.nominal, pts, with(FitMethod::least_squares, FitFreedom::none));
  const auto& le = zone(r, Zone::leading_edge);
  CHECK(!le.measured);
  CHECK(le.unmeasured > 1.5);
  CHECK(!zone(r, Zone::whole).measured);
  CHECK(zone(r, Zone::trailing_edge).measured);
  CHECK(zone(r, Zone::pressure).measured);
  CHECK(zone(r, Zone::suction).measured);
  section::Tolerance band{"profile", -1, -0.03, 0.03};
  const auto judged = [&](Zone z, const section::Tolerance& t) {
    const auto& zr = zone(r, z);
    return section::verdict(t, zr.min, zr.max, zr.measured);
  };
  CHECK(judged(Zone::leading_edge, band) == section::Verdict::not_measured);
  CHECK(judged(Zone::suction, band) == section::Verdict::fail);
  CHECK(judged(Zone::pressure, band) == section::Verdict::pass);
  CHECK(judged(Zone::trailing_edge, band) == section::Verdict::pass);
  section::Tolerance loose{"profile", -1, -0.06, 0.06};
  CHECK(judged(Zone::suction, loose) == section::Verdict::pass);
  CHECK(judged(Zone::whole, loose) == section::Verdict::not_measured);
  // A failing value is a failure even over a hole; a NaN is not measured.
  CHECK(section::verdict(band, -0.05, 0, false) == section::Verdict::fail);
  CHECK(section::verdict(band, std::nan(""), std::nan(""), true) == section::Verdict::not_measured);
  // The row naming the section wins over the row for every section.
  const std::vector<section::Tolerance> rows{{"chord", -1, -0.1, 0.1}, {"chord", 2, -0.2, 0.2}};
  CHECK(section::find_tolerance(rows, "chord", 2)->high == 0.2);
  CHECK(section::find_tolerance(rows, "chord", 1)->high == 0.1);
  CHECK(section::find_tolerance(rows, "area", 1) == nullptr);
}

TEST_CASE("compare: a value known to +- U passes or fails only beyond U from its limits", "[compare]") {
  using section::Verdict;
  const section::Tolerance band{"le_radius", -1, -0.02, 0.03};
  const auto judged = [&](double x, double u) { return section::verdict(band, x, x, true, u); };
  // Exact (U = 0): by the value alone, a value on a limit passes.
  CHECK(judged(0.03, 0) == Verdict::pass);
  CHECK(judged(0.0301, 0) == Verdict::fail);
  CHECK(judged(-0.02, 0) == Verdict::pass);
  // U = 0.004: pass inside [-0.016, 0.026], fail outside [-0.024, 0.034], uncertain between.
  for (const auto& [x, expected] : std::vector<std::pair<double, Verdict>>{{0.0, Verdict::pass},
                                                                           {0.0259, Verdict::pass},
                                                                           {0.0261, Verdict::uncertain},
                                                                           {0.03, Verdict::uncertain},
                                                                           {0.0339, Verdict::uncertain},
                                                                           {0.0341, Verdict::fail},
                                                                           {-0.0159, Verdict::pass},
                                                                           {-0.0161, Verdict::uncertain},
                                                                           {-0.0239, Verdict::uncertain},
                                                                           {-0.0241, Verdict::fail}}) {
    INFO("x = " << x);
    CHECK(judged(x, 0.004) == expected);
  }
  // A band narrower than 2 U holds no proven pass; one bound alone guards one side.
  CHECK(judged(0.005, 0.03) == Verdict::uncertain);
  const section::Tolerance most{"te_radius", -1, -std::numeric_limits<double>::infinity(), 0.01};
  CHECK(section::verdict(most, -5, -5, true, 0.004) == Verdict::pass);
  CHECK(section::verdict(most, 0.007, 0.007, true, 0.004) == Verdict::uncertain);
  // An uncertainty that is not a number decides nothing but a clear failure; a hole still
  // wins over uncertain, a failure over a hole.
  CHECK(judged(0.0, std::nan("")) == Verdict::uncertain);
  CHECK(judged(0.5, std::nan("")) == Verdict::fail);
  CHECK(section::verdict(band, 0.028, 0.028, false, 0.004) == Verdict::not_measured);
  CHECK(section::verdict(band, 0.05, 0.05, false, 0.004) == Verdict::fail);
}

TEST_CASE("compare: outliers are left out of the fit and the zones", "[compare]") {
  const Case c = make_case(section::design_family()[0]);
  std::vector<Vector2d> normals;
  std::vector<Vector2d> pts = profile_points(c.truth, 0.05, 0.005, 6, &normals);
  for (std::size_t i : {100u, 700u, 1300u}) pts[i] += 0.3 * normals[i];
  const auto r = section::compare_section(c.nominal, pts, with(FitMethod::minimum_zone));
  CHECK(r.outliers == 3);
  CHECK(r.points[700].outlier);
  CHECK(r.fit.max_after < 0.03);
  CHECK(zone(r, Zone::whole).max < 0.03);
}

TEST_CASE("compare: the whole-blade fit recovers one move of all sections", "[compare]") {
  const section::BladeDesign blade = section::turbine_blade();
  const double angle = 0.08;                     // degrees about z through (5, 3, 0)
  const Eigen::Vector3d shift(0.02, -0.015, 0);  // then this translation
  const Eigen::Vector3d centre(5, 3, 0);
  std::vector<Case> cases;
  std::vector<std::vector<Vector2d>> truth, measured;
  std::vector<section::Frame> frames;
  for (double z : {10.0, 30.0, 50.0}) {
    cases.push_back(make_case(blade.at(z)));
    section::Frame f;
    f.origin = Eigen::Vector3d(0, 0, z);
    frames.push_back(f);
    truth.push_back(profile_points(cases.back().truth, 0.1));
    std::vector<Vector2d> m;
    for (const auto& p : truth.back())
      m.push_back(moved(p - centre.head<2>(), angle, centre.head<2>() + shift.head<2>()));
    measured.push_back(m);
  }
  // One section turned upside down (its normal -z) sees the same move mirrored.
  frames[1].v = -frames[1].v;
  frames[1].n = -frames[1].n;
  for (auto* v : {&truth[1], &measured[1]})
    for (auto& p : *v) p.y() = -p.y();
  cases[1].truth = section::section_truth(blade.at(30), 20000);
  for (auto& p : cases[1].truth.profile) p.y() = -p.y();
  std::reverse(cases[1].truth.profile.begin(), cases[1].truth.profile.end());
  cases[1].nominal.curve = camber_test::dense_spline(cases[1].truth.profile, 2000);
  cases[1].nominal.le_point.y() = -cases[1].nominal.le_point.y();
  cases[1].nominal.te_point.y() = -cases[1].nominal.te_point.y();
  cases[1].nominal.pressure_side = -cases[1].nominal.pressure_side;
  std::vector<section::ComparedSection> sections;
  for (std::size_t i = 0; i < cases.size(); ++i)
    sections.push_back({&cases[i].nominal, &measured[i], frames[i]});
  for (FitMethod m : {FitMethod::least_squares, FitMethod::minimum_zone}) {
    const auto r = section::compare_blade(sections, with(m));
    CHECK(std::abs(r.angle + angle) < 0.001);
    for (std::size_t i = 0; i < cases.size(); ++i) CHECK(recovery_error(r.sections[i], truth[i]) < 0.001);
    // The motion in 3D undoes the move: R (R0 (x - c) + c + t) + T = x.
    const Eigen::Matrix3d r3 = Eigen::AngleAxisd(r.angle * pi / 180, r.axis).toRotationMatrix();
    const Eigen::Matrix3d r0 =
        Eigen::AngleAxisd(angle * pi / 180, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    const Eigen::Vector3d x(12, -4, 30);
    CHECK((r3 * (r0 * (x - centre) + centre + shift) + r.translation - x).norm() < 0.001);
  }
  // Planes that are not parallel cannot share the motion.
  sections[2].frame = section::make_frame(Eigen::Vector3d(0, 0, 50), Eigen::Vector3d(0, 0.1, 1));
  CHECK_THROWS_AS(section::compare_blade(sections), section::Error);
}

TEST_CASE("compare: a prepared nominal gives the same results, shared by concurrent calls", "[compare]") {
  const auto designs = section::design_family();
  for (std::size_t d = 0; d < designs.size(); ++d) {
    const Case c = make_case(designs[d]);
    const section::PreparedNominal prepared = section::prepare_nominal(c.nominal);
    // Noisy moved sections, some with points 0.2 mm off (outliers, left out with their feet kept).
    std::vector<std::vector<Vector2d>> sections;
    for (std::uint64_t seed = 1; seed <= 4; ++seed) {
      std::vector<Vector2d> normals;
      std::vector<Vector2d> pts = profile_points(c.truth, 0.05, 0.005, seed, &normals);
      for (std::size_t i = 0; seed % 2 == 0 && i < pts.size(); i += 97) pts[i] += 0.2 * normals[i];
      for (auto& p : pts) p = moved(p, 0.03 * seed, Vector2d(0.01 * seed, -0.02));
      sections.push_back(pts);
    }
    std::vector<section::SectionComparison> parallel(sections.size());
    std::vector<std::thread> threads;
    for (std::size_t k = 0; k < sections.size(); ++k)
      threads.emplace_back([&, k] { parallel[k] = section::compare_section(prepared, sections[k]); });
    for (auto& t : threads) t.join();
    for (std::size_t k = 0; k < sections.size(); ++k) {
      const auto once = section::compare_section(c.nominal, sections[k]);
      INFO("design " << d << " section " << k);
      CHECK(parallel[k].outliers == once.outliers);
      CHECK((k % 2 == 1) == (once.outliers > 0));
      CHECK(parallel[k].fit.motion.angle == once.fit.motion.angle);
      for (std::size_t i = 0; i < once.points.size(); ++i) {
        CHECK(parallel[k].points[i].after == once.points[i].after);
        CHECK(parallel[k].points[i].t == once.points[i].t);
      }
      // The fit undoes the move (0.03 to 0.12 deg) to within a few um over the chord.
      CHECK(std::abs(once.fit.motion.angle + 0.03 * (k + 1)) < 0.01);
    }
  }
  CompareOptions wider;
  wider.edge_zone = 0.1;
  const Case c = make_case(designs[0]);
  CHECK_THROWS_WITH(
      section::compare_section(section::prepare_nominal(c.nominal), profile_points(c.truth, 0.05), wider),
      Catch::Contains("prepared for an edge zone of 5% of the chord"));
  CHECK_THROWS_WITH(section::compare_section(section::PreparedNominal{}, profile_points(c.truth, 0.05)),
                    Catch::Contains("has not been prepared"));
}

// SPDX-License-Identifier: GPL-3.0-or-later
// Tests of the camber line (section/camber.h) against exact ground truth (sections built
// as envelopes of circles), its orientation, profiles that are not blades, and the stream
// stage's tables and issues.
#include "section/camber.h"

#include "camber_fixtures.h"
#include "section/checks.h"
#include "section/error.h"
#include "section/extras/generate.h"
#include "section/fit_spline.h"
#include "section/io/stream.h"
#include "section/params.h"
#include "section/pipe/camber_stream.h"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <string>
#include <vector>

using namespace camber_test;

TEST_CASE("camber: envelope-of-circles sections give the true camber line and parameters", "[camber]") {
  int k = 0;
  for (const SectionDesign& d : designs()) {
    CAPTURE(k++);
    const SectionTruth truth = section::section_truth(d, 20000);
    const BSpline profile = dense_spline(truth.profile);
    // The spline's own end slopes: exact to 1e-4 deg on exact profiles (the default end
    // tangents, fitted over 10% of the axis for noise, are checked in test_pipeline.cpp).
    section::CamberOptions exact;
    exact.tangent_span = 0;
    const section::CamberResult c = section::camber_line(profile, exact);
    const section::SectionParams p = section::section_params(profile, c);

    double worst = 0;
    for (const Vector2d& q : c.points) worst = std::max(worst, section::camber_distance(truth, q));
    CHECK(worst < 1e-3);  // 1 um
    CHECK((p.le_point - truth.le_point).norm() < 1e-3);
    CHECK((p.te_point - truth.te_point).norm() < 1e-3);
    CHECK((c.le.center - truth.le_center).norm() < 1e-3);
    CHECK((c.te.center - truth.te_center).norm() < 1e-3);

    CHECK(relative(p.chord, truth.chord) < 1e-4);
    CHECK(relative(p.camber_length, truth.camber_length) < 1e-4);
    CHECK(relative(p.max_thickness, truth.max_thickness) < 1e-4);
    CHECK(relative(p.max_thickness_pos, truth.max_thickness_pos) < 1e-4);
    CHECK(relative(p.le_radius, truth.le_radius) < 1e-4);
    // The grown edge arc reaches the arc-flank junction, where the spline's O(h^2) error
    // of the curvature jump sits: 1.4e-4 on the thinnest (0.15 mm) trailing edge = 20 nm.
    CHECK(relative(p.te_radius, truth.te_radius) < 2e-4);
    CHECK(relative(p.area, truth.area) < 1e-4);
    CHECK((p.centroid - truth.centroid).norm() < 1e-4 * truth.chord);
    CHECK(relative(p.stagger, truth.stagger) < 1e-4);
    // Angles: 1e-4 relative of the larger of the angle and 45 degrees (the outlet angle of a
    // thin trailing edge carries ~0.005 deg from the spline fit of the edge junction).
    CHECK(std::abs(p.inlet_angle - truth.inlet_angle) < 1e-4 * std::max(std::abs(truth.inlet_angle), 45.0));
    CHECK(std::abs(p.outlet_angle - truth.outlet_angle) <
          1e-4 * std::max(std::abs(truth.outlet_angle), 45.0));
    CHECK(std::abs(p.camber_angle - (truth.inlet_angle - truth.outlet_angle)) < 1e-2);
    // The curvature radius at the edge point carries the spline's O(h^2) curvature error.
    CHECK(relative(p.le_curvature_radius, truth.le_radius) < 3e-3);
    CHECK(relative(p.te_curvature_radius, truth.te_radius) < 3e-3);
    CHECK(c.le.shape == section::EdgeShape::round);
    CHECK(c.te.shape == section::EdgeShape::round);
    CHECK_FALSE(c.le_by_direction);
  }
}

TEST_CASE("camber: orientation follows the thickness or the given direction", "[camber]") {
  const SectionTruth truth = section::section_truth(SectionDesign{}, 8000);
  const BSpline profile = dense_spline(truth.profile, 800);
  const section::CamberResult c = section::camber_line(profile);
  CHECK((c.le.point - truth.le_point).norm() < 1e-2);
  // The pressure side is the concave one: the camber line bulges away from it, so at
  // mid-camber the pressure side lies on the chord's side of the camber line.
  const section::Sides sides = section::split_sides(profile, c, 101);
  const Vector2d chord = (c.te.point - c.le.point).normalized();
  const std::size_t mid = c.points.size() / 2;
  const Vector2d tangent = (c.points[mid + 1] - c.points[mid - 1]).normalized();
  auto cross = [](const Vector2d& u, const Vector2d& v) { return u.x() * v.y() - u.y() * v.x(); };
  const double bulge = cross(chord, c.points[mid] - c.le.point);
  CHECK(cross(tangent, sides.pressure[50] - c.points[mid]) * bulge < 0);
  CHECK(cross(tangent, sides.suction[50] - c.points[mid]) * bulge > 0);
  CHECK((sides.pressure.front() - c.le.point).norm() < 1e-9);
  CHECK((sides.pressure.back() - c.te.point).norm() < 1e-9);

  section::CamberOptions o;
  o.le_direction = direction(truth.stagger);  // point at the TE instead: the ends swap
  const section::CamberResult f = section::camber_line(profile, o);
  CHECK(f.le_by_direction);
  CHECK((f.le.point - truth.te_point).norm() < 1e-2);
  CHECK((f.te.point - truth.le_point).norm() < 1e-2);
}

TEST_CASE("camber: a circle and a square are not blades", "[camber]") {
  std::vector<Vector2d> circle, square;
  for (int i = 0; i < 2000; ++i) {
    const double t = 2 * pi * i / 2000;
    circle.push_back({5 * std::cos(t), 5 * std::sin(t)});
  }
  for (int side = 0; side < 4; ++side)
    for (int i = 0; i < 500; ++i) {
      const double s = -5 + 10.0 * i / 500;
      const Vector2d q[4] = {{s, -5}, {5, s}, {-s, 5}, {-5, -s}};
      square.push_back(q[side]);
    }
  CHECK_THROWS_WITH(section::camber_line(dense_spline(circle, 400)), Catch::Contains("not blade-like"));
  CHECK_THROWS_AS(section::camber_line(dense_spline(square, 400)), section::Error);
}

TEST_CASE("camber: stream stage writes the tables and flags a two-loop section", "[camber]") {
  const SectionTruth truth = section::section_truth(section::compressor_blade().at(30), 8000);
  const BSpline profile = dense_spline(truth.profile, 800);
  section::Stream stream = section::profile_stream(profile);
  section::CamberOptions o;
  o.stations = {0.25, 0.5, 0.75};
  section::camber_stream(stream, o);
  REQUIRE(stream.find("params"));
  CHECK(stream.find("params")->rows() == 1);
  CHECK(stream.find("thickness")->rows() == 3);
  CHECK(stream.find("camber")->rows() == static_cast<std::size_t>(o.samples));
  CHECK(stream.find("sides")->rows() == static_cast<std::size_t>(2 * o.side_samples));
  const section::Table& params = *stream.find("params");
  CHECK(relative(params.at(0, params.column("chord")), truth.chord) < 1e-3);
  CHECK(stream.issues.empty());

  // A second loop in section 0: an issue, no made-up camber line.
  section::Stream two = section::profile_stream(profile);
  for (const char* name : {"splines", "spline_knots", "spline_ctrl"}) {
    section::Table* t = two.find(name);
    const std::size_t rows = t->rows(), loop = t->column("loop");
    for (std::size_t r = 0; r < rows; ++r) {
      std::vector<double> row(t->values.begin() + r * t->columns.size(),
                              t->values.begin() + (r + 1) * t->columns.size());
      row[loop] = 1;
      t->add_row(row);
    }
  }
  section::camber_stream(two, o);
  CHECK(two.find("params")->rows() == 0);
  REQUIRE(two.issues.size() == 1);
  CHECK(two.issues[0].stage == "camber");
  CHECK(two.issues[0].message.find("2 loops") != std::string::npos);
  CHECK(two.issues[0].message.find("cut off") == std::string::npos);  // a loop as large as the profile

  // A small loop just past the trailing edge: the message says where it lies and what it
  // usually is.
  section::Stream cut = section::profile_stream(profile);
  std::vector<Vector2d> blob;
  const Vector2d centre = truth.te_point + 0.8 * (truth.te_point - truth.te_center).normalized();
  for (int i = 0; i < 200; ++i) {
    const double a = 2 * pi * i / 200;
    blob.push_back(centre + 0.5 * Vector2d(std::cos(a), std::sin(a)));
  }
  const BSpline piece = dense_spline(blob, 40);
  cut.find("splines")->add_row({0, 1, 3, 1, double(piece.control.size()), 0, 0, 0, 0});
  for (std::size_t i = 0; i < piece.knots.size(); ++i)
    cut.find("spline_knots")->add_row({0, 1, double(i), piece.knots[i]});
  for (std::size_t i = 0; i < piece.control.size(); ++i)
    cut.find("spline_ctrl")->add_row({0, 1, double(i), piece.control[i].x(), piece.control[i].y()});
  section::camber_stream(cut, o);
  REQUIRE(cut.issues.size() == 1);
  CAPTURE(cut.issues[0].message);
  CHECK(cut.issues[0].message.find("loop 1: area 0.78") != std::string::npos);
  CHECK(cut.issues[0].message.find("cut off by a gap") != std::string::npos);

  // Slice found two loops (table loops), fitspline fitted loop 0 alone: loop 0 may be only a
  // piece of the profile (a 10 mm hole along a suction side split a turbine section in two,
  // and camber measured the TE piece: chord 19 mm of 40.6, max thickness and area unflagged).
  section::Stream split = section::profile_stream(profile);
  split.put(
      section::Table("loops", {"section", "loop", "points", "area"}, {0, 0, 900, 120.5, 0, 1, 700, 36.6}));
  section::camber_stream(split, o);
  CHECK(split.find("params")->rows() == 0);
  REQUIRE(split.issues.size() == 1);
  CAPTURE(split.issues[0].message);
  CHECK(split.issues[0].message.find("2 loops") != std::string::npos);
  CHECK(split.issues[0].message.find("loop 1: area 36.6 mm2, not fitted") != std::string::npos);
}

TEST_CASE("camber: a whole stream's notes flag every row, once, unless checked across parts", "[camber]") {
  // A doubtful unit and an unconfirmed registration, as slice notes them: camber_stream on a
  // whole stream (a program's, the Python module's) flags the rows as the camber tool does.
  const SectionTruth truth = section::section_truth(section::compressor_blade().at(30), 4000);
  const BSpline profile = dense_spline(truth.profile, 600);
  const auto noted = [&] {
    section::Stream s = section::profile_stream(profile);
    s.notes = {"units_doubtful in (read as mm; the extent suggests inches)",
               "register view=b.ply translation=0,0,0 rotation=0,0,0 unconfirmed=1"};
    return s;
  };
  const auto flags_of = [](const section::Stream& s) {
    const section::Table& t = *s.find("params");
    REQUIRE(t.rows() == 1);
    return static_cast<section::CheckBits>(t.at(0, t.column("flags")));
  };
  const section::CheckBits both =
      section::bit(section::Check::units) | section::bit(section::Check::registration);
  section::Stream whole = noted();
  section::camber_stream(whole);
  CHECK((flags_of(whole) & both) == both);
  // Every value: each thickness station's row too.
  const section::Table& stations = *whole.find("thickness");
  REQUIRE(stations.rows() > 0);
  for (std::size_t r = 0; r < stations.rows(); ++r)
    CHECK((static_cast<section::CheckBits>(stations.at(r, stations.column("flags"))) & both) == both);
  REQUIRE(whole.issues.size() == 2);
  CHECK(whole.issues[0].message.find("fail check units") != std::string::npos);
  CHECK(whole.issues[1].message.find("fail check registration") != std::string::npos);
  // Flagged again (a caller's own hold step): the same bits, no second issue.
  section::flag_doubtful_units(whole);
  section::flag_unconfirmed_registration(whole);
  section::check_blade_stream({&whole});
  CHECK(whole.issues.size() == 2);
  // One part of a split stream: left to the check across the parts.
  section::Stream part = noted();
  section::CamberOptions o;
  o.across_sections = false;
  section::camber_stream(part, o);
  CHECK((flags_of(part) & both) == 0);
  CHECK(part.issues.empty());
}

TEST_CASE("camber: a 3D leading-edge direction is projected onto each section's plane", "[camber]") {
  const SectionTruth truth = section::section_truth(section::compressor_blade().at(30), 4000);
  const BSpline profile = dense_spline(truth.profile, 600);
  // The section's plane is the 3D y-z plane (u = z, v = x, normal = y): the true LE-to-TE
  // direction in (u, v) is a 3D direction there.
  const Vector2d along = truth.le_point - truth.te_point;
  const Eigen::Vector3d u(0, 0, 1), v(1, 0, 0);
  const Eigen::Vector3d upstream =
      along.x() * u + along.y() * v + Eigen::Vector3d(0, 5, 0);  // plus a normal part
  for (const double sign : {1.0, -1.0}) {
    section::Stream stream = section::profile_stream(profile);
    stream.put(section::Table{"frames",
                              {"section", "origin_x", "origin_y", "origin_z", "u_x", "u_y", "u_z", "v_x",
                               "v_y", "v_z", "n_x", "n_y", "n_z"},
                              {0, 0, 0, 0, u.x(), u.y(), u.z(), v.x(), v.y(), v.z(), 0, 1, 0}});
    section::CamberOptions options;
    options.le_direction_3d = sign * upstream;
    section::camber_stream(stream, options);
    const section::Table& params = *stream.find("params");
    REQUIRE(params.rows() == 1);
    const Vector2d le(params.at(0, params.column("le_u")), params.at(0, params.column("le_v")));
    INFO("sign " << sign << ": LE point " << le.transpose());
    CHECK(params.at(0, params.column("le_by_direction")) == 1);
    CHECK((le - (sign > 0 ? truth.le_point : truth.te_point)).norm() < 0.01);
  }
  // A direction along the plane's normal cannot choose: the section gets an issue.
  section::Stream stream = section::profile_stream(profile);
  section::CamberOptions options;
  options.le_direction_3d = Eigen::Vector3d(0, 0, 2);  // no frames table: the plane is x, y
  section::camber_stream(stream, options);
  CHECK(stream.find("params")->rows() == 0);
  REQUIRE(stream.issues.size() == 1);
  CHECK(stream.issues[0].message.find("normal to the plane of section 0") != std::string::npos);
}

TEST_CASE("camber: an LE chosen by thickness near mid-chord is reported as a guess", "[camber]") {
  for (const double position : {0.3, 0.5}) {
    SectionDesign design = section::compressor_blade().at(30);
    design.max_thickness_pos = position;
    const SectionTruth truth = section::section_truth(design, 4000);
    const BSpline profile = dense_spline(truth.profile, 600);
    for (const bool given : {false, true}) {
      section::Stream stream = section::profile_stream(profile);
      section::CamberOptions options;
      if (given) options.le_direction = truth.le_point - truth.te_point;
      section::camber_stream(stream, options);
      REQUIRE(stream.find("params")->rows() == 1);
      std::string messages;
      for (const auto& issue : stream.issues) messages += issue.message + "; ";
      INFO("maximum thickness at " << position << ", direction given " << given << ": " << messages);
      CHECK((messages.find("too near mid-chord") != std::string::npos) == (position == 0.5 && !given));
    }
  }
}

TEST_CASE("camber: a medial branch that stops short of an edge centre is bridged on the axis", "[camber]") {
  // A fitted compressor section (8 um of noise) and the skeleton slice made of it, whose
  // medial branch ends 2.9 mm before the trailing-edge centre. Bridged by the axis spline
  // alone, the line bulged 0.25 mm off the axis there (a 0.18 mm kink between samples, no
  // warning then); marched with inscribed circles, the line runs smooth, on the axis, and
  // no issue is raised.
  section::Stream s = section::read_stream(std::string(SECTION_TEST_DATA) + "/camber_short_branch.csv");
  section::camber_stream(s);
  for (const auto& issue : s.issues)
    CHECK(issue.message.find("strays from the medial axis") == std::string::npos);
  const section::Table& t = s.get("camber", "test");
  const std::size_t cu = t.column("u"), cv = t.column("v");
  std::vector<Vector2d> p;
  for (std::size_t r = 0; r < t.rows(); ++r) p.emplace_back(t.at(r, cu), t.at(r, cv));
  REQUIRE(p.size() > 100);
  double kink = 0;
  for (std::size_t k = 1; k + 1 < p.size(); ++k)
    kink = std::max(kink, (p[k + 1] - 2 * p[k] + p[k - 1]).norm());
  INFO("largest second difference " << kink * 1e3 << " um");
  CHECK(kink < 0.02);
}

TEST_CASE("camber: a finger the spline leaves beside a trailing edge is measured through or flagged",
          "[camber]") {
  // A bump of `height` edge radii, 0.12 R wide, a quarter radius to either side of the
  // TE point: the medial branch runs on into it past the edge centre. Up to 6 % of R
  // (12 um on a 0.2 mm edge) the edge is measured as without it; a taller one may take
  // the edge circle, which then subtends too little of the flanks' turning and is flagged.
  for (double side : {-1.0, 1.0})
    for (double height : {0.03, 0.06, 0.1}) {
      int k = 0;
      for (const SectionDesign& d : designs()) {
        CAPTURE(side, height, k++);
        const SectionTruth truth = section::section_truth(d, 20000);
        std::vector<Vector2d> pts = truth.profile;
        const double r = truth.te_radius, at = truth.te_s + side * 0.25 * r, width = 0.12 * r;
        for (std::size_t i = 0; i < pts.size(); ++i) {
          const double x = (truth.profile_s[i] - at) / width;
          pts[i] += height * r * std::exp(-0.5 * x * x) * truth.profile_normal[i];
        }
        const BSpline spline = dense_spline(pts);
        const section::CamberResult c = section::camber_line(spline);
        const section::SectionParams p = section::section_params(spline, c);
        const section::CheckBits te_flags =
            section::bit(section::Check::te_circle) | section::bit(section::Check::te_radius);
        const bool flag = (section::check_section(spline, c, p).flags & te_flags) != 0;
        const bool good = std::abs(p.outlet_angle - truth.outlet_angle) < 0.5 &&
                          relative(p.te_radius, r) < 0.1 && (c.te.center - truth.te_center).norm() < 0.1 * r;
        CAPTURE(p.outlet_angle - truth.outlet_angle, relative(p.te_radius, r), c.te.arc);
        if (height <= 0.06) CHECK(good);
        CHECK((good || flag));
        CHECK_FALSE((good && flag));
      }
    }
}

TEST_CASE("camber: an axis turning past 90 degrees keeps its far end beside each edge", "[camber]") {
  // The turbine's tip twisted 40 degrees with its metal angles kept (evaluate_pipeline
  // --twist 40): 108 degrees of turning at a stagger of 26, so the TE's outward direction
  // points back past the LE centre. Dropping the circles beyond the TE centre then cut the
  // LE fifth of the axis off and no check saw it: here camber line 0.33 mm off, inlet
  // angle 3.9 degrees, chord 0.11 mm short (z = 54 in the pipeline: 0.23 mm, 3.0 deg).
  SectionDesign d;
  d.chord = 38;
  d.stagger = 26;
  d.inlet_angle = 40;
  d.outlet_angle = -68;
  d.le_radius = 1.8;
  d.te_radius = 0.45;
  d.max_thickness = 7;
  d.max_thickness_pos = 0.32;
  const SectionTruth truth = section::section_truth(d, 20000);
  const Vector2d te_out(std::cos(truth.outlet_angle * pi / 180), std::sin(truth.outlet_angle * pi / 180));
  REQUIRE((truth.le_center - truth.te_center).dot(te_out) > 0);  // the case this test is for
  const BSpline profile = dense_spline(truth.profile);
  const section::CamberResult c = section::camber_line(profile);  // default end tangents
  const section::SectionParams p = section::section_params(profile, c);
  double worst = 0;
  for (const Vector2d& q : c.points) worst = std::max(worst, section::camber_distance(truth, q));
  CHECK(worst < 5e-3);
  CHECK(std::abs(p.inlet_angle - truth.inlet_angle) < 0.3);
  CHECK(std::abs(p.outlet_angle - truth.outlet_angle) < 0.3);
  CHECK(std::abs(p.chord - truth.chord) < 5e-3);
  CHECK((p.le_point - truth.le_point).norm() < 5e-3);
}

TEST_CASE("camber: a plain profile's sparse noisy points flag its thickness (noise), exact ones not",
          "[camber]") {
  // A CMM row: points 0.05 mm apart within 4 mm of either edge point, 2 mm apart between.
  // Fitted, the spline has about a coefficient a point mid-chord and follows their noise
  // there, where the thickness is measured (T-Blade3 rows: 10-29 um off, unflagged before):
  // 2 um of noise, which the fit's share of coefficients over the whole profile passes.
  const section::SectionTruth truth = section::section_truth(section::compressor_blade().at(30), 40000);
  std::vector<Eigen::Vector2d> exact, noisy;
  std::mt19937 rng(5);
  std::normal_distribution<double> noise(0, 0.002);
  for (std::size_t i = 0, next = 0; i < truth.profile.size(); ++i) {
    const double s = truth.profile_s[i];
    const double from_edge = std::min({s, std::abs(s - truth.te_s), truth.perimeter - s});
    if (double(next) > s * 1e3) continue;  // next: the arc length of the next point, in um
    exact.push_back(truth.profile[i]);
    noisy.push_back(truth.profile[i] + noise(rng) * truth.profile_normal[i]);
    next = std::size_t(1e3 * (s + (from_edge < 4 ? 0.05 : 2.0)));
  }
  REQUIRE(exact.size() > 150);
  for (const bool with_noise : {false, true}) {
    const std::vector<Eigen::Vector2d>& points = with_noise ? noisy : exact;
    const section::FitSplineResult fit = section::fit_spline(points, points);
    section::Stream s = section::profile_stream(fit.spline, fit.rms, points);
    section::camber_stream(s);
    const section::Table& params = s.get("params", "test");
    REQUIRE(params.rows() == 1);
    const auto flags = static_cast<section::CheckBits>(params.at(0, params.column("flags")));
    INFO("noise " << with_noise << ": flags " << section::check_names_text(flags) << ", max thickness "
                  << params.at(0, params.column("max_thickness")) << " against " << truth.max_thickness);
    CHECK(((flags & section::bit(section::Check::noise)) != 0) == with_noise);
    if (!with_noise)
      CHECK(std::abs(params.at(0, params.column("max_thickness")) - truth.max_thickness) < 0.005);
  }
}

TEST_CASE("camber: a dense profile's noise that leaves it uncertain beyond the accuracy flags it (noise)",
          "[camber]") {
  // Points every 0.03 mm (a drift band's): the fit averages their noise over the points each
  // coefficient rests on, and its rms is that noise. 5 um leaves the profile within 1.5e-4
  // of its size (6 um here); 20 um does not: the max thickness was off by 6-10 um, the chord
  // by 14-17 um, unflagged.
  const section::SectionTruth truth = section::section_truth(section::turbine_blade().at(30), 40000);
  for (const double sigma : {0.005, 0.02}) {
    std::vector<Eigen::Vector2d> points;
    std::mt19937 rng(11);
    std::normal_distribution<double> noise(0, sigma);
    for (std::size_t i = 0, next = 0; i < truth.profile.size(); ++i) {
      if (double(next) > truth.profile_s[i] * 1e3) continue;  // next: the next point's arc length, in um
      points.push_back(truth.profile[i] + noise(rng) * truth.profile_normal[i]);
      next = std::size_t(1e3 * (truth.profile_s[i] + 0.03));
    }
    const section::FitSplineResult fit = section::fit_spline(points, points);
    REQUIRE(points.size() >= 16 * fit.spline.control.size());  // many points a coefficient
    section::Stream s = section::profile_stream(fit.spline, fit.rms, points);
    section::camber_stream(s);
    const section::Table& params = s.get("params", "test");
    REQUIRE(params.rows() == 1);
    const auto flags = section::flags_mask(params.at(0, params.column("flags")));
    INFO("noise " << sigma << " mm: fit rms " << fit.rms << ", " << fit.spline.control.size()
                  << " control points, flags " << section::check_names_text(flags));
    CHECK(((flags & section::bit(section::Check::noise)) != 0) == (sigma > 0.01));
    if (sigma > 0.01)
      CHECK(std::any_of(s.issues.begin(), s.issues.end(), [](const section::SectionIssue& i) {
        return i.message.find("the points' noise (the fit's rms) leaves the profile uncertain") !=
               std::string::npos;
      }));
  }
}

namespace {

// A row of the thickness table: its contacts and whether its flags say a hole.
struct Station {
  double fraction;
  Eigen::Vector2d pressure, suction;
  bool unmeasured;
};

std::vector<Station> stations(const section::Stream& s) {
  const section::Table& t = s.get("thickness", "test");
  auto at = [&](std::size_t r, const char* c) { return t.at(r, t.column(c)); };
  std::vector<Station> out;
  for (std::size_t r = 0; r < t.rows(); ++r)
    out.push_back(
        {at(r, "fraction"),
         {at(r, "pressure_u"), at(r, "pressure_v")},
         {at(r, "suction_u"), at(r, "suction_v")},
         (section::flags_mask(at(r, "flags")) & section::bit(section::Check::thickness_measured)) != 0});
  return out;
}

}  // namespace

TEST_CASE(
    "camber: the thickest circle touching a hole in the data flags the max thickness "
    "(thickness_measured), and each thickness station touching one its row; a measured one or evenly "
    "sparse points not",
    "[camber]") {
  // A turbine section's exact profile, a point every 0.08 mm (a dense scan's spacing).
  const section::SectionTruth truth = section::section_truth(section::turbine_blade().at(30), 40000);
  std::vector<Eigen::Vector2d> dense;
  for (std::size_t i = 0, next = 0; i < truth.profile.size(); ++i) {
    if (double(next) > truth.profile_s[i] * 1e3) continue;  // next: the next point's arc length, in um
    dense.push_back(truth.profile[i]);
    next = std::size_t(1e3 * (truth.profile_s[i] + 0.08));
  }
  const auto measured = [](const std::vector<Eigen::Vector2d>& points) {
    const section::FitSplineResult fit = section::fit_spline(points, points);
    section::Stream s = section::profile_stream(fit.spline, fit.rms, points);
    section::camber_stream(s);
    return s;
  };
  const auto flagged = [](const section::Stream& s) {
    const section::Table& params = s.get("params", "test");
    REQUIRE(params.rows() == 1);
    const auto flags = section::flags_mask(params.at(0, params.column("flags")));
    return (flags & section::bit(section::Check::thickness_measured)) != 0;
  };
  const section::Stream whole = measured(dense);
  CHECK_FALSE(flagged(whole));
  for (const Station& st : stations(whole)) CHECK_FALSE(st.unmeasured);
  // The contacts of the thickest circle, from the same profile measured whole.
  const section::CamberResult c = section::camber_line(section::fit_spline(dense, dense).spline);
  for (const Eigen::Vector2d contact : {c.thickest.left, c.thickest.right}) {
    // Holes 1 and 4 mm across at the contact (the chord is 40.4 mm: 0.05 of it is 2 mm).
    for (const double across : {1.0, 4.0}) {
      std::vector<Eigen::Vector2d> holed;
      for (const auto& p : dense)
        if ((p - contact).norm() > across / 2) holed.push_back(p);
      const section::Stream s = measured(holed);
      INFO("a hole " << across << " mm across at (" << contact.transpose() << ")");
      CHECK(flagged(s) == (across > 2));
      if (across > 2)
        CHECK(std::any_of(s.issues.begin(), s.issues.end(), [](const section::SectionIssue& i) {
          return i.message.find("fails check thickness_measured") != std::string::npos;
        }));
      // Each thickness station by its own circle: flagged with a contact in the hole, not
      // with both farther than the hole and half the limit (1 mm) beyond it.
      const auto rows = stations(s);
      REQUIRE(rows.size() == 19);
      for (const Station& st : rows) {
        const double from_hole = std::min((st.pressure - contact).norm(), (st.suction - contact).norm());
        INFO("station " << st.fraction << ", " << from_hole << " mm from the hole's centre");
        if (across < 2 || from_hole > across / 2 + 1.5)
          CHECK_FALSE(st.unmeasured);
        else if (from_hole < across / 2)
          CHECK(st.unmeasured);
      }
    }
  }
  // Points 2.5 mm apart all along (a CMM row): every stretch is that long, none a hole.
  std::vector<Eigen::Vector2d> sparse;
  for (std::size_t i = 0, next = 0; i < truth.profile.size(); ++i) {
    const double s = truth.profile_s[i];
    if (double(next) > s * 1e3) continue;
    sparse.push_back(truth.profile[i]);
    const double from_edge = std::min({s, std::abs(s - truth.te_s), truth.perimeter - s});
    next = std::size_t(1e3 * (s + (from_edge < 4 ? 0.05 : 2.5)));
  }
  const section::Stream row = measured(sparse);
  CHECK_FALSE(flagged(row));
  for (const Station& st : stations(row)) CHECK_FALSE(st.unmeasured);
}

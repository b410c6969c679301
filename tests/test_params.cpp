// SPDX-License-Identifier: GPL-3.0-or-later
// Tests of the section parameters (section/params.h): thickness stations against the
// true inscribed diameters, the enclosed area of a circle.
#include "section/params.h"

#include "camber_fixtures.h"
#include "section/error.h"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <vector>

using namespace camber_test;

TEST_CASE("params: thickness stations match the true inscribed diameters", "[params]") {
  const SectionTruth truth = section::section_truth(section::turbine_blade().at(30), 20000);
  const BSpline profile = dense_spline(truth.profile);
  const section::CamberResult c = section::camber_line(profile);
  const std::vector<double> fractions{0.05, 0.1, 0.3, 0.5, 0.7, 0.9, 0.95};
  const auto stations = section::thickness_stations(profile, c, fractions);
  REQUIRE(stations.size() == fractions.size());
  // Truth at the same arc-length fraction of the true camber line.
  std::vector<double> s{0};
  for (std::size_t i = 1; i < truth.camber.size(); ++i)
    s.push_back(s.back() + (truth.camber[i] - truth.camber[i - 1]).norm());
  for (const auto& st : stations) {
    CAPTURE(st.fraction);
    const double target = st.fraction * s.back();
    const std::size_t i = std::upper_bound(s.begin(), s.end(), target) - s.begin();
    const double w = (target - s[i - 1]) / (s[i] - s[i - 1]);
    const Vector2d point = (1 - w) * truth.camber[i - 1] + w * truth.camber[i];
    const double thickness = 2 * ((1 - w) * truth.camber_radius[i - 1] + w * truth.camber_radius[i]);
    CHECK((st.point - point).norm() < 1e-3);
    CHECK(relative(st.thickness, thickness) < 1e-4);
    CHECK(std::abs((st.pressure - st.point).norm() - st.thickness / 2) < 1e-6);
    CHECK(std::abs((st.suction - st.point).norm() - st.thickness / 2) < 1e-6);
  }
}

TEST_CASE("params: stations microns from an edge point are measured across the profile", "[params]") {
  // A station 2 um short of the trailing edge point (on a 48 mm camber line) lay outside the
  // sampled polygon, whose chords cut the edge's arc: the rays across missed it, and the
  // section lost every param. The crossings are now found on the exact profile.
  const SectionTruth truth = section::section_truth(section::turbine_blade().at(30), 20000);
  const BSpline profile = dense_spline(truth.profile);
  const section::CamberResult c = section::camber_line(profile);
  for (int edge = 0; edge < 2; ++edge) {
    double last = 0;
    for (double depth : {0.02, 0.005, 0.002}) {  // mm from the edge point, inward
      CAPTURE(edge, depth);
      const double fraction = edge == 0 ? depth / c.length : 1 - depth / c.length;
      std::vector<section::ThicknessStation> st;
      REQUIRE_NOTHROW(st = section::thickness_stations(profile, c, {fraction}));
      const Vector2d tangent = edge == 0 ? c.le_tangent : c.te_tangent;
      for (const Vector2d& side : {st[0].pressure, st[0].suction}) {
        CHECK(section::locate(truth, side).distance < 1e-4);
        CHECK(std::abs((side - st[0].point).dot(tangent)) < 1e-6);
      }
      CHECK(st[0].thickness == Approx((st[0].pressure - st[0].suction).norm()));
      if (last > 0) CHECK(st[0].thickness < last);  // narrower toward the edge point
      last = st[0].thickness;
    }
  }
}

TEST_CASE("params: a thickness station outside [0, 1] is refused", "[params]") {
  const SectionTruth truth = section::section_truth(SectionDesign{}, 8000);
  const BSpline profile = dense_spline(truth.profile, 800);
  const section::CamberResult c = section::camber_line(profile);
  CHECK(section::thickness_stations(profile, c, {0.05, 0.95}).size() == 2);
  CHECK_THROWS_WITH(section::thickness_stations(profile, c, {0.5, 1.5}), Catch::Contains("outside [0, 1]"));
}

TEST_CASE("params: the enclosed area and centroid of a circle", "[params]") {
  // Radius 5 about (2, -1), counterclockwise; reversed, the area changes sign.
  std::vector<Vector2d> pts;
  for (int i = 0; i < 2000; ++i) {
    const double t = 2 * pi * i / 2000;
    pts.push_back(Vector2d(2, -1) + 5 * Vector2d(std::cos(t), std::sin(t)));
  }
  Vector2d centroid;
  const double area = section::enclosed_area(dense_spline(pts, 400), &centroid);
  CHECK(relative(area, 25 * pi) < 1e-6);
  CHECK((centroid - Vector2d(2, -1)).norm() < 1e-6);
  std::reverse(pts.begin(), pts.end());
  CHECK(relative(section::enclosed_area(dense_spline(pts, 400)), -25 * pi) < 1e-6);
}

// SPDX-License-Identifier: GPL-3.0-or-later
// Tests of the medial axis (section/medial_axis.h) against exact ground truth: an
// ellipse's medial axis and inscribed circles; the sampled profile's searches against full
// scans.
#include "section/medial_axis.h"
#include "section/error.h"

#include "camber_fixtures.h"
#include "detail/sampled_profile.h"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

using namespace camber_test;

TEST_CASE("medial_axis: an ellipse's medial axis is the segment between its vertex curvature centres",
          "[medial_axis]") {
  for (const auto& [a, b] : {std::pair{10.0, 4.0}, std::pair{6.0, 1.5}}) {
    CAPTURE(a, b);
    std::vector<Vector2d> pts;
    const int n = 20000;
    for (int i = 0; i < n; ++i) {
      const double t = 2 * pi * i / n;
      pts.push_back({a * std::cos(t), b * std::sin(t)});
    }
    const BSpline profile = dense_spline(pts);
    const section::MedialAxis m = section::medial_axis(profile);
    const double end = (a * a - b * b) / a;
    double lo = 1e300, hi = -1e300, off = 0;
    for (const auto& c : m.circles) {
      lo = std::min(lo, c.center.x());
      hi = std::max(hi, c.center.x());
      off = std::max(off, std::abs(c.center.y()));
      // Inscribed radius at (x, 0): distance to the ellipse, b sqrt(1 - x^2 / (a^2 - b^2)).
      CHECK(std::abs(c.radius -
                     b * std::sqrt(std::max(0.0, 1 - c.center.x() * c.center.x() / (a * a - b * b)))) < 1e-5);
    }
    CHECK(off < 1e-9);
    // The ends are the vertices' centres of curvature, up to the spline's curvature error.
    CHECK(std::abs(lo + end) < 2e-4 * a);
    CHECK(std::abs(hi - end) < 2e-4 * a);
  }
}

TEST_CASE("medial_axis: an inscribed circle on an ellipse's major axis has the true radius",
          "[medial_axis]") {
  // Ellipse 10 x 4: the circle centred on the line x = 3 touching both sides is centred on
  // the major axis, its radius b sqrt(1 - x^2 / (a^2 - b^2)).
  const double a = 10, b = 4;
  std::vector<Vector2d> pts;
  for (int i = 0; i < 20000; ++i) {
    const double t = 2 * pi * i / 20000;
    pts.push_back({a * std::cos(t), b * std::sin(t)});
  }
  const BSpline profile = dense_spline(pts);
  const double t_left = section::closest_point(profile, {3, b}).t;
  const double t_right = section::closest_point(profile, {3, -b}).t;
  section::InscribedCircle c;
  REQUIRE(section::inscribed_circle(profile, {3, 1}, {0, 2}, t_left, t_right, c));
  CHECK((c.center - Vector2d(3, 0)).norm() < 1e-6);
  CHECK(std::abs(c.radius - b * std::sqrt(1 - 9 / (a * a - b * b))) < 1e-6);
  CHECK(c.left.y() > 0);
  CHECK(c.right.y() < 0);
  CHECK(std::abs((c.left - c.center).norm() - (c.right - c.center).norm()) < 1e-9);
}

TEST_CASE("sampled profile: a sample nearer a point than r, on an ellipse", "[medial_axis]") {
  // Ellipse 10 x 4: a point (x, 0) with |x| < (a^2 - b^2) / a is b sqrt(1 - x^2 / (a^2 - b^2))
  // from it; (20, 0) is 10 from the vertex (10, 0).
  const double a = 10, b = 4;
  std::vector<Vector2d> pts;
  for (int i = 0; i < 20000; ++i)
    pts.push_back({a * std::cos(2 * pi * i / 20000), b * std::sin(2 * pi * i / 20000)});
  const BSpline profile = dense_spline(pts);
  const section::detail::SampledProfile pr(profile, 1000);
  std::vector<std::pair<Vector2d, double>> cases = {{{20, 0}, 10}, {{-20, 3}, std::hypot(10.0, 3.0)}};
  for (const double x : {0.0, 1.5, -3.0, 5.0, 8.0})
    cases.push_back({{x, 0}, b * std::sqrt(1 - x * x / (a * a - b * b))});
  for (const auto& [q, d] : cases) {
    CAPTURE(q.x(), q.y(), d);
    CHECK_FALSE(pr.sample_within(q, 0.99 * d));
    CHECK(pr.sample_within(q, 1.01 * d));
    CHECK(pr.sample_distance(q) == Approx(d).epsilon(1e-2));
  }
}

TEST_CASE("sampled profile: the nearest sample is the first one a full scan finds, with or without a hint",
          "[medial_axis]") {
  // Ellipse 10 x 4; points inside, on and outside it, the centre (nearly equidistant from
  // many samples) and far away; hints right and wrong.
  const double a = 10, b = 4;
  std::vector<Vector2d> pts;
  for (int i = 0; i < 20000; ++i)
    pts.push_back({a * std::cos(2 * pi * i / 20000), b * std::sin(2 * pi * i / 20000)});
  const section::detail::SampledProfile pr(dense_spline(pts), 1000);
  std::vector<Vector2d> queries = {{0, 0}, {100, -50}, {-10, 0}, {0, 4}};
  for (int i = 0; i < 400; ++i) {
    const double t = 2 * pi * i / 400, f = 0.2 + 0.005 * i;
    queries.push_back({f * a * std::cos(t), f * b * std::sin(t)});
  }
  const int n = static_cast<int>(pr.samples.size());
  for (const auto& q : queries) {
    int full = 0;
    for (int i = 1; i < n; ++i)
      if ((pr.samples[i] - q).squaredNorm() < (pr.samples[full] - q).squaredNorm()) full = i;
    CAPTURE(q.x(), q.y());
    CHECK(pr.nearest(q) == full);
    for (const int hint : {full, (full + n / 2) % n, 0, n - 1}) CHECK(pr.nearest(q, hint) == full);
    CHECK(pr.sample_distance(q) == (pr.samples[full] - q).norm());
  }
}

TEST_CASE("medial_axis: a profile flat on one line has no inside and is refused, not crashed on",
          "[medial_axis]") {
  BSpline line;
  line.degree = 3;
  line.closed = true;
  for (int i = 0; i < 12; ++i) line.control.push_back({i <= 6 ? i : 12 - i, 0.5 * (i <= 6 ? i : 12 - i)});
  for (int i = 0; i <= 12; ++i) line.knots.push_back(i);
  try {
    section::medial_axis(line);
    FAIL("no error");
  } catch (const section::Error& e) {
    REQUIRE(std::string(e.what()) ==
            "camber: the profile encloses no area to triangulate (flat on a line, or self-intersecting)");
  }
}

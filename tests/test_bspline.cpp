// SPDX-License-Identifier: GPL-3.0-or-later
#include "detail/basis_values.h"
#include "section/bspline.h"
#include "section/error.h"

#include <catch2/catch.hpp>

#include <cmath>
#include <random>

using Eigen::Vector2d;
using section::BSpline;

namespace {

const double pi = std::acos(-1.0);

std::vector<Vector2d> circle_points(int m, double r, Vector2d c = {0, 0}, double phase = 0) {
  std::vector<Vector2d> p;
  for (int i = 0; i < m; ++i) {
    const double a = phase + 2 * pi * i / m;
    p.push_back(c + r * Vector2d(std::cos(a), std::sin(a)));
  }
  return p;
}

std::vector<Vector2d> ellipse_points(int m, double a, double b) {
  std::vector<Vector2d> p;
  for (int i = 0; i < m; ++i) {
    const double s = 2 * pi * i / m;
    p.push_back({a * std::cos(s), b * std::sin(s)});
  }
  return p;
}

BSpline fit_circle(double r, int points, int control, Vector2d c = {0, 0}) {
  section::CurveFitOptions o;
  o.control_points = control;
  return section::fit_curve(circle_points(points, r, c, 0.3), o);
}

}  // namespace

TEST_CASE("bspline: uniform periodic cubic matches the closed-form knot values", "[bspline]") {
  BSpline c;
  c.closed = true;
  c.control = {{0, 0}, {4, 0}, {4, 4}, {0, 4}, {-2, 2}};
  for (int i = 0; i <= 5; ++i) c.knots.push_back(i);
  // At knot j the non-zero cubic basis values are 1/6, 4/6, 1/6 on controls j-3, j-2, j-1.
  for (int j = 0; j < 5; ++j) {
    auto P = [&](int i) { return c.control[((i % 5) + 5) % 5]; };
    const Vector2d expect = (P(j - 3) + 4 * P(j - 2) + P(j - 1)) / 6;
    REQUIRE((c.point(j) - expect).norm() < 1e-14);
    REQUIRE((c.point(j + 5) - expect).norm() < 1e-12);   // one period later
    REQUIRE((c.point(j - 10) - expect).norm() < 1e-12);  // two periods earlier
    // First derivative at a knot: (P(j-1) - P(j-3)) / 2 for unit spacing.
    REQUIRE((c.derivative(j, 1) - (P(j - 1) - P(j - 3)) / 2).norm() < 1e-13);
  }
  std::vector<int> idx;
  std::vector<double> val;
  for (double t : {0.0, 0.37, 2.5, 4.99, 7.1}) {
    c.basis(t, idx, val);
    double sum = 0;
    Vector2d p = Vector2d::Zero();
    for (std::size_t k = 0; k < idx.size(); ++k) {
      REQUIRE(idx[k] >= 0);
      REQUIRE(idx[k] < 5);
      sum += val[k];
      p += val[k] * c.control[idx[k]];
    }
    REQUIRE(sum == Approx(1).margin(1e-14));
    REQUIRE((p - c.point(t)).norm() < 1e-13);
  }
}

TEST_CASE("bspline: basis_values gives the basis values bit for bit", "[bspline]") {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> step(0.05, 1.7), at(0, 1);
  for (bool closed : {true, false})
    for (int p = 1; p <= 5; ++p) {
      BSpline c;
      c.degree = p;
      c.closed = closed;
      c.control.assign(p + 6, Vector2d::Zero());
      const int n = static_cast<int>(c.control.size()), knots = closed ? n + 1 : n + p + 1;
      c.knots = {0.0};  // from 0: a closed curve's parameters need no wrapping
      while (static_cast<int>(c.knots.size()) < knots) c.knots.push_back(c.knots.back() + step(rng));
      // The knots about every span as the evaluation extends them (knot j at around[j + p]).
      const double period = c.knots.back() - c.knots.front();
      std::vector<double> around;
      for (int i = -p; i <= n + p; ++i) {
        const int k = closed ? (i >= 0 && i < n ? 0 : (i < 0 ? -1 : i / n)) : 0;
        around.push_back(closed ? c.knots[i - k * n] + static_cast<double>(k) * period : 0);
      }
      if (!closed) around = c.knots;
      std::vector<int> idx;
      std::vector<double> val;
      for (int j = closed ? 0 : p; j < n; ++j)
        for (int s = 0; s < 20; ++s) {
          const double t = c.knots[j] + at(rng) * (c.knots[j + 1] - c.knots[j]);
          double v[8];
          section::detail::basis_values(&around[j + (closed ? p : 0)], p, t, v);
          c.basis(t, idx, val);
          for (int r = 0; r <= p; ++r) REQUIRE(v[r] == val[r]);
        }
    }
}

TEST_CASE("bspline: closed fit of a circle has radius error below 0.01 um", "[bspline]") {
  for (double r : {0.2, 5.0, 20.0}) {
    const Vector2d centre(3, -1);
    const BSpline c = fit_circle(r, 400, 48, centre);
    REQUIRE(c.closed);
    REQUIRE(c.control.size() == 48);
    double worst = 0;
    for (int i = 0; i < 2000; ++i) {
      const double t = c.t_min() + (c.t_max() - c.t_min()) * i / 2000.0;
      worst = std::max(worst, std::abs((c.point(t) - centre).norm() - r));
    }
    INFO("r = " << r << " worst radius error " << worst);
    REQUIRE(worst < 1e-5);
    // Curvature 1/r counterclockwise.
    REQUIRE(c.curvature(0.123 * c.t_max()) == Approx(1 / r).epsilon(1e-2));
    // Arc length 2 pi r.
    REQUIRE(section::arc_length(c, c.t_min(), c.t_max()) == Approx(2 * pi * r).epsilon(1e-7));
  }
}

TEST_CASE("bspline: ellipse fit error below 1 um", "[bspline]") {
  section::CurveFitOptions o;
  o.control_points = 80;
  const auto pts = ellipse_points(1000, 20, 8);
  const BSpline c = section::fit_curve(pts, o);
  double worst = 0;
  for (const auto& s : section::sample(c, 3000)) {
    // Distance to the ellipse via the algebraic value scaled by the gradient (first order).
    const double f = s.x() * s.x() / 400 + s.y() * s.y() / 64 - 1;
    const double g = 2 * std::hypot(s.x() / 400, s.y() / 64);
    worst = std::max(worst, std::abs(f / g));
  }
  INFO("worst " << worst);
  REQUIRE(worst < 1e-3);
}

TEST_CASE("bspline: derivatives agree with finite differences, across the seam", "[bspline]") {
  const BSpline c = fit_circle(10, 300, 24);
  const double h = 1e-5;
  for (double t :
       {c.t_min(), c.t_min() + 1e-9, 0.31 * c.t_max(), c.t_max() - 1e-9, c.knots[5], c.t_max() + 2.5}) {
    const Vector2d d1 = (c.point(t + h) - c.point(t - h)) / (2 * h);
    const Vector2d d2 = (c.point(t + h) - 2 * c.point(t) + c.point(t - h)) / (h * h);
    const Vector2d d3 = (c.derivative(t + h, 2) - c.derivative(t - h, 2)) / (2 * h);
    REQUIRE((c.derivative(t, 1) - d1).norm() < 1e-6 * c.derivative(t, 1).norm());
    REQUIRE((c.derivative(t, 2) - d2).norm() < 1e-3 * c.derivative(t, 2).norm());
    // Third derivative jumps at knots: compare only inside a span.
    if (std::abs(t - c.knots[5]) > 1e-3 && std::abs(t - c.t_min()) > 1e-3 && std::abs(t - c.t_max()) > 1e-3)
      REQUIRE((c.derivative(t, 3) - d3).norm() < 1e-4 * c.derivative(t, 3).norm());
    REQUIRE(c.derivative(t, 4).norm() == 0);
  }
}

TEST_CASE("bspline: closed curve is C2 at the seam", "[bspline]") {
  BSpline c;
  c.closed = true;
  c.control = {{0, 0}, {3, -1}, {5, 2}, {4, 6}, {1, 5}, {-1, 2}};
  c.knots = {0.5, 1.0, 2.2, 2.5, 4.0, 4.1, 6.0};  // non-uniform
  const double eps = 1e-10;
  for (int k = 0; k <= 2; ++k) {
    const Vector2d before = c.derivative(c.t_max() - eps, k);
    const Vector2d after = c.derivative(c.t_min() + eps, k);
    const Vector2d at = c.derivative(c.t_min(), k);
    INFO("k = " << k);
    REQUIRE((before - after).norm() < 1e-6 * (1 + at.norm()));
    REQUIRE((at - c.derivative(c.t_max(), k)).norm() < 1e-12 * (1 + at.norm()));
  }
  // Also C2 at every interior knot.
  for (std::size_t i = 1; i + 1 < c.knots.size(); ++i)
    for (int k = 0; k <= 2; ++k)
      REQUIRE((c.derivative(c.knots[i] - eps, k) - c.derivative(c.knots[i] + eps, k)).norm() <
              1e-6 * (1 + c.derivative(c.knots[i], k).norm()));
}

TEST_CASE("bspline: closest point on a fitted circle is the radial projection", "[bspline]") {
  const double r = 8;
  const Vector2d centre(1, 2);
  const BSpline c = fit_circle(r, 500, 64, centre);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> ang(0, 2 * pi), rad(0.3 * r, 3 * r);
  for (int i = 0; i < 60; ++i) {
    const double a = i < 8 ? 0.3 + 1e-7 * (i - 4) : ang(rng);  // first ones at the seam
    const double q_r = rad(rng);
    const Vector2d q = centre + q_r * Vector2d(std::cos(a), std::sin(a));
    const auto cp = section::closest_point(c, q);
    const Vector2d expect = centre + r * Vector2d(std::cos(a), std::sin(a));
    // The fitted circle ripples by < 1 um in radius, which tilts its normals slightly:
    // the foot point is the radial one to 0.1 um, and exactly a stationary, global minimum.
    REQUIRE((cp.point - expect).norm() < 1e-4);
    REQUIRE(cp.distance == Approx(std::abs(q_r - r)).margin(1e-5));
    const Vector2d tan = c.derivative(cp.t, 1).normalized();
    REQUIRE(std::abs((q - cp.point).dot(tan)) < 1e-9 * (1 + cp.distance));
    double dense = 1e300;
    for (const auto& s : section::sample(c, 20000)) dense = std::min(dense, (s - q).norm());
    REQUIRE(cp.distance <= dense + 1e-12);
    REQUIRE(cp.t >= c.t_min());
    REQUIRE(cp.t < c.t_max());
    // Tracking from a nearby parameter finds the same foot point, wrapped.
    const auto near = section::closest_point_near(c, q, cp.t + 0.3 * (c.knots[1] - c.knots[0]));
    REQUIRE((near.point - cp.point).norm() < 1e-9);
  }
}

TEST_CASE("bspline: closest point on an open curve may be an end point", "[bspline]") {
  std::vector<Vector2d> pts;
  for (int i = 0; i <= 100; ++i) pts.push_back({i * 0.1, std::sin(i * 0.1)});
  section::CurveFitOptions o;
  o.closed = false;
  o.control_points = 40;
  const BSpline c = section::fit_curve(pts, o);
  REQUIRE((c.point(c.t_min()) - pts.front()).norm() < 1e-4);
  REQUIRE((c.point(c.t_max()) - pts.back()).norm() < 1e-4);
  const auto cp = section::closest_point(c, {-3, -1});
  REQUIRE(cp.t == Approx(c.t_min()));
  const auto cp2 = section::closest_point(c, {5, 3});
  // Foot of a point above the sine: the residual is normal to the curve.
  const Vector2d tan = c.derivative(cp2.t, 1).normalized();
  REQUIRE(std::abs((Vector2d(5, 3) - cp2.point).dot(tan)) < 1e-9);
  REQUIRE(section::arc_length(c, c.t_min(), c.t_max()) > 10);
}

TEST_CASE("bspline: chord-length parameters", "[bspline]") {
  const std::vector<Vector2d> sq = {{0, 0}, {1, 0}, {1, 2}, {0, 2}};
  const auto open = section::chord_length_parameters(sq, false);
  const auto closed = section::chord_length_parameters(sq, true);
  REQUIRE(open == std::vector<double>{0, 1, 3, 4});
  REQUIRE(closed == std::vector<double>{0, 1, 3, 4, 6});
}

TEST_CASE("bspline: degenerate fits throw section::Error", "[bspline]") {
  std::vector<Vector2d> line, same;
  for (int i = 0; i < 50; ++i) {
    line.push_back({i * 0.5, i * 0.25});
    same.push_back({1, 1});
  }
  REQUIRE_THROWS_AS(section::fit_curve(line), section::Error);
  REQUIRE_THROWS_AS(section::fit_curve(same), section::Error);
  section::CurveFitOptions o;
  o.control_points = 40;
  REQUIRE_THROWS_AS(section::fit_curve(circle_points(20, 1), o), section::Error);
  o.control_points = 0;
  o.closed = false;
  REQUIRE_NOTHROW(section::fit_curve(line, o));  // an open curve through a line is fine
  try {
    section::fit_curve(same);
  } catch (const section::Error& e) {
    REQUIRE(std::string(e.what()).rfind("fit_curve:", 0) == 0);
  }
}

TEST_CASE("bspline: sample spreads points evenly in parameter", "[bspline]") {
  const BSpline c = fit_circle(2, 200, 16);
  const auto s = section::sample(c, 100);
  REQUIRE(s.size() == 100);
  REQUIRE((s.front() - s.back()).norm() > 0.05);  // the end point is not repeated
}

TEST_CASE("bspline: check_spline names the knot vector or point that defines no curve", "[bspline]") {
  const BSpline good = fit_circle(2, 200, 16);
  REQUIRE_NOTHROW(section::check_spline(good));
  auto message = [](const BSpline& c) {
    try {
      section::check_spline(c);
    } catch (const section::Error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  BSpline c = good;
  c.knots.back() = c.knots.front();  // a period of 0 (knot 16 also below knot 15)
  REQUIRE(message(c).find("knot 16 (") != std::string::npos);
  for (double& k : c.knots) k = 0;
  REQUIRE(message(c) ==
          "bspline: the curve's parameter range is empty: the last knot equals the first, a period of 0");
  c = good;
  c.knots[3] = std::nan("");
  REQUIRE(message(c) == "bspline: knot 3 is not finite");
  c = good;
  c.control[5].y() = INFINITY;
  REQUIRE(message(c) == "bspline: control point 5 is not finite");
  // Five equal knots in a row on a cubic, across the seam (knot 8 is knot 0 one period on).
  c.control = section::sample(good, 8);
  c.knots = {0, 0, 0, 1, 2, 3, 5, 5, 5};
  REQUIRE(message(c) == "bspline: 5 equal knots in a row at knot 2; a curve of degree 3 allows at most 4");
  c.knots = {0, 0, 0, 1, 2, 3, 4, 5, 5};  // four in a row: a cubic's limit, accepted
  REQUIRE(message(c) == "no error");
  BSpline open;
  open.degree = 1;
  open.control = {{0, 0}, {1, 0}};
  open.knots = {0, 1, 1, 1};  // knot 1 equals knot 2: no parameter range
  REQUIRE(message(open) == "bspline: the curve's parameter range is empty: knot 1 equals knot 2");
  open.knots = {0, 0, 1, 1};
  REQUIRE(message(open) == "no error");
}

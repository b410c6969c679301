// SPDX-License-Identifier: GPL-3.0-or-later
#include "detail/axis_curve.h"

#include "section/error.h"

#include <algorithm>
#include <utility>

namespace section::detail {

namespace {

// Arc length of a spline between a and b (5-point Gauss-Legendre; the pieces are short).
double piece_length(const PiecewiseCurve& f, double a, double b) {
  static const double x[5] = {-0.9061798459386640, -0.5384693101056831, 0.0, 0.5384693101056831,
                              0.9061798459386640};
  static const double w[5] = {0.2369268850561891, 0.4786286704993665, 0.5688888888888889, 0.4786286704993665,
                              0.2369268850561891};
  double sum = 0;
  PiecewiseCurve::Cursor at;  // the nodes lie in one span or a few
  for (int i = 0; i < 5; ++i)
    sum += w[i] * f.jet(f.locate(0.5 * (a + b) + 0.5 * (b - a) * x[i], at)).d1.norm();
  return 0.5 * (b - a) * sum;
}

}  // namespace

BSpline fit_open(const std::vector<Eigen::Vector2d>& points, int control_points, double fairness) {
  CurveFitOptions fo;
  fo.closed = false;
  fo.control_points = control_points;
  fo.fairness = fairness;
  return fit_curve(points, fo);
}

AxisCurve::AxisCurve(BSpline s) : spline(std::move(s)), a(spline.t_min()), b(spline.t_max()), f(spline) {}

Eigen::Vector2d AxisCurve::point(double u) const {
  if (u < a) return f.point(a) + (u - a) * tangent(a);
  if (u > b) return f.point(b) + (u - b) * tangent(b);
  return f.point(u);
}

Eigen::Vector2d AxisCurve::tangent(double u) const {
  return f.jet(std::clamp(u, a, b)).d1.normalized();
}

AxisCurve make_axis(const std::vector<Eigen::Vector2d>& points, double fairness) {
  // Drop repeated points (Delaunay fans share circumcentres).
  std::vector<Eigen::Vector2d> p;
  for (const auto& q : points)
    if (p.empty() || (q - p.back()).norm() > 1e-12) p.push_back(q);
  if (p.size() < 4) throw Error("camber: the medial axis has fewer than 4 distinct points");
  return AxisCurve(fit_open(p, std::clamp(static_cast<int>(p.size()) / 2, 4, 200), fairness));
}

ArcLengthTable::ArcLengthTable(PiecewiseCurve c, int pieces) : f(std::move(c)) {
  const double a = f.t_min(), b = f.t_max();
  t.push_back(a);
  s.push_back(0);
  for (int i = 1; i <= pieces; ++i) {
    t.push_back(a + (b - a) * i / pieces);
    s.push_back(s.back() + piece_length(f, t[i - 1], t[i]));
  }
}

double ArcLengthTable::param(double target) const {
  target = std::clamp(target, 0.0, length());
  const std::size_t i =
      std::min<std::size_t>(std::upper_bound(s.begin(), s.end(), target) - s.begin(), s.size() - 1);
  const std::size_t k = std::max<std::size_t>(i, 1);
  double x = t[k - 1] + (t[k] - t[k - 1]) * (target - s[k - 1]) / std::max(s[k] - s[k - 1], 1e-300);
  PiecewiseCurve::Cursor at;  // Newton's steps are short: the span before is tried first
  for (int it = 0; it < 3; ++it) {
    const double err = s[k - 1] + piece_length(f, t[k - 1], x) - target;
    x -= err / std::max(f.jet(f.locate(x, at)).d1.norm(), 1e-300);
  }
  return x;
}

double ArcLengthTable::arc(double param_t) const {
  const std::size_t i =
      std::min<std::size_t>(std::upper_bound(t.begin(), t.end(), param_t) - t.begin(), t.size() - 1);
  const std::size_t k = std::max<std::size_t>(i, 1);
  return s[k - 1] + piece_length(f, t[k - 1], param_t);
}

}  // namespace section::detail

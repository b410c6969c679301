// SPDX-License-Identifier: GPL-3.0-or-later
// Other forms of a B-spline: the least-squares fit through points, samples and chord-length
// parameters, the clamped open form CAD formats read, and a polyline within a tolerance of
// the curve.
#include "section/bspline.h"

#include "detail/fit_points.h"

#include "section/error.h"
#include "section/units.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdio>
#include <limits>
#include <string>
#include <utility>
#include <vector>

namespace section {

namespace {

// A curve in the plain form of Piegl and Tiller: knots u_0..u_m and control points
// q_0..q_{m-p-1}, basis function i over [u_i, u_{i+p+1}).
struct OpenForm {
  int degree = 3;
  std::vector<double> knots;
  std::vector<Eigen::Vector2d> control;
};

// The closed curve as an unclamped open curve over the same parameter: with n control
// points and breakpoints t_0..t_n, u_k = t_{k-p} (extended by the period) for k = 0..n+2p and
// q_k = P_{(k-p) mod n}; on [u_p, u_{n+p}] = [t_0, t_n] it is the closed curve.
OpenForm unwrap(const BSpline& c) {
  const int n = static_cast<int>(c.control.size()), p = c.degree;
  const double period = c.knots.back() - c.knots.front();
  OpenForm f;
  f.degree = p;
  for (int k = 0; k <= n + 2 * p; ++k) {
    const int i = k - p;
    if (i < 0)
      f.knots.push_back(c.knots[static_cast<std::size_t>(i + n)] - period);
    else if (i > n)
      f.knots.push_back(c.knots[static_cast<std::size_t>(i - n)] + period);
    else
      f.knots.push_back(c.knots[static_cast<std::size_t>(i)]);
  }
  for (int k = 0; k < n + p; ++k)
    f.control.push_back(c.control[static_cast<std::size_t>(((k - p) % n + n) % n)]);
  return f;
}

// Inserts the knot u once (Boehm; Piegl and Tiller, A5.1 with r = 1). u must lie in
// [u_p, u_{m-p}].
void insert_knot(OpenForm& f, double u) {
  const int p = f.degree;
  const int m = static_cast<int>(f.knots.size()) - 1;
  // The span k with u_k <= u < u_{k+1}, among the spans p..m-p-1.
  int k = static_cast<int>(std::upper_bound(f.knots.begin(), f.knots.end(), u) - f.knots.begin()) - 1;
  k = std::clamp(k, p, m - p - 1);
  std::vector<Eigen::Vector2d> q;
  q.reserve(f.control.size() + 1);
  for (int i = 0; i <= k - p; ++i) q.push_back(f.control[i]);
  for (int i = k - p + 1; i <= k; ++i) {
    const double span = f.knots[i + p] - f.knots[i];
    const double a = span > 0 ? (u - f.knots[i]) / span : 0;
    q.push_back(a * f.control[i] + (1 - a) * f.control[i - 1]);
  }
  for (int i = k; i < static_cast<int>(f.control.size()); ++i) q.push_back(f.control[i]);
  f.control = std::move(q);
  f.knots.insert(f.knots.begin() + k + 1, u);
}

// Index of the first knot equal to u.
std::size_t first_knot(const OpenForm& f, double u) {
  return static_cast<std::size_t>(std::lower_bound(f.knots.begin(), f.knots.end(), u) - f.knots.begin());
}

// Distance of q from the segment a-b.
double off_chord(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& q) {
  const Eigen::Vector2d chord = b - a;
  const double len2 = chord.squaredNorm();
  const double s = len2 > 0 ? std::clamp((q - a).dot(chord) / len2, 0.0, 1.0) : 0.0;
  return (q - (a + s * chord)).norm();
}

struct Flattening {
  double tolerance;
  std::size_t max_points;
};

// Chordal bisection of [a, b]: appends the parameters after a up to b (b excluded). A piece
// is kept when the curve at its quarter points and midpoint lies within half the tolerance
// of its chord: the quarter points catch an inflection that puts the midpoint on the chord,
// and the half covers the curve between the points checked.
void bisect(const BSpline& c, double a, double b, const Eigen::Vector2d& pa, const Eigen::Vector2d& pb,
            const Flattening& f, int depth, std::vector<double>& out) {
  if (out.size() >= f.max_points) {
    char text[32];  // with an exponent: format_length shows 1e-6 as 0
    std::snprintf(text, sizeof text, "%.3g mm", f.tolerance);
    throw Error("bspline: a polyline within " + std::string(text) + " of the curve needs more than " +
                std::to_string(f.max_points) + " points; a larger tolerance is needed");
  }
  const double tolerance = f.tolerance;
  const double mid = 0.5 * (a + b);
  const Eigen::Vector2d pm = c.point(mid);
  if (depth > 0) {
    const double off = std::max({off_chord(pa, pb, pm), off_chord(pa, pb, c.point(0.5 * (a + mid))),
                                 off_chord(pa, pb, c.point(0.5 * (mid + b)))});
    if (off <= 0.5 * tolerance || depth >= 40) return;
  }
  bisect(c, a, mid, pa, pm, f, depth + 1, out);
  out.push_back(mid);
  bisect(c, mid, b, pm, pb, f, depth + 1, out);
}

}  // namespace

std::vector<double> chord_length_parameters(const std::vector<Eigen::Vector2d>& points, bool closed) {
  std::vector<double> t;
  if (points.empty()) return t;
  t.reserve(points.size() + 1);
  t.push_back(0);
  for (std::size_t i = 1; i < points.size(); ++i) t.push_back(t.back() + (points[i] - points[i - 1]).norm());
  if (closed) t.push_back(t.back() + (points.front() - points.back()).norm());
  return t;
}

namespace detail {

void check_fit_points(const std::vector<Eigen::Vector2d>& points, bool closed) {
  const int m = static_cast<int>(points.size());
  for (const auto& q : points)
    if (!q.allFinite()) throw Error("fit_curve: a point is not finite");
  // Degeneracy from the spread of the points: all equal, or all on a line for closed curves.
  Eigen::Vector2d mean = Eigen::Vector2d::Zero();
  for (const auto& q : points) mean += q;
  mean /= m;
  Eigen::Matrix2d cov = Eigen::Matrix2d::Zero();
  for (const auto& q : points) cov += (q - mean) * (q - mean).transpose();
  // Eigenvalues of the symmetric 2x2 scatter matrix.
  const double half_trace = 0.5 * (cov(0, 0) + cov(1, 1));
  const double root = std::hypot(0.5 * (cov(0, 0) - cov(1, 1)), cov(0, 1));
  const double big = half_trace + root, small = std::max(0.0, half_trace - root);
  if (!(big > 0) || std::sqrt(big / m) <= 1e-12 * std::max(1.0, mean.norm()))
    throw Error("fit_curve: all " + std::to_string(m) + " points are equal");
  if (closed && small <= 1e-14 * big)
    throw Error("fit_curve: all points lie on a line, no closed curve fits them");
}

}  // namespace detail

BSpline fit_curve(const std::vector<Eigen::Vector2d>& points, const CurveFitOptions& options) {
  const int m = static_cast<int>(points.size());
  const int p = options.degree;
  if (p < 1 || p > max_spline_degree)
    throw Error("fit_curve: degree " + std::to_string(p) + " is not in 1.." +
                std::to_string(max_spline_degree));
  const int n = options.control_points > 0 ? options.control_points : std::max(8, m / 4);
  if (n < p + 1)
    throw Error("fit_curve: " + std::to_string(n) + " control points are too few for degree " +
                std::to_string(p) + ", at least " + std::to_string(p + 1) + " are needed");
  if (m < n)
    throw Error("fit_curve: " + std::to_string(m) + " points are fewer than the " + std::to_string(n) +
                " control points");
  detail::check_fit_points(points, options.closed);

  const std::vector<double> s = chord_length_parameters(points, options.closed);
  const double length = s.back();
  BSpline shape;
  shape.degree = p;
  shape.closed = options.closed;
  shape.control.assign(n, Eigen::Vector2d::Zero());
  if (options.closed) {
    shape.knots.resize(n + 1);
    for (int i = 0; i <= n; ++i) shape.knots[i] = length * i / n;
  } else {
    shape.knots.assign(n + p + 1, 0.0);
    for (int i = 0; i < n + p + 1; ++i) {
      if (i <= p)
        shape.knots[i] = 0;
      else if (i >= n)
        shape.knots[i] = length;
      else
        shape.knots[i] = length * (i - p) / (n - p);
    }
  }
  return fit_control_points(points, s, shape, options.fairness, {});
}

std::vector<Eigen::Vector2d> sample(const BSpline& curve, int count) {
  check_spline(curve);
  std::vector<Eigen::Vector2d> out;
  if (count <= 0) return out;
  if (count > 100000000) throw Error("bspline: " + std::to_string(count) + " samples, at most 100000000");
  out.reserve(count);
  const double a = curve.t_min(), b = curve.t_max();
  for (int i = 0; i < count; ++i) {
    const double t =
        curve.closed ? a + (b - a) * i / count : (count == 1 ? a : a + (b - a) * i / (count - 1));
    out.push_back(curve.point(t));
  }
  return out;
}

std::vector<double> span_samples(const BSpline& c, int per_span) {
  if (per_span < 1 || per_span > 1000000)
    throw Error("bspline: " + std::to_string(per_span) + " samples a knot span, not in 1..1000000");
  if (c.knots.size() * static_cast<double>(per_span) > 1e8)
    throw Error("bspline: " + std::to_string(per_span) + " samples on each of " +
                std::to_string(c.knots.size()) + " knot spans, over 100000000");
  std::vector<double> ts;
  ts.reserve(c.control.size() * per_span);
  for (std::size_t j = 0; j + 1 < c.knots.size(); ++j)
    for (int s = 0; s < per_span; ++s)
      ts.push_back(c.knots[j] + (c.knots[j + 1] - c.knots[j]) * s / per_span);
  return ts;
}

BSpline clamped(const BSpline& curve) {
  check_spline(curve);
  if (!curve.closed) return curve;
  const int p = curve.degree;
  OpenForm f = unwrap(curve);
  const double t0 = curve.knots.front(), tn = curve.knots.back();
  for (int r = 0; r < p; ++r) insert_knot(f, t0);
  for (int r = 0; r < p; ++r) insert_knot(f, tn);
  const std::size_t a = first_knot(f, t0);
  const std::size_t b = first_knot(f, tn) + static_cast<std::size_t>(p);
  BSpline out;
  out.degree = p;
  out.closed = false;
  out.knots.assign(f.knots.begin() + a, f.knots.begin() + b + 1);
  const std::size_t count = out.knots.size() - p - 1;
  out.control.assign(f.control.begin() + a, f.control.begin() + a + count);
  out.control.back() = out.control.front();  // both are the point at t_0 (equal up to rounding)
  return out;
}

std::vector<double> flatten(const BSpline& curve, double tolerance, std::size_t max_points) {
  if (!(tolerance > 0))
    throw Error("bspline: a polyline's tolerance must be above 0, got " + format_length(tolerance));
  check_spline(curve);
  // Below a few units in the last place of the coordinates no chord test can pass.
  double extent = 0;
  for (const auto& p : curve.control) extent = std::max(extent, p.cwiseAbs().maxCoeff());
  if (tolerance < 64 * std::numeric_limits<double>::epsilon() * extent) {
    char text[32];  // with an exponent: format_length shows 1e-300 as 0
    std::snprintf(text, sizeof text, "%.3g mm", tolerance);
    throw Error("bspline: a polyline's tolerance of " + std::string(text) +
                " is below the resolution of the curve's coordinates (up to " + format_length(extent) + ")");
  }
  std::vector<double> breaks;
  for (double k : curve.knots)
    if (k >= curve.t_min() && k <= curve.t_max() && (breaks.empty() || k > breaks.back()))
      breaks.push_back(k);
  std::vector<double> out;
  for (std::size_t j = 0; j + 1 < breaks.size(); ++j) {
    out.push_back(breaks[j]);
    bisect(curve, breaks[j], breaks[j + 1], curve.point(breaks[j]), curve.point(breaks[j + 1]),
           {tolerance, max_points}, 0, out);
  }
  if (!curve.closed) out.push_back(breaks.back());
  return out;
}

}  // namespace section

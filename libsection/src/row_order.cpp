// SPDX-License-Identifier: GPL-3.0-or-later
// The order of a row's points along its profile (slice --rows, docs/SAMPLING.md): the
// morphology where it closes one loop, else along the chord, side by side.
#include "section/error.h"
#include "detail/slice_steps.h"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <optional>
#include <utility>
#include <string>

namespace section::detail {

namespace {

using Vec = Eigen::Vector2d;

double cross(const Vec& a, const Vec& b, const Vec& c) {
  return (b - a).x() * (c - a).y() - (b - a).y() * (c - a).x();
}

// Two edges of the closed polygon that cross without sharing a vertex, as the indices
// of their first vertices (i < j), or none (a sweep over the edges sorted by lowest x).
std::optional<std::pair<std::size_t, std::size_t>> crossing(const std::vector<Vec>& p) {
  const std::size_t m = p.size();
  std::vector<std::size_t> order(m);
  std::iota(order.begin(), order.end(), std::size_t(0));
  const auto lo = [&](std::size_t i) { return std::min(p[i].x(), p[(i + 1) % m].x()); };
  const auto hi = [&](std::size_t i) { return std::max(p[i].x(), p[(i + 1) % m].x()); };
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return lo(a) < lo(b); });
  for (std::size_t x = 0; x < m; ++x) {
    const std::size_t i = order[x];
    const Vec &a = p[i], &b = p[(i + 1) % m];
    for (std::size_t y = x + 1; y < m && lo(order[y]) <= hi(i); ++y) {
      const std::size_t j = order[y];
      if ((i + 1) % m == j || (j + 1) % m == i) continue;
      const Vec &c = p[j], &d = p[(j + 1) % m];
      const double d1 = cross(a, b, c), d2 = cross(a, b, d), d3 = cross(c, d, a), d4 = cross(c, d, b);
      if (((d1 > 0 && d2 < 0) || (d1 < 0 && d2 > 0)) && ((d3 > 0 && d4 < 0) || (d3 < 0 && d4 > 0)))
        return std::make_pair(std::min(i, j), std::max(i, j));
    }
  }
  return std::nullopt;
}

// Undoes the crossings of the closed polygon through points[order] (2-opt: the stretch
// between two crossing edges reversed, which shortens the polygon, so it ends); false when
// some are left after a generous number of moves.
bool untangle(const std::vector<Vec>& points, std::vector<std::size_t>& order) {
  std::vector<Vec> p(order.size());
  for (std::size_t move = 0; move <= 4 * order.size(); ++move) {
    for (std::size_t k = 0; k < order.size(); ++k) p[k] = points[order[k]];
    const auto c = crossing(p);
    if (!c) return true;
    std::reverse(order.begin() + std::ptrdiff_t(c->first + 1), order.begin() + std::ptrdiff_t(c->second + 1));
  }
  return false;
}

// The loop of points in `order`: counterclockwise, normals out of it, its own boundary.
Loop loop_of(const std::vector<Vec>& points, std::vector<std::size_t> order) {
  double area = 0;
  for (std::size_t k = 0; k < order.size(); ++k) {
    const Vec &a = points[order[k]], &b = points[order[(k + 1) % order.size()]];
    area += 0.5 * (a.x() * b.y() - b.x() * a.y());
  }
  if (area < 0) std::reverse(order.begin(), order.end());
  Loop loop;
  loop.index = order;
  for (std::size_t k : order) loop.points.push_back(points[k]);
  const std::size_t n = order.size();
  for (std::size_t k = 0; k < n; ++k) {
    const Vec t = loop.points[(k + 1) % n] - loop.points[(k + n - 1) % n];
    loop.normals.push_back(t.norm() > 0 ? Vec(Vec(t.y(), -t.x()).normalized()) : Vec(0, 0));
    loop.length += (loop.points[(k + 1) % n] - loop.points[k]).norm();
  }
  loop.area = std::abs(area);
  loop.boundary = loop.points;
  return loop;
}

}  // namespace

MorphologyResult order_along_chord(const std::vector<Eigen::Vector2d>& points) {
  const std::size_t n = points.size();
  if (n < 8) throw Error("morphology: " + std::to_string(n) + " points, at least 8 are needed");
  Vec centre = Vec::Zero();
  for (const Vec& p : points) centre += p;
  centre /= double(n);
  Eigen::Matrix2d cov = Eigen::Matrix2d::Zero();
  for (const Vec& p : points) cov += (p - centre) * (p - centre).transpose();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eig(cov);
  const Vec along = eig.eigenvectors().col(1), across = eig.eigenvectors().col(0);
  std::vector<double> x(n), y(n);
  double reach = 0;
  for (std::size_t i = 0; i < n; ++i) {
    x[i] = along.dot(points[i] - centre), y[i] = across.dot(points[i] - centre);
    reach = std::max(reach, std::abs(x[i]));
  }
  // The mean line: a quartic in x through all the points, both sides alike.
  Eigen::MatrixXd a(n, 5);
  Eigen::VectorXd b(n);
  for (std::size_t i = 0; i < n; ++i) {
    const double t = x[i] / reach;
    a.row(Eigen::Index(i)) << 1, t, t * t, t * t * t, t * t * t * t;
    b(Eigen::Index(i)) = y[i];
  }
  const Eigen::VectorXd c = a.colPivHouseholderQr().solve(b);
  std::vector<std::size_t> upper, lower;
  std::vector<double> off(n);
  for (std::size_t i = 0; i < n; ++i) {
    off[i] = y[i] - a.row(Eigen::Index(i)).dot(c);
    (off[i] > 0 ? upper : lower).push_back(i);
  }
  // Round a profile the points lie on both sides of the mean line, up to half its thickness
  // off (1 % of the chord for a blade 2 % thick; the 90 % quantile, as points crowd at the
  // thin edges); along one curve (an open arc, a line) on it.
  for (double& o : off) o = std::abs(o);
  const std::size_t q = n * 9 / 10;
  std::nth_element(off.begin(), off.begin() + std::ptrdiff_t(q), off.end());
  if (!(off[q] > 0.002 * 2 * reach))
    throw Error("morphology: the " + std::to_string(n) +
                " points close into no loop and lie along one curve, not round a profile");
  std::sort(upper.begin(), upper.end(), [&](std::size_t i, std::size_t j) { return x[i] < x[j]; });
  std::sort(lower.begin(), lower.end(), [&](std::size_t i, std::size_t j) { return x[i] > x[j]; });
  upper.insert(upper.end(), lower.begin(), lower.end());
  // Near a thin edge a point can fall on the other side of the mean line: the crossings
  // it makes are undone.
  if (!untangle(points, upper))
    throw Error(
        "morphology: the " + std::to_string(n) +
        " points close into no loop, and taken along their chord, side by side, they cross themselves");
  MorphologyResult result;
  result.loops.push_back(loop_of(points, std::move(upper)));
  return result;
}

MorphologyResult order_row(const std::vector<Eigen::Vector2d>& points, const MorphologyOptions& options) {
  try {
    MorphologyResult m = order_section(points, options);
    if (m.loops.size() == 1 && 50 * m.dropped <= points.size() && !crossing(m.loops[0].points)) return m;
  } catch (const Error&) {
  }
  return order_along_chord(points);
}

}  // namespace section::detail

// SPDX-License-Identifier: GPL-3.0-or-later
// The geometry of a section's drawing: its curves as polylines and path data, and the
// windows of the edge insets; see plot_parts.h.
#include "plot_parts.h"

#include "section/fit_spline.h"

#include <Eigen/Dense>

namespace section::detail::plot {

std::vector<V2> curve_of(const SectionData& d, int loop, const PlotOptions& o, double factor) {
  if (const auto it = d.splines.find(loop); it != d.splines.end()) {
    const int n = static_cast<int>(std::clamp(o.spline_samples * factor, 16.0, 400000.0));
    return sample(it->second, n);
  }
  if (const auto it = d.polyline.find(loop); it != d.polyline.end()) return it->second;
  return {};
}

std::vector<int> curve_loops(const SectionData& d) {
  std::vector<int> out;
  for (const auto& [loop, b] : d.splines) out.push_back(loop);
  for (const auto& [loop, p] : d.polyline) out.push_back(loop);
  return out;
}

bool closed_loop(const SectionData& d, int loop) {
  const auto it = d.splines.find(loop);
  return it == d.splines.end() || it->second.closed;
}

std::string path_data(const std::vector<V2>& pts, bool closed, const View& v, const Box& window, bool whole) {
  std::string d;
  const std::size_t n = pts.size();
  if (n < 2) return d;
  if (whole) {
    bool pen = false;
    for (const auto& p : pts) {
      if (!finite(p)) {
        pen = false;
        continue;
      }
      d += (pen ? " L" : (d.empty() ? "M" : " M")) + px(v.x(p.x())) + " " + px(v.y(p.y()));
      pen = true;
    }
    if (closed) d += " Z";
    return d;
  }
  const std::size_t segments = closed ? n : n - 1;
  bool open_run = false;
  for (std::size_t i = 0; i < segments; ++i) {
    const V2& a = pts[i];
    const V2& b = pts[(i + 1) % n];
    Box seg;
    seg.add(a);
    seg.add(b);
    if (!finite(a) || !finite(b) || !seg.touches(window)) {
      open_run = false;
      continue;
    }
    if (!open_run) d += (d.empty() ? "M" : " M") + px(v.x(a.x())) + " " + px(v.y(a.y()));
    d += " L" + px(v.x(b.x())) + " " + px(v.y(b.y()));
    open_run = true;
  }
  return d;
}

std::vector<V2> refined(const std::vector<V2>& pts, double step) {
  const std::size_t n = pts.size();
  if (n < 3 || !(step > 0)) return pts;
  std::vector<V2> out{pts.front()};
  for (std::size_t i = 0; i + 1 < n; ++i) {
    const V2 &p0 = pts[i > 0 ? i - 1 : i], &p1 = pts[i], &p2 = pts[i + 1],
             &p3 = pts[i + 2 < n ? i + 2 : i + 1];
    const int k = static_cast<int>(std::min(1000.0, std::ceil((p2 - p1).norm() / step)));
    for (int j = 1; j < k; ++j) {  // uniform Catmull-Rom between p1 and p2
      const double t = double(j) / k, t2 = t * t, t3 = t2 * t;
      out.push_back(0.5 * (2 * p1 + (p2 - p0) * t + (2 * p0 - 5 * p1 + 4 * p2 - p3) * t2 +
                           (3 * p1 - p0 - 3 * p2 + p3) * t3));
    }
    out.push_back(p2);
  }
  return out;
}

std::vector<V2> thinned(const std::vector<V2>& pts, const View& v, double tolerance) {
  // Douglas-Peucker on each run of finite points: a vertex is kept when the chord between
  // the kept ones around it would pass farther than `tolerance` px from it.
  const std::size_t n = pts.size();
  if (n < 3) return pts;
  const double limit = tolerance / v.scale;
  std::vector<char> keep(n, 0);
  std::vector<std::pair<std::size_t, std::size_t>> todo;
  for (std::size_t i = 0; i < n;) {
    if (!finite(pts[i])) {
      keep[i++] = 1;  // a break in the curve stays a break
      continue;
    }
    std::size_t j = i;
    while (j + 1 < n && finite(pts[j + 1])) ++j;
    keep[i] = keep[j] = 1;
    if (j > i + 1) todo.push_back({i, j});
    i = j + 1;
  }
  while (!todo.empty()) {
    const auto [i, j] = todo.back();
    todo.pop_back();
    const V2 a = pts[i], ab = pts[j] - a;
    const double len = ab.norm();
    double worst = -1;
    std::size_t at = i;
    for (std::size_t k = i + 1; k < j; ++k) {
      const V2 ap = pts[k] - a;
      const double dist = len > 0 ? std::abs(ab.x() * ap.y() - ab.y() * ap.x()) / len : ap.norm();
      if (dist > worst) worst = dist, at = k;
    }
    if (worst <= limit) continue;
    keep[at] = 1;
    if (at > i + 1) todo.push_back({i, at});
    if (j > at + 1) todo.push_back({at, j});
  }
  std::vector<V2> out;
  for (std::size_t i = 0; i < n; ++i)
    if (keep[i]) out.push_back(pts[i]);
  return out;
}

namespace {

// Farthest pair along the principal axis of some points: the two ends of a profile.
std::pair<V2, V2> principal_ends(const std::vector<V2>& pts) {
  V2 mean(0, 0);
  for (const auto& p : pts) mean += p;
  mean /= static_cast<double>(pts.size());
  Eigen::Matrix2d cov = Eigen::Matrix2d::Zero();
  for (const auto& p : pts) cov += (p - mean) * (p - mean).transpose();
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eig(cov);
  const V2 axis = eig.eigenvectors().col(1);
  V2 lo = pts.front(), hi = pts.front();
  for (const auto& p : pts) {
    if ((p - mean).dot(axis) < (lo - mean).dot(axis)) lo = p;
    if ((p - mean).dot(axis) > (hi - mean).dot(axis)) hi = p;
  }
  return {lo, hi};
}

}  // namespace

std::vector<EdgeInset> edge_insets(const SectionData& d, const Box& all, const PlotOptions& o,
                                   double max_half) {
  const double extent = std::max(all.u1 - all.u0, all.v1 - all.v0);
  const double min_half = std::min(std::max(o.inset_min_fraction * extent, 1e-9), max_half);
  std::vector<EdgeInset> out;
  if (!d.params.empty()) {
    for (const std::string key : {"le", "te"}) {
      EdgeInset e;
      e.key = key;
      e.label = key == "le" ? "LE" : "TE";
      e.edge_point = {param(d, key + "_u"), param(d, key + "_v")};
      e.point = finite(e.edge_point);
      e.circle_center = {param(d, key + "_center_u"), param(d, key + "_center_v")};
      e.radius = param(d, key + "_radius");
      e.circle = finite(e.circle_center) && std::isfinite(e.radius) && e.radius > 0;
      if (e.circle && o.inset_radii * e.radius <= max_half) {
        e.center = e.circle_center;
        e.half = std::max(o.inset_radii * e.radius, min_half);
      } else if (e.point) {  // no circle, or one too large to show the edge magnified
        e.center = e.edge_point;
        e.half = std::min(2.5 * min_half, max_half);
      } else if (e.circle) {
        e.center = e.circle_center;
        e.half = max_half;
      } else {
        continue;
      }
      out.push_back(e);
    }
    return out;
  }
  // No parameters: the ends of the camber line, else the profile's extremes along its
  // principal axis, each window moved inward so that it shows the edge, not the outside.
  std::pair<V2, V2> ends;
  double half = std::min(2.5 * min_half, max_half);
  if (d.camber.size() >= 2) {
    ends = {d.camber.front(), d.camber.back()};
  } else {
    std::vector<V2> pts;
    if (!d.splines.empty() || !d.polyline.empty()) pts = curve_of(d, curve_loops(d).front(), o, 1);
    if (pts.empty() && !d.points.empty()) pts = d.points.begin()->second;
    if (pts.size() < 3) return out;
    ends = principal_ends(pts);
    const V2 axis = (ends.second - ends.first).normalized();
    half = std::min(3 * min_half, max_half);
    if (finite(axis)) {
      ends.first += 0.6 * half * axis;
      ends.second -= 0.6 * half * axis;
    }
  }
  for (int k = 0; k < 2; ++k) {
    EdgeInset e;
    e.key = k == 0 ? "le" : "te";
    e.label = k == 0 ? "end 1" : "end 2";
    e.center = k == 0 ? ends.first : ends.second;
    e.half = half;
    out.push_back(e);
  }
  return out;
}

}  // namespace section::detail::plot

// SPDX-License-Identifier: GPL-3.0-or-later
// The blunt face of an edge (detail::blunt_face): the straightest cap of the profile
// near a medial end, across the directions about the axis behind its fork.
#include "detail/edge_fit.h"
#include "detail/sampled_profile.h"
#include "section/camber.h"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace section {

using detail::Face;
using detail::pi;
using detail::SampledProfile;

namespace {

// Scale W of an end: the diameter of the first circle (from the end) more than 1.5 radii
// back from it, and that circle's index in `iw`; 0 when there is none.
double end_width(const std::vector<InscribedCircle>& from_end, std::size_t& iw) {
  const Eigen::Vector2d end = from_end.front().center;
  for (std::size_t i = 0; i < from_end.size(); ++i)
    if ((from_end[i].center - end).norm() > 1.5 * from_end[i].radius) {
      iw = i;
      return 2 * from_end[i].radius;
    }
  return 0;
}

// Reference direction of a face: the axis behind the fork, from the circle `iw` outward
// (the end tangent itself follows the corner branch and can be 40 degrees off the face
// normal); d_end when the axis is too short.
Eigen::Vector2d behind_fork(const std::vector<InscribedCircle>& from_end, std::size_t iw, double w,
                            const Eigen::Vector2d& d_end) {
  for (std::size_t j = iw + 1; j < from_end.size(); ++j)
    if ((from_end[j].center - from_end[iw].center).norm() > w)
      return (from_end[iw].center - from_end[j].center).normalized();
  return d_end.normalized();
}

// The profile near `end`, densely resampled (601 points): the samples within `reach` of
// it, contiguous around the nearest one.
std::vector<Eigen::Vector2d> profile_near(const SampledProfile& pr, const Eigen::Vector2d& end,
                                          double reach) {
  const int n = static_cast<int>(pr.samples.size());
  const int near = pr.nearest(end);
  int lo = 0, hi = 0;
  while (lo > -n / 2 && (pr.samples[((near + lo - 1) % n + n) % n] - end).norm() < reach) --lo;
  while (hi < n / 2 && (pr.samples[(near + hi + 1) % n] - end).norm() < reach) ++hi;
  const double ta = pr.ts[near] + pr.period * lo / n, tb = pr.ts[near] + pr.period * hi / n;
  return pr.fast.points(ta, tb, 601);
}

// The largest distance between consecutive points of `p`, rounded up, and at least 1e-12
// of their largest coordinate (far above the rounding of a height along a direction).
double largest_step(const std::vector<Eigen::Vector2d>& p) {
  double step = 0, size = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    size = std::max(size, p[i].cwiseAbs().maxCoeff());
    if (i > 0) step = std::max(step, (p[i] - p[i - 1]).norm());
  }
  return std::max(step, 1e-12 * size) * (1 + 1e-9);
}

// The first point of `p` (consecutive points at most `step` apart) farthest along the unit
// f, as a full scan finds it. Point i + k lies at most h_i + k step along f, so the points
// after i that cannot reach the best height known (point `hint`'s, the highest along a
// direction close to f; else from every 8th point), less two steps for the rounding, are
// passed over: every point at the greatest height is still visited, in order.
int first_highest(const std::vector<Eigen::Vector2d>& p, const Eigen::Vector2d& f, double step, int hint) {
  const int m = static_cast<int>(p.size()) - 1;
  double bound = -std::numeric_limits<double>::infinity();
  if (hint >= 0)
    bound = p[hint].dot(f);
  else
    for (int i = 0; i <= m; i += 8) bound = std::max(bound, p[i].dot(f));
  int top = 0;
  double hmax = p[0].dot(f);
  for (int i = 1; i <= m;) {
    const double h = p[i].dot(f);
    if (h > hmax) top = i, hmax = h;
    const double gap = bound - h;  // NaN (a non-finite point): the next
    i += 1 + (gap > 3 * step ? static_cast<int>(std::min(gap / step - 2, static_cast<double>(m))) : 0);
  }
  return top;
}

// The points p[first..last] of a cap.
struct CapRange {
  int first = 0, last = -1;
  int size() const { return last - first + 1; }
};

// The cap of `p` (consecutive points at most `step` apart) within `depth` below its
// extreme point along f: its points into `out` and its width across f; -1 when the cap
// runs out of `p` (not an edge). `top`: the extreme point along the direction before
// (-1: none), replaced by this one.
double cap_along(const std::vector<Eigen::Vector2d>& p, const Eigen::Vector2d& f, double step, double depth,
                 CapRange& out, int& top) {
  const int m = static_cast<int>(p.size()) - 1;
  top = first_highest(p, f, step, top);
  const double hmax = p[top].dot(f);
  int a = top, b = top;
  while (a > 0 && p[a - 1].dot(f) >= hmax - depth) --a;
  while (b < m && p[b + 1].dot(f) >= hmax - depth) ++b;
  if (a == 0 || b == m) return -1.0;
  const Eigen::Vector2d u = detail::left_normal(f);
  double lo_u = std::numeric_limits<double>::infinity(), hi_u = -lo_u;
  for (int i = a; i <= b; ++i) lo_u = std::min(lo_u, p[i].dot(u)), hi_u = std::max(hi_u, p[i].dot(u));
  out = {a, b};
  return hi_u - lo_u;
}

// A straight cap: its points and total-least-squares line (mean, direction, normal, rms).
struct Cap {
  std::vector<Eigen::Vector2d> points;
  Eigen::Vector2d mean{0, 0}, along{1, 0}, normal{0, 1};
  double rms = std::numeric_limits<double>::infinity();
};

// Straightness of the points q of a cap: their total-least-squares line into `cap`.
void line_fit(const std::vector<Eigen::Vector2d>& p, CapRange q, Cap& cap) {
  cap.mean.setZero();
  for (int i = q.first; i <= q.last; ++i) cap.mean += p[i];
  cap.mean /= static_cast<double>(q.size());
  Eigen::Matrix2d cov = Eigen::Matrix2d::Zero();
  for (int i = q.first; i <= q.last; ++i) cov += (p[i] - cap.mean) * (p[i] - cap.mean).transpose();
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eig(cov);
  cap.along = eig.eigenvectors().col(1);
  cap.normal = eig.eigenvectors().col(0);
  cap.rms = std::sqrt(std::max(eig.eigenvalues()(0), 0.0) / q.size());
}

// The straightest cap of `p` among the directions within 40 degrees of d (a face need not
// be square to the end tangent; the widest cap would be square to a flank, running along
// it and round the corner). False when no direction gives a cap, or none can be
// `min_width` wide: a cap `width` wide across its direction and at most `depth` deep
// along it is at most hypot(width, depth) wide along any line, so the lines need not be
// fitted (a round edge's caps: 0.64 W at most).
bool straightest_cap(const std::vector<Eigen::Vector2d>& p, const Eigen::Vector2d& d, double depth,
                     double min_width, Cap& best) {
  const double step = largest_step(p);
  std::vector<CapRange> caps;
  bool wide_enough = false;
  int top = -1;
  for (int k = -40; k <= 40; ++k) {
    const double a = k * pi / 180;
    const Eigen::Vector2d g =
        Eigen::Vector2d(std::cos(a) * d.x() - std::sin(a) * d.y(), std::sin(a) * d.x() + std::cos(a) * d.y())
            .normalized();
    CapRange cap;
    const double width = cap_along(p, g, step, depth, cap, top);
    if (width < 0 || cap.size() < 3) continue;
    caps.push_back(cap);
    if (!(std::hypot(width, depth) * (1 + 1e-6) < min_width)) wide_enough = true;
  }
  if (!wide_enough) return false;
  bool found = false;
  for (const CapRange& range : caps) {
    Cap cap;
    line_fit(p, range, cap);
    if (cap.rms >= best.rms) continue;
    cap.points.assign(p.begin() + range.first, p.begin() + range.last + 1);
    best = cap;
    found = true;
  }
  return found;
}

}  // namespace

namespace detail {

// The cap of the profile within 0.1 W of its extreme point along a direction f is, at a
// round edge, a circular segment 2 sqrt(2 R 0.1 W) <= 0.63 W wide and bowed; at a blunt
// edge, with f the face normal, it is the face itself: as wide as the blade there (at
// least `blunt_face` W) and straight (line-fit rms below 0.2 of the cap depth; a circular
// segment gives 0.3).
Face blunt_face(const SampledProfile& pr, const std::vector<InscribedCircle>& from_end,
                const Eigen::Vector2d& d_end, const CamberOptions& options) {
  Face face;
  if (from_end.size() < 4) return face;
  const Eigen::Vector2d end = from_end.front().center;
  std::size_t iw = 0;
  const double w = end_width(from_end, iw);
  if (!(w > 1e-9 * pr.scale)) return face;
  const Eigen::Vector2d d = behind_fork(from_end, iw, w, d_end);
  const std::vector<Eigen::Vector2d> p =
      profile_near(pr, end, 1.5 * w + 2 * pr.period / static_cast<int>(pr.samples.size()));
  const double depth = 0.1 * w;
  Cap cap;
  if (!straightest_cap(p, d, depth, options.blunt_face * w, cap)) return face;
  const Eigen::Vector2d f = cap.normal.dot(d) < 0 ? Eigen::Vector2d(-cap.normal) : cap.normal;
  double smin = std::numeric_limits<double>::infinity(), smax = -smin;
  for (const auto& q : cap.points) {
    smin = std::min(smin, (q - cap.mean).dot(cap.along));
    smax = std::max(smax, (q - cap.mean).dot(cap.along));
  }
  const double width = smax - smin;
  if (width < options.blunt_face * w || cap.rms > 0.2 * depth) return face;
  face.found = true;
  face.width = width;
  face.mid = cap.mean + 0.5 * (smin + smax) * cap.along;
  face.normal = f;
  return face;
}

}  // namespace detail

}  // namespace section

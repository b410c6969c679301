// SPDX-License-Identifier: GPL-3.0-or-later
#include "section/medial_axis.h"

#include "detail/axis_curve.h"
#include "detail/camber_line.h"
#include "detail/cgal_medial_axis.h"
#include "detail/inscribed.h"
#include "detail/sampled_profile.h"
#include "section/error.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

namespace section {

using detail::AxisCurve;
using detail::SampledProfile;

namespace {

// The station at axis parameter u.
bool station(const SampledProfile& pr, const AxisCurve& ax, double u, const InscribedCircle* guess,
             InscribedCircle& out, bool fresh = true, int end = -1) {
  return detail::circle_on_normal(pr, ax.point(u), detail::left_normal(ax.tangent(u)), guess, out, fresh,
                                  end);
}

// From the last valid station outward (direction +1 or -1 in u): march until a station
// fails, then bisect for the end of the branch.
InscribedCircle find_end(const SampledProfile& pr, const AxisCurve& ax, double u, InscribedCircle last,
                         int direction, double tolerance, double first_step) {
  double lo = u, hi = u;
  InscribedCircle c;
  // March: the step grows while stations stay valid, bounded by the local radius.
  double h = std::clamp(first_step, 4 * tolerance * pr.scale, 0.05 * last.radius);
  for (int k = 0; k < 200; ++k) {
    hi = lo + direction * h;
    if (!station(pr, ax, hi, &last, c, false, direction > 0)) break;
    lo = hi;
    last = c;
    h = std::min(2 * h, 0.25 * c.radius);
    if (k == 199) return last;
  }
  while (std::abs(hi - lo) > tolerance * pr.scale) {
    const double mid = 0.5 * (lo + hi);
    if (station(pr, ax, mid, &last, c, false, direction > 0)) {
      lo = mid;
      last = c;
    } else {
      hi = mid;
    }
  }
  return last;
}

// The seed branch: options.seed, else the Delaunay medial axis of the profile samples.
std::vector<Eigen::Vector2d> seed_branch(const SampledProfile& pr, const MedialAxisOptions& options) {
  std::vector<Eigen::Vector2d> seed = options.seed;
  if (seed.empty()) {
    seed = detail::medial_axis_seed(pr.samples).points;
    if (seed.size() < 2)
      throw Error(
          "camber: the profile encloses no area to triangulate (flat on a line, or self-intersecting)");
  }
  return seed;
}

// The first axis: a stiff fit to the seed, whose ends wander into the edges; it only gives
// stations and normals.
AxisCurve seed_axis(const SampledProfile& pr, const std::vector<Eigen::Vector2d>& seed) {
  std::vector<Eigen::Vector2d> p;
  for (const auto& q : seed)
    if (p.empty() || (q - p.back()).norm() > 1e-9 * pr.scale) p.push_back(q);
  if (p.size() < 4) {
    // A branch shorter than 4 points: a circle-like shape, reported by the caller.
    if (p.size() == 1) p.push_back(p[0] + Eigen::Vector2d(1e-6 * pr.scale, 0));
    const Eigen::Vector2d a = p.front(), b = p.back();
    p.clear();
    for (int i = 0; i < 8; ++i) p.push_back(a + (b - a) * i / 7.0);
  }
  return AxisCurve(detail::fit_open(p, std::clamp(static_cast<int>(p.size()) / 4, 4, 24), 1e-2));
}

// One refinement pass: `m` stations along `ax`, clustered toward the ends (cosine
// spacing, where the axis turns fastest), solved outward from the widest valid one near
// the middle, then the branch's ends searched for from the outermost. Returns the
// circles end to end, the two ends included.
std::vector<InscribedCircle> branch_circles(const SampledProfile& pr, const AxisCurve& ax, int m,
                                            const std::vector<Eigen::Vector2d>& seed, double tolerance,
                                            double first_step) {
  std::vector<double> u(m);
  for (int k = 0; k < m; ++k) u[k] = ax.a + (ax.b - ax.a) * 0.5 * (1 - std::cos(detail::pi * k / (m - 1)));
  std::vector<InscribedCircle> solved(m);
  int start = -1;
  for (int d = 0; d < m && start < 0; ++d)
    for (int k : {m / 2 - d, m / 2 + d})
      if (k >= 0 && k < m && station(pr, ax, u[k], nullptr, solved[k])) {
        start = k;
        break;
      }
  if (start < 0) {
    // A circle's medial axis is its centre: the seed collapses and no station solves.
    if ((seed.front() - seed.back()).norm() < 1e-3 * pr.scale)
      throw Error("camber: the profile is not blade-like: its medial axis collapses to a point");
    throw Error("camber: no circle inscribed in the profile was found on the seed axis");
  }
  int first = start, last = start;
  while (last + 1 < m && station(pr, ax, u[last + 1], &solved[last], solved[last + 1])) ++last;
  while (first - 1 >= 0 && station(pr, ax, u[first - 1], &solved[first], solved[first - 1])) --first;
  const InscribedCircle e0 = find_end(pr, ax, u[first], solved[first], -1, tolerance, first_step);
  const InscribedCircle e1 = find_end(pr, ax, u[last], solved[last], +1, tolerance, first_step);
  std::vector<InscribedCircle> circles{e0};
  for (int k = first; k <= last; ++k)
    if ((solved[k].center - circles.back().center).norm() > 1e-6 * pr.scale) circles.push_back(solved[k]);
  if ((e1.center - circles.back().center).norm() <= 1e-6 * pr.scale) circles.pop_back();
  circles.push_back(e1);
  return circles;
}

}  // namespace

bool inscribed_circle(const BSpline& profile, const Eigen::Vector2d& point, const Eigen::Vector2d& normal,
                      double t_left, double t_right, InscribedCircle& circle) {
  check_spline(profile);
  if (!point.allFinite() || !normal.allFinite() || normal.isZero() || !std::isfinite(t_left) ||
      !std::isfinite(t_right))
    throw Error("medial_axis: inscribed_circle needs a finite point and parameters and a non-zero normal");
  double scale = 0;
  for (const auto& c : profile.control) scale = std::max(scale, (c - profile.control[0]).norm());
  return detail::solve_circle(detail::PiecewiseCurve(profile), point, normal.normalized(), t_left, t_right,
                              std::max(scale, 1e-300), circle);
}

MedialAxis medial_axis(const BSpline& profile, const MedialAxisOptions& options) {
  detail::check_options(options);
  return detail::medial_axis(SampledProfile(profile, options.samples), options);
}

namespace detail {

MedialAxis medial_axis(const SampledProfile& pr, const MedialAxisOptions& options, AxisCurve* axis) {
  MedialAxis result;
  const std::vector<Eigen::Vector2d> seed = seed_branch(pr, options);
  result.seed_points = static_cast<int>(seed.size());
  AxisCurve ax = seed_axis(pr, seed);
  const int m = std::max(options.stations, 16);
  std::vector<InscribedCircle> circles;
  Eigen::Vector2d end0(0, 0), end1(0, 0);
  result.change = pr.scale;
  for (int pass = 0; pass < std::max(options.iterations, 1); ++pass) {
    // Later passes start at the previous ends: a first step of the last change suffices.
    const double step = pass == 0 ? pr.scale : 2 * result.change;
    circles = branch_circles(pr, ax, m, seed, options.tolerance, step);
    const Eigen::Vector2d e0 = circles.front().center, e1 = circles.back().center;
    result.change = pass == 0 ? pr.scale : std::max((e0 - end0).norm(), (e1 - end1).norm());
    end0 = e0;
    end1 = e1;
    result.iterations = pass + 1;
    if (circles.size() < 4) break;
    ax = detail::make_axis(detail::centers(circles), 1e-8);
    if (result.change < 1e-6 * pr.scale) break;
  }
  if (circles.size() < 4)
    throw Error("camber: the medial axis has only " + std::to_string(circles.size()) +
                " inscribed circles (the profile is not blade-like)");
  result.circles = circles;
  result.curve = ax.spline;
  if (axis) *axis = std::move(ax);
  return result;
}

}  // namespace detail

}  // namespace section

// SPDX-License-Identifier: GPL-3.0-or-later
#include "detail/coverage.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>

namespace section::detail {

namespace {

// How many of the `measured` points lie nearest to each of `samples` (h apart along the
// profile), counting a point only when that sample lies within 2h. Samples are bucketed in
// cells wider than 4h, so the 2 x 2 cells that the disc of radius 2h about a point reaches
// hold every sample that can count; ties go to the lowest index, as a scan of all samples
// would give.
std::vector<int> nearest_counts(const std::vector<Eigen::Vector2d>& samples,
                                const std::vector<Eigen::Vector2d>& measured, double h) {
  const double cell = 4.5 * h;
  Eigen::Vector2d low = samples.front(), high = samples.front();
  for (const auto& s : samples)
    if (s.allFinite()) low = low.cwiseMin(s), high = high.cwiseMax(s);
  const int nx = static_cast<int>((high.x() - low.x()) / cell) + 1,
            ny = static_cast<int>((high.y() - low.y()) / cell) + 1;
  auto cell_of = [&](double v, double v0, int n) {
    return static_cast<int>(std::clamp(std::floor((v - v0) / cell), -1.0, double(n)));
  };
  std::vector<int> head(static_cast<std::size_t>(nx) * ny, -1), next(samples.size(), -1);
  for (int k = static_cast<int>(samples.size()) - 1; k >= 0; --k) {
    if (!samples[k].allFinite()) continue;
    const std::size_t c =
        std::size_t(cell_of(samples[k].y(), low.y(), ny - 1)) * nx + cell_of(samples[k].x(), low.x(), nx - 1);
    next[k] = head[c];
    head[c] = k;
  }
  // Points farther than 2h outside the samples' box count for none.
  const Eigen::Vector2d margin(2 * h, 2 * h), box_low = low - margin, box_high = high + margin;
  std::vector<int> covered(samples.size(), 0);
  for (const auto& q : measured) {
    if (!(q.x() >= box_low.x() && q.y() >= box_low.y() && q.x() <= box_high.x() && q.y() <= box_high.y()))
      continue;
    // The cells the disc reaches: the point's and, on each axis, the one its nearer side faces.
    const int x0 = cell_of(q.x() - 2 * h, low.x(), nx), x1 = cell_of(q.x() + 2 * h, low.x(), nx),
              y0 = cell_of(q.y() - 2 * h, low.y(), ny), y1 = cell_of(q.y() + 2 * h, low.y(), ny);
    int best = -1;
    double best_d = std::numeric_limits<double>::infinity();
    for (int y = std::max(y0, 0); y <= std::min(y1, ny - 1); ++y)
      for (int x = std::max(x0, 0); x <= std::min(x1, nx - 1); ++x)
        for (int k = head[std::size_t(y) * nx + x]; k >= 0; k = next[k]) {
          const double d = (q - samples[k]).squaredNorm();
          if (d < best_d || (d == best_d && k < best)) best_d = d, best = k;
        }
    if (best >= 0 && std::sqrt(best_d) <= 2 * h) ++covered[best];
  }
  return covered;
}

// Which of 2 half + 1 samples of `curve`, every h = reach / half along it from -reach to
// +reach about parameter t, the `measured` points cover, and by how many. Empty where the
// curve stops advancing (a zero speed).
std::vector<int> covered_about(const detail::PiecewiseCurve& curve, double t0,
                               const std::vector<Eigen::Vector2d>& measured, double reach, int half,
                               std::vector<Eigen::Vector2d>& samples) {
  const double h = reach / half;
  samples.assign(2 * half + 1, Eigen::Vector2d::Zero());
  detail::PiecewiseCurve::Cursor cursor;
  detail::CurveJet jet = curve.jet(curve.locate(t0, cursor));
  samples[half] = jet.point;
  const double speed0 = jet.d1.norm();
  for (int dir : {-1, 1}) {
    double t = t0, speed = speed0;
    for (int k = 1; k <= half; ++k) {
      if (!(speed > 0)) return {};
      t += dir * h / speed;
      jet = curve.jet(curve.locate(t, cursor));
      samples[half + dir * k] = jet.point;
      speed = jet.d1.norm();
    }
  }
  return nearest_counts(samples, measured, h);
}

// f(k, e, length, distance) for each uncovered run k..e-1 of `covered` (samples h apart
// about its middle one): its length counts one sample more (up to the covered ones about
// it), its distance from the middle is 0 when it holds the middle.
template <class F>
void each_run(const std::vector<int>& covered, double h, F&& f) {
  const int half = int(covered.size() / 2);
  for (int k = 0; k <= 2 * half;) {
    if (covered[k]) {
      ++k;
      continue;
    }
    int e = k;
    while (e <= 2 * half && !covered[e]) ++e;
    f(k, e, (e - k + 1) * h, k > half ? (k - 1 - half) * h : e <= half ? (half - e) * h : 0.0);
    k = e;
  }
}

// The longest uncovered stretch of `covered` (samples h apart about its middle one) that
// begins within `near` of the middle, into `length` and its `distance` from it (0 when it
// holds the middle); both left as they are when there is none. `first`, `last` (when
// given): its uncovered samples.
void longest_hole(const std::vector<int>& covered, double h, double near, double& length, double& distance,
                  int* first = nullptr, int* last = nullptr) {
  each_run(covered, h, [&](int k, int e, double l, double d) {
    if (d <= near && l > length) {
      length = l, distance = d;
      if (first && last) *first = k, *last = e - 1;
    }
  });
}

// The points' mean distance over samples [from, to) of `covered` (h apart); 0 with no point.
double mean_distance(const std::vector<int>& covered, int from, int to, double h) {
  double points = 0;
  for (int k = from; k < to; ++k) points += covered[std::size_t(k)];
  return points > 0 ? (to - from) * h / points : 0.0;
}

// Of the holes of `covered` (samples h apart about its middle one) beginning within `near`
// of the middle, the one whose curve (`samples`) strays farthest from the segment between
// the covered samples that close it: that distance into `out.bend`, the hole's length and
// distance from the middle into bend_hole and bend_distance. A hole is an uncovered run
// longer than `spacings` times the points' mean distance over its length either side, the
// sparser side's: evenly sparse points (a CMM row's) leave runs between them, not holes.
void widest_bend(const std::vector<int>& covered, const std::vector<Eigen::Vector2d>& samples, double h,
                 double near, double spacings, EdgeCoverage& out) {
  const int last = int(covered.size()) - 1;
  each_run(covered, h, [&](int k, int e, double length, double d) {
    const int run = e - k;
    const double spacing = std::max(mean_distance(covered, std::max(k - run, 0), k, h),
                                    mean_distance(covered, e, std::min(e + run, last + 1), h));
    if (!(d <= near && length > spacings * spacing)) return;
    const Eigen::Vector2d a = samples[std::max(k - 1, 0)], ab = samples[std::min(e, last)] - a;
    const double length2 = ab.squaredNorm();
    double bend = 0;
    for (int i = k; i < e; ++i) {
      const double along = length2 > 0 ? std::clamp((samples[i] - a).dot(ab) / length2, 0.0, 1.0) : 0.0;
      bend = std::max(bend, (samples[i] - a - along * ab).norm());
    }
    if (bend > out.bend) out.bend = bend, out.bend_hole = length, out.bend_distance = d;
  });
}

}  // namespace

EdgeCoverage edge_coverage(const detail::PiecewiseCurve& curve, const Edge& edge,
                           const std::vector<Eigen::Vector2d>& measured, double arc_reach,
                           double hole_spacings) {
  EdgeCoverage out;
  const double size = edge_size(edge);
  if (measured.empty() || !(size > 0) || !std::isfinite(edge.t)) return out;
  const int half = 200;
  const double reach = 3 * 3.14159265358979 * size, h = reach / half;
  std::vector<Eigen::Vector2d> samples;
  const std::vector<int> covered = covered_about(curve, edge.t, measured, reach, half, samples);
  if (covered.empty()) return out;
  int lo = half, hi = half;
  while (lo > 0 && !covered[lo]) --lo;
  while (hi < 2 * half && !covered[hi]) ++hi;
  if (!covered[half]) out.around = (hi - lo) * h;
  longest_hole(covered, h, arc_reach * size, out.hole, out.hole_distance);
  widest_bend(covered, samples, h, arc_reach * size, hole_spacings, out);
  return out;
}

bool unmeasured(const ContactCoverage& c, double limit, double spacings) {
  return c.hole > limit && c.hole > spacings * c.spacing;
}

ProfileCoverage::ProfileCoverage(const detail::PiecewiseCurve& curve,
                                 const std::vector<Eigen::Vector2d>& measured, double h)
    : h_(h), t_min_(curve.t_min()), period_(curve.t_max() - curve.t_min()) {
  if (measured.empty() || !(h > 0) || !(period_ > 0)) return;
  // Far more samples than any profile needs at its step (a blade's is about 2 000 around)
  // say the step or the parameter is wrong (one that no longer advances): no coverage then,
  // as for a zero speed.
  constexpr std::size_t most = 4'000'000;
  std::vector<Eigen::Vector2d> samples;
  detail::PiecewiseCurve::Cursor cursor;
  for (double t = t_min_; t < t_min_ + period_;) {
    const detail::CurveJet jet = curve.jet(curve.locate(t, cursor));
    const double speed = jet.d1.norm();
    if (!(speed > 0) || samples.size() == most) {
      t_.clear();
      return;
    }
    t_.push_back(t);
    samples.push_back(jet.point);
    t += h / speed;
  }
  covered_ = nearest_counts(samples, measured, h);
}

ContactCoverage ProfileCoverage::about(double t, double reach, double near) const {
  ContactCoverage out;
  if (t_.empty() || !std::isfinite(t) || !(reach > 0)) return out;
  // The sample nearest t (in parameter, wrapped into the period), and the window about it.
  const double w = t_min_ + std::fmod(std::fmod(t - t_min_, period_) + period_, period_);
  const std::size_t n = t_.size(),
                    above = std::size_t(std::upper_bound(t_.begin(), t_.end(), w) - t_.begin());
  const double to_next = (above < n ? t_[above] : t_min_ + period_) - w;
  const std::size_t centre = above == 0 ? 0 : to_next < w - t_[above - 1] ? above % n : above - 1;
  const int half = static_cast<int>(std::min<double>(std::round(reach / h_), double((n - 1) / 2)));
  std::vector<int> covered(2 * std::size_t(half) + 1);
  for (int k = -half; k <= half; ++k)
    covered[std::size_t(k + half)] = covered_[std::size_t((long(centre) + long(n) + k) % long(n))];
  int first = half, last = half - 1;  // the hole near t (none: an empty stretch at t)
  longest_hole(covered, h_, near, out.hole, out.hole_distance, &first, &last);
  if (first <= half && half <= last) out.inside = std::min(half - first + 1, last + 1 - half) * h_;
  // The points' mean distance either side of that hole, the sparser side's: a hole is one
  // in the points on both sides (evenly sparse points beside dense ones, a CMM row's
  // beside its edges', hold none).
  const int end = 2 * half + 1;
  out.spacing = std::max(mean_distance(covered, 0, first, h_), mean_distance(covered, last + 1, end, h_));
  return out;
}

ContactCoverage ProfileCoverage::longest(double reach) const {
  const std::size_t n = covered_.size();
  std::size_t best = 0, best_end = 0, run = 0;
  for (std::size_t k = 0; k < 2 * n; ++k) {  // twice around: a run across the period's end
    run = covered_[k % n] ? 0 : std::min(run + 1, n);
    if (run > best) best = run, best_end = k;
  }
  if (best == 0) return {};
  return about(t_[(best_end + n - best / 2) % n], reach, 0);
}

double end_fit_weight(const ContactCoverage& c, double limit, double spacings) {
  if (!(c.inside > 0) || !(c.hole > 0)) return 1;
  const double ratio =
      std::min(c.hole / limit, c.spacing > 0 ? c.hole / (2 * spacings * c.spacing) : c.hole / limit);
  return 1 - std::clamp(ratio - 1, 0.0, 1.0) * std::clamp(c.inside / (0.1 * c.hole), 0.0, 1.0);
}

void weigh_bridged(const PiecewiseCurve& curve, const std::vector<Eigen::Vector2d>& measured, double reach,
                   double hole, double spacings, std::vector<InscribedCircle>& circles) {
  const std::size_t n = circles.size();
  if (measured.empty() || !(hole > 0) || !(reach > 0) || n < 3) return;
  // Samples every 15 % of the hole length tell it; the points' mean distance is read over
  // 5 hole lengths either side.
  const double h = 0.15 * hole;
  const ProfileCoverage cover(curve, measured, h);
  const auto weight = [&](double t) { return end_fit_weight(cover.about(t, 5 * hole, 0), hole, spacings); };
  const auto weigh = [&](InscribedCircle& c) {
    c.fit_weight = std::min(weight(c.t_left), weight(c.t_right));
  };
  double from_front = 0, from_back = 0;
  std::size_t front = 1, back = n - 2;  // the next circles to weigh from either end
  for (; front < n - 1; ++front) {
    from_front += (circles[front].center - circles[front - 1].center).norm();
    if (from_front > reach) break;
    weigh(circles[front]);
  }
  for (; back > front; --back) {
    from_back += (circles[back].center - circles[back + 1].center).norm();
    if (from_back > reach) break;
    weigh(circles[back]);
  }
}

}  // namespace section::detail

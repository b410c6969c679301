// SPDX-License-Identifier: GPL-3.0-or-later
#include "detail/sampled_profile.h"

#include "section/error.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

namespace section::detail {

namespace {

// The circle about the mean of samples [begin, end) through the farthest of them.
SampledProfile::Run run_of(const std::vector<Eigen::Vector2d>& samples, std::size_t begin, std::size_t end) {
  Eigen::Vector2d center = Eigen::Vector2d::Zero();
  for (std::size_t i = begin; i < end; ++i) center += samples[i];
  center /= static_cast<double>(end - begin);
  double radius = 0;
  for (std::size_t i = begin; i < end; ++i) radius = std::max(radius, (samples[i] - center).norm());
  return {center, radius + 1e-9 * (radius + center.cwiseAbs().sum())};
}

// The point of the segment nearest q, less q.
Eigen::Vector2d segment_offset(const SampledProfile::Segment& s, const Eigen::Vector2d& q) {
  const double t = std::clamp((q - s.a).dot(s.ab) * s.inverse_length2, 0.0, 1.0);
  return s.a + t * s.ab - q;
}

// The segment of samples [begin, end).
SampledProfile::Segment segment_of(const std::vector<Eigen::Vector2d>& samples, std::size_t begin,
                                   std::size_t end) {
  const Eigen::Vector2d ab = samples[end - 1] - samples[begin];
  SampledProfile::Segment s{samples[begin], ab, ab.squaredNorm() > 0 ? 1 / ab.squaredNorm() : 0, 0};
  double spread = 0;
  for (std::size_t i = begin; i < end; ++i) spread = std::max(spread, segment_offset(s, samples[i]).norm());
  s.reach = spread + 1e-9 * (spread + s.a.cwiseAbs().sum() + samples[end - 1].cwiseAbs().sum());
  return s;
}

}  // namespace

namespace {

// The curve checked before its pieces are built: every public entry reaches it from here.
PiecewiseCurve checked_pieces(const BSpline& c) {
  check_spline(c);
  return PiecewiseCurve(c);
}

}  // namespace

SampledProfile::SampledProfile(const BSpline& c, int count) : SampledProfile(c, checked_pieces(c), count) {}

SampledProfile::SampledProfile(const BSpline& c, PiecewiseCurve f, int count, bool with_runs)
    : curve(c), fast(std::move(f)) {
  if (!c.closed) throw Error("camber: the profile spline is open, a closed curve is needed");
  if (c.control.size() < 4) throw Error("camber: the profile spline has too few control points");
  t0 = c.t_min();
  period = c.t_max() - t0;
  count = std::max(count, 64);
  samples.reserve(count);
  ts.reserve(count);
  // In order: the span of the sample before is tried first (the same span a search finds),
  // and only the point is evaluated (the same arithmetic as the jet's).
  PiecewiseCurve::Local at{0, 0};
  for (int i = 0; i < count; ++i) {
    ts.push_back(t0 + period * i / count);
    at = fast.locate(ts.back(), at.span);
    samples.push_back(fast.point(at));
  }
  Eigen::Vector2d low = samples[0], high = samples[0];
  double area = 0;
  for (int i = 0; i < count; ++i) {
    low = low.cwiseMin(samples[i]);
    high = high.cwiseMax(samples[i]);
    area += cross(samples[i], samples[(i + 1) % count]);
  }
  for (int i = 0; i < count; ++i) step = std::max(step, (samples[(i + 1) % count] - samples[i]).norm());
  step *= 1 + 1e-9;  // an upper bound despite the rounding of the norms
  scale = (high - low).norm();
  if (!(scale > 0) || !std::isfinite(scale)) throw Error("camber: the profile is degenerate");
  sigma = area >= 0 ? 1 : -1;
  if (!with_runs) return;
  const std::size_t n = samples.size(), k = run_samples;
  for (std::size_t i = 0; i < n; i += k) runs.push_back(segment_of(samples, i, std::min(n, i + k)));
  for (std::size_t i = 0; i < n; i += k * long_run)
    long_runs.push_back(run_of(samples, i, std::min(n, i + k * long_run)));
}

namespace {

// How far a scan moves on from a sample `gap` farther from q than it needs (samples
// `step` apart, n of them): the samples that cannot come near enough are passed over, with
// a margin of two steps over the rounding.
int samples_on(double gap, double step, int n) {
  const double skip = gap > 3 * step ? gap / step - 2 : 0;
  return 1 + static_cast<int>(std::min(skip, static_cast<double>(n)));
}

// The first sample at the least distance from q (as a full scan finds it) and its squared
// distance (infinite for a non-finite q, index 0). Sample i + m is at least r_i - m step
// from q (r_i: sample i's distance), so the samples after i that cannot come nearer than
// the best so far are skipped, with a margin of two steps over the rounding: every sample
// at the least distance is still visited, in order. The best starts at `bound2`, a squared
// distance of some sample to q: the nearer it is, the more samples are skipped.
std::pair<int, double> first_nearest(const std::vector<Eigen::Vector2d>& samples, double step,
                                     const Eigen::Vector2d& q, double bound2) {
  const int n = static_cast<int>(samples.size());
  double bound = std::sqrt(bound2), best2 = std::numeric_limits<double>::infinity();
  int best = 0;
  for (int i = 0; i < n;) {
    const double d2 = (samples[i] - q).squaredNorm();
    if (d2 < best2) best2 = d2, best = i;
    if (d2 < bound2) bound2 = d2, bound = std::sqrt(d2);
    i += samples_on(std::sqrt(d2) - bound, step, n);  // NaN gap (a non-finite q): the next
  }
  return {best, best2};
}

// The least squared distance from q to every 16th sample: most samples are far from q
// and then skipped (the scan visits one in five or fewer).
double coarse_bound(const std::vector<Eigen::Vector2d>& samples, const Eigen::Vector2d& q) {
  double bound2 = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < samples.size(); i += 16)
    bound2 = std::min(bound2, (samples[i] - q).squaredNorm());
  return bound2;
}

}  // namespace

int SampledProfile::nearest_on_side(const Eigen::Vector2d& q, const Eigen::Vector2d& n) const {
  // As first_nearest, the best so far that side of the line: the samples after i that
  // cannot come nearer are skipped (whichever side they lie), every one at the least
  // distance still visited, in order.
  const int count = static_cast<int>(samples.size());
  int best = -1;
  double d = std::numeric_limits<double>::infinity(), bound = d;
  for (int i = 0; i < count;) {
    const Eigen::Vector2d e = samples[i] - q;
    if (e.dot(n) > 0 && e.squaredNorm() < d) d = e.squaredNorm(), best = i, bound = std::sqrt(d);
    i += samples_on(std::sqrt(e.squaredNorm()) - bound, step, count);  // NaN gap: the next
  }
  return best;
}

int SampledProfile::nearest(const Eigen::Vector2d& q) const {
  return first_nearest(samples, step, q, coarse_bound(samples, q)).first;
}

int SampledProfile::nearest(const Eigen::Vector2d& q, int hint) const {
  // The hint and its neighbours bound the distance (points in order along the profile:
  // the last point's nearest sample lies close).
  const int n = static_cast<int>(samples.size());
  double bound2 = std::numeric_limits<double>::infinity();
  for (int k = -8; k <= 8; ++k)
    bound2 = std::min(bound2, (samples[((hint + k) % n + n) % n] - q).squaredNorm());
  return first_nearest(samples, step, q, bound2).first;
}

double SampledProfile::sample_distance(const Eigen::Vector2d& q) const {
  return std::sqrt(first_nearest(samples, step, q, coarse_bound(samples, q)).second);
}

bool SampledProfile::sample_within(const Eigen::Vector2d& q, double r) const {
  if (!(r > 0)) return false;  // no distance is less (none is NaN)
  // Only the samples of the runs within reach of q are compared, with the same distance
  // as sample_distance's. A run's samples lie r or more from q, also as rounded, when q
  // lies farther from its circle's center (its segment) than its radius (spread) plus r,
  // each widened by a million times the rounding of the distances (q's |q|_1 + r bounds
  // its share).
  const double reach = r + 1e-9 * (q.cwiseAbs().sum() + r);
  auto beyond = [&](const Run& run) {
    return (run.center - q).squaredNorm() > std::pow(run.reach + reach, 2);
  };
  const std::size_t n = samples.size(), k = run_samples;
  if (runs.empty())
    return std::any_of(samples.begin(), samples.end(),
                       [&](const Eigen::Vector2d& p) { return std::sqrt((p - q).squaredNorm()) < r; });
  for (std::size_t l = 0; l < long_runs.size(); ++l) {
    if (beyond(long_runs[l])) continue;
    for (std::size_t j = l * long_run; j < std::min(runs.size(), (l + 1) * long_run); ++j) {
      if (segment_offset(runs[j], q).squaredNorm() > std::pow(runs[j].reach + reach, 2)) continue;
      for (std::size_t i = j * k; i < std::min(n, (j + 1) * k); ++i)
        if (std::sqrt((samples[i] - q).squaredNorm()) < r) return true;
    }
  }
  return false;
}

bool inside_polygon(const std::vector<Eigen::Vector2d>& polygon, const Eigen::Vector2d& q) {
  const int n = static_cast<int>(polygon.size());
  if (n < 3) return false;
  int crossings = 0;
  // The segments (i - 1, i), the closing one first; each end's side of q carried over.
  bool a_above = polygon[n - 1].y() > q.y();
  for (int i = 0; i < n; ++i) {
    const Eigen::Vector2d& a = polygon[i == 0 ? n - 1 : i - 1];
    const Eigen::Vector2d& b = polygon[i];
    const bool b_above = b.y() > q.y();
    if (a_above != b_above && q.x() < a.x() + (q.y() - a.y()) / (b.y() - a.y()) * (b.x() - a.x()))
      ++crossings;
    a_above = b_above;
  }
  return crossings % 2 == 1;
}

double foot_parameter(const SampledProfile& pr, const Eigen::Vector2d& q, double t) {
  const double h = pr.period / static_cast<double>(pr.samples.size());
  PiecewiseCurve::Cursor at;  // Newton's steps are short: the span before is tried first
  for (int it = 0; it < 30; ++it) {
    const CurveJet j = pr.fast.jet(pr.fast.locate(t, at));
    const Eigen::Vector2d e = j.point - q;
    const double g = e.dot(j.d1), dg = j.d1.squaredNorm() + e.dot(j.d2);
    if (!(dg > 0)) break;
    const double step = std::clamp(g / dg, -h, h);
    t -= step;
    if (std::abs(step) < 1e-14 * pr.period) break;
  }
  return t;
}

bool ray_hit(const SampledProfile& pr, const Eigen::Vector2d& m, const Eigen::Vector2d& d, double& t_hit) {
  const int n = static_cast<int>(pr.samples.size());
  double best = std::numeric_limits<double>::infinity();
  int seg = -1;
  for (int i = 0; i < n; ++i) {
    const Eigen::Vector2d p = pr.samples[i] - m, q = pr.samples[(i + 1) % n] - m;
    const double gp = cross(d, p), gq = cross(d, q);
    if ((gp > 0) == (gq > 0) && gp != 0 && gq != 0) continue;
    const double w = gp == gq ? 0 : gp / (gp - gq);
    const double along = (p + w * (q - p)).dot(d);
    if (along > 0 && along < best) best = along, seg = i;
  }
  if (seg < 0) return false;
  // Safeguarded secant on g(t) = d x (C(t) - m) inside the bracketing span.
  double a = pr.ts[seg], b = a + pr.period / n;
  PiecewiseCurve::Cursor at;  // the bracket narrows: its span is tried first
  auto g = [&](double t) { return cross(d, pr.fast.point(pr.fast.locate(t, at)) - m); };
  double ga = g(a), gb = g(b);
  for (int it = 0; it < 100 && std::abs(b - a) > 1e-15 * pr.period; ++it) {
    double t = ga == gb ? 0.5 * (a + b) : a - ga * (b - a) / (gb - ga);
    if (!(t > a && t < b)) t = 0.5 * (a + b);
    const double gt = g(t);
    if (gt == 0) {
      a = b = t;
      break;
    }
    if ((gt > 0) == (ga > 0)) {
      a = t, ga = gt;
      gb *= 0.5;  // Illinois step keeps both ends moving
    } else {
      b = t, gb = gt;
      ga *= 0.5;
    }
  }
  t_hit = pr.wrap(0.5 * (a + b));
  return true;
}

}  // namespace section::detail

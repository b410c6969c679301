// SPDX-License-Identifier: GPL-3.0-or-later
#include "fit_spline_steps.h"

#include <algorithm>
#include <cmath>

namespace section::fit {

// The curve on new knots: least squares on dense samples of the old curve, so that the
// shape carries over to the refined knot vector (almost exactly: the old space nests in
// the new one when knots were only inserted).
BSpline reknot(const BSpline& c, const detail::PiecewiseCurve& pc, const std::vector<double>& knots) {
  BSpline shape = c;
  shape.knots = knots;
  shape.control.assign(knots.size() - 1, Eigen::Vector2d::Zero());
  std::vector<double> ts = span_samples(shape, 12);
  Points pts(ts.size());
  detail::PiecewiseCurve::Local at{0, 0};
  for (std::size_t i = 0; i < ts.size(); ++i) pts[i] = pc.point(at = pc.locate(ts[i], at.span));
  return fit_control_points(pts, ts, shape, 1e-12);
}

// Fewest measured points per knot span: on near-exact data the change-of-curvature
// penalty, scaled by the noise variance, no longer acts and a denser floor keeps the
// curve from wiggling between points.
double points_per_span(const FitSplineOptions& o, double sigma) {
  return sigma < o.exact_noise ? std::max(o.min_span_points, o.exact_min_span_points) : o.min_span_points;
}

namespace {

// The largest of v[i - reach .. i + reach] (wrapped) and 0 for each i, NaNs ignored,
// m > reach: maxima over blocks of 2 reach + 1 from both ends (van Herk, Gil and Werman),
// so a few operations per sample instead of 2 reach + 1. A maximum is exact in any order.
std::vector<double> window_max(const std::vector<double>& v, std::size_t reach) {
  const std::size_t m = v.size(), width = 2 * reach + 1, len = m + 2 * reach;
  auto at = [&](std::size_t x) {  // x in [0, m + 2 reach): v[x - reach], wrapped
    const std::size_t j = x + m - reach;
    return v[j >= 2 * m ? j - 2 * m : (j >= m ? j - m : j)];
  };
  std::vector<double> forward(len), backward(len);
  for (std::size_t x = 0; x < len; ++x) forward[x] = std::max(x % width == 0 ? 0.0 : forward[x - 1], at(x));
  for (std::size_t x = len; x-- > 0;)
    backward[x] = std::max(x + 1 == len || (x + 1) % width == 0 ? 0.0 : backward[x + 1], at(x));
  std::vector<double> out(m);
  for (std::size_t i = 0; i < m; ++i) out[i] = std::max(backward[i], forward[i + width - 1]);
  return out;
}

// Measured points per unit length around each sample i: the hits and lengths ds of the
// samples i - k .. i + k (wrapped), k growing until the length reaches 2 window (or half
// the loop). The lengths add up in that order, a pair (i + k, i - k) at a time, as the
// density always has; the hits are whole numbers, whose sums are exact in any order (so
// prefix sums). ds is laid out unwrapped: the inner loop wraps nothing.
std::vector<double> window_density(const std::vector<double>& ds, const std::vector<double>& hits,
                                   double window) {
  const std::size_t m = ds.size(), reach = m / 2 > 0 ? m / 2 - 1 : 0;  // the largest k
  std::vector<double> wide(m + 2 * reach), hits_before(m + 2 * reach + 1, 0);
  for (std::size_t x = 0; x < wide.size(); ++x) {
    const std::size_t j = (x + m - reach) % m;  // sample x - reach, wrapped
    wide[x] = ds[j];
    hits_before[x + 1] = hits_before[x] + hits[j];
  }
  std::vector<double> out(m);
  const double limit = 2 * window;
  for (std::size_t i = 0; i < m; ++i) {
    const double* centre = &wide[i + reach];
    const double *up = centre + 1, *down = centre - 1, *last = centre + reach;
    double length = centre[0];
    // Four pairs a pass (hundreds of pairs around an edge's short spans), each tested.
    while (up + 3 <= last && length < limit) {
      if (!((length += up[0] + down[0]) < limit)) {
        up += 1, down -= 1;
        break;
      }
      if (!((length += up[1] + down[-1]) < limit)) {
        up += 2, down -= 2;
        break;
      }
      if (!((length += up[2] + down[-2]) < limit)) {
        up += 3, down -= 3;
        break;
      }
      length += up[3] + down[-3];
      up += 4, down -= 4;
    }
    for (; up <= last && length < limit; ++up, --down) length += *up + *down;
    const std::size_t k = static_cast<std::size_t>(up - centre);  // the pairs added: k - 1
    const double count = hits_before[i + reach + k] - hits_before[i + reach + 1 - k];
    out[i] = length > 0 ? count / length : 0;
  }
  return out;
}

}  // namespace

// Knots spread by the approximation error of a cubic on a circle: a span of length h on
// curvature k deviates by about (5/384) h^4 k^3, so h = (76.8 tol / k^3)^(1/4), between
// min_span and initial_span. Edges (small radii) get dense knots, flanks sparse ones.
// Noise sets the useful tolerance (half a sigma: a shorter span fits the noise more than
// it removes bias), and each span keeps at least min_span_points measured points.
std::vector<double> curvature_knots(const BSpline& c, const detail::PiecewiseCurve& pc, const Feet& feet,
                                    double sigma, const FitSplineOptions& o) {
  const std::vector<double> ts = span_samples(c, 32);
  const std::size_t m = ts.size();
  std::vector<detail::CurveJet> jets;  // reserved, not zeroed: it is filled once
  jets.reserve(m);
  detail::PiecewiseCurve::Local at{0, 0};
  for (std::size_t i = 0; i < m; ++i) jets.push_back(pc.jet(at = pc.locate(ts[i], at.span)));
  std::vector<double> density(m), ds(m);
  const double tol = std::max(o.tolerance, 0.5 * sigma);
  // Measured points per unit length around each sample, over a window of +-window.
  // The feet in order along the curve meet the samples in order: one walk, not a search each.
  std::vector<double> hits(m, 0);
  std::size_t next = 0;  // first sample after the foot (std::upper_bound)
  for (std::size_t k : feet.order) {
    while (next < m && !(feet.t[k] < ts[next])) ++next;
    hits[next > 0 ? next - 1 : 0] += 1;
  }
  for (std::size_t i = 0; i < m; ++i)
    ds[i] = jets[i].d1.norm() * ((i + 1 < m ? ts[i + 1] : c.t_max()) - ts[i]);
  const std::vector<double> point_density = window_density(ds, hits, 0.5 * o.initial_span);
  // An h^4 past these bounds (by a margin far above pow's rounding) is clamped without
  // the pow, to what the clamp of the pow gives.
  const double h4_long = std::pow(std::max(o.initial_span, o.min_span), 4) * (1 + 1e-12);
  const double h4_short = std::pow(o.min_span, 4) * (1 - 1e-12);
  for (std::size_t i = 0; i < m; ++i) {
    const double k = std::abs(jets[i].curvature());
    const double h4 = 76.8 * tol / std::max(k * k * k, 1e-300);
    const double h = h4 >= h4_long    ? o.initial_span
                     : h4 <= h4_short ? o.min_span
                                      : std::clamp(std::pow(h4, 0.25), o.min_span, o.initial_span);
    // Spans hold points_per_span points where the points are sparse, even past initial_span:
    // a span between two points is shaped by the fairness term alone and swings with their
    // noise (T-Blade3's tip sections, 1 um of noise: 7 um of thickness). Near-exact data
    // (points_per_span 4) may still have initial_span where min_span_points points support
    // it: no noise to follow there, and an edge's curvature needs the knots (LS89's LE).
    const double supported = std::max(point_density[i] / points_per_span(o, sigma),
                                      std::min(1 / o.initial_span, point_density[i] / o.min_span_points));
    density[i] = std::min(1 / h, supported);
  }
  // Widen the dense stretches a little: the curvature of a curve that still cuts an
  // edge is lower than the true one and its peak narrower.
  const std::vector<double> widened = window_max(density, 16);
  std::vector<double> cum(m + 1, 0);
  for (std::size_t i = 0; i < m; ++i) cum[i + 1] = cum[i] + widened[i] * ds[i];
  const int n = std::clamp(static_cast<int>(std::ceil(cum[m])), std::max(8, o.degree + 1),
                           std::max(o.max_control_points, 8));
  std::vector<double> knots(n + 1);
  knots[0] = c.t_min();
  knots[n] = c.t_max();
  std::size_t i = 0;
  for (int k = 1; k < n; ++k) {
    const double target = cum[m] * k / n;
    while (i + 1 < m && cum[i + 1] < target) ++i;
    const double a = ts[i], b = i + 1 < m ? ts[i + 1] : c.t_max();
    const double f = cum[i + 1] > cum[i] ? (target - cum[i]) / (cum[i + 1] - cum[i]) : 0;
    knots[k] = a + f * (b - a);
  }
  return knots;
}

namespace {

// Spans a bridge from parameter a to b gets: one per 30 degrees of the turning between the
// tangents at its ends (which the points on either side fix), at least two. A cubic span
// turning 30 degrees on a circle is within (5/384) (pi/6)^4 r, 1 um on a 1 mm radius.
std::size_t bridge_spans(const BSpline& c, double a, double b) {
  const double max_turn = std::acos(-1.0) / 6;
  const Eigen::Vector2d ta = c.derivative(a, 1), tb = c.derivative(b, 1);
  const double turn = std::abs(std::atan2(ta.x() * tb.y() - ta.y() * tb.x(), ta.dot(tb)));
  return std::max<std::size_t>(2, static_cast<std::size_t>(std::ceil(turn / max_turn)));
}

}  // namespace

// A hole (a stretch without measured points longer than `factor` median spacings) with
// more knots than its bridge needs leaves spans that no point determines: only the
// fairness terms shape the curve there, and the knots an edge's curvature asks for (the
// point density counts over +-1 mm) let it bulge. They are replaced by knots evenly spread
// over the hole, one span per 30 degrees of turning, at least two: each span is held by
// the points at the hole's ends through its neighbours and can follow an edge's arc, but
// not bulge (compressor seed 33 z = 30, a 0.19 mm hole past a 0.12 mm TE: 21 um off the
// truth with its knots, 8 um bridged).
std::vector<double> bridge_holes(const BSpline& c, const Feet& feet, const Points& q,
                                 const std::vector<double>& w, double factor, int degree) {
  const std::vector<double>& knots = c.knots;
  const std::size_t n = knots.size() - 1;
  std::vector<std::size_t> kept;  // the points that count, in order along the curve
  for (std::size_t k : feet.order)
    if (w[k] > 0) kept.push_back(k);
  const std::size_t m = kept.size();
  if (m < 2) return knots;
  std::vector<double> chords(m - 1);
  for (std::size_t r = 1; r < m; ++r) chords[r - 1] = (q[kept[r]] - q[kept[r - 1]]).norm();
  const double longest = factor * median_nonnegative(chords);
  const auto foot = [&](std::size_t r) { return feet.t[kept[r]]; };
  // Knots 0 and n (the period's ends) stay, and so do the knots of the stretch across them.
  std::vector<double> out{knots[0]};
  std::size_t r = 0;  // the first point whose foot is at or after knots[j]
  for (std::size_t j = 1; j < n;) {
    while (r < m && foot(r) < knots[j]) ++r;
    std::size_t e = j + 1;  // knots j..e-1 lie between the feet of points r - 1 and r
    while (e < n && (r == m || knots[e] <= foot(r))) ++e;
    const std::size_t spans =
        r > 0 && r < m && chords[r - 1] > longest ? bridge_spans(c, foot(r - 1), foot(r)) : n;
    if (e - j + 1 > spans)
      for (std::size_t k = 1; k < spans; ++k)
        out.push_back(foot(r - 1) + (foot(r) - foot(r - 1)) * k / spans);
    else
      out.insert(out.end(), knots.begin() + j, knots.begin() + e);
    j = e;
  }
  out.push_back(knots[n]);
  if (out.size() - 1 < static_cast<std::size_t>(std::max(8, degree + 1))) return knots;
  return out;
}

// Knots after splitting every span whose residuals hold more than noise: mean square
// above sigma^2 (1 + 3 sqrt(2 / m)) + tolerance^2 with m points in the span. A span under
// twice min_span (but not under min_span) is split too when its mean square is 4 times
// that limit or more: no noise does that, a curve cutting a tight edge does (a TE of
// 0.23 mm radius missed by 20-30 um over spans of 0.06 mm, where the fairness holds the
// curve; docs/ACCURACY.md).
std::vector<double> split_spans(const BSpline& c, const Feet& f, const std::vector<double>& w, double sigma,
                                const FitSplineOptions& o) {
  const std::size_t spans = c.knots.size() - 1;
  std::vector<double> sum(spans, 0), count(spans, 0);
  for (std::size_t k = 0; k < f.t.size(); ++k) {
    if (w[k] <= 0) continue;
    auto it = std::upper_bound(c.knots.begin(), c.knots.end(), f.t[k]);
    const std::size_t j =
        std::min<std::size_t>(std::max<std::ptrdiff_t>(it - c.knots.begin() - 1, 0), spans - 1);
    sum[j] += f.signed_distance[k] * f.signed_distance[k];
    count[j] += 1;
  }
  std::vector<double> knots;
  for (std::size_t j = 0; j < spans; ++j) {
    knots.push_back(c.knots[j]);
    if (count[j] < points_per_span(o, sigma)) continue;
    const double ms = sum[j] / count[j];
    const double limit = sigma * sigma * (1 + 3 * std::sqrt(2 / count[j])) + o.tolerance * o.tolerance;
    if (!(ms > limit)) continue;
    const double a = c.knots[j], b = c.knots[j + 1];
    const double arc = arc_length(c, a, b);
    if (arc >= 2 * o.min_span || (ms >= 4 * limit && arc >= o.min_span)) knots.push_back(0.5 * (a + b));
  }
  knots.push_back(c.knots.back());
  return knots;
}

}  // namespace section::fit

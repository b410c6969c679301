// SPDX-License-Identifier: GPL-3.0-or-later
#include "fit_spline_steps.h"

#include <algorithm>
#include <cmath>

namespace section {

namespace fit {

// A finger: the curve runs out and back (and out again) alongside itself, two hairpin
// turns of opposite sense close together, without crossing. Within any stretch of 2.5 %
// of the perimeter, the turning that cancels out (total absolute turning less the net
// turning) is a few degrees on a fitted blade profile, even around a 0.2 mm edge; two
// opposite hairpins give about 360. More than 180 is a fold.
bool doubles_back(const Points& p) {
  const std::size_t m = p.size();
  if (m < 4) return false;
  std::vector<double> turn(m), at(m);
  double length = 0;
  for (std::size_t i = 0; i < m; ++i) {
    const Eigen::Vector2d a = p[i] - p[(i + m - 1) % m], b = p[(i + 1) % m] - p[i];
    turn[i] = std::atan2(a.x() * b.y() - a.y() * b.x(), a.dot(b));
    at[i] = length;
    length += b.norm();
  }
  const double window = 0.025 * length, limit = 3.14159265358979323846;
  // Two pointers over the vertices, the window wrapping past the start.
  double absolute = 0, net = 0;
  std::size_t j = 0;  // window [i, j), j counted over two laps
  auto position = [&](std::size_t k) { return k < m ? at[k] : at[k - m] + length; };
  for (std::size_t i = 0; i < m; ++i) {
    if (j < i) j = i, absolute = net = 0;
    while (j < i + m && position(j) - at[i] <= window) {
      absolute += std::abs(turn[j % m]);
      net += turn[j % m];
      ++j;
    }
    if (absolute - std::abs(net) > limit) return true;
    if (j > i) {
      absolute -= std::abs(turn[i]);
      net -= turn[i];
    }
  }
  return false;
}

Along along_curve(const Refinement& r) {
  Along a;
  for (std::size_t k : r.feet.order)
    if (r.weights[k] > 0) a.points.push_back(k), a.ts.push_back(r.feet.t[k]);
  if (a.ts.empty()) return a;
  const detail::PiecewiseCurve& pc = r.pc;
  a.chords.resize(a.ts.size());
  detail::PiecewiseCurve::Local at = pc.locate(a.ts[0]);
  Eigen::Vector2d previous = pc.point(at);
  for (std::size_t i = 0; i < a.ts.size(); ++i) {
    at = pc.locate(i + 1 < a.ts.size() ? a.ts[i + 1] : a.ts[0], at.span);
    const Eigen::Vector2d next = pc.point(at);
    a.chords[i] = (next - previous).norm();
    previous = next;
  }
  return a;
}

// The longest stretch of the curve between consecutive measured feet, and the median
// spacing, as arc lengths: a hole in the data is where the curve is bridged, not measured.
// The spacing is the median of the stretches that are not zero: exact copies of a point
// add zero stretches, which would make it zero and every stretch a hole.
void measure_gaps(const Refinement& r, const Along& along, double gap_factor, FitSplineResult& result) {
  const std::vector<double>& ts = along.ts;
  const std::vector<double>& lengths = along.chords;
  if (ts.size() < 2) return;
  const BSpline& c = r.curve;
  const double period = c.t_max() - c.t_min();
  std::vector<double> apart;
  for (double l : lengths)
    if (l > 0) apart.push_back(l);
  result.spacing = median_nonnegative(std::move(apart));
  for (std::size_t i = 0; i < ts.size(); ++i) {
    if (!(lengths[i] > gap_factor * result.spacing)) continue;
    const double end = i + 1 < ts.size() ? ts[i + 1] : ts[0] + period;
    result.gaps.push_back({ts[i], ts[(i + 1) % ts.size()], arc_length(c, ts[i], end)});
  }
  std::stable_sort(result.gaps.begin(), result.gaps.end(),
                   [](const auto& x, const auto& y) { return x.length > y.length; });
  if (!result.gaps.empty()) {
    result.max_gap = result.gaps.front().length;
    result.gap_start = result.gaps.front().start;
    result.gap_end = result.gaps.front().end;
  } else {
    const std::size_t worst =
        static_cast<std::size_t>(std::max_element(lengths.begin(), lengths.end()) - lengths.begin());
    const double end = worst + 1 < ts.size() ? ts[worst + 1] : ts[0] + period;
    result.max_gap = arc_length(c, ts[worst], end);
    result.gap_start = ts[worst];
    result.gap_end = ts[(worst + 1) % ts.size()];
  }
}

namespace {

// Two layers all along the profile: where the views overlap everywhere, consecutive
// differences see both layers, the noise they give takes the layers' distance in, and no
// window stands out from it. The residuals are then a mixture of two copies of the noise
// Delta apart, flatter than one (kurtosis under 3: 2.04 for two equal layers 3 sigma
// apart; its standard error on n normal residuals is sqrt(24 / n)). For two equal layers
// m4 - 3 m2^2 = -2 (Delta / 2)^4, and the noise's variance is m2 - (Delta / 2)^2. Returns
// Delta, or 0 where the residuals (within 4 robust spreads of their median) are not that
// flat, the layers not `separation` noise sigmas apart, or not parted by a dip.
double flat_layers(const std::vector<double>& s, double separation) {
  if (s.size() < 100) return 0;
  std::vector<double> dev(s.size());
  const double m = median(s);
  for (std::size_t i = 0; i < s.size(); ++i) dev[i] = std::abs(s[i] - m);
  const double spread = 1.4826 * median(dev);
  double n = 0, sum = 0;
  for (double x : s)
    if (std::abs(x - m) <= 4 * spread) sum += x, ++n;
  const double mean = sum / n;
  double m2 = 0, m4 = 0;
  for (double x : s)
    if (std::abs(x - m) <= 4 * spread) {
      const double d2 = (x - mean) * (x - mean);
      m2 += d2 / n, m4 += d2 * d2 / n;
    }
  if (!(m2 > 0) || !(m4 / (m2 * m2) - 3 < -std::max(0.5, 5 * std::sqrt(24 / n)))) return 0;
  const double half = std::pow((3 * m2 * m2 - m4) / 2, 0.25), sigma2 = m2 - half * half;
  if (!(sigma2 > 0) || 2 * half < separation * std::sqrt(sigma2)) return 0;
  // Two layers leave fewer residuals between them than at either: a dip at the mean (two
  // layers 3 sigma apart: 0.64 of the density at each). Coordinates rounded to a coarse
  // step spread the residuals as flat (a uniform's kurtosis is 1.8), with no dip: points
  // rounded to 0.01 mm at 2 um of noise gave "layers" 5 um apart all along.
  double middle = 0, sides = 0;
  for (double x : s) {
    const double d = x - mean;
    if (std::abs(x - m) > 4 * spread) continue;
    if (std::abs(d) < 0.25 * half) ++middle;
    if (std::abs(std::abs(d) - half) < 0.25 * half) ++sides;
  }
  return middle < 0.85 * sides / 2 ? 2 * half : 0;
}

}  // namespace

// Two layers of points along the profile: views merged with a misregistration put two
// copies of the surface a few noise sigmas apart where they overlap, and the curve runs
// between them. Windows of consecutive points (in the order of their feet) get their
// residuals' robust spread (1.4826 MAD about a straight trend along the window: the fit's
// own smooth error is no layer). A spread above `layer_ratio` x the noise estimated from
// consecutive differences (dominated by the single-layer rest) in at least two
// overlapping windows is a second layer. Its distance from the first: two equal layers
// Delta apart have a standard deviation sqrt(noise^2 + Delta^2 / 4) (the MAD overstates
// Delta by a third), median over those windows; reported from layer_separation noise
// sigmas up.
void measure_layers(const Refinement& r, const Along& along, const FitSplineOptions& o,
                    FitSplineResult& result) {
  // On near-exact data the fit's own shape error (a fraction of a micrometre) is what
  // spreads: the noise counts as at least exact_noise.
  const double noise = std::max(result.noise, o.exact_noise);
  if (!(o.layer_ratio > 0) || !(noise > 0)) return;
  std::vector<double> s, arc;
  for (std::size_t i = 0; i < along.points.size(); ++i) {
    arc.push_back(i ? arc.back() + along.chords[i - 1] : 0.0);
    s.push_back(r.feet.signed_distance[along.points[i]]);
  }
  const std::size_t window = 48, step = 16;
  if (s.size() < 4 * window) return;
  struct Hit {
    std::size_t begin;
    double separation;
  };
  std::vector<Hit> hits;
  std::vector<double> res(window), dev(window);
  const double noise2 = noise * noise;
  for (std::size_t b = 0; b + window <= s.size(); b += step) {
    double sa = 0, ss = 0, saa = 0, sas = 0;
    for (std::size_t i = b; i < b + window; ++i)
      sa += arc[i], ss += s[i], saa += arc[i] * arc[i], sas += arc[i] * s[i];
    const double n = double(window), det = n * saa - sa * sa;
    const double slope = det > 0 ? (n * sas - sa * ss) / det : 0, icpt = (ss - slope * sa) / n;
    for (std::size_t i = 0; i < window; ++i) res[i] = s[b + i] - (icpt + slope * arc[b + i]);
    const double m = median(res);
    for (std::size_t i = 0; i < window; ++i) dev[i] = std::abs(res[i] - m);
    const double spread = 1.4826 * median(dev);
    if (!(spread > o.layer_ratio * noise)) continue;
    // Standard deviation without stragglers (beyond 3.5 spreads).
    double sum = 0, sum2 = 0;
    int kept = 0;
    for (double x : res)
      if (std::abs(x - m) <= 3.5 * spread) sum += x, sum2 += x * x, ++kept;
    const double var = kept > 1 ? (sum2 - sum * sum / kept) / (kept - 1) : 0;
    hits.push_back({b, 2 * std::sqrt(std::max(var - noise2, 0.0))});
  }
  // Runs of overlapping windows; a run of one window is chance.
  std::vector<double> separations;
  for (std::size_t i = 0; i < hits.size();) {
    std::size_t j = i + 1;
    while (j < hits.size() && hits[j].begin < hits[j - 1].begin + window) ++j;
    if (j - i >= 2) {
      result.layers_length += arc[hits[j - 1].begin + window - 1] - arc[hits[i].begin];
      for (std::size_t k = i; k < j; ++k) separations.push_back(hits[k].separation);
    }
    i = j;
  }
  // Noise alone, where it runs high, also spreads a few windows, into "layers" closer
  // together than two views give (docs/FITSPLINE.md): below layer_separation noise sigmas
  // nothing is reported.
  // Nor do the points slice's band carried onto the plane, by up to a few micrometres where
  // an edge changes with height faster than the band's drift follows: on near-exact data a
  // single surface, yet "layers" 2-3 um apart. Layers closer than 5 exact_noise (5 um, a
  // third of the fit's own bound) go unsaid.
  const double separation = separations.empty() ? 0.0 : median(separations);
  if (!separations.empty() && separation >= std::max(o.layer_separation * noise, 5 * o.exact_noise)) {
    result.layers = separation;
    return;
  }
  result.layers_length = 0;
  const double flat = flat_layers(s, o.layer_separation);
  if (flat >= 5 * o.exact_noise) result.layers = flat, result.layers_length = arc.back();
}

namespace {

// The x range of one segment p[i] p[i + 1] of a closed polyline.
struct XSpan {
  double lo, hi;
  std::size_t i;
};

// The segments of the closed polyline p by increasing lo. Along a profile, lo rises or
// falls monotonically over long stretches (a side, read forwards or backwards): those runs
// are merged, a few merges instead of a sort of all the segments.
std::vector<XSpan> x_spans_sorted(const Points& p) {
  const std::size_t m = p.size();
  std::vector<XSpan> spans(m);
  for (std::size_t i = 0; i < m; ++i) {
    const double x0 = p[i].x(), x1 = p[i + 1 < m ? i + 1 : 0].x();
    spans[i] = {std::min(x0, x1), std::max(x0, x1), i};
  }
  const auto by_lo = [](const XSpan& a, const XSpan& b) { return a.lo < b.lo; };
  std::vector<std::size_t> bounds{0};  // runs [bounds[r], bounds[r + 1])
  for (std::size_t s = 0; s < m;) {
    std::size_t e = s + 1;
    if (e < m && spans[e].lo < spans[s].lo) {
      while (e < m && !(spans[e - 1].lo < spans[e].lo)) ++e;
      std::reverse(spans.begin() + s, spans.begin() + e);
    } else {
      while (e < m && !(spans[e].lo < spans[e - 1].lo)) ++e;
    }
    bounds.push_back(s = e);
  }
  while (bounds.size() > 2) {
    std::vector<std::size_t> merged{0};
    for (std::size_t r = 0; r + 2 < bounds.size(); r += 2) {
      std::inplace_merge(spans.begin() + bounds[r], spans.begin() + bounds[r + 1],
                         spans.begin() + bounds[r + 2], by_lo);
      merged.push_back(bounds[r + 2]);
    }
    if (bounds.size() % 2 == 0) merged.push_back(bounds.back());  // an odd run out, carried
    bounds = std::move(merged);
  }
  return spans;
}

}  // namespace

}  // namespace fit

bool self_intersects(const BSpline& curve) {
  check_spline(curve);  // equal or decreasing knots crashed the conversion below
  const std::vector<double> ts = span_samples(curve, 16);
  if (ts.empty()) return false;
  return fit::self_intersects(curve, detail::PiecewiseCurve(curve));
}

namespace fit {

// The samples evaluated on the polynomials (16 per span, a dozen operations each instead
// of a basis evaluation): they differ from BSpline::derivatives' only in the last bits,
// which decide nothing here (a crossing, cusp or finger is not a matter of 1e-16).
bool self_intersects(const BSpline& curve, const detail::PiecewiseCurve& pc) {
  const std::vector<double> ts = span_samples(curve, 16);
  const std::size_t m = ts.size();
  Points p(m);
  double speed_max = 0;
  std::vector<double> speed(m);
  detail::PiecewiseCurve::Local at{0, 0};
  for (std::size_t i = 0; i < m; ++i) {
    const detail::CurveJet jet = pc.jet(at = pc.locate(ts[i], at.span));
    p[i] = jet.point;
    speed[i] = jet.d1.norm();
    speed_max = std::max(speed_max, speed[i]);
  }
  for (double s : speed)
    if (!(s > 1e-9 * speed_max)) return true;  // cusp: the curve stops and turns back
  return doubles_back(p) || polyline_crosses(p);
}

bool polyline_crosses(const Points& p) {
  const std::size_t m = p.size();
  // Segments sorted by their lowest x; sweep to test only overlapping boxes. Whether two
  // segments cross does not depend on which of them comes first: any sweep order gives
  // the same answer.
  const std::vector<XSpan> spans = x_spans_sorted(p);
  auto cross = [](const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c) {
    return (b - a).x() * (c - a).y() - (b - a).y() * (c - a).x();
  };
  for (std::size_t x = 0; x < m; ++x) {
    const std::size_t i = spans[x].i;
    const Eigen::Vector2d &a = p[i], &b = p[(i + 1) % m];
    for (std::size_t y = x + 1; y < m && spans[y].lo <= spans[x].hi; ++y) {
      const std::size_t j = spans[y].i;
      if (j == i || (i + 1) % m == j || (j + 1) % m == i) continue;  // neighbours share a point
      const Eigen::Vector2d &c = p[j], &d = p[(j + 1) % m];
      if (std::max(a.y(), b.y()) < std::min(c.y(), d.y()) || std::max(c.y(), d.y()) < std::min(a.y(), b.y()))
        continue;
      const double d1 = cross(a, b, c), d2 = cross(a, b, d), d3 = cross(c, d, a), d4 = cross(c, d, b);
      if (((d1 > 0 && d2 < 0) || (d1 < 0 && d2 > 0)) && ((d3 > 0 && d4 < 0) || (d3 < 0 && d4 > 0)))
        return true;
    }
  }
  return false;
}

}  // namespace fit

bool in_gap(const BSpline& curve, const FitSplineResult::Gap& gap, double t) {
  const double period = curve.t_max() - curve.t_min();
  auto wrap = [&](double x) {
    if (!curve.closed || !(period > 0)) return x;
    x = std::fmod(x - curve.t_min(), period);
    return curve.t_min() + (x < 0 ? x + period : x);
  };
  const double a = wrap(gap.start), b = wrap(gap.end), x = wrap(t);
  return a <= b ? (x >= a && x <= b) : (x >= a || x <= b);
}

}  // namespace section

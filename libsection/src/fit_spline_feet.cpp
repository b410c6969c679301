// SPDX-License-Identifier: GPL-3.0-or-later
#include "fit_spline_steps.h"

#include "detail/flann_nearest.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <numeric>

namespace section::fit {

double median(std::vector<double> v) {
  if (v.empty()) return 0;
  const std::size_t mid = v.size() / 2;
  std::nth_element(v.begin(), v.begin() + mid, v.end());
  return v[mid];
}

// In a few linear passes instead of a selection over all of them: non-negative doubles
// order as their bit patterns, so a count by the leading bits that vary finds the
// median's bucket, and a selection among its few members the value. Anything else (a
// NaN, a -0) goes to `median`.
double median_nonnegative(std::vector<double> v) {
  if (v.empty()) return 0;
  auto bits = [](double x) {
    std::uint64_t b;
    std::memcpy(&b, &x, sizeof b);
    return b;
  };
  const std::uint64_t infinity = 0x7ff0000000000000u;
  std::uint64_t lo = infinity, hi = 0;
  for (double x : v) {
    const std::uint64_t b = bits(x);
    lo = std::min(lo, b);
    hi = std::max(hi, b);
  }
  if (hi > infinity) return median(std::move(v));
  if (lo == hi) return v.front();
  int top = 63;  // highest bit that varies
  while (!(((lo ^ hi) >> top) & 1)) --top;
  // About two values per bucket, up to 2048 buckets: few points (sparse rows) zero and walk
  // a short count; the median found is the same.
  int digits = 4;
  while (digits < 11 && (std::size_t(1) << digits) < v.size() / 2) ++digits;
  const int shift = std::max(top + 1 - digits, 0);
  const std::uint64_t mask = (std::uint64_t(1) << digits) - 1;
  auto bucket = [&](double x) { return static_cast<std::size_t>((bits(x) >> shift) & mask); };
  // 32-bit counts: half the table to clear (a selection over more points goes to `median`).
  if (v.size() > std::numeric_limits<std::uint32_t>::max()) return median(std::move(v));
  std::vector<std::uint32_t> count(std::size_t(1) << digits, 0);
  for (double x : v) ++count[bucket(x)];
  const std::size_t mid = v.size() / 2;
  std::size_t b = 0, below = 0;
  while (below + count[b] <= mid) below += count[b++];
  std::size_t kept = 0;
  for (double x : v)
    if (bucket(x) == b) v[kept++] = x;
  v.resize(kept);
  std::nth_element(v.begin(), v.begin() + (mid - below), v.end());
  return v[mid - below];
}

namespace {

// Sorts `order` by t[order[i]], fast when it is nearly sorted already (the feet on the
// previous curve: a few points moved a little, a few crossed the start of the period):
// ascending runs merged pairwise, O(n log runs). Returns false, `order` sorted or not, if
// two parameters are equal (or NaN), as the result would then depend on the method.
bool sort_runs(std::vector<std::size_t>& order, const std::vector<double>& t) {
  const std::size_t n = order.size();
  std::vector<std::size_t> starts{0};
  for (std::size_t i = 1; i < n; ++i)
    if (!(t[order[i - 1]] < t[order[i]])) {
      if (!(t[order[i]] < t[order[i - 1]])) return false;
      starts.push_back(i);
    }
  starts.push_back(n);
  if (starts.size() == 2) return true;
  auto before = [&](std::size_t x, std::size_t y) { return t[x] < t[y]; };
  std::vector<std::size_t> merged(n);
  while (starts.size() > 2) {
    std::vector<std::size_t> next;
    for (std::size_t r = 0; r + 1 < starts.size(); r += 2) {
      next.push_back(starts[r]);
      const std::size_t mid = starts[r + 1], end = r + 2 < starts.size() ? starts[r + 2] : mid;
      std::merge(order.begin() + starts[r], order.begin() + mid, order.begin() + mid, order.begin() + end,
                 merged.begin() + starts[r], before);
    }
    next.push_back(n);
    order.swap(merged);
    starts.swap(next);
  }
  for (std::size_t i = 1; i < n; ++i)
    if (!(t[order[i - 1]] < t[order[i]])) return false;
  return true;
}

// t wrapped into [t_min, t_max) by one period.
double wrap(const detail::PiecewiseCurve& pc, double t) {
  const double t_min = pc.t_min(), t_max = pc.t_max(), period = t_max - t_min;
  return t < t_min ? t + period : (t >= t_max ? t - period : t);
}

// Newton on the squared distance to q from t0 while `inside` holds for its iterates, at
// most 8 steps: true, with the foot's parameter (not wrapped) and signed distance, when it
// converges (a step of `converged` at most).
template <class Inside>
bool newton_foot(const detail::PiecewiseCurve& pc, const Eigen::Vector2d& q, double t0, double converged,
                 Inside inside, detail::PiecewiseCurve::Cursor& at, double& t, double& signed_distance) {
  t = t0;
  for (int it = 0; it < 8; ++it) {
    const detail::CurveJet j = pc.jet(pc.locate(t, at));
    const detail::SquaredDistance g = detail::squared_distance(j, q);
    if (!(g.ddg > 0)) return false;
    const double dt = -g.dg / g.ddg;
    t += dt;
    if (!inside(t)) return false;
    if (std::abs(dt) <= converged) {
      // This jet is within `converged` of the foot: its distance is exact to far below a nm.
      const Eigen::Vector2d normal = Eigen::Vector2d(j.d1.y(), -j.d1.x()).normalized();
      signed_distance = (q - j.point).dot(normal);
      return true;
    }
  }
  return false;
}

// Tracks each foot by Newton from previous->t (when given); returns the points lost.
std::vector<std::size_t> track_feet(const BSpline& c, const detail::PiecewiseCurve& pc, const Points& q,
                                    const Feet* previous, Feet& f) {
  const double period = c.t_max() - c.t_min();
  const double step = period / (8.0 * static_cast<double>(c.control.size()));
  // Parameter step (about a length) that ends Newton: the iterate after a step of 1e-8 of
  // the period (1e-6 mm on a 100 mm profile) is within ~1e-12 mm of the foot (quadratic
  // convergence), and so is the distance; 1e-12 took one more evaluation a point.
  const double converged = 1e-8 * period;
  std::vector<std::size_t> lost;
  detail::PiecewiseCurve::Cursor at;  // the last span located: consecutive points are close
  for (std::size_t k = 0; k < q.size(); ++k) {
    if (!previous) {
      lost.push_back(k);
      continue;
    }
    const double t0 = previous->t[k];
    auto near_t0 = [&](double x) { return !(std::abs(x - t0) > step); };
    double t;
    if (newton_foot(pc, q[k], t0, converged, near_t0, at, t, f.signed_distance[k]))
      f.t[k] = wrap(pc, t);
    else
      lost.push_back(k);
  }
  return lost;
}

// The samples of a FootSearch.
Points search_samples(const detail::PiecewiseCurve& pc, const std::vector<double>& ts) {
  detail::PiecewiseCurve::Local at{0, 0};
  Points pts(ts.size());
  for (std::size_t i = 0; i < ts.size(); ++i) pts[i] = pc.point(at = pc.locate(ts[i], at.span));
  return pts;
}

// The samples nearest to one point (the anchor) and how far every other sample is from
// it at least.
struct SampleWindow {
  static constexpr int size = 16;
  int index[size];
  double d2[size];
  int count = 0;
  Eigen::Vector2d anchor;
  double reach = 0;
};

// The sample nearest to q, the kd-tree's answer: consecutive points (slice's loops come in
// order) mostly share it with the window of a point before, where the triangle inequality
// proves it (every sample outside is at least reach - |q - anchor| from q); else the tree
// gives it and, when `more` points follow, a new window.
std::size_t nearest_sample(const FootSearch& search, const Eigen::Vector2d& q, bool more, SampleWindow& w) {
  if (w.count > 0) {
    const double moved = (q - w.anchor).norm();
    if (moved < w.reach) {
      double best = std::numeric_limits<double>::infinity();
      int at = 0;
      for (int j = 0; j < w.count; ++j) {
        const double d2 = (search.points[w.index[j]] - q).squaredNorm();
        if (d2 < best) best = d2, at = w.index[j];
      }
      // The margin covers the rounding of the three distances.
      if (std::sqrt(best) + moved < (1 - 1e-12) * w.reach) return static_cast<std::size_t>(at);
    }
  }
  const int k = more ? std::min<int>(SampleWindow::size, static_cast<int>(search.ts.size())) : 1;
  search.tree.k_nearest(q, k, w.index, w.d2);
  w.count = more ? k : 0;
  w.anchor = q;
  w.reach = k < static_cast<int>(search.ts.size()) ? std::sqrt(w.d2[k - 1])
                                                   : std::numeric_limits<double>::infinity();
  return static_cast<std::size_t>(w.index[0]);
}

// The full search for the points `lost`: the nearest dense sample; the foot lies between
// its neighbours.
void search_feet(const BSpline& c, const detail::PiecewiseCurve& pc, const Points& q,
                 const std::vector<std::size_t>& lost, const FootSearch& search, Feet& f) {
  const double period = c.t_max() - c.t_min();
  detail::PiecewiseCurve::Cursor at;
  const std::vector<double>& ts = search.ts;
  const std::size_t m = ts.size();
  SampleWindow window;
  // The jets at a sample and its neighbours, where every search from that sample starts:
  // consecutive points mostly share it.
  std::size_t sample = m;
  detail::CurveJet at_a, at_b, at_sample;
  for (std::size_t l = 0; l < lost.size(); ++l) {
    const std::size_t k = lost[l];
    const bool more = l + 1 < lost.size() && lost[l + 1] == k + 1;
    const std::size_t i = nearest_sample(search, q[k], more, window);
    const double a = i > 0 ? ts[i - 1] : ts[m - 1] - period;
    const double b = i + 1 < m ? ts[i + 1] : c.t_max();
    if (i != sample) {
      sample = i;
      at_a = pc.jet(pc.locate(a, at));
      at_b = pc.jet(pc.locate(b, at));
      at_sample = pc.jet(pc.locate(ts[i], at));
    }
    auto distance = [&](double x) {
      return detail::squared_distance(x == ts[i] ? at_sample
                                      : x == a   ? at_a
                                      : x == b   ? at_b
                                                 : pc.jet(pc.locate(x, at)),
                                      q[k]);
    };
    f.t[k] = wrap(pc, detail::minimise_bracket(distance, a, b, ts[i]));
    const detail::CurveJet j = pc.jet(pc.locate(f.t[k], at));
    const Eigen::Vector2d normal = Eigen::Vector2d(j.d1.y(), -j.d1.x()).normalized();
    f.signed_distance[k] = (q[k] - j.point).dot(normal);
  }
}

// f.order: the points sorted by f.t. They start in the previous order or in input order,
// both nearly sorted. Two feet on one parameter keep the order between them that the
// sorts below give.
void order_feet(std::size_t count, const Feet* previous, Feet& f) {
  auto before = [&](std::size_t x, std::size_t y) { return f.t[x] < f.t[y]; };
  auto start = [&] {
    if (previous) {
      f.order = previous->order;
    } else {
      f.order.resize(count);
      std::iota(f.order.begin(), f.order.end(), 0);
    }
  };
  start();
  if (sort_runs(f.order, f.t)) return;
  start();
  if (previous) {
    // The previous order is nearly right: insertion sort, unless it moves too much.
    std::size_t moves = 0;
    for (std::size_t i = 1; i < f.order.size() && moves <= 8 * f.order.size(); ++i)
      for (std::size_t j = i; j > 0 && before(f.order[j], f.order[j - 1]); --j, ++moves)
        std::swap(f.order[j], f.order[j - 1]);
    if (moves > 8 * f.order.size()) std::sort(f.order.begin(), f.order.end(), before);
  } else {
    std::sort(f.order.begin(), f.order.end(), before);
  }
}

}  // namespace

FootSearch::FootSearch(const BSpline& c, const detail::PiecewiseCurve& pc)
    : ts(span_samples(c, 8)), points(search_samples(pc, ts)), tree(points, 10) {}

Feet foot_points(const BSpline& c, const detail::PiecewiseCurve& pc, const Points& q, const Feet* previous,
                 const FootSearch* search) {
  Feet f;
  f.t.assign(q.size(), std::numeric_limits<double>::quiet_NaN());
  f.signed_distance.resize(q.size());
  const std::vector<std::size_t> lost = track_feet(c, pc, q, previous, f);
  if (!lost.empty()) {
    if (search)
      search_feet(c, pc, q, lost, *search, f);
    else
      search_feet(c, pc, q, lost, FootSearch(c, pc), f);
  }
  order_feet(q.size(), previous, f);
  return f;
}

double noise_sigma(const Feet& f, const std::vector<double>& w) {
  // With no point left out it is the one of all the points, asked for again and again.
  if (!std::isnan(f.noise_all) && std::all_of(w.begin(), w.end(), [](double x) { return x > 0; }))
    return f.noise_all;
  const std::vector<std::size_t>& order = f.order;
  std::vector<double> diffs;  // reserved, not zeroed: it is filled once
  diffs.reserve(order.size());
  auto r = order.begin();
  while (r != order.end() && w[*r] <= 0) ++r;
  if (r != order.end()) {
    double last = f.signed_distance[*r];  // of the point before, kept in hand
    for (++r; r != order.end(); ++r) {
      if (w[*r] <= 0) continue;
      const double d = f.signed_distance[*r];
      diffs.push_back(std::abs(d - last));
      last = d;
    }
  }
  return 1.4826 * median_nonnegative(std::move(diffs)) / std::sqrt(2.0);
}

std::vector<double> outlier_weights(const Feet& f, const Points& q, double threshold) {
  const std::size_t m = f.t.size();
  const std::vector<std::size_t>& order = f.order;
  std::vector<double> w(m, 1.0);
  for (std::size_t i = 0; i < m; ++i) {
    const double s = f.signed_distance[order[i]];
    if (std::abs(s) <= threshold) continue;
    // Supported by a neighbour along the curve that stands off on the same side, at least a
    // hundredth as far: not by the few points a coarse first curve leaves off a sharp edge,
    // for a stray point 40 mm beyond that edge (it pulled the curve into a fold). A tenth
    // moved 3 of the 1 458 sections of evaluate_pipeline --seeds 81, each by a few um.
    bool supported = false;
    for (std::size_t d : {std::size_t(1), std::size_t(2), m - 1, m - 2}) {
      if (m < 5) break;
      const double o = f.signed_distance[order[(i + d) % m]];
      if (std::abs(o) > 0.5 * threshold && o * s > 0 && 100 * std::abs(o) >= std::abs(s)) supported = true;
    }
    if (!supported && m >= 5) {
      const Eigen::Vector2d& a = q[order[(i + m - 1) % m]];
      const Eigen::Vector2d& b = q[order[(i + 1) % m]];
      const Eigen::Vector2d ab = b - a, ap = q[order[i]] - a;
      const double len = ab.norm();
      supported = len > 0 && std::abs(ab.x() * ap.y() - ab.y() * ap.x()) / len <= threshold &&
                  ap.dot(ab) > 0 && ap.dot(ab) < len * len;
    }
    if (!supported) w[order[i]] = 0;
  }
  return w;
}

double weighted_rms(const Feet& f, const std::vector<double>& w) {
  double s = 0, sw = 0;
  for (std::size_t k = 0; k < w.size(); ++k) {
    s += w[k] * f.signed_distance[k] * f.signed_distance[k];
    sw += w[k];
  }
  return sw > 0 ? std::sqrt(s / sw) : 0;
}

}  // namespace section::fit

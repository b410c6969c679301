#include "section/fit_spline.h"

#include "detail/flann_nearest.h"
#include "detail/parallel.h"
#include "detail/piecewise_curve.h"
#include "section/error.h"

#include <Eigen/Sparse>
#include <Eigen/SparseCholesky>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <numeric>
#include <string>

namespace section {

namespace {

using Points = std::vector<Eigen::Vector2d>;

double median(std::vector<double> v) {
  if (v.empty()) return 0;
  const std::size_t mid = v.size() / 2;
  std::nth_element(v.begin(), v.begin() + mid, v.end());
  return v[mid];
}

// The same value as `median`, for non-negative numbers, in a few linear passes instead of a
// selection over all of them: non-negative doubles order as their bit patterns, so a count
// by the leading bits that vary finds the median's bucket, and a selection among its few
// members the value. Anything else (a NaN, a -0) goes to `median`.
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
  const int digits = 11, shift = std::max(top + 1 - digits, 0);
  auto bucket = [&](double x) {
    return static_cast<std::size_t>((bits(x) >> shift) & ((1u << digits) - 1));
  };
  std::vector<std::size_t> count(std::size_t(1) << digits, 0);
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

double polygon_area(const Points& p) {
  double a = 0;
  for (std::size_t i = 0, j = p.size() - 1; i < p.size(); j = i++)
    a += p[j].x() * p[i].y() - p[i].x() * p[j].y();
  return 0.5 * a;
}

// Foot points of the measured points: nearest dense curve sample from a kd-tree, then a
// local Newton projection.
struct Feet {
  std::vector<double> t;       // curve parameter of the foot
  std::vector<double> signed_distance;  // positive on the outer side (tangent turned clockwise)
  std::vector<std::size_t> order;       // point indices sorted by t
  double noise_all = std::numeric_limits<double>::quiet_NaN();  // noise_sigma of all the points, once known
};

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

// With `previous` (the feet on a curve that moved a little since), each foot is tracked
// by Newton from its old parameter; a point whose Newton leaves the old foot's
// neighbourhood or meets a non-convex stretch gets the full search.
// `pc`: the curve c as polynomials.
Feet foot_points(const BSpline& c, const detail::PiecewiseCurve& pc, const Points& q,
                 const Feet* previous = nullptr) {
  const double t_min = c.t_min(), t_max = c.t_max(), period = t_max - t_min;
  auto wrap = [&](double t) { return t < t_min ? t + period : (t >= t_max ? t - period : t); };
  Feet f;
  f.t.assign(q.size(), std::numeric_limits<double>::quiet_NaN());
  f.signed_distance.resize(q.size());
  const double step = period / (8.0 * static_cast<double>(c.control.size()));
  const double converged = 1e-12 * period;  // parameter step (about a length) that ends Newton
  std::vector<std::size_t> lost;
  detail::PiecewiseCurve::Local at{0, 0};  // the last span located: consecutive points are close
  for (std::size_t k = 0; k < q.size(); ++k) {
    if (!previous) {
      lost.push_back(k);
      continue;
    }
    double t = previous->t[k];
    bool ok = false;
    for (int it = 0; it < 8; ++it) {
      at = pc.locate(t, at.span);
      const detail::CurveJet j = pc.jet(at);
      const detail::SquaredDistance g = detail::squared_distance(j, q[k]);
      if (!(g.ddg > 0)) break;
      const double dt = -g.dg / g.ddg;
      t += dt;
      if (std::abs(t - previous->t[k]) > step) break;
      if (std::abs(dt) <= converged) {
        // This jet is within `converged` of the foot: its distance is exact to far below a nm.
        ok = true;
        const Eigen::Vector2d normal = Eigen::Vector2d(j.d1.y(), -j.d1.x()).normalized();
        f.signed_distance[k] = (q[k] - j.point).dot(normal);
        break;
      }
    }
    if (ok) f.t[k] = wrap(t);
    else lost.push_back(k);
  }
  if (!lost.empty()) {
    // Nearest dense sample from a kd-tree; the foot lies between its neighbours.
    const std::vector<double> ts = span_samples(c, 8);
    const std::size_t m = ts.size();
    Points pts(m);
    for (std::size_t i = 0; i < m; ++i) pts[i] = pc.point(at = pc.locate(ts[i], at.span));
    const detail::NearestPoints<2> tree(pts, 10);
    Points lost_points(lost.size());
    for (std::size_t l = 0; l < lost.size(); ++l) lost_points[l] = q[lost[l]];
    const std::vector<int> idx = tree.nearest(lost_points);
    for (std::size_t l = 0; l < lost.size(); ++l) {
      const std::size_t k = lost[l];
      const std::size_t i = static_cast<std::size_t>(idx[l]);
      const double a = i > 0 ? ts[i - 1] : ts[m - 1] - period;
      const double b = i + 1 < m ? ts[i + 1] : c.t_max();
      auto distance = [&](double x) { return detail::squared_distance(pc.jet(at = pc.locate(x, at.span)), q[k]); };
      f.t[k] = wrap(detail::minimise_bracket(distance, a, b, ts[i]));
      const detail::CurveJet j = pc.jet(at = pc.locate(f.t[k], at.span));
      const Eigen::Vector2d normal = Eigen::Vector2d(j.d1.y(), -j.d1.x()).normalized();
      f.signed_distance[k] = (q[k] - j.point).dot(normal);
    }
  }
  auto before = [&](std::size_t x, std::size_t y) { return f.t[x] < f.t[y]; };
  // Points start in the previous order or in input order, both nearly sorted. Two feet on
  // one parameter keep the order between them that the sorts below give.
  auto start = [&] {
    if (previous) {
      f.order = previous->order;
    } else {
      f.order.resize(q.size());
      std::iota(f.order.begin(), f.order.end(), 0);
    }
  };
  start();
  if (sort_runs(f.order, f.t)) return f;
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
  return f;
}

// Robust noise sigma: from differences of residuals consecutive along the curve, which
// cancel the smooth (model) part of the residual and keep the noise.
double noise_sigma(const Feet& f, const std::vector<double>& w) {
  // With no point left out it is the one of all the points, asked for again and again.
  if (!std::isnan(f.noise_all) && std::all_of(w.begin(), w.end(), [](double x) { return x > 0; }))
    return f.noise_all;
  const std::vector<std::size_t>& order = f.order;
  std::vector<double> diffs(order.size());
  std::size_t count = 0, prev = order.size();
  for (std::size_t i : order) {
    if (w[i] <= 0) continue;
    if (prev != order.size()) diffs[count++] = std::abs(f.signed_distance[i] - f.signed_distance[prev]);
    prev = i;
  }
  diffs.resize(count);
  return 1.4826 * median_nonnegative(std::move(diffs)) / std::sqrt(2.0);
}

// Ignores isolated points far from the curve; runs of far points on one side are kept,
// as they mean the curve is not there yet (a cut edge), not outliers. So is a lone far
// point that lies on the line through its two neighbours (in the order along the curve):
// the data agree with it, the curve does not (a sharp edge's tip point).
std::vector<double> outlier_weights(const Feet& f, const Points& q, double threshold) {
  const std::size_t m = f.t.size();
  const std::vector<std::size_t>& order = f.order;
  std::vector<double> w(m, 1.0);
  for (std::size_t i = 0; i < m; ++i) {
    const double s = f.signed_distance[order[i]];
    if (std::abs(s) <= threshold) continue;
    bool supported = false;
    for (std::size_t d : {std::size_t(1), std::size_t(2), m - 1, m - 2}) {
      if (m < 5) break;
      const double o = f.signed_distance[order[(i + d) % m]];
      if (std::abs(o) > 0.5 * threshold && o * s > 0) supported = true;
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

// One Gauss-Newton step of squared-distance minimisation: each measured point q_k with
// foot C(t_k), unit tangent T and outward normal N contributes
//   ((C(t_k) - q_k) . N)^2 + alpha ((C(t_k) - q_k) . T)^2,
// alpha = |d| / (|d| + rho) on the convex side and 0 (tangent distance) on the concave side
// within the radius of curvature rho (Wang, Pottmann and Liu 2006, eq. 9), kept above a
// small floor so that sliding along the curve stays bounded.
// The factorisation of the previous step's system, whose fill-reducing ordering a step
// with the same matrix pattern (the same knots, mostly) takes over.
struct StepSolver {
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt;
  std::vector<int> outer, inner;  // the pattern it was analysed for
};

// `pc`: the curve c as polynomials.
BSpline sdm_step(const BSpline& c, const detail::PiecewiseCurve& pc, const Points& q, const Feet& f,
                 const std::vector<double>& w, double fairness, double smoothing_length,
                 StepSolver& solver) {
  const int n = static_cast<int>(c.control.size());
  const int p = c.degree;
  // Each point couples p + 1 consecutive control points: accumulate the 2x2 blocks of
  // the normal equations in a band (row i, offset 0..p), then hand them over as triplets.
  std::vector<Eigen::Matrix2d> band(static_cast<std::size_t>(n) * (p + 1), Eigen::Matrix2d::Zero());
  Eigen::VectorXd rhs = Eigen::VectorXd::Zero(2 * n);
  double val[8];
  int idx[8];
  double trace = 0;
  detail::PiecewiseCurve::Local at{0, 0};  // the last span located: consecutive points are close
  for (std::size_t k = 0; k < q.size(); ++k) {
    if (w[k] <= 0) continue;
    at = pc.locate(f.t[k], at.span);
    const int first = pc.basis(at, val);
    for (int a = 0; a <= p; ++a) idx[a] = first + a < n ? first + a : first + a - n;
    const detail::CurveJet jet = pc.jet(at);
    const Eigen::Vector2d tangent = jet.d1.normalized();
    const Eigen::Vector2d normal(tangent.y(), -tangent.x());
    const double d = f.signed_distance[k];
    const double kappa = jet.curvature();
    double alpha = 1;
    if (kappa == 0) {
      alpha = 0;
    } else {
      const double rho = 1 / std::abs(kappa);
      const bool centre_side = d * kappa < 0;
      alpha = centre_side ? (std::abs(d) < rho ? 0 : 1) : std::abs(d) / (std::abs(d) + rho);
    }
    alpha = std::max(alpha, 1e-3);
    const Eigen::Matrix2d M = w[k] * (normal * normal.transpose() + alpha * tangent * tangent.transpose());
    const Eigen::Vector2d Mq = M * q[k];
    for (int a = 0; a <= p; ++a) {
      rhs.segment<2>(2 * idx[a]) += val[a] * Mq;
      for (int b = a; b <= p; ++b) band[static_cast<std::size_t>(idx[a]) * (p + 1) + (b - a)] += val[a] * val[b] * M;
      trace += w[k] * val[a] * val[a];
    }
  }
  if (smoothing_length > 0 && p == 3) {
    // Change of curvature: the normal component of C''' (for a curve parameterised by
    // arc length, dk/ds), integrated over each span with the normal of the current curve,
    // which keeps the term quadratic. It is zero on lines and circular arcs (edges keep
    // their radius) and large on the wiggles a dense knot vector makes between sparse
    // noisy points. Weight: mean point density times length^6, so that it balances the
    // data on wiggles about 2 pi smoothing_length long where the data are of mean density
    // (and on longer ones where they are sparser), times (noise sigma / 5 um)^2: exact
    // data need no smoothing (it rounds the curvature jump where an edge meets a flank).
    double points = 0;
    for (double x : w) points += std::max(x, 0.0);
    const double noise = noise_sigma(f, w) / 0.005;
    const double lambda3 = points / (c.t_max() - c.t_min()) * std::pow(smoothing_length, 6) * noise * noise;
    double v[4][8], jerk[4];
    for (int j = 0; j < n; ++j) {
      const double a = c.knots[j], h = (c.knots[j + 1] - a) / 4;
      if (!(h > 0)) continue;
      // C''' is constant on a cubic span: the third difference of the basis values at
      // four equally spaced parameters.
      int first = 0;
      detail::PiecewiseCurve::Local l[4];  // span j, unless knots repeat
      for (int g = 0; g < 4; ++g) first = pc.basis(l[g] = pc.locate(a + (g + 0.5) * h, j), v[g]);
      for (int b = 0; b <= p; ++b) {
        idx[b] = first + b < n ? first + b : first + b - n;
        jerk[b] = (v[3][b] - 3 * v[2][b] + 3 * v[1][b] - v[0][b]) / (h * h * h);
      }
      for (int g = 0; g < 4; ++g) {
        const Eigen::Vector2d d1 = pc.jet(l[g]).d1;
        const double speed = d1.norm();
        if (!(speed > 0)) continue;
        const Eigen::Vector2d normal(d1.y() / speed, -d1.x() / speed);
        const Eigen::Matrix2d M = lambda3 * h * normal * normal.transpose();
        for (int a2 = 0; a2 <= p; ++a2)
          for (int b = a2; b <= p; ++b) band[static_cast<std::size_t>(idx[a2]) * (p + 1) + (b - a2)] += jerk[a2] * jerk[b] * M;
      }
    }
  }
  std::vector<Eigen::Triplet<double>> trip;
  trip.reserve(static_cast<std::size_t>(n) * (8 * (p + 1) + 40));
  for (int i = 0; i < n; ++i)
    for (int o = 0; o <= p; ++o) {
      const Eigen::Matrix2d& B = band[static_cast<std::size_t>(i) * (p + 1) + o];
      if (o > 0 && B.isZero(0)) continue;
      const int j = (i + o) % n;
      for (int r = 0; r < 2; ++r)
        for (int s = 0; s < 2; ++s) {
          trip.emplace_back(2 * i + r, 2 * j + s, B(r, s));
          if (o > 0) trip.emplace_back(2 * j + s, 2 * i + r, B(r, s));
        }
    }
  // Fairness (second differences of the control polygon) keeps spans without data
  // determined; a tiny pull toward the current control points keeps the system definite.
  const double lambda = fairness * std::max(trace / n, 1e-12);
  const double mu = 1e-9 * std::max(trace / n, 1e-12);
  for (int i = 0; i < n; ++i) {
    const int ids[3] = {(i + n - 1) % n, i, (i + 1) % n};
    const double coef[3] = {1, -2, 1};
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b)
        for (int r = 0; r < 2; ++r)
          trip.emplace_back(2 * ids[a] + r, 2 * ids[b] + r, lambda * coef[a] * coef[b]);
    for (int r = 0; r < 2; ++r) {
      trip.emplace_back(2 * i + r, 2 * i + r, mu);
      rhs(2 * i + r) += mu * c.control[i](r);
    }
  }
  Eigen::SparseMatrix<double> H(2 * n, 2 * n);
  H.setFromTriplets(trip.begin(), trip.end());
  // The ordering depends on the pattern only: kept while the pattern is the same.
  const int *outer = H.outerIndexPtr(), *inner = H.innerIndexPtr();
  const std::size_t outers = static_cast<std::size_t>(H.outerSize()) + 1;
  const std::size_t nnz = static_cast<std::size_t>(H.nonZeros());
  if (solver.outer.size() != outers || !std::equal(outer, outer + outers, solver.outer.begin()) ||
      solver.inner.size() != nnz || !std::equal(inner, inner + nnz, solver.inner.begin())) {
    solver.ldlt.analyzePattern(H);
    solver.outer.assign(outer, outer + outers);
    solver.inner.assign(inner, inner + nnz);
  }
  solver.ldlt.factorize(H);
  if (solver.ldlt.info() != Eigen::Success)
    throw Error("fit_spline: the distance-minimisation system is singular");
  const Eigen::VectorXd x = solver.ldlt.solve(rhs);
  if (solver.ldlt.info() != Eigen::Success || !x.allFinite())
    throw Error("fit_spline: the distance-minimisation system is singular");
  BSpline out = c;
  for (int i = 0; i < n; ++i) out.control[i] = Eigen::Vector2d(x(2 * i), x(2 * i + 1));
  return out;
}

// Weighted RMS of the signed distances.
double weighted_rms(const Feet& f, const std::vector<double>& w) {
  double s = 0, sw = 0;
  for (std::size_t k = 0; k < w.size(); ++k) {
    s += w[k] * f.signed_distance[k] * f.signed_distance[k];
    sw += w[k];
  }
  return sw > 0 ? std::sqrt(s / sw) : 0;
}

// The curve on new knots: least squares on dense samples of the old curve, so that the
// shape carries over to the refined knot vector (almost exactly: the old space nests in
// the new one when knots were only inserted).
BSpline reknot(const BSpline& c, const std::vector<double>& knots) {
  BSpline shape = c;
  shape.knots = knots;
  shape.control.assign(knots.size() - 1, Eigen::Vector2d::Zero());
  std::vector<double> ts = span_samples(shape, 12);
  Points pts(ts.size());
  const detail::PiecewiseCurve pc(c);
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

// Knots spread by the approximation error of a cubic on a circle: a span of length h on
// curvature k deviates by about (5/384) h^4 k^3, so h = (76.8 tol / k^3)^(1/4), between
// min_span and initial_span. Edges (small radii) get dense knots, flanks sparse ones.
// Noise sets the useful tolerance (half a sigma: a shorter span fits the noise more than
// it removes bias), and each span keeps at least min_span_points measured points.
std::vector<double> curvature_knots(const BSpline& c, const Feet& feet, double sigma,
                                    const FitSplineOptions& o) {
  const std::vector<double> ts = span_samples(c, 32);
  const std::size_t m = ts.size();
  const detail::PiecewiseCurve pc(c);
  std::vector<detail::CurveJet> jets(m);
  detail::PiecewiseCurve::Local at{0, 0};
  for (std::size_t i = 0; i < m; ++i) jets[i] = pc.jet(at = pc.locate(ts[i], at.span));
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
  std::vector<double> point_density(m);
  const double window = 0.5 * o.initial_span;
  for (std::size_t i = 0; i < m; ++i) {
    double count = hits[i], length = ds[i];
    // Samples i + k and i - k, wrapped (without a division per step).
    std::size_t up = i, down = i;
    for (std::size_t k = 1; k < m / 2 && length < 2 * window; ++k) {
      up = up + 1 == m ? 0 : up + 1;
      down = down == 0 ? m - 1 : down - 1;
      count += hits[up] + hits[down];
      length += ds[up] + ds[down];
    }
    point_density[i] = length > 0 ? count / length : 0;
  }
  for (std::size_t i = 0; i < m; ++i) {
    const double k = std::abs(jets[i].curvature());
    const double h = std::pow(76.8 * tol / std::max(k * k * k, 1e-300), 0.25);
    const double supported = std::max(1 / o.initial_span, point_density[i] / points_per_span(o, sigma));
    density[i] = std::min(1 / std::clamp(h, o.min_span, o.initial_span), supported);
  }
  // Widen the dense stretches a little: the curvature of a curve that still cuts an
  // edge is lower than the true one and its peak narrower.
  std::vector<double> widened(m);
  const int reach = 16;
  for (std::size_t i = 0; i < m; ++i) {
    double d = 0;
    for (int k = -reach; k <= reach; ++k) {
      const std::size_t j = i + m + k;  // in [m - reach, 2 m + reach): one wrap at most, m > reach
      d = std::max(d, density[j >= 2 * m ? j - 2 * m : (j >= m ? j - m : j)]);
    }
    widened[i] = d;
  }
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

struct Refinement {
  BSpline curve;
  Feet feet;
  std::vector<double> weights;
  double rms = 0;
  int iterations = 0;
};

// Squared-distance minimisation iterations on fixed knots until the RMS settles.
// `start`: feet on a curve of nearly the same shape and parameter (the curve before a
// change of knots), tracked instead of searched afresh.
Refinement refine(BSpline c, const Points& q, const FitSplineOptions& o, const Feet* start = nullptr) {
  const std::vector<double> all(q.size(), 1.0);
  auto weights_for = [&](Feet& ft) {
    double threshold = o.outlier_distance;
    if (threshold <= 0) threshold = std::max(6 * (ft.noise_all = noise_sigma(ft, all)), o.outlier_floor);
    return outlier_weights(ft, q, threshold);
  };
  Refinement now;
  // Both the feet and the next step evaluate the current curve: converted once.
  detail::PiecewiseCurve pc(c);
  StepSolver solver;
  now.feet = foot_points(c, pc, q, start);
  now.weights = weights_for(now.feet);
  now.rms = weighted_rms(now.feet, now.weights);
  now.curve = std::move(c);
  // The best state is set aside only when a worse one replaces it (states are moved, not copied).
  Refinement best;
  bool now_best = true;
  double best_rms = now.rms;
  int it = 0;
  for (; it < o.max_iterations; ++it) {
    BSpline next = sdm_step(now.curve, pc, q, now.feet, now.weights, o.fairness, o.smoothing_length, solver);
    pc = detail::PiecewiseCurve(next);
    Feet nf = foot_points(next, pc, q, &now.feet);
    std::vector<double> nw = weights_for(nf);
    const double nrms = weighted_rms(nf, nw);
    const double change = std::abs(now.rms - nrms);
    if (now_best) best = std::move(now);
    now = {std::move(next), std::move(nf), std::move(nw), nrms, 0};
    now_best = nrms <= best_rms;
    if (now_best) best_rms = nrms;
    if (change <= o.convergence * nrms + 1e-3 * o.tolerance) {
      ++it;
      break;
    }
  }
  if (now_best) best = std::move(now);
  best.iterations = it;
  return best;
}

// Knots after splitting every span whose residuals hold more than noise: mean square
// above sigma^2 (1 + 3 sqrt(2 / m)) + tolerance^2 with m points in the span.
std::vector<double> split_spans(const BSpline& c, const Feet& f, const std::vector<double>& w,
                                double sigma, const FitSplineOptions& o) {
  const std::size_t spans = c.knots.size() - 1;
  std::vector<double> sum(spans, 0), count(spans, 0);
  for (std::size_t k = 0; k < f.t.size(); ++k) {
    if (w[k] <= 0) continue;
    auto it = std::upper_bound(c.knots.begin(), c.knots.end(), f.t[k]);
    const std::size_t j = std::min<std::size_t>(
        std::max<std::ptrdiff_t>(it - c.knots.begin() - 1, 0), spans - 1);
    sum[j] += f.signed_distance[k] * f.signed_distance[k];
    count[j] += 1;
  }
  std::vector<double> knots;
  for (std::size_t j = 0; j < spans; ++j) {
    knots.push_back(c.knots[j]);
    if (count[j] < points_per_span(o, sigma)) continue;
    const double ms = sum[j] / count[j];
    const double limit = sigma * sigma * (1 + 3 * std::sqrt(2 / count[j])) + o.tolerance * o.tolerance;
    const double a = c.knots[j], b = c.knots[j + 1];
    if (ms > limit && arc_length(c, a, b) >= 2 * o.min_span) knots.push_back(0.5 * (a + b));
  }
  knots.push_back(c.knots.back());
  return knots;
}

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

}  // namespace

bool self_intersects(const BSpline& curve) {
  const std::vector<double> ts = span_samples(curve, 16);
  const std::size_t m = ts.size();
  Points p(m);
  double speed_max = 0;
  std::vector<double> speed(m);
  for (std::size_t i = 0; i < m; ++i) {
    Eigen::Vector2d d[2];  // the same point and derivative as point() and derivative(), one evaluation
    curve.derivatives(ts[i], 1, d);
    p[i] = d[0];
    speed[i] = d[1].norm();
    speed_max = std::max(speed_max, speed[i]);
  }
  for (double s : speed)
    if (!(s > 1e-9 * speed_max)) return true;  // cusp: the curve stops and turns back
  if (doubles_back(p)) return true;
  // Segments sorted by their lowest x; sweep to test only overlapping boxes.
  std::vector<std::size_t> order(m);
  std::iota(order.begin(), order.end(), 0);
  auto lo_x = [&](std::size_t i) { return std::min(p[i].x(), p[(i + 1) % m].x()); };
  auto hi_x = [&](std::size_t i) { return std::max(p[i].x(), p[(i + 1) % m].x()); };
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return lo_x(a) < lo_x(b); });
  auto cross = [](const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c) {
    return (b - a).x() * (c - a).y() - (b - a).y() * (c - a).x();
  };
  for (std::size_t x = 0; x < m; ++x) {
    const std::size_t i = order[x];
    const Eigen::Vector2d &a = p[i], &b = p[(i + 1) % m];
    for (std::size_t y = x + 1; y < m && lo_x(order[y]) <= hi_x(i); ++y) {
      const std::size_t j = order[y];
      if (j == i || (i + 1) % m == j || (j + 1) % m == i) continue;  // neighbours share a point
      const Eigen::Vector2d &c = p[j], &d = p[(j + 1) % m];
      if (std::max(a.y(), b.y()) < std::min(c.y(), d.y()) ||
          std::max(c.y(), d.y()) < std::min(a.y(), b.y()))
        continue;
      const double d1 = cross(a, b, c), d2 = cross(a, b, d), d3 = cross(c, d, a), d4 = cross(c, d, b);
      if (((d1 > 0 && d2 < 0) || (d1 < 0 && d2 > 0)) && ((d3 > 0 && d4 < 0) || (d3 < 0 && d4 > 0)))
        return true;
    }
  }
  return false;
}

namespace {

// The measured points (outliers left out) in the order of their feet along the curve:
// the foot parameters, and the chord from each foot to the next (the last to the first),
// close to the arc for all but the holes.
struct Along {
  std::vector<std::size_t> points;
  std::vector<double> ts, chords;
};

Along along_curve(const Refinement& r) {
  Along a;
  for (std::size_t k : r.feet.order)
    if (r.weights[k] > 0) a.points.push_back(k), a.ts.push_back(r.feet.t[k]);
  if (a.ts.empty()) return a;
  const detail::PiecewiseCurve pc(r.curve);
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
void measure_gaps(const Refinement& r, const Along& along, double gap_factor, FitSplineResult& result) {
  const std::vector<double>& ts = along.ts;
  const std::vector<double>& lengths = along.chords;
  if (ts.size() < 2) return;
  const BSpline& c = r.curve;
  const double period = c.t_max() - c.t_min();
  result.spacing = median_nonnegative(lengths);
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
    const std::size_t worst = static_cast<std::size_t>(std::max_element(lengths.begin(), lengths.end()) - lengths.begin());
    const double end = worst + 1 < ts.size() ? ts[worst + 1] : ts[0] + period;
    result.max_gap = arc_length(c, ts[worst], end);
    result.gap_start = ts[worst];
    result.gap_end = ts[(worst + 1) % ts.size()];
  }
}

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
void measure_layers(const Refinement& r, const Along& along, const FitSplineOptions& o, FitSplineResult& result) {
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
    for (std::size_t i = b; i < b + window; ++i) sa += arc[i], ss += s[i], saa += arc[i] * arc[i], sas += arc[i] * s[i];
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
  if (separations.empty()) return;
  // Noise alone, where it runs high, also spreads a few windows: their "layers" come out
  // 6-10 um apart at 5 um of noise (11 of 1458 clean generated sections); two views 15 um
  // apart give 9-16 um. Below layer_separation noise sigmas nothing is reported.
  const double separation = median(separations);
  if (separation >= o.layer_separation * noise) result.layers = separation;
  else result.layers_length = 0;
}

struct FoldError : Error {
  using Error::Error;
};

// `stop_at_fold`: a knot round whose curve folds is not taken and ends the rounds (the
// last resort of fit_spline: dense knots on a thin edge can wrap the edge twice).
// `distances`, when given, receives every measured point's distance to the curve
// (outliers included).
FitSplineResult fit_once(const Points& profile, const Points& measured, const FitSplineOptions& o,
                         bool stop_at_fold = false, std::vector<double>* distances = nullptr) {
  if (o.degree < 1 || o.degree > 7)
    throw Error("fit_spline: degree " + std::to_string(o.degree) + " is not in 1..7");
  if (o.control_points != 0 && o.control_points < o.degree + 1)
    throw Error("fit_spline: " + std::to_string(o.control_points) +
                " control points are too few, at least " + std::to_string(o.degree + 1) +
                " are needed");
  if (!(o.tolerance > 0) || !(o.initial_span > 0) || !(o.min_span > 0))
    throw Error("fit_spline: tolerance, initial span and minimum span must be positive");
  if (!(o.smoothing_length >= 0) || !(o.outlier_floor >= 0))
    throw Error("fit_spline: smoothing length and outlier floor must not be negative");
  const std::size_t min_points = 8;
  if (profile.size() < min_points || measured.size() < min_points)
    throw Error("fit_spline: the loop has " + std::to_string(std::min(profile.size(), measured.size())) +
                " points, at least " + std::to_string(min_points) + " are needed");
  for (const auto& p : measured)
    if (!p.allFinite()) throw Error("fit_spline: a measured point is not finite");

  // First curve: least squares through the ordered profile on uniform chord-length knots.
  const std::vector<double> s = chord_length_parameters(profile, true);
  const double perimeter = s.back();
  int n = o.control_points;
  if (n == 0) n = static_cast<int>(std::ceil(perimeter / o.initial_span));
  n = std::max(n, std::max(8, o.degree + 1));
  if (o.control_points == 0) n = std::min<int>(n, static_cast<int>(profile.size()) / 2);
  if (n > static_cast<int>(profile.size()))
    throw Error("fit_spline: " + std::to_string(n) + " control points are more than the " +
                std::to_string(profile.size()) + " points of the loop");
  CurveFitOptions fo;
  fo.degree = o.degree;
  fo.control_points = n;
  fo.fairness = o.fairness;
  fo.closed = true;
  BSpline curve;
  try {
    curve = fit_curve(profile, fo);
  } catch (const Error& e) {
    std::string m = e.what();
    if (m.rfind("fit_curve: ", 0) == 0) m = m.substr(11);
    throw Error("fit_spline: " + m);
  }
  const double input_area = polygon_area(profile);
  if (self_intersects(curve))
    throw Error("fit_spline: the loop crosses itself (its points are not ordered along one profile)");

  FitSplineResult result;
  // In adaptive mode the first curve only has to show where the curvature is: its
  // uniform spans cannot follow the edges, and iterating them to convergence is slow.
  FitSplineOptions first = o;
  if (o.control_points == 0) first.max_iterations = std::min(o.max_iterations, 4);
  Refinement r = refine(curve, measured, first);
  result.iterations = r.iterations;
  if (o.control_points == 0) {
    // Knots by curvature first (a few passes: an edge sharpens as it gets knots), then
    // splits where the residuals still hold more than noise.
    for (int pass = 0; pass < 3; ++pass) {
      const std::vector<double> knots = curvature_knots(r.curve, r.feet, noise_sigma(r.feet, r.weights), o);
      Refinement next = refine(reknot(r.curve, knots), measured, o, &r.feet);
      result.iterations += next.iterations;
      if (stop_at_fold && self_intersects(next.curve)) break;
      const bool same = knots.size() == r.curve.knots.size();
      r = std::move(next);
      if (same) break;
    }
    for (int round = 0; round < o.max_rounds; ++round) {
      const double sigma = noise_sigma(r.feet, r.weights);
      const std::vector<double> knots = split_spans(r.curve, r.feet, r.weights, sigma, o);
      if (knots.size() == r.curve.knots.size() ||
          static_cast<int>(knots.size()) - 1 > o.max_control_points)
        break;
      Refinement next = refine(reknot(r.curve, knots), measured, o, &r.feet);
      result.iterations += next.iterations;
      if (stop_at_fold && self_intersects(next.curve)) break;
      result.rounds = round + 1;
      r = std::move(next);
    }
  }

  result.spline = r.curve;
  if (self_intersects(result.spline))
    throw FoldError("fit_spline: the fitted curve folds or crosses itself");
  // The curve must enclose the profile's region on the same side (no turned-over loop).
  const Points dense = sample(result.spline, 16 * static_cast<int>(result.spline.control.size()));
  const double area = polygon_area(dense);
  if (area * input_area <= 0 || std::abs(area - input_area) > 0.5 * std::abs(input_area))
    throw Error("fit_spline: the fitted curve does not enclose the profile's area (fold or wrong ordering)");

  std::vector<double> d;
  for (std::size_t k = 0; k < measured.size(); ++k)
    if (r.weights[k] > 0) d.push_back(std::abs(r.feet.signed_distance[k]));
  result.points = static_cast<int>(d.size());
  result.outliers = static_cast<int>(measured.size() - d.size());
  result.noise = noise_sigma(r.feet, r.weights);
  if (!d.empty()) {
    double ss = 0;
    for (double x : d) ss += x * x;
    result.rms = std::sqrt(ss / d.size());
    // Two order statistics of finite numbers: selected, not sorted.
    const auto p95 =
        d.begin() + std::min(d.size() - 1, static_cast<std::size_t>(std::ceil(0.95 * d.size())) - 1);
    std::nth_element(d.begin(), p95, d.end());
    result.p95 = *p95;
    result.max = *std::max_element(p95, d.end());
  }
  result.control_points = static_cast<int>(result.spline.control.size());
  const Along along = along_curve(r);
  measure_gaps(r, along, o.gap_factor, result);
  measure_layers(r, along, o, result);
  if (distances) {
    distances->clear();
    for (double x : r.feet.signed_distance) distances->push_back(std::abs(x));
  }
  return result;
}

}  // namespace

FitSplineResult fit_spline(const Points& profile, const Points& measured, const FitSplineOptions& o) {
  try {
    return fit_once(profile, measured, o);
  } catch (const FoldError&) {
    if (o.control_points != 0) throw;
  }
  // A fold comes from knots denser than the data support (a thin edge measured sparsely,
  // misregistered views). Candidates: the same knots with the rounds stopped before the
  // first curve that folds, and fewer, longer spans (twice and four times). A coarser
  // curve may not fold yet cut a tight edge short, so the candidate lying closest to all
  // the measured points is taken: truncated squares (10 noise sigmas), so that outliers
  // weigh alike on every candidate.
  struct Candidate {
    FitSplineResult result;
    std::vector<double> distances;
  };
  std::vector<Candidate> candidates;
  auto attempt = [&](const FitSplineOptions& options, bool stop_at_fold) {
    Candidate c;
    try {
      c.result = fit_once(profile, measured, options, stop_at_fold, &c.distances);
      candidates.push_back(std::move(c));
    } catch (const Error&) {
    }
  };
  attempt(o, true);
  FitSplineOptions coarser = o;
  for (int k = 0; k < 2; ++k) {
    coarser.min_span_points *= 2;
    coarser.exact_min_span_points *= 2;
    coarser.min_span *= 2;
    coarser.tolerance *= 4;
    attempt(coarser, false);
  }
  if (candidates.empty()) throw FoldError("fit_spline: the fitted curve folds or crosses itself");
  double sigma = std::numeric_limits<double>::infinity();
  for (const auto& c : candidates)
    if (c.result.noise > 0) sigma = std::min(sigma, c.result.noise);
  const double cap = std::isfinite(sigma) ? 10 * sigma : std::numeric_limits<double>::infinity();
  std::size_t best = 0;
  double best_score = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < candidates.size(); ++i) {
    double score = 0;
    for (double d : candidates[i].distances) score += std::pow(std::min(d, cap), 2);
    if (score < best_score) best_score = score, best = i;
  }
  return std::move(candidates[best].result);
}

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

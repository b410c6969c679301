// SPDX-License-Identifier: GPL-3.0-or-later
#include "section/bspline.h"

#include "section/error.h"
#include "detail/basis_values.h"
#include "detail/ldlt_patterns.h"
#include "detail/piecewise_curve.h"

#include <Eigen/Sparse>
#include <Eigen/SparseCholesky>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <sstream>
#include <string>

namespace section {

namespace {

constexpr int max_degree = max_spline_degree;

int control_count(const BSpline& c) {
  return static_cast<int>(c.control.size());
}

void check_curve(const BSpline& c) {
  const int n = control_count(c);
  if (c.degree < 1 || c.degree > max_degree)
    throw Error("bspline: degree " + std::to_string(c.degree) + " is not in 1.." +
                std::to_string(max_degree));
  if (c.closed) {
    if (n < c.degree + 1 || static_cast<int>(c.knots.size()) != n + 1)
      throw Error("bspline: a closed curve of degree " + std::to_string(c.degree) + " needs at least " +
                  std::to_string(c.degree + 1) + " control points and control points + 1 knots, it has " +
                  std::to_string(n) + " and " + std::to_string(c.knots.size()));
  } else if (n < c.degree + 1 || static_cast<int>(c.knots.size()) != n + c.degree + 1) {
    throw Error("bspline: an open curve of degree " + std::to_string(c.degree) + " needs at least " +
                std::to_string(c.degree + 1) +
                " control points and control points + degree + 1 knots, it has " + std::to_string(n) +
                " and " + std::to_string(c.knots.size()));
  }
}

double period(const BSpline& c) {
  return c.knots.back() - c.knots.front();
}

long floor_div(long a, long b) {
  long q = a / b;
  if ((a % b != 0) && ((a < 0) != (b < 0))) --q;
  return q;
}

// Knot i of the (periodically extended, when closed) knot vector.
double knot(const BSpline& c, long i) {
  if (!c.closed) return c.knots[static_cast<std::size_t>(i)];
  const long n = control_count(c);
  const long k = i >= 0 && i < n ? 0 : floor_div(i, n);  // no division in the first period
  return c.knots[static_cast<std::size_t>(i - k * n)] + static_cast<double>(k) * period(c);
}

// Wraps t into [t_0, t_0 + period) for closed curves, clamps into the domain for open ones.
double normalise(const BSpline& c, double t) {
  if (c.closed) {
    const double p = period(c);
    double r = t - c.knots.front();
    if (!(r >= 0 && r < p)) r = std::fmod(r, p);  // fmod returns r itself inside the period
    if (r < 0) r += p;
    if (r >= p) r = 0;
    return c.knots.front() + r;
  }
  return std::clamp(t, c.t_min(), c.t_max());
}

// Span index j with knot(j) <= t < knot(j + 1); t must be normalised.
long find_span(const BSpline& c, double t) {
  const int n = control_count(c);
  if (c.closed) {
    auto it = std::upper_bound(c.knots.begin(), c.knots.end(), t);
    long j = static_cast<long>(it - c.knots.begin()) - 1;
    return std::clamp<long>(j, 0, n - 1);
  }
  const int p = c.degree;
  if (t >= c.knots[n]) {
    long j = n - 1;
    while (j > p && c.knots[j] >= c.knots[j + 1]) --j;
    return j;
  }
  auto it = std::upper_bound(c.knots.begin() + p, c.knots.begin() + n + 1, t);
  long j = static_cast<long>(it - c.knots.begin()) - 1;
  return std::clamp<long>(j, p, n - 1);
}

// find_span, trying span `hint` first (parameters in order mostly stay in one): a span of
// the domain that holds t is the one the search would find.
long find_span_near(const BSpline& c, double t, long hint) {
  const long first = c.closed ? 0 : c.degree;
  if (hint >= first && hint < control_count(c) && c.knots[hint] <= t && t < c.knots[hint + 1]) return hint;
  return find_span(c, t);
}

using BasisTable = std::array<std::array<double, max_degree + 1>, max_degree + 1>;

// basis_derivatives at degree Degree (the curve's when 0) up to derivative Derivs (nd's
// when negative): cubics (nearly every curve) get the loops unrolled, the same arithmetic
// in the same order.
template <int Degree, int Derivs>
void basis_derivatives_of(const BSpline& c, long j, double t, int derivs, BasisTable& ders) {
  const int p = Degree > 0 ? Degree : c.degree;
  const int nd = Derivs >= 0 ? Derivs : derivs;
  // Not zeroed (that took most of the time at degree 3): every entry read is written first.
  BasisTable ndu;
  std::array<double, max_degree + 1> left, right;
  ndu[0][0] = 1.0;
  for (int r = 1; r <= p; ++r) {
    left[r] = t - knot(c, j + 1 - r);
    right[r] = knot(c, j + r) - t;
    double saved = 0.0;
    for (int s = 0; s < r; ++s) {
      ndu[r][s] = right[s + 1] + left[r - s];
      const double temp = ndu[r][s] == 0 ? 0 : ndu[s][r - 1] / ndu[r][s];
      ndu[s][r] = saved + right[s + 1] * temp;
      saved = left[r - s] * temp;
    }
    ndu[r][r] = saved;
  }
  for (int r = 0; r <= p; ++r) ders[0][r] = ndu[r][p];
  std::array<std::array<double, max_degree + 1>, 2> a{};
  for (int r = 0; r <= p; ++r) {
    int s1 = 0, s2 = 1;
    a[0][0] = 1.0;
    for (int k = 1; k <= nd; ++k) {
      double d = 0.0;
      const int rk = r - k, pk = p - k;
      if (r >= k) {
        a[s2][0] = ndu[pk + 1][rk] == 0 ? 0 : a[s1][0] / ndu[pk + 1][rk];
        d = a[s2][0] * ndu[rk][pk];
      }
      const int j1 = rk >= -1 ? 1 : -rk;
      const int j2 = (r - 1 <= pk) ? k - 1 : p - r;
      for (int jj = j1; jj <= j2; ++jj) {
        a[s2][jj] = ndu[pk + 1][rk + jj] == 0 ? 0 : (a[s1][jj] - a[s1][jj - 1]) / ndu[pk + 1][rk + jj];
        d += a[s2][jj] * ndu[rk + jj][pk];
      }
      if (r <= pk) {
        a[s2][k] = ndu[pk + 1][r] == 0 ? 0 : -a[s1][k - 1] / ndu[pk + 1][r];
        d += a[s2][k] * ndu[r][pk];
      }
      ders[k][r] = d;
      std::swap(s1, s2);
    }
  }
  double f = p;
  for (int k = 1; k <= nd; ++k) {
    for (int r = 0; r <= p; ++r) ders[k][r] *= f;
    f *= (p - k);
  }
}

// Basis functions and their derivatives up to `nd` at t in span j (Piegl & Tiller A2.3).
// ders[k][r] is the k-th derivative of N_{j-p+r}.
void basis_derivatives(const BSpline& c, long j, double t, int nd, BasisTable& ders) {
  if (c.degree != 3 || nd > 3)
    basis_derivatives_of<0, -1>(c, j, t, nd, ders);
  else if (nd == 0)  // values (fits, points)
    basis_derivatives_of<3, 0>(c, j, t, nd, ders);
  else if (nd == 1)
    basis_derivatives_of<3, 1>(c, j, t, nd, ders);
  else if (nd == 2)
    basis_derivatives_of<3, 2>(c, j, t, nd, ders);
  else  // all derivatives (PiecewiseCurve)
    basis_derivatives_of<3, 3>(c, j, t, nd, ders);
}

int control_index(const BSpline& c, long i) {
  if (!c.closed) return static_cast<int>(i);
  const long n = control_count(c);
  if (i >= 0 && i < n) return static_cast<int>(i);  // no division in the first period
  return static_cast<int>(((i % n) + n) % n);
}

// Derivatives 0..nd into out[0..nd] at a parameter of span j, the basis functions'
// derivatives there (k <= min(nd, degree)) given as ders(k, r).
template <class Ders>
void weigh(const BSpline& c, long j, int nd, const Ders& ders, Eigen::Vector2d* out) {
  const int p = c.degree;
  for (int k = 0; k <= nd; ++k) {
    out[k].setZero();
    if (k > p) continue;
    for (int r = 0; r <= p; ++r) out[k] += ders(k, r) * c.control[control_index(c, j - p + r)];
  }
}

// Point and derivatives up to nd at t into out[0..nd].
void evaluate(const BSpline& c, double t, int nd, Eigen::Vector2d* out) {
  check_curve(c);
  const double tn = normalise(c, t);
  const long j = find_span(c, tn);
  BasisTable ders;  // rows 0..min(nd, degree) written, only those read
  basis_derivatives(c, j, tn, std::min(nd, c.degree), ders);
  weigh(
      c, j, nd, [&](int k, int r) { return ders[k][r]; }, out);
}

// Minimum of |C(t) - q|^2 over [a, b] from t0 (see detail::minimise_bracket).
double minimise_bracket(const BSpline& c, const Eigen::Vector2d& q, double a, double b, double t0) {
  return detail::minimise_bracket(
      [&](double t) {
        Eigen::Vector2d d[3];
        evaluate(c, t, 2, d);
        return detail::squared_distance({d[0], d[1], d[2]}, q);
      },
      a, b, t0);
}

ClosestPoint make_closest(const BSpline& c, const Eigen::Vector2d& q, double t) {
  ClosestPoint cp;
  cp.t = normalise(c, t);
  cp.point = c.point(cp.t);
  cp.distance = (cp.point - q).norm();
  return cp;
}

// Refines the local minima of the sampled squared distance at parameters ts (ascending,
// covering the domain; for closed curves one period without the repeated end).
ClosestPoint refine_samples(const BSpline& c, const Eigen::Vector2d& q, const std::vector<double>& ts,
                            int max_candidates) {
  const int m = static_cast<int>(ts.size());
  std::vector<double> g(m);
  for (int i = 0; i < m; ++i) g[i] = (c.point(ts[i]) - q).squaredNorm();
  const double per = c.closed ? period(c) : 0;
  auto param = [&](int i) {
    if (!c.closed) return ts[std::clamp(i, 0, m - 1)];
    if (i < 0) return ts[i + m] - per;
    if (i >= m) return ts[i - m] + per;
    return ts[i];
  };
  auto value = [&](int i) {
    if (!c.closed) return i < 0 || i >= m ? std::numeric_limits<double>::infinity() : g[i];
    return g[(i + m) % m];
  };
  std::vector<int> minima;
  for (int i = 0; i < m; ++i)
    if (g[i] <= value(i - 1) && g[i] <= value(i + 1)) minima.push_back(i);
  std::sort(minima.begin(), minima.end(), [&](int x, int y) { return g[x] < g[y]; });
  if (static_cast<int>(minima.size()) > max_candidates) minima.resize(max_candidates);
  ClosestPoint best;
  best.distance = std::numeric_limits<double>::infinity();
  for (int i : minima) {
    const double a = param(i - 1), b = param(i + 1);
    const double t = minimise_bracket(c, q, a, b, ts[i]);
    const ClosestPoint cp = make_closest(c, q, t);
    if (cp.distance < best.distance) best = cp;
  }
  return best;
}

// knot(c, i) for i in [-p, n + p] when closed (the knots when open): the knots about every
// span, for detail::basis_values without wrapping them one by one.
std::vector<double> knots_around(const BSpline& c) {
  if (!c.closed) return c.knots;
  std::vector<double> out;
  for (long i = -c.degree; i <= control_count(c) + c.degree; ++i) out.push_back(knot(c, i));
  return out;
}

// Where fit_control_points sums a point's terms: a row meets the 2 p + 1 columns within p
// of it at most: slot p + (column - row), p - a + b for a span's basis functions a, b
// without a wrap, or the column itself when n <= 2 p + 1 (closed).
struct RowSlots {
  explicit RowSlots(const BSpline& shape)
      : shape(shape), n(control_count(shape)), p(shape.degree), slots(2 * p + 1), by_column(n <= slots) {}
  int slot_of(int row, int column) const {
    if (by_column) return column;
    int d = column - row;
    if (d > p) d -= n;
    if (d < -p) d += n;
    return d + p;
  }
  // Takes span j: its control points idx and the entries of their pairs.
  void span(long j) {
    for (int r = 0; r <= p; ++r) idx[r] = control_index(shape, j - p + r);
    const bool plain = !by_column && idx[p] == idx[0] + p;
    for (int a = 0; a <= p; ++a)
      for (int b = 0; b <= p; ++b)
        pair[a][b] = static_cast<std::size_t>(idx[a]) * slots + (plain ? p - a + b : slot_of(idx[a], idx[b]));
  }
  // The entry of the span's basis functions a, b.
  std::size_t entry(int a, int b) const { return pair[a][b]; }
  const BSpline& shape;
  const int n, p, slots;
  const bool by_column;
  int idx[max_degree + 1];
  std::size_t pair[max_degree + 1][max_degree + 1];
};

}  // namespace

namespace detail {

long basis_table(const BSpline& curve, double t, int nd, double* table) {
  check_curve(curve);
  const double tn = normalise(curve, t);
  const long j = find_span(curve, tn);
  const int p = curve.degree, nk = std::min(nd, p);
  BasisTable ders;
  basis_derivatives(curve, j, tn, nk, ders);
  for (int k = 0; k <= nk; ++k)
    for (int r = 0; r <= p; ++r) table[k * (p + 1) + r] = ders[k][r];
  return j;
}

void weigh_basis(const BSpline& curve, long span, int nd, const double* table, Eigen::Vector2d* out) {
  const int stride = curve.degree + 1;
  weigh(
      curve, span, nd, [&](int k, int r) { return table[k * stride + r]; }, out);
}

}  // namespace detail

void check_spline(const BSpline& c) {
  check_curve(c);
  auto number = [](double x) {
    std::ostringstream o;
    o << x;
    return o.str();
  };
  for (std::size_t i = 0; i < c.control.size(); ++i)
    if (!c.control[i].allFinite())
      throw Error("bspline: control point " + std::to_string(i) + " is not finite");
  for (std::size_t i = 0; i < c.knots.size(); ++i) {
    if (!std::isfinite(c.knots[i])) throw Error("bspline: knot " + std::to_string(i) + " is not finite");
    if (i > 0 && c.knots[i] < c.knots[i - 1])
      throw Error("bspline: knot " + std::to_string(i) + " (" + number(c.knots[i]) + ") is below knot " +
                  std::to_string(i - 1) + " (" + number(c.knots[i - 1]) + "); knots must not decrease");
  }
  if (!(c.t_max() > c.t_min()))
    throw Error(
        std::string("bspline: the curve's parameter range is empty: ") +
        (c.closed ? "the last knot equals the first, a period of 0"
                  : "knot " + std::to_string(c.degree) + " equals knot " + std::to_string(c.control.size())));
  // Runs of equal knots (across the wrap): de Boor divides by knot differences degree apart.
  const long stored = static_cast<long>(c.closed ? c.control.size() : c.knots.size());
  const long n = c.closed ? 2 * stored : stored;
  long run = 1;
  for (long i = 1; i < n; ++i) {
    run = knot(c, i) == knot(c, i - 1) ? run + 1 : 1;
    if (run > c.degree + 1)
      throw Error("bspline: " + std::to_string(run) + " equal knots in a row at knot " +
                  std::to_string(i % stored) + "; a curve of degree " + std::to_string(c.degree) +
                  " allows at most " + std::to_string(c.degree + 1));
  }
}

// A curve with too few knots for its parameter range (a default BSpline: no knots) is an
// error, not a read past the vector.
double BSpline::t_min() const {
  if (knots.size() <= (closed ? 0 : static_cast<std::size_t>(std::max(degree, 0))))
    throw Error("bspline: the curve has " + std::to_string(knots.size()) + " knots, too few for its range");
  return closed ? knots.front() : knots[degree];
}

double BSpline::t_max() const {
  if (knots.size() <= (closed ? 0 : control.size()))
    throw Error("bspline: the curve has " + std::to_string(knots.size()) + " knots, too few for its range");
  return closed ? knots.back() : knots[control.size()];
}

Eigen::Vector2d BSpline::point(double t) const {
  return derivative(t, 0);
}

Eigen::Vector2d BSpline::derivative(double t, int k) const {
  if (k < 0) throw Error("bspline: derivative order " + std::to_string(k) + " is negative");
  Eigen::Vector2d out[max_degree + 2];
  if (k > degree) {
    check_curve(*this);
    return Eigen::Vector2d::Zero();
  }
  evaluate(*this, t, k, out);
  return out[k];
}

void BSpline::derivatives(double t, int k, Eigen::Vector2d* out) const {
  if (k < 0) throw Error("bspline: derivative order " + std::to_string(k) + " is negative");
  evaluate(*this, t, k, out);
}

double BSpline::curvature(double t) const {
  Eigen::Vector2d d[3];
  evaluate(*this, t, 2, d);
  const double speed = d[1].norm();
  if (speed == 0) return 0;
  return (d[1].x() * d[2].y() - d[1].y() * d[2].x()) / (speed * speed * speed);
}

void BSpline::basis(double t, std::vector<int>& index, std::vector<double>& value) const {
  check_curve(*this);
  const double tn = normalise(*this, t);
  const long j = find_span(*this, tn);
  BasisTable ders{};
  basis_derivatives(*this, j, tn, 0, ders);
  index.resize(degree + 1);
  value.resize(degree + 1);
  for (int r = 0; r <= degree; ++r) {
    index[r] = control_index(*this, j - degree + r);
    value[r] = ders[0][r];
  }
}

ClosestPoint closest_point(const BSpline& curve, const Eigen::Vector2d& q, int samples) {
  check_curve(curve);
  if (!q.allFinite()) throw Error("bspline: the point to project is not finite");
  if (samples > 1000000)
    throw Error("bspline: " + std::to_string(samples) + " samples a knot span, at most 1000000");
  samples = std::max(samples, 2);
  std::vector<double> ts;
  const int n = control_count(curve);
  const long first = curve.closed ? 0 : curve.degree;
  const long last = curve.closed ? n : n;  // spans first .. last-1
  for (long j = first; j < last; ++j) {
    const double a = knot(curve, j), b = knot(curve, j + 1);
    if (b <= a) continue;
    for (int s = 0; s < samples; ++s) ts.push_back(a + (b - a) * s / samples);
  }
  if (!curve.closed) ts.push_back(curve.t_max());
  const ClosestPoint c = refine_samples(curve, q, ts, 4);
  if (!std::isfinite(c.distance))  // squared distances overflowed: the foot is not known
    throw Error("bspline: the point to project lies too far from the curve (its distance overflows)");
  return c;
}

ClosestPoint closest_point_near(const BSpline& curve, const Eigen::Vector2d& q, double t_guess) {
  check_curve(curve);
  const double tn = normalise(curve, t_guess);
  const long j = find_span(curve, tn);
  double a, b;
  if (curve.closed) {
    // Unwrapped parameters are fine here: evaluation wraps them.
    a = knot(curve, j - 1);
    b = knot(curve, j + 2);
  } else {
    const int n = control_count(curve);
    a = knot(curve, std::max<long>(j - 1, curve.degree));
    b = knot(curve, std::min<long>(j + 2, n));
  }
  constexpr int samples = 12;
  std::vector<double> ts(samples + 1);
  for (int s = 0; s <= samples; ++s) ts[s] = a + (b - a) * s / samples;
  // Treat the bracket as an open curve piece: end samples may be minima.
  const int m = samples + 1;
  std::vector<double> g(m);
  for (int i = 0; i < m; ++i) g[i] = (curve.point(ts[i]) - q).squaredNorm();
  const int best = static_cast<int>(std::min_element(g.begin(), g.end()) - g.begin());
  const double lo = ts[std::max(best - 1, 0)], hi = ts[std::min(best + 1, m - 1)];
  return make_closest(curve, q, minimise_bracket(curve, q, lo, hi, ts[best]));
}

BSpline fit_control_points(const std::vector<Eigen::Vector2d>& points, const std::vector<double>& parameters,
                           const BSpline& shape, double fairness, const std::vector<double>& weights) {
  check_curve(shape);
  const int n = control_count(shape);
  const int m = static_cast<int>(points.size());
  if (m == 0) throw Error("fit_curve: no points to fit");
  if (!weights.empty() && weights.size() != points.size())
    throw Error("fit_curve: " + std::to_string(weights.size()) + " weights for " + std::to_string(m) +
                " points");
  if (static_cast<int>(parameters.size()) < m)
    throw Error("fit_curve: " + std::to_string(m) + " points but only " + std::to_string(parameters.size()) +
                " parameters");
  // The data term summed per matrix entry in point order: the sums that setFromTriplets
  // would form from one triplet per point and entry, without the triplets. The terms are
  // non-negative (or NaN), so the first added to a zero is itself, and the entries a point
  // touches are those of its span.
  RowSlots at(shape);
  const int p = at.p, slots = at.slots;
  std::vector<double> entries(static_cast<std::size_t>(n) * slots, 0.0);
  std::vector<char> used(entries.size(), 0), span_used(static_cast<std::size_t>(n), 0);
  Eigen::MatrixXd rhs = Eigen::MatrixXd::Zero(n, 2);
  const std::vector<double> around = knots_around(shape);  // knot j at around[j + shift]
  const long shift = shape.closed ? p : 0;
  double val[max_degree + 1];  // the basis_derivatives_of values (basis_values)
  double trace = 0;
  long j = -1;  // the last point's span
  for (int i = 0; i < m; ++i) {
    const double w = weights.empty() ? 1.0 : weights[i];
    if (w <= 0) continue;
    const double tn = normalise(shape, parameters[i]);  // as BSpline::basis, without its checks
    const long before = j;
    j = find_span_near(shape, tn, j);
    detail::basis_values(&around[static_cast<std::size_t>(j + shift)], p, tn, val);
    if (j != before) at.span(j), span_used[static_cast<std::size_t>(j)] = 1;  // points in order share spans
    for (int a = 0; a <= p; ++a) {
      rhs.row(at.idx[a]) += w * val[a] * points[i].transpose();
      for (int b = 0; b <= p; ++b) entries[at.entry(a, b)] += w * val[a] * val[b];
      trace += w * val[a] * val[a];
    }
  }
  for (long s = 0; s < n; ++s) {
    if (!span_used[static_cast<std::size_t>(s)]) continue;
    at.span(s);
    for (int a = 0; a <= p; ++a)
      for (int b = 0; b <= p; ++b) used[at.entry(a, b)] = 1;
  }
  std::vector<Eigen::Triplet<double>> trip;
  trip.reserve(static_cast<std::size_t>(n) * (2 * shape.degree + 1 + 9));
  for (int r = 0; r < n; ++r)
    for (int e = 0; e < slots; ++e) {
      const std::size_t k = static_cast<std::size_t>(r) * slots + e;
      if (!used[k]) continue;
      const int column = at.by_column ? e : (r + e - p + n) % n;
      trip.emplace_back(r, column, entries[k]);
    }
  // Second differences of the control polygon keep the system regular where spans hold
  // no data; the weight is relative to the mean diagonal of the data term.
  const double lambda = std::max(fairness, 1e-12) * std::max(trace / n, 1e-12);
  const int first = shape.closed ? 0 : 1, last = shape.closed ? n : n - 1;
  for (int i = first; i < last; ++i) {
    const int ids[3] = {control_index(shape, i - 1), i, control_index(shape, i + 1)};
    const double coef[3] = {1, -2, 1};
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b) trip.emplace_back(ids[a], ids[b], lambda * coef[a] * coef[b]);
  }
  Eigen::SparseMatrix<double> A(n, n);
  A.setFromTriplets(trip.begin(), trip.end());
  detail::Ldlt& solver = detail::factored(A);  // as Ldlt solver(A) would
  if (solver.info() != Eigen::Success)
    throw Error("fit_curve: the least-squares system is singular (too few or degenerate points)");
  const Eigen::MatrixXd x = solver.solve(rhs);
  if (solver.info() != Eigen::Success || !x.allFinite())
    throw Error("fit_curve: the least-squares system is singular (too few or degenerate points)");
  BSpline out = shape;
  for (int i = 0; i < n; ++i) out.control[i] = x.row(i).transpose();
  return out;
}

double arc_length(const BSpline& curve, double a, double b) {
  check_curve(curve);
  if (!std::isfinite(a) || !std::isfinite(b)) throw Error("bspline: an arc length's bound is not finite");
  const double one = curve.closed ? period(curve) : 0;
  if (curve.closed && !(one > 0)) throw Error("bspline: the closed curve's period is not above 0");
  if (b < a) std::swap(a, b);
  // Whole periods of a closed curve counted once, not span by span (1e12 periods ran for
  // hours).
  if (curve.closed && b - a > one) {
    const double periods = std::floor((b - a) / one);
    const double rest = (b - a) - periods * one;
    return periods * arc_length(curve, curve.t_min(), curve.t_max()) + arc_length(curve, a, a + rest);
  }
  if (!curve.closed) {
    a = std::clamp(a, curve.t_min(), curve.t_max());
    b = std::clamp(b, curve.t_min(), curve.t_max());
  }
  if (b <= a) return 0;
  static const double x[5] = {-0.9061798459386640, -0.5384693101056831, 0.0, 0.5384693101056831,
                              0.9061798459386640};
  static const double w[5] = {0.2369268850561891, 0.4786286704993665, 0.5688888888888889, 0.4786286704993665,
                              0.2369268850561891};
  // Breakpoints between a and b (extended periodically when closed).
  long j = find_span(curve, normalise(curve, a));
  if (curve.closed) {
    const long n = control_count(curve);
    const long k = static_cast<long>(std::floor((a - curve.knots.front()) / period(curve)));
    j += k * n;
    while (knot(curve, j) > a) --j;
    while (knot(curve, j + 1) <= a) ++j;
  }
  double total = 0;
  double lo = a;
  const long j_end = curve.closed ? std::numeric_limits<long>::max() : control_count(curve);
  while (lo < b) {
    const double hi = (j + 1 <= j_end) ? std::min(b, knot(curve, j + 1)) : b;
    if (hi > lo) {
      const double half = 0.5 * (hi - lo), mid = 0.5 * (hi + lo);
      for (int g = 0; g < 5; ++g) total += w[g] * half * curve.derivative(mid + half * x[g], 1).norm();
    }
    lo = std::max(lo, hi);
    ++j;
    if (!curve.closed && j >= j_end) break;
  }
  return total;
}

}  // namespace section

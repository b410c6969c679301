// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// A B-spline converted to one polynomial per knot span, for the loops that evaluate the
// same curve hundreds of thousands of times (foot points of every measured point in
// every fit iteration): Horner's rule on a few coefficients instead of Cox-de Boor.
#include "section/bspline.h"

#include <Eigen/Core>

#include <algorithm>
#include <cmath>
#include <vector>

namespace section::detail {

/// The basis of `curve` at t as BSpline::derivatives(t, nd) weighs the control points
/// with (it depends on the knots only): derivative k <= min(nd, degree) of the r-th
/// function non-zero there in table[k * (degree + 1) + r]. Returns the knot span.
long basis_table(const BSpline& curve, double t, int nd, double* table);

/// BSpline::derivatives(t, nd, out) of `curve` from basis_table(curve, t, nd, table)'s
/// span and table, on this or any curve with the same knots.
void weigh_basis(const BSpline& curve, long span, int nd, const double* table, Eigen::Vector2d* out);

/// Point and first two derivatives of a curve at one parameter.
struct CurveJet {
  Eigen::Vector2d point, d1, d2;
  /// Signed curvature (positive turning counterclockwise); 0 where the curve stops.
  double curvature() const {
    const double speed = d1.norm();
    return speed > 0 ? (d1.x() * d2.y() - d1.y() * d2.x()) / (speed * speed * speed) : 0;
  }
};

class PiecewiseCurve {
public:
  /// No curve yet (a state to assign one to).
  PiecewiseCurve() = default;

  /// Converts `curve` (checked by the caller: a valid open or closed B-spline).
  /// `keep_basis`: the basis at the spans' starts kept, for curves on the same knots
  /// (the constructor below).
  explicit PiecewiseCurve(const BSpline& curve, bool keep_basis = false)
      : degree_(curve.degree), closed_(curve.closed), t_min_(curve.t_min()), t_max_(curve.t_max()) {
    const std::vector<double>& k = curve.knots;
    std::vector<double> breaks;
    if (closed_) {
      breaks = k;
    } else {
      for (std::size_t i = curve.degree; i + curve.degree < k.size(); ++i) breaks.push_back(k[i]);
    }
    // Zero-length spans carry no curve.
    const long first = closed_ ? 0 : curve.degree;
    const long n = static_cast<long>(curve.control.size());
    const double period = closed_ ? k.back() - k.front() : 0;
    auto knot = [&](long i) {  // periodically extended when closed
      if (!closed_) return k[static_cast<std::size_t>(i)];
      const long wraps = i >= 0 ? i / n : -((-i + n - 1) / n);
      return k[static_cast<std::size_t>(i - wraps * n)] + static_cast<double>(wraps) * period;
    };
    breaks_.push_back(breaks.front());
    for (std::size_t i = 1; i < breaks.size(); ++i) {
      if (breaks[i] <= breaks_.back()) continue;
      const long j = first + static_cast<long>(i) - 1;  // knot index of the span's start
      breaks_.push_back(breaks[i]);
      first_control_.push_back(static_cast<int>(closed_ ? ((j - degree_) % n + n) % n : j - degree_));
      for (long r = j - degree_ + 1; r <= j + degree_; ++r) local_knots_.push_back(knot(r));
    }
    // Taylor coefficients at each span's start, from inside the span (right limits).
    if (!keep_basis) {
      coef_.resize((breaks_.size() - 1) * (degree_ + 1));
      for (std::size_t j = 0; j + 1 < breaks_.size(); ++j) {
        Eigen::Vector2d ders[8];
        curve.derivatives(breaks_[j], degree_, ders);
        set_span(j, ders);
      }
      return;
    }
    const std::size_t table = static_cast<std::size_t>(degree_ + 1) * (degree_ + 1);
    span_.resize(breaks_.size() - 1);
    basis_.resize(span_.size() * table);
    for (std::size_t j = 0; j < span_.size(); ++j)
      span_[j] = basis_table(curve, breaks_[j], degree_, &basis_[j * table]);
    set_controls(curve);
  }

  /// `curve`, whose knots are those of the curve `same_knots` was converted from (the
  /// control points moved): the basis at the spans' starts taken over, or kept here for
  /// the next such curve.
  PiecewiseCurve(const BSpline& curve, const PiecewiseCurve& same_knots) {
    if (same_knots.basis_.empty()) {
      *this = PiecewiseCurve(curve, true);
    } else {
      *this = same_knots;
      set_controls(curve);
    }
  }

  double t_min() const { return t_min_; }
  double t_max() const { return t_max_; }
  /// A closed curve's parameter distance going forward (in its direction) from a to b, in
  /// [0, period).
  double forward(double a, double b) const {
    const double period = t_max_ - t_min_;
    return std::fmod(std::fmod(b - a, period) + period, period);
  }

  /// Where a parameter lies: its span and the parameter from the span's start.
  struct Local {
    std::size_t span;
    double s;
  };

  /// The span of t (wrapped into one period when closed, clamped when open). `hint`: a
  /// span to try first (the last one located, when the parameters come in order).
  Local locate(double t, std::size_t hint = 0) const {
    if (closed_) {
      const double period = t_max_ - t_min_;
      if (t < t_min_ || t >= t_max_) {
        t = t_min_ + std::fmod(t - t_min_, period);
        if (t < t_min_) t += period;
        if (t >= t_max_) t = t_min_;
      }
    } else {
      t = std::clamp(t, t_min_, t_max_);
    }
    // Breaks increase strictly: a span that holds t is the one the search would find.
    if (hint + 1 < breaks_.size() && breaks_[hint] <= t && t < breaks_[hint + 1])
      return {hint, t - breaks_[hint]};
    const auto it = std::upper_bound(breaks_.begin(), breaks_.end(), t);
    const std::size_t span = std::min<std::size_t>(
        static_cast<std::size_t>(std::max<std::ptrdiff_t>(it - breaks_.begin() - 1, 0)), breaks_.size() - 2);
    return {span, t - breaks_[span]};
  }

  /// The last span located and its breaks, for loops that locate nearby parameters one after
  /// another (Newton on a foot, points in order along the curve).
  struct Cursor {
    Local at{0, 0};
    double lo = 0, hi = 0;  // the span's breaks (none before the first locate)
  };

  /// locate(t, cursor.at.span), and the cursor moved there. A t inside the cursor's span
  /// takes two comparisons: a span lies inside the period (the domain), so such a t needs
  /// no wrapping (clamping), and the search would find that span.
  Local locate(double t, Cursor& cursor) const {
    if (cursor.lo <= t && t < cursor.hi) return cursor.at = {cursor.at.span, t - cursor.lo};
    cursor.at = locate(t, cursor.at.span);
    cursor.lo = breaks_[cursor.at.span];
    cursor.hi = breaks_[cursor.at.span + 1];
    return cursor.at;
  }

  /// Point and derivatives at t (wrapped into one period when closed, clamped when open).
  CurveJet jet(double t) const { return jet(locate(t)); }

  // Cubics (nearly every curve) take the same arithmetic with the degree known to the
  // compiler: the loops unrolled, the fits' inner loops take a fifth less time.
  CurveJet jet(const Local& l) const { return degree_ == 3 ? jet_of<3>(l) : jet_of<0>(l); }

  /// The p + 1 basis functions non-zero at t: the first one's control index (the others
  /// follow consecutively, wrapping around when closed) and their values in `value`.
  int basis(double t, double* value) const { return basis(locate(t), value); }

  int basis(const Local& l, double* value) const {
    return degree_ == 3 ? basis_of<3>(l, value) : basis_of<0>(l, value);
  }

  Eigen::Vector2d point(double t) const { return point(locate(t)); }
  /// `count` (2 or more) points evenly in parameter from t0 to t1, both included:
  /// point(t0 + (t1 - t0) * i / (count - 1)), each span tried from the one before.
  std::vector<Eigen::Vector2d> points(double t0, double t1, int count) const {
    std::vector<Eigen::Vector2d> out;
    out.reserve(static_cast<std::size_t>(std::max(count, 0)));
    Local at{0, 0};
    for (int i = 0; i < count; ++i) {
      at = locate(t0 + (t1 - t0) * i / (count - 1), at.span);
      out.push_back(point(at));
    }
    return out;
  }

  Eigen::Vector2d point(const Local& l) const {
    const Eigen::Vector2d* c = &coef_[l.span * (degree_ + 1)];
    Eigen::Vector2d p = c[degree_];
    for (int d = degree_ - 1; d >= 0; --d) p = p * l.s + c[d];
    return p;
  }

private:
  // Span j's Taylor coefficients from the curve's derivatives at its start.
  void set_span(std::size_t j, const Eigen::Vector2d* ders) {
    double factorial = 1;
    for (int d = 0; d <= degree_; ++d) {
      if (d > 0) factorial *= d;
      coef_[j * (degree_ + 1) + d] = ders[d] / factorial;
    }
  }

  // The Taylor coefficients of every span from the control points of `curve`, on the basis kept.
  void set_controls(const BSpline& curve) {
    const int stride = degree_ + 1;
    coef_.resize(span_.size() * stride);
    for (std::size_t j = 0; j < span_.size(); ++j) {
      Eigen::Vector2d ders[8];
      weigh_basis(curve, span_[j], degree_, &basis_[j * stride * stride], ders);
      set_span(j, ders);
    }
  }

  // Degree: the curve's when 0, else equal to it.
  template <int Degree>
  CurveJet jet_of(const Local& l) const {
    const int degree = Degree > 0 ? Degree : degree_;
    const Eigen::Vector2d* c = &coef_[l.span * (degree + 1)];
    CurveJet out{c[degree], Eigen::Vector2d::Zero(), Eigen::Vector2d::Zero()};
    for (int d = degree - 1; d >= 0; --d) {
      out.d2 = out.d2 * l.s + 2 * out.d1;
      out.d1 = out.d1 * l.s + out.point;
      out.point = out.point * l.s + c[d];
    }
    return out;
  }

  template <int Degree>
  int basis_of(const Local& l, double* value) const {
    const int degree = Degree > 0 ? Degree : degree_;
    const double* u = &local_knots_[l.span * 2 * degree];  // knots j-p+1 .. j+p
    const double x = breaks_[l.span] + l.s;
    double left[8], right[8];
    value[0] = 1;
    for (int r = 1; r <= degree; ++r) {
      left[r] = x - u[degree - r];
      right[r] = u[degree - 1 + r] - x;
      double saved = 0;
      for (int i = 0; i < r; ++i) {
        // Never 0 (unlike BSpline's on any knot span): the knots it spans hold this span,
        // of positive length, and x lies in it.
        const double temp = value[i] / (right[i + 1] + left[r - i]);
        value[i] = saved + right[i + 1] * temp;
        saved = left[r - i] * temp;
      }
      value[r] = saved;
    }
    return first_control_[l.span];
  }

  int degree_ = 0;
  bool closed_ = false;
  double t_min_ = 0, t_max_ = 0;
  std::vector<double> breaks_;
  std::vector<int> first_control_;     // per span: control index of its first basis function
  std::vector<double> local_knots_;    // per span: the 2 degree knots around it
  std::vector<Eigen::Vector2d> coef_;  // (degree + 1) per span, constant term first
  std::vector<long> span_;             // per span: its knot span in the curve (BSpline's numbering)
  std::vector<double> basis_;          // per span: basis_table at its start, all derivatives
};

/// |C(t) - q|^2 and its first two derivatives in t.
struct SquaredDistance {
  double g, dg, ddg;
};

inline SquaredDistance squared_distance(const CurveJet& j, const Eigen::Vector2d& q) {
  const Eigen::Vector2d r = j.point - q;
  return {r.squaredNorm(), 2 * r.dot(j.d1), 2 * (j.d1.squaredNorm() + r.dot(j.d2))};
}

/// Minimum of a squared distance g over the bracket [a, b] starting at t0, `f(t)` giving
/// g and its derivatives: Newton on g', kept inside a shrinking bracket and falling back
/// to bisection, or to golden section when g' does not change sign, so that flat or
/// non-convex stretches (points near a centre of curvature) cannot throw it out.
template <class F>
double minimise_bracket(F&& f, double a, double b, double t0) {
  const SquaredDistance fa = f(a), fb = f(b);
  const double tol = 1e-13 * std::max({1.0, std::abs(a), std::abs(b)});
  if (fa.dg < 0 && fb.dg > 0) {
    double t = std::clamp(t0, a, b);
    for (int it = 0; it < 60 && b - a > tol; ++it) {
      const SquaredDistance ft = f(t);
      if (ft.dg == 0) return t;
      if (ft.dg < 0)
        a = t;
      else
        b = t;
      double next = ft.ddg > 0 ? t - ft.dg / ft.ddg : 0.5 * (a + b);
      // Newton's step under the tolerance: t is the root, though a bracket end (bisecting
      // on from there only halves the bracket down to the tolerance, ~35 times).
      if (ft.ddg > 0 && std::abs(next - t) < tol) return std::clamp(next, a, b);
      if (!(next > a && next < b)) next = 0.5 * (a + b);
      if (std::abs(next - t) < tol) return next;
      t = next;
    }
    return 0.5 * (a + b);
  }
  const double gr = 0.5 * (std::sqrt(5.0) - 1.0);
  const double a0 = a, b0 = b;
  double x1 = b - gr * (b - a), x2 = a + gr * (b - a);
  double g1 = f(x1).g, g2 = f(x2).g;
  for (int it = 0; it < 100 && b - a > tol; ++it) {
    if (g1 < g2) {
      b = x2;
      x2 = x1;
      g2 = g1;
      x1 = b - gr * (b - a);
      g1 = f(x1).g;
    } else {
      a = x1;
      x1 = x2;
      g1 = g2;
      x2 = a + gr * (b - a);
      g2 = f(x2).g;
    }
  }
  double t = 0.5 * (a + b);
  double best = f(t).g;
  if (fa.g < best) {
    t = a0;
    best = fa.g;
  }
  if (fb.g < best) t = b0;
  return t;
}

}  // namespace section::detail

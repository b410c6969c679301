#pragma once
// Fast joint evaluation of a B-spline's point and first two derivatives, for camber's
// Newton solves (BSpline::derivative evaluates one order per call).
#include "section/bspline.h"
#include "detail/piecewise_curve.h"

#include <Eigen/Core>
#include <algorithm>
#include <cmath>

namespace section::detail {

// Point, first and second derivative in one evaluation (BSpline::derivative computes one
// order per call; the Newton solves below need all three at once, thousands of times).
// Same knot conventions as bspline.h: closed curves extend their breakpoints
// periodically and wrap their control points.
class FastCurve {
public:
  explicit FastCurve(const BSpline& c)
      : c_(c), n_(static_cast<long>(c.control.size())), p_(c.degree),
        period_(c.closed ? c.knots.back() - c.knots.front() : 0) {}
  inline CurveJet jet(double t) const {
    const int p = p_;
    if (p < 1 || p > 7) return {c_.point(t), c_.derivative(t, 1), c_.derivative(t, 2)};
    double tn;
    long j;
    if (c_.closed) {
      double r = std::fmod(t - c_.knots.front(), period_);
      if (r < 0) r += period_;
      if (r >= period_) r = 0;
      tn = c_.knots.front() + r;
      j = std::clamp<long>(std::upper_bound(c_.knots.begin(), c_.knots.end(), tn) - c_.knots.begin() - 1, 0, n_ - 1);
    } else {
      tn = std::clamp(t, c_.t_min(), c_.t_max());
      if (tn >= c_.knots[n_]) {
        j = n_ - 1;
        while (j > p && c_.knots[j] >= c_.knots[j + 1]) --j;
      } else {
        j = std::clamp<long>(std::upper_bound(c_.knots.begin() + p, c_.knots.begin() + n_ + 1, tn) -
                                 c_.knots.begin() - 1, p, n_ - 1);
      }
    }
    // Basis functions of degrees p-2, p-1, p in span j (Piegl & Tiller A2.2).
    double nb[8] = {1}, left[8], right[8], n1[8] = {0}, n2[8] = {0};
    if (p == 1) n1[0] = 1;
    for (int r = 1; r <= p; ++r) {
      left[r] = tn - knot(j + 1 - r);
      right[r] = knot(j + r) - tn;
      double saved = 0;
      for (int s = 0; s < r; ++s) {
        const double den = right[s + 1] + left[r - s];
        const double temp = den == 0 ? 0 : nb[s] / den;
        nb[s] = saved + right[s + 1] * temp;
        saved = left[r - s] * temp;
      }
      nb[r] = saved;
      if (r == p - 2) std::copy(nb, nb + r + 1, n2);
      if (r == p - 1) std::copy(nb, nb + r + 1, n1);
    }
    if (p == 2) n2[0] = 1;
    Eigen::Vector2d q[8], q1[8], q2[8];
    for (int r = 0; r <= p; ++r) q[r] = c_.control[ctrl(j - p + r)];
    for (int r = 0; r < p; ++r) {
      const double den = knot(j + 1 + r) - knot(j - p + 1 + r);
      q1[r] = den == 0 ? Eigen::Vector2d::Zero() : Eigen::Vector2d(p * (q[r + 1] - q[r]) / den);
    }
    for (int r = 0; r + 1 < p; ++r) {
      const double den = knot(j + 1 + r) - knot(j - p + 2 + r);
      q2[r] = den == 0 ? Eigen::Vector2d::Zero() : Eigen::Vector2d((p - 1) * (q1[r + 1] - q1[r]) / den);
    }
    CurveJet out{Eigen::Vector2d::Zero(), Eigen::Vector2d::Zero(), Eigen::Vector2d::Zero()};
    for (int r = 0; r <= p; ++r) out.point += nb[r] * q[r];
    for (int r = 0; r < p; ++r) out.d1 += n1[r] * q1[r];
    for (int r = 0; r + 1 < p; ++r) out.d2 += n2[r] * q2[r];
    return out;
  }
  const BSpline& curve() const { return c_; }

private:
  double knot(long i) const {
    if (!c_.closed) return c_.knots[static_cast<std::size_t>(i)];
    long k = i / n_;
    if (i % n_ != 0 && i < 0) --k;
    return c_.knots[static_cast<std::size_t>(i - k * n_)] + static_cast<double>(k) * period_;
  }
  int ctrl(long i) const { return c_.closed ? static_cast<int>(((i % n_) + n_) % n_) : static_cast<int>(i); }
  const BSpline& c_;
  long n_;
  int p_;
  double period_;
};

}  // namespace section::detail

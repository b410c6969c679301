// SPDX-License-Identifier: GPL-3.0-or-later
// The nominal of compare prepared for foot points: arc length along it and its zones.
#include "compare_steps.h"
#include "io/text.h"

#include "section/error.h"
#include "section/params.h"
#include "section/units.h"

#include <algorithm>
#include <cmath>
#include <string>

namespace section::compare {

namespace {

// Sample index at or after parameter t (wrapping).
std::size_t sample_after(const std::vector<double>& ts, double t) {
  const auto it = std::lower_bound(ts.begin(), ts.end(), t);
  return it == ts.end() ? 0 : static_cast<std::size_t>(it - ts.begin());
}

// Walking from sample `start` in direction `step` (+1 or -1), the arc length (from t_min,
// wrapped) where `x` first crosses `limit` going `up` (or down); interpolated between the
// two samples around the crossing. Throws when it never does.
double crossing(const Geometry& g, const std::vector<double>& x, std::size_t start, int step, double limit,
                bool up) {
  const std::size_t n = x.size();
  std::size_t prev = start;
  for (std::size_t walked = 1; walked < n; ++walked) {
    const std::size_t at = (start + n + static_cast<std::size_t>(step) * walked) % n;
    const bool past = up ? x[at] >= limit : x[at] <= limit;
    if (past) {
      const double f = x[at] != x[prev] ? (limit - x[prev]) / (x[at] - x[prev]) : 0.0;
      double a = g.arc[prev], b = g.arc[at];
      if (step > 0 && b < a) b += g.perimeter;
      if (step < 0 && b > a) b -= g.perimeter;
      double s = a + f * (b - a);
      s = std::fmod(s, g.perimeter);
      return s < 0 ? s + g.perimeter : s;
    }
    prev = at;
  }
  throw Error("compare: the nominal profile has no point beyond its edge zones: check the edge points");
}

// The nominal's curve, once checked closed (before anything is built on it).
const BSpline& checked(const BSpline& curve) {
  if (!curve.closed || curve.control.size() < static_cast<std::size_t>(curve.degree + 1))
    throw Error("compare: the nominal profile is not a closed curve");
  check_spline(curve);
  for (const auto& c : curve.control)
    if (!(c.cwiseAbs().maxCoeff() <= detail::max_coordinate))
      throw Error(
          "compare: the nominal profile has a control point beyond +-1e15 (corrupt or in another unit?)");
  return curve;
}

}  // namespace

Geometry::Geometry(const NominalSection& nominal, double edge_zone)
    : curve(nominal.curve), pc(checked(nominal.curve)), search(curve, pc) {
  const double area = enclosed_area(curve, &centroid);
  orientation = area >= 0 ? 1.0 : -1.0;
  ts = span_samples(curve, 16);
  arc.resize(ts.size());
  Eigen::Vector2d prev = pc.point(ts.front());
  for (std::size_t i = 0; i < ts.size(); ++i) {
    const Eigen::Vector2d p = pc.point(ts[i]);
    arc[i] = i ? arc[i - 1] + (p - prev).norm() : 0.0;
    prev = p;
  }
  perimeter = arc.back() + (pc.point(ts.front()) - prev).norm();
  const Eigen::Vector2d chord = nominal.te_point - nominal.le_point;
  if (!(chord.norm() > 0) || !std::isfinite(chord.norm()))
    throw Error("compare: the nominal's edge points coincide or are not finite");
  std::vector<double> x(ts.size());  // chord fraction of each sample
  for (std::size_t i = 0; i < ts.size(); ++i)
    x[i] = (pc.point(ts[i]) - nominal.le_point).dot(chord) / chord.squaredNorm();
  const std::size_t le = sample_after(ts, closest_point(curve, nominal.le_point).t);
  const std::size_t te = sample_after(ts, closest_point(curve, nominal.te_point).t);
  origin = crossing(*this, x, le, -1, edge_zone, true);
  const double le_end = crossing(*this, x, le, +1, edge_zone, true);
  const double te_begin = crossing(*this, x, te, -1, 1 - edge_zone, false);
  const double te_end = crossing(*this, x, te, +1, 1 - edge_zone, false);
  auto from_origin = [&](double s) {
    const double d = std::fmod(s - origin + 2 * perimeter, perimeter);
    return d;
  };
  ends = {from_origin(le_end), from_origin(te_begin), from_origin(te_end)};
  if (!(0 < ends[0] && ends[0] < ends[1] && ends[1] < ends[2] && ends[2] < perimeter))
    throw Error("compare: the edge zones (" + format_share(edge_zone) +
                " of the chord from each edge point) overlap or leave no side between them");
  a_is_pressure = nominal.pressure_side == -static_cast<int>(orientation);
}

double Geometry::arc_at(double t) const {
  const double t0 = curve.t_min(), period = curve.t_max() - t0;
  double u = std::fmod(t - t0, period);
  if (u < 0) u += period;
  u += t0;
  const auto it = std::upper_bound(ts.begin(), ts.end(), u);
  const std::size_t i = it == ts.begin() ? 0 : static_cast<std::size_t>(it - ts.begin()) - 1;
  const double t1 = i + 1 < ts.size() ? ts[i + 1] : curve.t_max();
  const double s1 = i + 1 < arc.size() ? arc[i + 1] : perimeter;
  const double f = t1 > ts[i] ? (u - ts[i]) / (t1 - ts[i]) : 0.0;
  const double s = arc[i] + f * (s1 - arc[i]);
  return s >= perimeter ? s - perimeter : s;
}

double Geometry::position(double t) const {
  const double d = std::fmod(arc_at(t) - origin + 2 * perimeter, perimeter);
  return d;
}

Zone Geometry::zone_at(double t) const {
  const double s = position(t);
  if (s < ends[0]) return Zone::leading_edge;
  if (s < ends[1]) return a_is_pressure ? Zone::pressure : Zone::suction;
  if (s < ends[2]) return Zone::trailing_edge;
  return a_is_pressure ? Zone::suction : Zone::pressure;
}

std::array<double, 2> Geometry::interval(Zone zone) const {
  switch (zone) {
    case Zone::leading_edge:
      return {0, ends[0]};
    case Zone::trailing_edge:
      return {ends[1], ends[2]};
    case Zone::pressure:
      return a_is_pressure ? std::array<double, 2>{ends[0], ends[1]}
                           : std::array<double, 2>{ends[2], perimeter};
    case Zone::suction:
      return a_is_pressure ? std::array<double, 2>{ends[2], perimeter}
                           : std::array<double, 2>{ends[0], ends[1]};
    default:
      return {0, perimeter};
  }
}

Eigen::Vector2d Geometry::normal_at(double t) const {
  const detail::CurveJet j = pc.jet(t);
  return orientation * Eigen::Vector2d(j.d1.y(), -j.d1.x()).normalized();
}

}  // namespace section::compare

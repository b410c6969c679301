// SPDX-License-Identifier: GPL-3.0-or-later
#include "section/params.h"

#include "detail/axis_curve.h"
#include "detail/camber_line.h"
#include "detail/inscribed.h"
#include "detail/local_origin.h"
#include "detail/piecewise_curve.h"
#include "detail/sampled_profile.h"
#include "section/error.h"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>

namespace section {

using detail::cross;
using detail::degrees;
using detail::left_normal;
using detail::pi;
using detail::wrap_degrees;

namespace {

// Indices of the convex hull of points (counterclockwise, Andrew's monotone chain).
std::vector<int> convex_hull(const std::vector<Eigen::Vector2d>& p) {
  // Sorted with the coordinates beside the index (the same comparisons in the same places,
  // so the same order, ties included, as sorting indices; without a lookup per comparison).
  struct Key {
    double x, y;
    int i;
  };
  std::vector<Key> idx(p.size());
  for (std::size_t i = 0; i < p.size(); ++i) idx[i] = {p[i].x(), p[i].y(), static_cast<int>(i)};
  std::sort(idx.begin(), idx.end(),
            [](const Key& a, const Key& b) { return a.x < b.x || (a.x == b.x && a.y < b.y); });
  std::vector<int> h(2 * p.size());
  std::size_t k = 0;
  for (int pass = 0; pass < 2; ++pass) {
    const std::size_t base = k;
    for (std::size_t n = 0; n < idx.size(); ++n) {
      const int i = pass == 0 ? idx[n].i : idx[idx.size() - 1 - n].i;
      while (k >= base + 2 && cross(p[h[k - 1]] - p[h[k - 2]], p[i] - p[h[k - 2]]) <= 0) --k;
      h[k++] = i;
    }
    --k;  // the last point starts the other chain
  }
  h.resize(k);
  return h;
}

// The two crossings of the exact profile with the line through m along `normal`, found
// from the edge point at parameter t_edge outward along each side (`ahead`: from m toward
// the edge point): for a station so near the edge point (2 um on a 48 mm camber line) that
// m lies outside the sampled polygon, whose chords cut the edge's arc, and the rays from m
// miss it. `left` gets the parameter of the crossing on the side of `normal`, `right` the other's.
bool edge_crossings(const detail::SampledProfile& pr, const Eigen::Vector2d& m, const Eigen::Vector2d& ahead,
                    const Eigen::Vector2d& normal, double t_edge, double& left, double& right) {
  const auto g = [&](double t) { return ahead.dot(pr.fast.point(pr.wrap(t)) - m); };
  if (!(g(t_edge) > 0)) return false;  // m is not short of the edge point
  const double step = pr.period / static_cast<double>(pr.samples.size()) / 8;
  Eigen::Vector2d hit[2];
  double at[2];
  for (int side = 0; side < 2; ++side) {
    const double dir = side == 0 ? 1 : -1;
    double a = t_edge, b = a;
    bool found = false;
    for (int k = 1; k <= 64 && !found; ++k) {  // within 8 samples of the edge point
      b = t_edge + dir * k * step;
      found = !(g(b) > 0);
      if (!found) a = b;
    }
    if (!found) return false;
    for (int it = 0; it < 60; ++it) {  // g(a) > 0 >= g(b)
      const double c = 0.5 * (a + b);
      (g(c) > 0 ? a : b) = c;
    }
    at[side] = pr.wrap(0.5 * (a + b));
    hit[side] = pr.fast.point(at[side]);
  }
  const double h0 = (hit[0] - m).dot(normal), h1 = (hit[1] - m).dot(normal);
  if (!(std::max(h0, h1) >= 0 && std::min(h0, h1) <= 0)) return false;
  left = h0 >= h1 ? at[0] : at[1];
  right = h0 >= h1 ? at[1] : at[0];
  return true;
}

// Profile parameter where the projection onto e is extreme, refined from a sample.
double extreme(const detail::PiecewiseCurve& f, double t, const Eigen::Vector2d& e) {
  for (int it = 0; it < 30; ++it) {
    const detail::CurveJet j = f.jet(t);
    const double g = j.d1.dot(e), dg = j.d2.dot(e);
    if (dg == 0) break;
    const double step = g / dg;
    t -= step;
    if (std::abs(step) < 1e-15 * (1 + std::abs(t))) break;
  }
  return t;
}

// The line touching the profile at ta and tb (a bitangent), by Newton from those
// parameters: its two touching points.
std::pair<Eigen::Vector2d, Eigen::Vector2d> bitangent(const detail::PiecewiseCurve& f, double ta, double tb,
                                                      double period) {
  for (int it = 0; it < 40; ++it) {
    const detail::CurveJet a = f.jet(ta), b = f.jet(tb);
    const Eigen::Vector2d d = b.point - a.point;
    const Eigen::Vector2d g(cross(d, a.d1), cross(d, b.d1));
    Eigen::Matrix2d j;
    j << cross(d, a.d2), cross(b.d1, a.d1), cross(-a.d1, b.d1), cross(d, b.d2);
    const Eigen::Vector2d step = j.fullPivLu().solve(g);
    if (!step.allFinite()) break;
    ta -= step(0);
    tb -= step(1);
    if (step.norm() < 1e-14 * period) break;
  }
  return {f.point(ta), f.point(tb)};
}

}  // namespace

namespace {

// enclosed_area on f, curve's piecewise form.
double area_of(const BSpline& curve, const detail::PiecewiseCurve& f, Eigen::Vector2d* centroid) {
  if (!curve.closed) throw Error("params: the area needs a closed curve");
  // 5-point Gauss-Legendre is exact for the degree-8 integrands of a cubic per span.
  static const double x[5] = {-0.9061798459386640, -0.5384693101056831, 0.0, 0.5384693101056831,
                              0.9061798459386640};
  static const double w[5] = {0.2369268850561891, 0.4786286704993665, 0.5688888888888889, 0.4786286704993665,
                              0.2369268850561891};
  // About a local origin far from 0: x^2 y' at 1e6 keeps few digits of the centroid.
  const Eigen::Vector2d origin = detail::local_origin(curve.control);
  double area = 0, mx = 0, my = 0;
  detail::PiecewiseCurve::Cursor at;              // in order: the span before is tried first
  const int sub = std::max(1, curve.degree / 3);  // higher degrees: split each span
  for (std::size_t k = 0; k + 1 < curve.knots.size(); ++k)
    for (int q = 0; q < sub; ++q) {
      const double a = curve.knots[k] + (curve.knots[k + 1] - curve.knots[k]) * q / sub;
      const double b = curve.knots[k] + (curve.knots[k + 1] - curve.knots[k]) * (q + 1) / sub;
      for (int i = 0; i < 5; ++i) {
        const double t = 0.5 * (a + b) + 0.5 * (b - a) * x[i];
        const detail::CurveJet j = f.jet(f.locate(t, at));
        const Eigen::Vector2d p = j.point - origin;
        const double ww = 0.5 * (b - a) * w[i];
        area += ww * 0.5 * cross(p, j.d1);
        mx += ww * 0.5 * p.x() * p.x() * j.d1.y();
        my -= ww * 0.5 * p.y() * p.y() * j.d1.x();
      }
    }
  if (centroid) *centroid = area != 0 ? Eigen::Vector2d(mx / area, my / area) + origin : origin;
  return area;
}

}  // namespace

double enclosed_area(const BSpline& curve, Eigen::Vector2d* centroid) {
  check_spline(curve);
  const double area = area_of(curve, detail::PiecewiseCurve(curve), centroid);
  if (!std::isfinite(area))
    throw Error("params: the enclosed area overflows (the curve's coordinates are too large)");
  return area;
}

namespace {

// The caliper laid against the pressure side of `profile` (SectionParams::caliper_*):
// the convex-hull edge bridging the pressure side is the line a caliper touches at both
// ends, refined to the exact bitangent; the chord is the profile's extent along it.
void caliper(const detail::PiecewiseCurve& f, const CamberResult& camber, SectionParams& out) {
  const int n = 2000;
  const double t0 = f.t_min(), period = f.t_max() - t0;
  std::vector<Eigen::Vector2d> s(n);
  detail::PiecewiseCurve::Cursor at;  // in order: the span before is tried first
  for (int i = 0; i < n; ++i) s[i] = f.point(f.locate(t0 + period * i / n, at));
  auto index_of = [&](double t) {
    double r = std::fmod(t - t0, period);
    if (r < 0) r += period;
    return static_cast<int>(std::lround(r / period * n)) % n;
  };
  const bool forward_le_te = detail::pressure_runs_forward(camber);
  const int ile = index_of(camber.le.t), ite = index_of(camber.te.t);
  const int from = forward_le_te ? ile : ite, to = forward_le_te ? ite : ile;
  const int span = ((to - from) % n + n) % n;
  const int mid = (from + span / 2) % n;
  // The hull vertices on either side of mid, cyclically (mid not one of them).
  std::vector<char> on_hull(n, 0);
  for (int i : convex_hull(s)) on_hull[i] = 1;
  int ha = -1, hb = -1;
  if (!on_hull[mid]) {
    for (int k = 1; k < n && hb < 0; ++k)
      if (on_hull[(mid + k) % n]) hb = (mid + k) % n;
    for (int k = 1; k < n && ha < 0; ++k)
      if (on_hull[(mid - k + n) % n]) ha = (mid - k + n) % n;
  }
  Eigen::Vector2d e = (out.te_point - out.le_point).normalized();
  if (ha >= 0 && ha != hb) {
    const std::pair<Eigen::Vector2d, Eigen::Vector2d> ab =
        bitangent(f, t0 + period * ha / n, t0 + period * hb / n, period);
    if ((ab.second - ab.first).norm() > 0) {
      e = (ab.second - ab.first).normalized();
      out.caliper_found = true;
      out.caliper_le = ab.first;
      out.caliper_te = ab.second;
    }
  }
  if (e.dot(out.te_point - out.le_point) < 0) {
    e = -e;
    std::swap(out.caliper_le, out.caliper_te);
  }
  if (!out.caliper_found) {
    out.caliper_le = out.le_point;
    out.caliper_te = out.te_point;
  }
  int imax = 0, imin = 0;
  for (int i = 0; i < n; ++i) {
    if (s[i].dot(e) > s[imax].dot(e)) imax = i;
    if (s[i].dot(e) < s[imin].dot(e)) imin = i;
  }
  const double hi = f.point(extreme(f, t0 + period * imax / n, e)).dot(e);
  const double lo = f.point(extreme(f, t0 + period * imin / n, e)).dot(e);
  out.caliper_chord = std::max(hi, s[imax].dot(e)) - std::min(lo, s[imin].dot(e));
  out.caliper_stagger = degrees(e);
}

}  // namespace

namespace {

// The profile and camber line a caller hands in: a default BSpline or CamberResult (not from
// camber_line) crashed the functions below.
void check_inputs(const BSpline& profile, const CamberResult& camber) {
  check_spline(profile);
  if (camber.medial.circles.size() < 2 || !(camber.length > 0) || camber.medial.curve.control.empty())
    throw Error("params: the camber line is empty (a CamberResult from camber_line is needed)");
}

}  // namespace

SectionParams section_params(const BSpline& profile, const CamberResult& camber) {
  check_inputs(profile, camber);
  return detail::section_params(profile, detail::PiecewiseCurve(profile), camber);
}

SectionParams detail::section_params(const BSpline& profile, const PiecewiseCurve& f,
                                     const CamberResult& camber) {
  SectionParams out;
  out.le_point = camber.le.point;
  out.te_point = camber.te.point;
  out.chord = (out.te_point - out.le_point).norm();
  out.camber_length = camber.length;
  out.max_thickness = 2 * camber.thickest.radius;
  out.max_thickness_pos = camber.length > 0 ? camber.thickest_s / camber.length : 0;
  out.le_radius = camber.le.radius;
  out.te_radius = camber.te.radius;
  out.le_curvature_radius = camber.le.curvature_radius;
  out.te_curvature_radius = camber.te.curvature_radius;
  out.stagger = degrees(out.te_point - out.le_point);
  out.inlet_angle = degrees(camber.le_tangent);
  out.outlet_angle = degrees(camber.te_tangent);
  out.camber_angle = wrap_degrees(out.inlet_angle - out.outlet_angle);
  out.area = std::abs(area_of(profile, f, &out.centroid));
  caliper(f, camber, out);
  return out;
}

std::vector<ThicknessStation> thickness_stations(const BSpline& profile, const CamberResult& camber,
                                                 const std::vector<double>& fractions) {
  check_inputs(profile, camber);
  const detail::AxisCurve ax(camber.medial.curve);
  const detail::ArcLengthTable table(ax.f, 4 * static_cast<int>(camber.medial.circles.size()));
  return detail::thickness_stations(detail::SampledProfile(profile, detail::thickness_samples), {ax, table},
                                    camber, fractions);
}

std::vector<ThicknessStation> detail::thickness_stations(const SampledProfile& pr, const CamberAxis& axis,
                                                         const CamberResult& camber,
                                                         const std::vector<double>& fractions) {
  const detail::AxisCurve& ax = axis.ax;
  const detail::ArcLengthTable& table = axis.table;
  const auto& circles = camber.medial.circles;
  std::vector<ThicknessStation> out;
  for (double f : fractions) {
    if (!(f >= 0 && f <= 1))
      throw Error("params: thickness station " + std::to_string(f) + " is outside [0, 1]");
    ThicknessStation st;
    st.fraction = f;
    st.s = f * camber.length;
    if (f == 0 || f == 1) {  // the edge point itself: no width across it
      st.point = st.pressure = st.suction = f == 0 ? camber.le.point : camber.te.point;
      st.pressure_t = st.suction_t = f == 0 ? camber.le.t : camber.te.t;
      out.push_back(st);
      continue;
    }
    InscribedCircle c;
    bool solved = false;
    if (st.s > camber.ext_le && st.s < camber.length - camber.ext_te) {
      const detail::AxisSample a = detail::axis_sample(ax, table, camber.ext_le, st.s);
      // Guess from the nearest medial circle (the fitted edge centres carry no contacts).
      std::size_t g = 0;
      double best = std::numeric_limits<double>::infinity();
      for (std::size_t k = 0; k < circles.size(); ++k)
        if (circles[k].t_left != circles[k].t_right && (circles[k].center - a.point).norm() < best)
          best = (circles[k].center - a.point).norm(), g = k;
      solved = detail::snap_to_axis(pr, a.point, a.normal, circles[g], c);
      if (!solved) c.center = a.point;
    } else {
      c.center = detail::extension_point(camber, st.s);
    }
    if (solved) {
      st.thickness = 2 * c.radius;
    } else {
      // On an extension (or where no circle fits): the width across the camber normal.
      const bool at_le = st.s <= camber.ext_le;
      const Eigen::Vector2d d = at_le ? camber.le_tangent : camber.te_tangent;
      double& tl = c.t_left;
      double& tr = c.t_right;
      if (!(detail::ray_hit(pr, c.center, left_normal(d), tl) &&
            detail::ray_hit(pr, c.center, -left_normal(d), tr)) &&
          !edge_crossings(pr, c.center, at_le ? Eigen::Vector2d(-d) : d, left_normal(d),
                          at_le ? camber.le.t : camber.te.t, tl, tr)) {
        char text[200];
        std::snprintf(text, sizeof text,
                      "params: the camber normal at station %.9g misses the profile (%.3g from the %s edge "
                      "point)",
                      f, at_le ? st.s : camber.length - st.s, at_le ? "leading" : "trailing");
        throw Error(text);
      }
      c.left = pr.fast.point(tl);
      c.right = pr.fast.point(tr);
      st.thickness = (c.left - c.right).norm();
    }
    st.point = c.center;
    const bool left_pressure = camber.pressure_side > 0;
    st.pressure = left_pressure ? c.left : c.right;
    st.suction = left_pressure ? c.right : c.left;
    st.pressure_t = left_pressure ? c.t_left : c.t_right;
    st.suction_t = left_pressure ? c.t_right : c.t_left;
    out.push_back(st);
  }
  return out;
}

Sides split_sides(const BSpline& profile, const CamberResult& camber, int count) {
  check_inputs(profile, camber);
  return detail::split_sides(detail::PiecewiseCurve(profile), camber, count);
}

Sides detail::split_sides(const PiecewiseCurve& f, const CamberResult& camber, int count) {
  if (count < 2 || count > 10000000)
    throw Error("params: " + std::to_string(count) + " samples a side, not in 2..10000000");
  const double le = camber.le.t, te = camber.te.t;
  // Forward from LE reaches TE along one side, backward along the other; both sampled
  // from LE to TE.
  std::vector<Eigen::Vector2d> fwd, bwd;
  const double lf = f.forward(le, te), lb = f.forward(te, le);
  for (int i = 0; i < count; ++i) {
    fwd.push_back(f.point(le + lf * i / (count - 1)));
    bwd.push_back(f.point(le - lb * i / (count - 1)));
  }
  const bool forward_is_pressure = pressure_runs_forward(camber);
  Sides sides;
  sides.pressure = forward_is_pressure ? fwd : bwd;
  sides.suction = forward_is_pressure ? bwd : fwd;
  return sides;
}

}  // namespace section

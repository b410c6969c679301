// SPDX-License-Identifier: GPL-3.0-or-later
#include "section/edge.h"

#include "detail/edge_fit.h"
#include "detail/flanks.h"
#include "detail/sampled_profile.h"
#include "section/camber.h"
#include "section/error.h"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <limits>
#include <tuple>
#include <utility>

namespace section {

using detail::cross;
using detail::Face;
using detail::pi;
using detail::SampledProfile;

namespace {

// Bisects [a, b] (30 steps) for where `past` turns true: false at a, true at b.
template <class Past>
void bisect(double& a, double& b, Past&& past) {
  for (int it = 0; it < 30; ++it) {
    const double mid = 0.5 * (a + b);
    (past(mid) ? b : a) = mid;
  }
}

// Walks from t in steps of h (direction +1 or -1) for at most half a period until `past`
// holds, then bisects: {the last parameter before, the first past}. `found` is false when
// the walk ran out (both are then where it stopped).
template <class Past>
std::pair<double, double> walk_until(const SampledProfile& pr, double t, int direction, double h, Past&& past,
                                     bool& found) {
  double a = t, b = t;
  found = false;
  for (double walked = 0; walked < 0.5 * pr.period; walked += h) {
    b = a + direction * h;
    if (past(b)) {
      found = true;
      break;
    }
    a = b;
  }
  if (!found) return {a, a};
  bisect(a, b, past);
  return {a, b};
}

// |atan2(y, x)| (y = cross(d, q), x = d.dot(q): the angle between d and q) where it lies
// within about 1e-9 of `limit`, else a stand-in on the same side of the limit, 0 below and
// pi above: walks compare it with the limit, and the arctangent was their costliest step.
// The side is told by sin(angle - limit), of the sign of cos(limit) |y| - sin(limit) x,
// with a margin of a million times its rounding (and the arctangent's).
class AngleNear {
public:
  explicit AngleNear(double limit)
      : cos_(std::cos(limit)), sin_(std::sin(limit)), told_(limit > 0 && limit < pi) {}
  double operator()(double y, double x) const {
    const double side = cos_ * std::abs(y) - sin_ * x, margin = 1e-9 * (std::abs(x) + std::abs(y));
    if (told_ && side < -margin) return 0;
    if (told_ && side > margin) return pi;
    return std::abs(std::atan2(y, x));  // near the limit, or NaN
  }

private:
  double cos_, sin_;
  bool told_;  // a limit in (0, pi): the stand-ins compare as the angle
};

// Parameter where the outward normal has turned by `angle` (radians) from direction d,
// walking from t_tip in `direction` (+1 forward, -1 backward); stops after half a period.
double arc_end(const SampledProfile& pr, double t_tip, const Eigen::Vector2d& d, double angle, int direction,
               const Eigen::Vector2d& center, double reach) {
  // Past the angle, or leaving the end circle's neighbourhood (a flank facing the same
  // way as the edge, as on a highly staggered blade): the value is > angle.
  const AngleNear near(angle);
  auto turn = [&](double t) {
    const Eigen::Vector2d nn = pr.outward(t);
    if ((pr.fast.point(t) - center).norm() > reach) return 4.0;
    return near(cross(d, nn), d.dot(nn));
  };
  const double h = pr.period / static_cast<double>(pr.samples.size());
  bool found = false;
  const auto [a, b] = walk_until(
      pr, t_tip, direction, h, [&](double t) { return turn(t) >= angle; }, found);
  return found ? 0.5 * (a + b) : a;
}

struct CircleFit {
  Eigen::Vector2d center{0, 0};
  double radius = 0, rms = 0;
  double radius_sigma = 0;  // standard error of the radius, from the fit's covariance and rms
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();  // of (centre, radius), the same scale
};

// The sum of the outer products row row^T of rows (u, v, w): the lower triangle summed and
// mirrored, the same sums as the full products in two thirds of the work (the circle
// fits' normal equations).
struct OuterSum {
  double uu = 0, vu = 0, vv = 0, wu = 0, wv = 0, ww = 0;
  void add(const Eigen::Vector3d& r) {
    uu += r.x() * r.x();
    vu += r.y() * r.x();
    vv += r.y() * r.y();
    wu += r.z() * r.x();
    wv += r.z() * r.y();
    ww += r.z() * r.z();
  }
  Eigen::Matrix3d matrix() const {
    Eigen::Matrix3d m;
    m << uu, vu, wu, vu, vv, wv, wu, wv, ww;
    return m;
  }
};

// Rms distance of the points from the circle.
double rms_about(const std::vector<Eigen::Vector2d>& p, const Eigen::Vector2d& center, double radius) {
  double sum = 0;
  for (const auto& q : p) sum += std::pow((q - center).norm() - radius, 2);
  return p.empty() ? 0.0 : std::sqrt(sum / p.size());
}

// The inverse of the Gauss-Newton normal matrix of a fitted circle's centre and radius:
// their covariance per unit of the residuals' variance.
Eigen::Matrix3d circle_covariance(const std::vector<Eigen::Vector2d>& p, const CircleFit& fit) {
  const int n = static_cast<int>(p.size());
  OuterSum jtj;
  for (const auto& q : p) {
    const Eigen::Vector2d r = q - fit.center;
    const double dist = r.norm();
    if (!(dist > 0)) continue;
    jtj.add(Eigen::Vector3d(-r.x() / dist, -r.y() / dist, -1));
  }
  return jtj.matrix().inverse();
}

// Geometric least-squares circle (Gauss-Newton from the algebraic fit). Normal equations
// (3 x 3) on centred points: well conditioned, and this runs tens of times per edge.
CircleFit fit_circle(const std::vector<Eigen::Vector2d>& p) {
  const int n = static_cast<int>(p.size());
  Eigen::Vector2d mean = Eigen::Vector2d::Zero();
  for (const auto& q : p) mean += q;
  mean /= n;
  OuterSum ata;
  Eigen::Vector3d atb = Eigen::Vector3d::Zero();
  for (int i = 0; i < n; ++i) {
    const Eigen::Vector2d q = p[i] - mean;
    const Eigen::Vector3d row(q.x(), q.y(), 1);
    ata.add(row);
    atb += row * -q.squaredNorm();
  }
  const Eigen::Vector3d s = ata.matrix().ldlt().solve(atb);
  Eigen::Vector3d x(-0.5 * s(0), -0.5 * s(1), 0);
  x(2) = std::sqrt(std::max(x.head<2>().squaredNorm() - s(2), 0.0));
  for (int it = 0; it < 30; ++it) {
    OuterSum jtj;
    Eigen::Vector3d jte = Eigen::Vector3d::Zero();
    for (int i = 0; i < n; ++i) {
      const Eigen::Vector2d q = p[i] - mean - x.head<2>();
      const double dist = q.norm();
      if (!(dist > 0)) continue;
      const Eigen::Vector3d row(-q.x() / dist, -q.y() / dist, -1);
      jtj.add(row);
      jte += row * (dist - x(2));
    }
    const Eigen::Vector3d dx = -jtj.matrix().ldlt().solve(jte);
    if (!dx.allFinite()) break;
    x += dx;
    if (dx.norm() < 1e-13 * std::max(1.0, x(2))) break;
  }
  CircleFit fit;
  fit.center = mean + x.head<2>();
  fit.radius = std::abs(x(2));
  fit.rms = rms_about(p, fit.center, fit.radius);
  if (n > 3) {
    const Eigen::Matrix3d inverse = circle_covariance(p, fit);
    // (In the order of operations the radius's standard error always had: its last bits.)
    fit.radius_sigma = std::sqrt(std::max(inverse(2, 2), 0.0) * fit.rms * fit.rms * n / (n - 3));
    fit.covariance = inverse * (fit.rms * fit.rms * n / (n - 3));
  }
  return fit;
}

// Arc of the profile around t_tip (walking both ways) seen from `c` within `half` radians of
// direction d: the core of an edge, chosen by position (normals are the noisiest part of
// a fitted profile).
std::pair<double, double> angular_arc(const SampledProfile& pr, double t_tip, const Eigen::Vector2d& c,
                                      const Eigen::Vector2d& d, double half) {
  const AngleNear near(half);
  detail::PiecewiseCurve::Cursor at;  // the walk's steps: the span before is tried first
  auto past = [&](double t) {
    const Eigen::Vector2d q = pr.fast.point(pr.fast.locate(t, at)) - c;
    return near(cross(d, q), d.dot(q)) > half;
  };
  const double h = pr.period / (2.0 * pr.samples.size());  // then bisected
  bool found = false;
  const double start = walk_until(pr, t_tip, -1, h, past, found).first;
  return {start, walk_until(pr, t_tip, 1, h, past, found).first};
}

std::vector<Eigen::Vector2d> arc_points(const SampledProfile& pr, double t0, double t1, int count = 121) {
  return pr.fast.points(t0, t1, count);
}

// The core circle of an edge: fitted to the profile within +-edge_core of d seen from the
// medial end centre c0, then once more seen from the fitted centre (the medial end may sit
// off the edge centre). A first fit that fails or is far too large falls back to c0, r0.
std::pair<double, double> core_arc(const SampledProfile& pr, double t_tip, const Eigen::Vector2d& d,
                                   const Eigen::Vector2d& c0, double r0, const CamberOptions& options,
                                   CircleFit& fit) {
  const double core = options.edge_core * pi / 180;
  std::pair<double, double> range = angular_arc(pr, t_tip, c0, d, core);
  fit = fit_circle(arc_points(pr, range.first, range.second));
  if (!(fit.radius > 0) || !std::isfinite(fit.radius) || fit.radius > 50 * std::max(r0, 1e-9 * pr.scale)) {
    fit.center = c0, fit.radius = r0;
  }
  range = angular_arc(pr, t_tip, fit.center, d, core);
  fit = fit_circle(arc_points(pr, range.first, range.second));
  return range;
}

// The walk of grown_arc from t_tip in `dir` about the circle `current`: the last point
// within tau outside it before the profile leaves it for good (far outside, or past `cap`
// radians from `mid_dir`; a noise bump inside the arc does not stop it), less the flank
// overshoot sqrt(2 R tau), never inside the core's end `keep`.
double grown_end(const SampledProfile& pr, double t_tip, int dir, double h, const CircleFit& current,
                 const Eigen::Vector2d& mid_dir, double tau, double cap, double keep) {
  detail::PiecewiseCurve::Cursor at;  // the walk's steps: the span before is tried first
  auto residual = [&](double t) {
    return (pr.fast.point(pr.fast.locate(t, at)) - current.center).norm() - current.radius;
  };
  const AngleNear near(cap);
  double a = t_tip, last_in = t_tip;
  for (double walked = 0; walked < 0.5 * pr.period; walked += h) {
    const double b = a + dir * h;
    const Eigen::Vector2d q = pr.fast.point(pr.fast.locate(b, at)) - current.center;
    const double res = q.norm() - current.radius;
    if (res > std::max(20 * tau, 0.2 * current.radius) || near(cross(mid_dir, q), mid_dir.dot(q)) > cap)
      break;
    if (res <= tau) last_in = b;
    a = b;
  }
  // Refine the crossing between last_in and the next step.
  double lo = last_in, hi = last_in + dir * h;
  if (residual(hi) > tau) bisect(lo, hi, [&](double t) { return residual(t) > tau; });
  a = lo;
  // Arc length converted with the local speed.
  const double trim = std::sqrt(2 * current.radius * tau) / std::max(pr.fast.jet(a).d1.norm(), 1e-300);
  return dir > 0 ? std::max(a - trim, std::min(keep, a)) : std::min(a + trim, std::max(keep, a));
}

// The edge arc grown geometrically (docs/CAMBER.md, step 4): from the core circle, each
// end walks outward while the profile stays within tau outside the fitted circle, tau =
// edge_residual x the core fit's rms, at least edge_noise_residual x the points' noise and
// 1e-6 of the profile size; circle, arc and trim iterated. Returns the arc's range.
std::pair<double, double> grown_arc(const SampledProfile& pr, double t_tip, const Eigen::Vector2d& d,
                                    const Eigen::Vector2d& c0, double r0, const CamberOptions& options,
                                    CircleFit& fit) {
  std::pair<double, double> range = core_arc(pr, t_tip, d, c0, r0, options, fit);
  // The noise floor keeps the arc from shrinking pass by pass onto a few quiet degrees.
  const double tau = std::max({options.edge_residual * fit.rms,
                               options.edge_noise_residual * options.profile_noise, 1e-6 * pr.scale});
  const double h = pr.period / (2.0 * pr.samples.size());  // then bisected
  const double cap = options.edge_max_arc * 0.5 * pi / 180;
  const std::pair<double, double> core_range = range;
  // Start from a half circle about the core circle: a circle fitted to the core alone can
  // be far off (a short noisy arc); from a longer arc the iteration shrinks onto the edge.
  {
    const std::pair<double, double> wide = angular_arc(pr, t_tip, fit.center, d, 0.5 * pi);
    const CircleFit w = fit_circle(arc_points(pr, wide.first, wide.second));
    if (w.radius > 0 && std::isfinite(w.radius)) fit = w, range = wide;
  }
  for (int pass = 0; pass < 4; ++pass) {
    const CircleFit current = fit;
    // The guard angle is measured from the middle of the current arc (the end tangent may
    // be skewed on a noisy profile).
    const Eigen::Vector2d mid_dir =
        (pr.fast.point(0.5 * (range.first + range.second)) - current.center).normalized();
    const double e0 = grown_end(pr, t_tip, -1, h, current, mid_dir, tau, cap, core_range.first);
    const double e1 = grown_end(pr, t_tip, 1, h, current, mid_dir, tau, cap, core_range.second);
    const CircleFit next = fit_circle(arc_points(pr, e0, e1));
    if (!(next.radius > 0) || !std::isfinite(next.radius)) break;
    fit = next;
    range = {e0, e1};
    if ((next.center - current.center).norm() < 1e-9 * pr.scale) break;
  }
  return range;
}

// The edge's circle refitted to the measured points on its arc (docs/CAMBER.md, step 4):
// points within the arc's angles seen from the circle's centre and within a band about
// it, twice, re-centred. True when the refit stands (`fit` replaced): the points cover the
// arc without a large angular gap and fix the radius well, and the circle moved little.
bool refit_on_measured(const SampledProfile& pr, const Edge& e, const Eigen::Vector2d& d,
                       const std::vector<Eigen::Vector2d>& measured, const CamberOptions& options,
                       CircleFit& fit, double& points_sigma) {
  if (measured.size() < 8 || !(fit.radius > 0)) return false;
  auto signed_angle = [&](const Eigen::Vector2d& c, const Eigen::Vector2d& q) {
    const Eigen::Vector2d r = q - c;
    return std::atan2(cross(d, r), d.dot(r));
  };
  CircleFit current = fit;
  for (int pass = 0; pass < 2; ++pass) {
    const double a0 = signed_angle(current.center, pr.fast.point(e.arc_t0)),
                 a1 = signed_angle(current.center, pr.fast.point(e.arc_t1));
    const double lo = std::min(a0, a1), hi = std::max(a0, a1);
    const double band = std::max({0.25 * current.radius, 6 * options.profile_noise, 3 * current.rms});
    std::vector<Eigen::Vector2d> on_arc;
    std::vector<double> angles;
    for (const auto& q : measured) {
      const double dist = (q - current.center).norm();
      if (std::abs(dist - current.radius) > band) continue;
      const double a = signed_angle(current.center, q);
      if (a < lo || a > hi) continue;
      on_arc.push_back(q);
      angles.push_back(a);
    }
    if (on_arc.size() < 8) return false;
    std::sort(angles.begin(), angles.end());
    double gap = std::max(angles.front() - lo, hi - angles.back());
    for (std::size_t i = 1; i < angles.size(); ++i) gap = std::max(gap, angles[i] - angles[i - 1]);
    // Fitted before any refusal: its standard error is the radius's spread, taken or not (a
    // gap left it unknown, and a TE 14 % off unflagged).
    const CircleFit next = fit_circle(on_arc);
    if (std::isfinite(next.radius_sigma)) points_sigma = next.radius_sigma;
    if (gap > options.edge_point_gap * (hi - lo)) return false;
    if (!(next.radius > 0) || !std::isfinite(next.radius) ||
        !(next.radius_sigma <= options.edge_point_sigma * next.radius) ||
        std::abs(next.radius - fit.radius) > 0.2 * fit.radius ||
        (next.center - fit.center).norm() > 0.2 * fit.radius)
      return false;
    current = next;
  }
  fit = current;
  return true;
}

// Edge point, arc and fitted circle for the axis end `end_circle` pointing outward along d.
Edge measure_edge(const SampledProfile& pr, const InscribedCircle& end_circle, const Eigen::Vector2d& d,
                  const CamberOptions& options, const std::vector<Eigen::Vector2d>& measured) {
  const Eigen::Vector2d& end = end_circle.center;
  Edge e;
  if (!detail::ray_hit(pr, end, d, e.t))
    throw Error("camber: the camber line's end tangent does not meet the profile");
  e.point = pr.fast.point(e.t);
  CircleFit fit;
  if (options.edge_arc > 0) {
    // Fixed arc: the profile around the edge point whose outward normal turns at most
    // edge_arc / 2 either way.
    const double half = 0.5 * options.edge_arc * pi / 180;
    const double reach = 1.5 * std::max(end_circle.radius, (e.point - end).norm());
    e.arc_t0 = arc_end(pr, e.t, d, half, -1, end, reach);
    e.arc_t1 = arc_end(pr, e.t, d, half, +1, end, reach);
    fit = fit_circle(arc_points(pr, e.arc_t0, e.arc_t1, 61));
  } else {
    std::tie(e.arc_t0, e.arc_t1) =
        grown_arc(pr, e.t, d, end, std::max(end_circle.radius, (e.point - end).norm()), options, fit);
  }
  // The fit rms stays the spline arc's about the circle (the circularity test's measure).
  if (options.edge_on_points && refit_on_measured(pr, e, d, measured, options, fit, e.points_sigma)) {
    e.radius_sigma = fit.radius_sigma;  // the measured points' own (before rms is the spline's)
    const Eigen::Vector3d g(d.x(), d.y(), 1);
    e.point_sigma = std::sqrt(std::max(g.dot(fit.covariance * g), 0.0));
    fit.rms = rms_about(arc_points(pr, e.arc_t0, e.arc_t1), fit.center, fit.radius);
    e.on_points = true;
  }
  // Arc: the angle the edge arc subtends at the fitted centre.
  const Eigen::Vector2d q0 = pr.fast.point(e.arc_t0) - fit.center, q1 = pr.fast.point(e.arc_t1) - fit.center;
  e.arc = (std::abs(std::atan2(cross(d, q0), d.dot(q0))) + std::abs(std::atan2(cross(d, q1), d.dot(q1)))) *
          180 / pi;
  e.center = fit.center;
  e.radius = fit.radius;
  e.fit_rms = fit.rms;
  const double k = pr.convexity(e.t);
  e.curvature_radius = k > 0 ? 1 / k : 0;  // 0: the edge point is flat or concave
  return e;
}

// The vertex of a sharp edge from its flanks: the measured points' (d: the outward end
// direction), else the fitted curve's (detail::flank_meeting, farther from the tip when its
// rounding reaches past the window's start). The tip itself when the flanks do not meet,
// or meet nearer to it than twice the lines' and parabolas' meetings lie apart, unless the
// measured points' flanks are parabolas (their curvature over the noise): exact points
// dense at the vertex give the curve's tip as well as the flanks (NACA 4412's TE from 150
// points a side: the tip 1 um off, the curve's flanks 7 um, their models 23 um apart; rows
// 0.2 mm apart: the tip 28-96 um short, the models 5-8 um apart; NACA 0012 every 0.2 mm:
// the tip 33-73 um short, the measured flanks' parabolas 1.5-5.6 um, the lines 30 um).
Eigen::Vector2d vertex_from_flanks(const SampledProfile& pr, const Eigen::Vector2d& tip,
                                   const Eigen::Vector2d& d, double noise,
                                   const std::vector<Eigen::Vector2d>& measured) {
  double near = 0.01 * pr.scale, far = 0.04 * pr.scale;
  const detail::FlankVertex m =
      detail::measured_flank_meeting(measured, tip, -d, 0.005 * pr.scale, far, noise);
  if (m.found) return m.parabolas || (m.point - tip).norm() > 2 * m.models_apart ? m.point : tip;
  for (int round = 0; round < 2; ++round) {
    const detail::FlankVertex v = detail::flank_meeting(pr, tip, near, far, noise);
    if (!v.found) break;
    const double gap = (v.point - tip).norm();
    if (gap <= 2 * v.models_apart) break;
    if (gap < 0.5 * near) return v.point;
    if (round == 1 && gap < near) return v.point;
    far = 2 * gap + (far - near);
    near = 2 * gap;
  }
  return tip;
}

// The vertex of a sharp edge: the profile point farthest along d near the end circle
// `end` (the medial branch runs into the vertex, its last circle shrinking to the spline's
// rounding of the corner), refined to where the tangent is square to d.
Edge sharp_vertex(const SampledProfile& pr, const InscribedCircle& end, const Eigen::Vector2d& d,
                  double noise, const std::vector<Eigen::Vector2d>& measured) {
  const int n = static_cast<int>(pr.samples.size());
  const int near = pr.nearest(end.center);
  const double reach = std::max(20 * end.radius, 2 * pr.period / n * pr.fast.jet(pr.ts[near]).d1.norm());
  int best = near;
  for (int dir : {-1, 1})
    for (int k = 1; k < n / 4; ++k) {
      const int i = ((near + dir * k) % n + n) % n;
      if ((pr.samples[i] - end.center).norm() > reach) break;
      if (pr.samples[i].dot(d) > pr.samples[best].dot(d)) best = i;
    }
  double t = pr.ts[best];
  const double h = pr.period / n;
  for (int it = 0; it < 30; ++it) {
    const detail::CurveJet j = pr.fast.jet(t);
    const double g = j.d1.dot(d), dg = j.d2.dot(d);
    if (!(dg < 0)) break;  // past a maximum along d: keep the sample's
    const double step = std::clamp(g / dg, -h, h);
    t -= step;
    if (std::abs(step) < 1e-15 * pr.period) break;
  }
  Edge e;
  e.t = pr.wrap(t);
  e.point = pr.fast.point(e.t);
  if (e.point.dot(d) < pr.samples[best].dot(d)) e.t = pr.ts[best], e.point = pr.samples[best];
  const double k = pr.convexity(e.t);
  e.curvature_radius = k > 0 ? 1 / k : 0;
  // The flanks' meeting, unless the measured points resolve the profile's turn at the tip
  // (a small round edge taken as sharp: camber's le_sharp / te_sharp note): over a radius
  // above 4 times the noise, 5 or more points within twice it.
  int resolving = 0;
  if (e.curvature_radius > 4 * noise)
    for (const auto& q : measured) resolving += (q - e.point).norm() <= 2 * e.curvature_radius;
  if (resolving < 5) e.point = vertex_from_flanks(pr, e.point, d, noise, measured);
  e.center = e.point;
  e.arc_t0 = e.arc_t1 = e.t;
  e.shape = EdgeShape::sharp;
  e.vertex = true;
  return e;
}

// The angles, seen from the edge's centre, of the measured points on its arc (within a
// quarter radius of its circle, between its ends' angles), ascending.
std::vector<double> arc_angles(const SampledProfile& pr, const Edge& e,
                               const std::vector<Eigen::Vector2d>& measured) {
  const Eigen::Vector2d d = (e.point - e.center).normalized();
  auto angle = [&](const Eigen::Vector2d& q) {
    const Eigen::Vector2d r = q - e.center;
    return std::atan2(cross(d, r), d.dot(r));
  };
  const double a0 = angle(pr.fast.point(e.arc_t0)), a1 = angle(pr.fast.point(e.arc_t1));
  const double lo = std::min(a0, a1), hi = std::max(a0, a1);
  std::vector<double> angles;
  for (const auto& q : measured) {
    if (std::abs((q - e.center).norm() - e.radius) > 0.25 * e.radius) continue;
    const double a = angle(q);
    if (a >= lo && a <= hi) angles.push_back(a);
  }
  std::sort(angles.begin(), angles.end());
  return angles;
}

// The misfit a fit through sparse exact points leaves about an edge circle: an eighth of
// the sagitta h^2 / (8 R) of the widest gap h between the measured points on the arc
// (`angles`: arc_angles). A smooth fit through
// points on a circle leaves it by far less than the chords do: on exact grids 0.1-0.2 of
// that sagitta, where the non-circular edges of real CFD sections (parablade's Aachen and
// impulse blades) leave their circles by 0.4-1.3 of it. 0 when fewer than 8 points lie on
// the arc or a gap exceeds the radius: such points cannot tell a circle from other curves.
double arc_sagitta(const Edge& e, const std::vector<double>& angles) {
  if (angles.size() < 8) return 0;
  double gap = 0;
  for (std::size_t i = 1; i < angles.size(); ++i) gap = std::max(gap, angles[i] - angles[i - 1]);
  const double h = 2 * e.radius * std::sin(0.5 * gap);
  return h <= e.radius ? h * h / (8 * e.radius) / 8 : 0.0;
}

// The radius's standard error per unit of noise of a circle fitted on points at `angles`
// about its centre: the (R, R) entry of the inverse normal matrix of the linearised fit,
// each point's residual moving with the centre along (cos a, sin a) and with the radius.
double arc_spread(const std::vector<double>& angles) {
  if (angles.size() < 3) return std::numeric_limits<double>::infinity();
  Eigen::Matrix3d m = Eigen::Matrix3d::Zero();
  for (const double a : angles) {
    const Eigen::Vector3d row(std::cos(a), std::sin(a), 1);
    m += row * row.transpose();
  }
  const Eigen::FullPivLU<Eigen::Matrix3d> lu(m);
  if (!lu.isInvertible()) return std::numeric_limits<double>::infinity();
  const double rr = lu.inverse()(2, 2);
  return rr > 0 && std::isfinite(rr) ? std::sqrt(rr) : std::numeric_limits<double>::infinity();
}

void classify_edge(Edge& e, double max_diameter, const CamberOptions& options) {
  if (e.radius < options.sharp_ratio * max_diameter)
    e.shape = EdgeShape::sharp;
  else if ((e.curvature_radius == 0 || e.curvature_radius > options.blunt_flatness * e.radius) &&
           e.fit_rms > options.blunt_rms * e.radius)
    e.shape = EdgeShape::blunt;
  else
    e.shape = EdgeShape::round;
}

}  // namespace

namespace detail {

Edge detect_edge(const SampledProfile& pr, const InscribedCircle& end, const Eigen::Vector2d& d,
                 const Face& face, double max_diameter, const CamberOptions& options,
                 const std::vector<Eigen::Vector2d>& measured) {
  // The medial branch runs into a vertex: a sharp (closed) edge, no circle to fit.
  if (!face.found && end.radius < options.sharp_ratio * max_diameter)
    return sharp_vertex(pr, end, d, options.profile_noise, measured);
  Edge e;
  try {
    e = measure_edge(pr, end, d, options, measured);
  } catch (const Error&) {
    if (!face.found) throw;
    e.point = face.mid;
    e.t = pr.ts[pr.nearest(face.mid)];
  }
  classify_edge(e, max_diameter, options);
  if (e.radius > 0) {
    const std::vector<double> angles = arc_angles(pr, e, measured);
    if (!measured.empty()) {
      e.arc_points = static_cast<int>(angles.size());
      e.arc_spread = arc_spread(angles);
    }
    e.sampling = arc_sagitta(e, angles);
  }
  if (options.profile_noise > 0 && e.radius > 0)
    e.circular = e.fit_rms <=
                 options.edge_circularity * std::max({options.profile_noise, 1e-4 * e.radius, e.sampling});
  if (face.found) {  // a face, not a circle: no radius, whatever the edge model
    e.shape = EdgeShape::blunt;
    e.face = face.width;
    e.radius = 0;
    e.radius_sigma = 0;
    e.center = face.mid;
  }
  return e;
}

}  // namespace detail

}  // namespace section

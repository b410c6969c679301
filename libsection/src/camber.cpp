#include "section/camber.h"

#include "detail/cgal_medial_axis.h"
#include "detail/piecewise_curve.h"
#include "section/error.h"
#include "section/params.h"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <tuple>

namespace section {

using detail::CurveJet;
using detail::PiecewiseCurve;

namespace {

constexpr double pi = 3.14159265358979323846;

Eigen::Vector2d left_normal(const Eigen::Vector2d& d) { return {-d.y(), d.x()}; }
double cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b) { return a.x() * b.y() - a.y() * b.x(); }

// A closed profile with dense samples for initial guesses and global checks.
struct Profile {
  const BSpline& curve;
  PiecewiseCurve fast;
  double t0 = 0, period = 1;
  double sigma = 1;  // +1 counterclockwise, -1 clockwise
  double scale = 1;  // bounding-box diagonal
  std::vector<Eigen::Vector2d> samples;
  std::vector<double> ts;

  Profile(const BSpline& c, int count) : curve(c), fast(c) {
    if (!c.closed) throw Error("camber: the profile spline is open, a closed curve is needed");
    if (c.control.size() < 4) throw Error("camber: the profile spline has too few control points");
    t0 = c.t_min();
    period = c.t_max() - t0;
    count = std::max(count, 64);
    samples.reserve(count);
    for (int i = 0; i < count; ++i) {
      ts.push_back(t0 + period * i / count);
      samples.push_back(fast.jet(ts.back()).point);
    }
    Eigen::Vector2d low = samples[0], high = samples[0];
    double area = 0;
    for (int i = 0; i < count; ++i) {
      low = low.cwiseMin(samples[i]);
      high = high.cwiseMax(samples[i]);
      area += cross(samples[i], samples[(i + 1) % count]);
    }
    scale = (high - low).norm();
    if (!(scale > 0) || !std::isfinite(scale)) throw Error("camber: the profile is degenerate");
    sigma = area >= 0 ? 1 : -1;
  }
  double wrap(double t) const { return t0 + std::fmod(std::fmod(t - t0, period) + period, period); }
  // Parameter distance going forward (in the curve's direction) from a to b.
  double forward(double a, double b) const { return std::fmod(std::fmod(b - a, period) + period, period); }
  int nearest(const Eigen::Vector2d& q) const {
    int best = 0;
    double d = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < samples.size(); ++i) {
      const double e = (samples[i] - q).squaredNorm();
      if (e < d) d = e, best = static_cast<int>(i);
    }
    return best;
  }
  // Nearest sample on the side of the line through q that `n` points to.
  int nearest_on_side(const Eigen::Vector2d& q, const Eigen::Vector2d& n) const {
    int best = -1;
    double d = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < samples.size(); ++i) {
      const Eigen::Vector2d e = samples[i] - q;
      if (e.dot(n) <= 0) continue;
      if (e.squaredNorm() < d) d = e.squaredNorm(), best = static_cast<int>(i);
    }
    return best;
  }
  double sample_distance(const Eigen::Vector2d& q) const {
    double d = std::numeric_limits<double>::infinity();
    for (const auto& s : samples) d = std::min(d, (s - q).squaredNorm());
    return std::sqrt(d);
  }
  // Outward unit normal.
  Eigen::Vector2d outward(double t) const {
    const Eigen::Vector2d d = fast.jet(t).d1.normalized();
    return sigma * Eigen::Vector2d(d.y(), -d.x());
  }
  // Curvature, positive where the profile is convex.
  double convexity(double t) const {
    const CurveJet j = fast.jet(t);
    return sigma * cross(j.d1, j.d2) / std::pow(j.d1.norm(), 3);
  }
};

// Newton on (t_a, t_b, lambda): centre c = p + lambda n, both contacts foot points of c
// and equally far from it.
bool solve_circle(const PiecewiseCurve& curve, const Eigen::Vector2d& p, const Eigen::Vector2d& n,
                  double ta, double tb, double scale, InscribedCircle& out, double* kappa = nullptr) {
  double lambda = 0;
  const double tol = 1e-13 * scale;
  double previous = std::numeric_limits<double>::infinity();
  for (int it = 0; it < 30; ++it) {
    const CurveJet ja = curve.jet(ta), jb = curve.jet(tb);
    const Eigen::Vector2d &a = ja.point, &a1 = ja.d1, &a2 = ja.d2, &b = jb.point, &b1 = jb.d1, &b2 = jb.d2;
    const Eigen::Vector2d c = p + lambda * n;
    const Eigen::Vector3d f((c - a).dot(a1), (c - b).dot(b1),
                            0.5 * ((c - a).squaredNorm() - (c - b).squaredNorm()));
    Eigen::Matrix3d j;
    j << -a1.squaredNorm() + (c - a).dot(a2), 0, n.dot(a1),  //
        0, -b1.squaredNorm() + (c - b).dot(b2), n.dot(b1),    //
        -f(0), f(1), (b - a).dot(n);
    Eigen::Vector3d dx = -j.fullPivLu().solve(f);
    if (!dx.allFinite()) return false;
    const double sa = a1.norm(), sb = b1.norm();
    const double r = std::max(0.5 * ((c - a).norm() + (c - b).norm()), 1e-6 * scale);
    double step = std::max({std::abs(dx(0)) * sa, std::abs(dx(1)) * sb, std::abs(dx(2))});
    if (step > 0.5 * r) dx *= 0.5 * r / step;  // damped far from the solution
    ta += dx(0);
    tb += dx(1);
    lambda += dx(2);
    // Converged, or stalled at the round-off floor of a near-singular system (close to
    // the end of a branch, where the contacts merge or osculate).
    const bool stalled = step < 1e-8 * scale && step > 0.25 * previous;
    previous = step;
    if (step < tol || stalled) {
      out.center = p + lambda * n;
      out.t_left = ta;
      out.t_right = tb;
      out.left = curve.jet(ta).point;
      out.right = curve.jet(tb).point;
      out.radius = 0.5 * ((out.center - out.left).norm() + (out.center - out.right).norm());
      if (kappa) {  // signed curvatures at the contacts, from the last iterate's derivatives
        kappa[0] = cross(a1, a2) / std::pow(a1.norm(), 3);
        kappa[1] = cross(b1, b2) / std::pow(b1.norm(), 3);
      }
      return std::isfinite(out.radius);
    }
  }
  return false;
}

// A solved circle is an inscribed circle of the medial branch when the contacts lie on
// their sides, are distinct, the circle does not cross the profile and does not exceed
// the osculating circle at either contact (beyond that the branch has ended).
bool valid_circle(const Profile& pr, const Eigen::Vector2d& n, const InscribedCircle& c,
                  const double* kappa, int end = -1) {
  const double r = c.radius;
  if (!(r > 1e-9 * pr.scale)) return false;
  if ((c.left - c.center).dot(n) <= 0 || (c.right - c.center).dot(n) >= 0) return false;
  if ((c.left - c.right).norm() < 1e-7 * pr.scale) return false;
  if (std::abs((c.center - c.left).norm() - (c.center - c.right).norm()) > 1e-6 * r) return false;
  const double ka = kappa ? pr.sigma * kappa[0] : pr.convexity(c.t_left);
  const double kb = kappa ? pr.sigma * kappa[1] : pr.convexity(c.t_right);
  // Local osculation test, loose: a spline's curvature ripples by O(h^2), a noisy
  // profile's much more; the macroscopic test below locates the ends.
  if (r * ka >= 2 || r * kb >= 2) return false;
  if (end >= 0) {
    // Toward an end the circle must stay clear of the profile between its contacts,
    // through that end: past the branch's end it would cut through the tip. This
    // macroscopic test is what locates the end, immune to curvature ripples.
    const bool from_left = (end == 0) == (pr.sigma > 0);
    const double from = from_left ? c.t_left : c.t_right, to = from_left ? c.t_right : c.t_left;
    const double length = pr.forward(from, to);
    for (int i = 1; i < 24; ++i) {
      const double t = from + length * (0.05 + 0.9 * i / 24.0);
      if ((pr.fast.jet(t).point - c.center).norm() < r * (1 - 1e-4)) return false;
    }
  }
  return pr.sample_distance(c.center) >= r * (1 - 1e-3);
}

// The current axis: an open spline, extended straight beyond its ends.
struct Axis {
  BSpline spline;
  double a = 0, b = 1;
  PiecewiseCurve f;
  explicit Axis(BSpline s) : spline(std::move(s)), a(spline.t_min()), b(spline.t_max()), f(spline) {}
  Eigen::Vector2d point(double u) const {
    if (u < a) return f.jet(a).point + (u - a) * tangent(a);
    if (u > b) return f.jet(b).point + (u - b) * tangent(b);
    return f.jet(u).point;
  }
  Eigen::Vector2d tangent(double u) const {
    return f.jet(std::clamp(u, a, b)).d1.normalized();
  }
};

// Unit tangent (toward the TE end of `c`) at one end of a chain of camber points: quadratic
// least squares over the points within `span` (arc length along them) of that end. The
// axis spline's own end slope follows the last few centres, whose contacts lie where a
// measured profile is noisiest (the edge-arc junction); a quadratic over a longer stretch
// averages that noise and still follows the camber's curvature. Zero when too few points.
Eigen::Vector2d end_tangent(const std::vector<Eigen::Vector2d>& c, bool front, double span) {
  const std::size_t n = c.size();
  std::vector<Eigen::Vector2d> p;
  std::vector<double> s;
  double acc = 0;
  for (std::size_t k = 0; k < n; ++k) {
    const Eigen::Vector2d& q = c[front ? k : n - 1 - k];
    if (!p.empty()) acc += (q - p.back()).norm();
    if (p.size() >= 6 && acc > span) break;
    p.push_back(q);
    s.push_back(acc);
  }
  if (p.size() < 6 || !(s.back() > 0)) return Eigen::Vector2d::Zero();
  Eigen::MatrixXd A(p.size(), 4), B(p.size(), 2);
  for (std::size_t i = 0; i < p.size(); ++i) {
    const double x = s[i] / s.back();
    A.row(i) << 1, x, x * x, x * x * x;
    B.row(i) = p[i].transpose();
  }
  const Eigen::MatrixXd X = A.colPivHouseholderQr().solve(B);
  const Eigen::Vector2d d = X.row(1).transpose();
  if (!(d.norm() > 0)) return Eigen::Vector2d::Zero();
  return (front ? 1.0 : -1.0) * d.normalized();
}

Axis make_axis(const std::vector<Eigen::Vector2d>& pts, double fairness) {
  // Drop repeated points (Delaunay fans share circumcentres).
  std::vector<Eigen::Vector2d> p;
  for (const auto& q : pts)
    if (p.empty() || (q - p.back()).norm() > 1e-12) p.push_back(q);
  if (p.size() < 4) throw Error("camber: the medial axis has fewer than 4 distinct points");
  CurveFitOptions fo;
  fo.closed = false;
  fo.control_points = std::clamp(static_cast<int>(p.size()) / 2, 4, 200);
  fo.fairness = fairness;
  return Axis(fit_curve(p, fo));
}

// The inscribed circle centred on the line through p along n, solved from a guess's
// contacts; unless !fresh, falls back to the profile's nearest samples on either side.
bool circle_on_normal(const Profile& pr, const Eigen::Vector2d& p, const Eigen::Vector2d& n,
                      const InscribedCircle* guess, InscribedCircle& out, bool fresh = true, int end = -1) {
  double k[2];
  if (guess && solve_circle(pr.fast, p, n, guess->t_left, guess->t_right, pr.scale, out, k) &&
      valid_circle(pr, n, out, k, end))
    return true;
  if (guess && fresh == false) return false;
  const int l = pr.nearest_on_side(p, n), r = pr.nearest_on_side(p, -n);
  if (l < 0 || r < 0) return false;
  return solve_circle(pr.fast, p, n, pr.ts[l], pr.ts[r], pr.scale, out, k) &&
         valid_circle(pr, n, out, k, end);
}

// The station at axis parameter u.
bool station(const Profile& pr, const Axis& ax, double u, const InscribedCircle* guess,
             InscribedCircle& out, bool fresh = true, int end = -1) {
  return circle_on_normal(pr, ax.point(u), left_normal(ax.tangent(u)), guess, out, fresh, end);
}

// From the last valid station outward (direction +1 or -1 in u): march until a station
// fails, then bisect for the end of the branch.
InscribedCircle find_end(const Profile& pr, const Axis& ax, double u, InscribedCircle last,
                         int direction, double tolerance, double first_step) {
  double lo = u, hi = u;
  InscribedCircle c;
  // March: the step grows while stations stay valid, bounded by the local radius.
  double h = std::clamp(first_step, 4 * tolerance * pr.scale, 0.05 * last.radius);
  for (int k = 0; k < 200; ++k) {
    hi = lo + direction * h;
    if (!station(pr, ax, hi, &last, c, false, direction > 0)) break;
    lo = hi;
    last = c;
    h = std::min(2 * h, 0.25 * c.radius);
    if (k == 199) return last;
  }
  while (std::abs(hi - lo) > tolerance * pr.scale) {
    const double mid = 0.5 * (lo + hi);
    if (station(pr, ax, mid, &last, c, false, direction > 0)) {
      lo = mid;
      last = c;
    } else {
      hi = mid;
    }
  }
  return last;
}

}  // namespace

bool inscribed_circle(const BSpline& profile, const Eigen::Vector2d& point,
                      const Eigen::Vector2d& normal, double t_left, double t_right,
                      InscribedCircle& circle) {
  double scale = 0;
  for (const auto& c : profile.control) scale = std::max(scale, (c - profile.control[0]).norm());
  return solve_circle(PiecewiseCurve(profile), point, normal.normalized(), t_left, t_right,
                      std::max(scale, 1e-300), circle);
}

MedialAxis medial_axis(const BSpline& profile, const MedialAxisOptions& options) {
  const Profile pr(profile, options.samples);
  MedialAxis result;
  std::vector<Eigen::Vector2d> seed = options.seed;
  if (seed.empty()) {
    seed = detail::medial_axis_seed(pr.samples).points;
    if (seed.size() < 2)
      throw Error("camber: the profile has no inside triangles (is it self-intersecting?)");
  }
  result.seed_points = static_cast<int>(seed.size());
  // The seed's ends wander into the edges: a stiff fit only gives stations and normals.
  Axis ax = [&] {
    std::vector<Eigen::Vector2d> p;
    for (const auto& q : seed)
      if (p.empty() || (q - p.back()).norm() > 1e-9 * pr.scale) p.push_back(q);
    if (p.size() < 4) {
      // A branch shorter than 4 points: a circle-like shape, reported by the caller.
      if (p.size() == 1) p.push_back(p[0] + Eigen::Vector2d(1e-6 * pr.scale, 0));
      const Eigen::Vector2d a = p.front(), b = p.back();
      p.clear();
      for (int i = 0; i < 8; ++i) p.push_back(a + (b - a) * i / 7.0);
    }
    CurveFitOptions fo;
    fo.closed = false;
    fo.control_points = std::clamp(static_cast<int>(p.size()) / 4, 4, 24);
    fo.fairness = 1e-2;
    return Axis(fit_curve(p, fo));
  }();

  const int m = std::max(options.stations, 16);
  std::vector<InscribedCircle> circles;
  Eigen::Vector2d end0(0, 0), end1(0, 0);
  result.change = pr.scale;
  for (int pass = 0; pass < std::max(options.iterations, 1); ++pass) {
    // Stations clustered toward the ends (cosine spacing) where the axis turns fastest.
    std::vector<double> u(m);
    for (int k = 0; k < m; ++k) u[k] = ax.a + (ax.b - ax.a) * 0.5 * (1 - std::cos(pi * k / (m - 1)));
    std::vector<InscribedCircle> solved(m);
    std::vector<char> ok(m, 0);
    // Start at the widest valid station near the middle and walk outward both ways.
    int start = -1;
    for (int d = 0; d < m && start < 0; ++d)
      for (int k : {m / 2 - d, m / 2 + d})
        if (k >= 0 && k < m && station(pr, ax, u[k], nullptr, solved[k])) {
          ok[k] = 1;
          start = k;
          break;
        }
    if (start < 0) {
      // A circle's medial axis is its centre: the seed collapses and no station solves.
      if ((seed.front() - seed.back()).norm() < 1e-3 * pr.scale)
        throw Error("camber: the profile is not blade-like: its medial axis collapses to a point");
      throw Error("camber: no circle inscribed in the profile was found on the seed axis");
    }
    int first = start, last = start;
    while (last + 1 < m && station(pr, ax, u[last + 1], &solved[last], solved[last + 1])) ok[++last] = 1;
    while (first - 1 >= 0 && station(pr, ax, u[first - 1], &solved[first], solved[first - 1])) ok[--first] = 1;
    const double tol = options.tolerance;
    // Later passes start at the previous ends: a first step of the last change suffices.
    const double step = pass == 0 ? pr.scale : 2 * result.change;
    const InscribedCircle e0 = find_end(pr, ax, u[first], solved[first], -1, tol, step);
    const InscribedCircle e1 = find_end(pr, ax, u[last], solved[last], +1, tol, step);
    circles.clear();
    circles.push_back(e0);
    for (int k = first; k <= last; ++k)
      if ((solved[k].center - circles.back().center).norm() > 1e-6 * pr.scale) circles.push_back(solved[k]);
    if ((e1.center - circles.back().center).norm() <= 1e-6 * pr.scale) circles.pop_back();
    circles.push_back(e1);
    result.change = pass == 0 ? pr.scale
                              : std::max((e0.center - end0).norm(), (e1.center - end1).norm());
    end0 = e0.center;
    end1 = e1.center;
    result.iterations = pass + 1;
    std::vector<Eigen::Vector2d> centers;
    for (const auto& c : circles) centers.push_back(c.center);
    if (centers.size() < 4) break;
    ax = make_axis(centers, 1e-8);
    if (result.change < 1e-6 * pr.scale) break;
  }
  if (circles.size() < 4)
    throw Error("camber: the medial axis has only " + std::to_string(circles.size()) +
                " inscribed circles (the profile is not blade-like)");
  result.circles = circles;
  result.curve = ax.spline;
  return result;
}

// ---------------------------------------------------------------------------------------
// Camber line and edges

namespace {

// First crossing of the ray m + lambda d (lambda > 0) with the profile.
bool ray_hit(const Profile& pr, const Eigen::Vector2d& m, const Eigen::Vector2d& d, double& t_hit) {
  const int n = static_cast<int>(pr.samples.size());
  double best = std::numeric_limits<double>::infinity();
  int seg = -1;
  for (int i = 0; i < n; ++i) {
    const Eigen::Vector2d p = pr.samples[i] - m, q = pr.samples[(i + 1) % n] - m;
    const double gp = cross(d, p), gq = cross(d, q);
    if ((gp > 0) == (gq > 0) && gp != 0 && gq != 0) continue;
    const double w = gp == gq ? 0 : gp / (gp - gq);
    const double along = (p + w * (q - p)).dot(d);
    if (along > 0 && along < best) best = along, seg = i;
  }
  if (seg < 0) return false;
  // Safeguarded secant on g(t) = d x (C(t) - m) inside the bracketing span.
  double a = pr.ts[seg], b = a + pr.period / n;
  auto g = [&](double t) { return cross(d, pr.fast.jet(t).point - m); };
  double ga = g(a), gb = g(b);
  for (int it = 0; it < 100 && std::abs(b - a) > 1e-15 * pr.period; ++it) {
    double t = ga == gb ? 0.5 * (a + b) : a - ga * (b - a) / (gb - ga);
    if (!(t > a && t < b)) t = 0.5 * (a + b);
    const double gt = g(t);
    if (gt == 0) {
      a = b = t;
      break;
    }
    if ((gt > 0) == (ga > 0)) {
      a = t, ga = gt;
      gb *= 0.5;  // Illinois step keeps both ends moving
    } else {
      b = t, gb = gt;
      ga *= 0.5;
    }
  }
  t_hit = pr.wrap(0.5 * (a + b));
  return true;
}

// Parameter where the outward normal has turned by `angle` (radians) from direction d,
// walking from t_tip in `direction` (+1 forward, -1 backward); stops after half a period.
double arc_end(const Profile& pr, double t_tip, const Eigen::Vector2d& d, double angle, int direction,
               const Eigen::Vector2d& center, double reach) {
  // Past the angle, or leaving the end circle's neighbourhood (a flank facing the same
  // way as the edge, as on a highly staggered blade): the value is > angle.
  auto turn = [&](double t) {
    const Eigen::Vector2d nn = pr.outward(t);
    if ((pr.fast.jet(t).point - center).norm() > reach) return 4.0;
    return std::abs(std::atan2(cross(d, nn), d.dot(nn)));
  };
  const double h = pr.period / static_cast<double>(pr.samples.size());
  double a = t_tip, b = t_tip;
  bool found = false;
  for (double walked = 0; walked < 0.5 * pr.period; walked += h) {
    b = a + direction * h;
    if (turn(b) >= angle) {
      found = true;
      break;
    }
    a = b;
  }
  if (!found) return a;
  for (int it = 0; it < 30; ++it) {
    const double mid = 0.5 * (a + b);
    (turn(mid) >= angle ? b : a) = mid;
  }
  return 0.5 * (a + b);
}

struct CircleFit {
  Eigen::Vector2d center{0, 0};
  double radius = 0, rms = 0;
  double radius_sigma = 0;  // standard error of the radius, from the fit's covariance and rms
};

// Rms distance of the points from the circle.
double rms_about(const std::vector<Eigen::Vector2d>& p, const Eigen::Vector2d& center, double radius) {
  double sum = 0;
  for (const auto& q : p) sum += std::pow((q - center).norm() - radius, 2);
  return p.empty() ? 0.0 : std::sqrt(sum / p.size());
}

// Geometric least-squares circle (Gauss-Newton from the algebraic fit). Normal equations
// (3 x 3) on centred points: well conditioned, and this runs tens of times per edge.
CircleFit fit_circle(const std::vector<Eigen::Vector2d>& p) {
  const int n = static_cast<int>(p.size());
  Eigen::Vector2d mean = Eigen::Vector2d::Zero();
  for (const auto& q : p) mean += q;
  mean /= n;
  Eigen::Matrix3d ata = Eigen::Matrix3d::Zero();
  Eigen::Vector3d atb = Eigen::Vector3d::Zero();
  for (int i = 0; i < n; ++i) {
    const Eigen::Vector2d q = p[i] - mean;
    const Eigen::Vector3d row(q.x(), q.y(), 1);
    ata += row * row.transpose();
    atb += row * -q.squaredNorm();
  }
  const Eigen::Vector3d s = ata.ldlt().solve(atb);
  Eigen::Vector3d x(-0.5 * s(0), -0.5 * s(1), 0);
  x(2) = std::sqrt(std::max(x.head<2>().squaredNorm() - s(2), 0.0));
  for (int it = 0; it < 30; ++it) {
    Eigen::Matrix3d jtj = Eigen::Matrix3d::Zero();
    Eigen::Vector3d jte = Eigen::Vector3d::Zero();
    for (int i = 0; i < n; ++i) {
      const Eigen::Vector2d q = p[i] - mean - x.head<2>();
      const double dist = q.norm();
      if (!(dist > 0)) continue;
      const Eigen::Vector3d row(-q.x() / dist, -q.y() / dist, -1);
      jtj += row * row.transpose();
      jte += row * (dist - x(2));
    }
    const Eigen::Vector3d dx = -jtj.ldlt().solve(jte);
    if (!dx.allFinite()) break;
    x += dx;
    if (dx.norm() < 1e-13 * std::max(1.0, x(2))) break;
  }
  CircleFit fit;
  fit.center = mean + x.head<2>();
  fit.radius = std::abs(x(2));
  fit.rms = rms_about(p, fit.center, fit.radius);
  if (n > 3) {
    Eigen::Matrix3d jtj = Eigen::Matrix3d::Zero();
    for (const auto& q : p) {
      const Eigen::Vector2d r = q - fit.center;
      const double dist = r.norm();
      if (!(dist > 0)) continue;
      const Eigen::Vector3d row(-r.x() / dist, -r.y() / dist, -1);
      jtj += row * row.transpose();
    }
    const Eigen::Matrix3d cov = jtj.inverse();
    fit.radius_sigma = std::sqrt(std::max(cov(2, 2), 0.0) * fit.rms * fit.rms * n / (n - 3));
  }
  return fit;
}

// Arc of the profile around t_tip (walking both ways) seen from `c` within `half` radians of
// direction d: the core of an edge, chosen by position (normals are the noisiest part of
// a fitted profile).
std::pair<double, double> angular_arc(const Profile& pr, double t_tip, const Eigen::Vector2d& c,
                                      const Eigen::Vector2d& d, double half) {
  auto angle = [&](double t) {
    const Eigen::Vector2d q = pr.fast.jet(t).point - c;
    return std::abs(std::atan2(cross(d, q), d.dot(q)));
  };
  const double h = pr.period / (2.0 * pr.samples.size());  // then bisected
  double ends[2];
  for (int k = 0; k < 2; ++k) {
    const int dir = k ? 1 : -1;
    double a = t_tip, b = t_tip;
    bool found = false;
    for (double walked = 0; walked < 0.5 * pr.period; walked += h) {
      b = a + dir * h;
      if (angle(b) > half) {
        found = true;
        break;
      }
      a = b;
    }
    if (found)
      for (int it = 0; it < 30; ++it) {
        const double mid = 0.5 * (a + b);
        (angle(mid) > half ? b : a) = mid;
      }
    ends[k] = a;
  }
  return {ends[0], ends[1]};
}

std::vector<Eigen::Vector2d> arc_points(const Profile& pr, double t0, double t1, int count = 121) {
  std::vector<Eigen::Vector2d> arc;
  for (int i = 0; i < count; ++i) arc.push_back(pr.fast.jet(t0 + (t1 - t0) * i / (count - 1)).point);
  return arc;
}

// The edge arc grown geometrically: starting from a core of +-edge_core degrees around the
// edge point, each end walks outward while the profile stays within `tau` outside the
// fitted circle, tau = edge_residual x the core fit's rms (the profile's own noise level
// there), at least edge_noise_residual x the points' noise and 1e-6 of the profile size.
// Past the arc's junction a flank leaves the circle outward as x^2 / 2R (its curvature is
// far below the edge's), so the walk overshoots by sqrt(2 R tau): that much is trimmed
// from each end. Circle, arc, trim are iterated. Returns the arc's parameter range.
std::pair<double, double> grown_arc(const Profile& pr, double t_tip, const Eigen::Vector2d& d,
                                    const Eigen::Vector2d& c0, double r0, const CamberOptions& options,
                                    CircleFit& fit) {
  const double core = options.edge_core * pi / 180;
  std::pair<double, double> range = angular_arc(pr, t_tip, c0, d, core);
  fit = fit_circle(arc_points(pr, range.first, range.second));
  if (!(fit.radius > 0) || !std::isfinite(fit.radius) || fit.radius > 50 * std::max(r0, 1e-9 * pr.scale)) {
    fit.center = c0, fit.radius = r0;
  }
  // Re-centre the core on the fitted circle once: the medial end may sit off the edge centre.
  range = angular_arc(pr, t_tip, fit.center, d, core);
  fit = fit_circle(arc_points(pr, range.first, range.second));
  // The core of a smooth spline can fit its circle far better than the spline follows the
  // edge over a longer arc (its noise-driven ripples run a micrometre or more per 5 um of
  // point noise): tau is at least edge_noise_residual x the points' noise, else the arc
  // can shrink pass by pass onto a few quiet degrees around the edge point.
  const double tau = std::max(
      {options.edge_residual * fit.rms, options.edge_noise_residual * options.profile_noise, 1e-6 * pr.scale});
  const double h = pr.period / (2.0 * pr.samples.size());  // then bisected
  const double cap = options.edge_max_arc * 0.5 * pi / 180;
  const std::pair<double, double> core_range = range;
  // Start the growth from a half circle about the core circle: a circle fitted to the core
  // alone can be far off (a short noisy arc), and the profile then leaves it right past
  // the core; from a longer arc the iteration shrinks onto the edge arc instead.
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
        (pr.fast.jet(0.5 * (range.first + range.second)).point - current.center).normalized();
    // Residual outside the circle; the walk ends where the profile has left the circle
    // for good (far outside it, or past the largest arc), and the arc's end is the last
    // point within tau before that: a noise bump inside the arc does not stop it.
    auto residual = [&](double t) { return (pr.fast.jet(t).point - current.center).norm() - current.radius; };
    double ends[2];
    for (int k = 0; k < 2; ++k) {
      const int dir = k ? 1 : -1;
      double a = t_tip, last_in = t_tip;
      for (double walked = 0; walked < 0.5 * pr.period; walked += h) {
        const double b = a + dir * h;
        const Eigen::Vector2d q = pr.fast.jet(b).point - current.center;
        const double res = q.norm() - current.radius;
        if (res > std::max(20 * tau, 0.2 * current.radius) ||
            std::abs(std::atan2(cross(mid_dir, q), mid_dir.dot(q))) > cap)
          break;
        if (res <= tau) last_in = b;
        a = b;
      }
      a = last_in;
      {
        // Refine the crossing between last_in and the next step.
        double lo = last_in, hi = last_in + dir * h;
        if (residual(hi) > tau)
          for (int it = 0; it < 30; ++it) {
            const double mid = 0.5 * (lo + hi);
            (residual(mid) > tau ? hi : lo) = mid;
          }
        a = lo;
      }
      // Trim the flank overshoot (arc length converted with the local speed), never past
      // the core.
      const double trim = std::sqrt(2 * current.radius * tau) / std::max(pr.fast.jet(a).d1.norm(), 1e-300);
      const double keep = k ? core_range.second : core_range.first;
      ends[k] = dir > 0 ? std::max(a - trim, std::min(keep, a)) : std::min(a + trim, std::max(keep, a));
    }
    const CircleFit next = fit_circle(arc_points(pr, ends[0], ends[1]));
    if (!(next.radius > 0) || !std::isfinite(next.radius)) break;
    fit = next;
    range = {ends[0], ends[1]};
    if ((next.center - current.center).norm() < 1e-9 * pr.scale) break;
  }
  return range;
}

// The circle of an edge refitted to the measured points on its arc. The spline's arc
// carries the fit's own shape error at a tight edge (a micrometre or two: a percent or
// more of a 0.2 mm radius); the measured points do not. Points are taken within the arc's
// angles seen from the spline circle's centre and within a band about that circle. They
// must cover the arc without a large angular gap and fix the radius well (its standard
// error), else (holes, a sparse edge) the spline's circle stands. Twice, the band
// re-centred on the refitted circle.
// True when the refit stands (`fit` replaced).
bool refit_on_measured(const Profile& pr, const Edge& e, const Eigen::Vector2d& d,
                       const std::vector<Eigen::Vector2d>& measured, const CamberOptions& options, CircleFit& fit) {
  if (measured.size() < 8 || !(fit.radius > 0)) return false;
  auto signed_angle = [&](const Eigen::Vector2d& c, const Eigen::Vector2d& q) {
    const Eigen::Vector2d r = q - c;
    return std::atan2(cross(d, r), d.dot(r));
  };
  CircleFit current = fit;
  for (int pass = 0; pass < 2; ++pass) {
    const double a0 = signed_angle(current.center, pr.fast.jet(e.arc_t0).point),
                 a1 = signed_angle(current.center, pr.fast.jet(e.arc_t1).point);
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
    if (gap > options.edge_point_gap * (hi - lo)) return false;
    const CircleFit next = fit_circle(on_arc);
    if (!(next.radius > 0) || !std::isfinite(next.radius) || !(next.radius_sigma <= options.edge_point_sigma * next.radius) ||
        std::abs(next.radius - fit.radius) > 0.2 * fit.radius ||
        (next.center - fit.center).norm() > 0.2 * fit.radius)
      return false;
    current = next;
  }
  fit = current;
  return true;
}

// Edge point, arc and fitted circle for the axis end `end` pointing outward along `d`.
Edge measure_edge(const Profile& pr, const InscribedCircle& end_circle, const Eigen::Vector2d& d,
                  const CamberOptions& options, const std::vector<Eigen::Vector2d>& measured) {
  const Eigen::Vector2d& end = end_circle.center;
  Edge e;
  if (!ray_hit(pr, end, d, e.t))
    throw Error("camber: the camber line's end tangent does not meet the profile");
  e.point = pr.fast.jet(e.t).point;
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
  if (options.edge_on_points && refit_on_measured(pr, e, d, measured, options, fit)) {
    fit.rms = rms_about(arc_points(pr, e.arc_t0, e.arc_t1), fit.center, fit.radius);
    e.on_points = true;
  }
  // Arc: the angle the edge arc subtends at the fitted centre.
  const Eigen::Vector2d q0 = pr.fast.jet(e.arc_t0).point - fit.center, q1 = pr.fast.jet(e.arc_t1).point - fit.center;
  e.arc = (std::abs(std::atan2(cross(d, q0), d.dot(q0))) + std::abs(std::atan2(cross(d, q1), d.dot(q1)))) * 180 / pi;
  e.center = fit.center;
  e.radius = fit.radius;
  e.fit_rms = fit.rms;
  const double k = pr.convexity(e.t);
  e.curvature_radius = k > 0 ? 1 / k : 0;  // 0: the edge point is flat or concave
  return e;
}

// A blunt (cut-off) edge: a flat face across the end of the blade.
struct Face {
  bool found = false;
  double width = 0;             // extent of the face
  Eigen::Vector2d mid{0, 0};    // its middle
  Eigen::Vector2d normal{0, 0}; // outward unit normal
};

// Looks for a flat face at the end of the medial branch `from_end` (circles ordered from
// the end inward), whose end tangent points outward along d. Scale: W, the diameter of
// the first circle more than 1.5 radii back from the end (at a round edge a little over
// 2R; at a blunt one the corner branch climbs at 45 degrees to the fork, 0.71 W back, so
// W is about the face width). The cap of the profile within 0.1 W of its extreme point
// along a direction f is, at a round edge, a circular segment 2 sqrt(2 R 0.1 W) <= 0.63 W
// wide and bowed; at a blunt edge, with f the face normal, it is the face itself: as wide
// as the blade there (at least `blunt_face` W) and straight (line-fit rms below 0.2 of the
// cap depth; a circular segment gives 0.3).
Face blunt_face(const Profile& pr, const std::vector<InscribedCircle>& from_end, const Eigen::Vector2d& d_end,
                const CamberOptions& options) {
  Face face;
  if (from_end.size() < 4) return face;
  const Eigen::Vector2d end = from_end.front().center;
  double w = 0;
  std::size_t iw = 0;
  for (std::size_t i = 0; i < from_end.size(); ++i)
    if ((from_end[i].center - end).norm() > 1.5 * from_end[i].radius) {
      w = 2 * from_end[i].radius;
      iw = i;
      break;
    }
  if (!(w > 1e-9 * pr.scale)) return face;
  // Reference direction: the axis behind the fork (the end tangent itself follows the
  // corner branch and can be 40 degrees off the face normal).
  Eigen::Vector2d d = d_end.normalized();
  for (std::size_t j = iw + 1; j < from_end.size(); ++j)
    if ((from_end[j].center - from_end[iw].center).norm() > w) {
      d = (from_end[iw].center - from_end[j].center).normalized();
      break;
    }
  // Profile near the end, densely resampled: the samples within 1.5 W of the end centre,
  // contiguous around the nearest one.
  const int n = static_cast<int>(pr.samples.size());
  const int near = pr.nearest(end);
  const double reach = 1.5 * w + 2 * pr.period / n;
  int lo = 0, hi = 0;
  while (lo > -n / 2 && (pr.samples[((near + lo - 1) % n + n) % n] - end).norm() < reach) --lo;
  while (hi < n / 2 && (pr.samples[(near + hi + 1) % n] - end).norm() < reach) ++hi;
  const double ta = pr.ts[near] + pr.period * lo / n, tb = pr.ts[near] + pr.period * hi / n;
  std::vector<Eigen::Vector2d> p;
  const int m = 600;
  for (int i = 0; i <= m; ++i) p.push_back(pr.fast.jet(ta + (tb - ta) * i / m).point);
  const double depth = 0.1 * w;
  // The cap of depth `depth` below the extreme point along f: its points, width across f.
  auto cap_along = [&](const Eigen::Vector2d& f, std::vector<Eigen::Vector2d>* out) {
    int top = 0;
    for (int i = 1; i <= m; ++i)
      if (p[i].dot(f) > p[top].dot(f)) top = i;
    const double hmax = p[top].dot(f);
    int a = top, b = top;
    while (a > 0 && p[a - 1].dot(f) >= hmax - depth) --a;
    while (b < m && p[b + 1].dot(f) >= hmax - depth) ++b;
    if (a == 0 || b == m) return -1.0;  // the cap runs out of the neighbourhood: not an edge
    const Eigen::Vector2d u = left_normal(f);
    double lo_u = std::numeric_limits<double>::infinity(), hi_u = -lo_u;
    for (int i = a; i <= b; ++i) lo_u = std::min(lo_u, p[i].dot(u)), hi_u = std::max(hi_u, p[i].dot(u));
    if (out) out->assign(p.begin() + a, p.begin() + b + 1);
    return hi_u - lo_u;
  };
  // Straightness of a cap: rms distance from its total-least-squares line.
  auto line_fit = [](const std::vector<Eigen::Vector2d>& q, Eigen::Vector2d& mean, Eigen::Vector2d& along,
                     Eigen::Vector2d& normal) {
    mean.setZero();
    for (const auto& x : q) mean += x;
    mean /= static_cast<double>(q.size());
    Eigen::Matrix2d cov = Eigen::Matrix2d::Zero();
    for (const auto& x : q) cov += (x - mean) * (x - mean).transpose();
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eig(cov);
    along = eig.eigenvectors().col(1);
    normal = eig.eigenvectors().col(0);
    return std::sqrt(std::max(eig.eigenvalues()(0), 0.0) / q.size());
  };
  // The face need not be square to the end tangent (which the corner branch skews): the
  // direction within 40 degrees of d whose cap is straightest. (The widest cap would be
  // square to a flank, running along it and round the corner.)
  std::vector<Eigen::Vector2d> cap, trial;
  Eigen::Vector2d mean(0, 0), along(1, 0), f = d;
  double best = -1, rms = std::numeric_limits<double>::infinity();
  for (int k = -40; k <= 40; ++k) {
    const double a = k * pi / 180;
    const Eigen::Vector2d g =
        Eigen::Vector2d(std::cos(a) * d.x() - std::sin(a) * d.y(), std::sin(a) * d.x() + std::cos(a) * d.y()).normalized();
    const double width = cap_along(g, &trial);
    if (width < 0 || trial.size() < 3) continue;
    Eigen::Vector2d m0(0, 0), a0(1, 0), n0(0, 1);
    const double r0 = line_fit(trial, m0, a0, n0);
    if (r0 >= rms) continue;
    best = width, cap = trial, mean = m0, along = a0, f = n0, rms = r0;
  }
  if (best < 0) return face;
  if (f.dot(d) < 0) f = -f;
  double smin = std::numeric_limits<double>::infinity(), smax = -smin;
  for (const auto& q : cap) {
    smin = std::min(smin, (q - mean).dot(along));
    smax = std::max(smax, (q - mean).dot(along));
  }
  const double width = smax - smin;
  if (width < options.blunt_face * w || rms > 0.2 * depth) return face;
  face.found = true;
  face.width = width;
  face.mid = mean + 0.5 * (smin + smax) * along;
  face.normal = f;
  return face;
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

InscribedCircle reversed(InscribedCircle c) {
  std::swap(c.left, c.right);
  std::swap(c.t_left, c.t_right);
  return c;
}

// Arc length of a spline between a and b (5-point Gauss-Legendre; the pieces are short).
double piece_length(const PiecewiseCurve& f, double a, double b) {
  static const double x[5] = {-0.9061798459386640, -0.5384693101056831, 0.0, 0.5384693101056831,
                              0.9061798459386640};
  static const double w[5] = {0.2369268850561891, 0.4786286704993665, 0.5688888888888889,
                              0.4786286704993665, 0.2369268850561891};
  double sum = 0;
  for (int i = 0; i < 5; ++i) sum += w[i] * f.jet(0.5 * (a + b) + 0.5 * (b - a) * x[i]).d1.norm();
  return 0.5 * (b - a) * sum;
}

// Arc-length table of an open spline for the inverse map s -> t.
struct ArcTable {
  PiecewiseCurve f;
  std::vector<double> t, s;
  ArcTable(const BSpline& c, int pieces) : f(c) {
    const double a = c.t_min(), b = c.t_max();
    t.push_back(a);
    s.push_back(0);
    for (int i = 1; i <= pieces; ++i) {
      t.push_back(a + (b - a) * i / pieces);
      s.push_back(s.back() + piece_length(f, t[i - 1], t[i]));
    }
  }
  double length() const { return s.back(); }
  double param(double target) const {
    target = std::clamp(target, 0.0, length());
    const std::size_t i = std::min<std::size_t>(
        std::upper_bound(s.begin(), s.end(), target) - s.begin(), s.size() - 1);
    const std::size_t k = std::max<std::size_t>(i, 1);
    double x = t[k - 1] + (t[k] - t[k - 1]) * (target - s[k - 1]) / std::max(s[k] - s[k - 1], 1e-300);
    for (int it = 0; it < 3; ++it) {
      const double err = s[k - 1] + piece_length(f, t[k - 1], x) - target;
      x -= err / std::max(f.jet(x).d1.norm(), 1e-300);
    }
    return x;
  }
  double arc(double param_t) const {
    const std::size_t i = std::min<std::size_t>(
        std::upper_bound(t.begin(), t.end(), param_t) - t.begin(), t.size() - 1);
    const std::size_t k = std::max<std::size_t>(i, 1);
    return s[k - 1] + piece_length(f, t[k - 1], param_t);
  }
};

}  // namespace

CamberResult camber_line(const BSpline& profile, const CamberOptions& options,
                         const std::vector<Eigen::Vector2d>& measured) {
  const Profile pr(profile, options.medial.samples);
  CamberResult res;
  res.orientation = pr.sigma;
  MedialAxis ma = medial_axis(profile, options.medial);
  std::vector<InscribedCircle> circles = ma.circles;

  // Blade-likeness: a circle or a square has a medial axis about as long as it is wide.
  double axis_length = 0, widest = 0;
  int widest_k = 0;
  for (std::size_t k = 0; k < circles.size(); ++k) {
    if (k) axis_length += (circles[k].center - circles[k - 1].center).norm();
    if (circles[k].radius > widest) widest = circles[k].radius, widest_k = static_cast<int>(k);
  }
  if (axis_length < options.min_slenderness * 2 * widest)
    throw Error("camber: the profile is not blade-like: its medial axis (" + std::to_string(axis_length) +
                ") is shorter than " + std::to_string(options.min_slenderness) +
                " times its largest inscribed diameter (" + std::to_string(2 * widest) + ")");

  // Orientation: LE = the end nearer the thickest circle, or the end farther along
  // le_direction when given.
  double before = 0;
  for (int k = 1; k <= widest_k; ++k) before += (circles[k].center - circles[k - 1].center).norm();
  bool flip = before > 0.5 * axis_length;
  if (options.le_direction.norm() > 0) {
    res.le_by_direction = true;
    flip = circles.back().center.dot(options.le_direction) > circles.front().center.dot(options.le_direction);
  }
  if (flip) {
    std::reverse(circles.begin(), circles.end());
    for (auto& c : circles) c = reversed(c);
  }
  // A noisy edge lets the medial branch run on past the edge circle's centre, chasing
  // curvature bumps toward the tip with ever closer contacts: trim the end circles whose
  // contacts subtend less than 2 x edge_prune degrees (the true edge centre sees its two
  // contacts 180 degrees minus the wedge angle apart).
  auto spread = [](const InscribedCircle& c) {
    const Eigen::Vector2d a = c.left - c.center, b = c.right - c.center;
    return 0.5 * std::acos(std::clamp(a.dot(b) / (a.norm() * b.norm()), -1.0, 1.0)) * 180 / pi;
  };
  while (circles.size() > 8 && spread(circles.front()) < options.edge_prune) circles.erase(circles.begin());
  while (circles.size() > 8 && spread(circles.back()) < options.edge_prune) circles.pop_back();
  const std::vector<InscribedCircle> medial = circles;

  // Round edges end at the centre of the circle fitted to the edge arc: the edge arc
  // depends on the end tangent, so iterate tangent -> edge point -> arc -> circle.
  Axis ax = make_axis([&] {
    std::vector<Eigen::Vector2d> c;
    for (const auto& x : medial) c.push_back(x.center);
    return c;
  }(), 1e-8);
  Edge le, te;
  // End tangents: fitted over tangent_span of the axis (see end_tangent), else the spline's.
  auto tangents = [&](const std::vector<InscribedCircle>& cs) {
    std::pair<Eigen::Vector2d, Eigen::Vector2d> t{ax.tangent(ax.a), ax.tangent(ax.b)};
    if (options.tangent_span > 0) {
      std::vector<Eigen::Vector2d> c;
      for (const auto& x : cs) c.push_back(x.center);
      const double span = options.tangent_span * axis_length;
      const Eigen::Vector2d a = end_tangent(c, true, span), b = end_tangent(c, false, span);
      if (a.norm() > 0) t.first = a;
      if (b.norm() > 0) t.second = b;
    }
    return t;
  };
  // Blunt faces, from the medial branch as found (before any end replacement).
  const std::vector<InscribedCircle> medial_rev(medial.rbegin(), medial.rend());
  Face face_le, face_te;
  // An edge: a blunt face when one is found (the circle fit, when it succeeds, is kept
  // for EdgeModel::round), else the fitted edge circle classified.
  auto edge_at = [&](const InscribedCircle& end, const Eigen::Vector2d& d, const Face& face) {
    Edge e;
    try {
      e = measure_edge(pr, end, d, options, measured);
    } catch (const Error&) {
      if (!face.found) throw;
      e.point = face.mid;
      e.t = pr.ts[pr.nearest(face.mid)];
    }
    classify_edge(e, 2 * widest, options);
    if (options.profile_noise > 0 && e.radius > 0)
      e.circular = e.fit_rms <= options.edge_circularity * std::max(options.profile_noise, 1e-4 * e.radius);
    if (face.found) {  // a face, not a circle: no radius, whatever the edge model
      e.shape = EdgeShape::blunt;
      e.face = face.width;
      e.radius = 0;
      e.center = face.mid;
    }
    return e;
  };
  for (int it = 0; it < 3; ++it) {
    const auto tg = tangents(circles);
    const Eigen::Vector2d d_le = -tg.first, d_te = tg.second;
    if (it == 0) {
      face_le = blunt_face(pr, medial, d_le, options);
      face_te = blunt_face(pr, medial_rev, d_te, options);
    }
    le = edge_at(circles.front(), d_le, face_le);
    te = edge_at(circles.back(), d_te, face_te);
    circles = medial;
    // A blunt end: the medial branch runs into a corner of the face; the circles that
    // touch the face belong to that corner branch and are dropped, so the camber line
    // ends where the branch forks and is extended along its tangent to the face.
    auto trim_face = [&](const Face& face, bool front) {
      if (!face.found) return;
      auto touches = [&](const InscribedCircle& c) {
        return (c.center - face.mid).norm() < 2 * face.width &&
               (face.mid - c.center).dot(face.normal) <= c.radius * 1.02;
      };
      // Everything from the first circle (coming from the other end) that touches the face.
      const long n = static_cast<long>(circles.size());
      std::vector<InscribedCircle> kept;
      if (front) {
        long i = n - 1;
        while (i >= 0 && !touches(circles[static_cast<std::size_t>(i)])) --i;
        kept.assign(circles.begin() + (i + 1), circles.end());
      } else {
        long i = 0;
        while (i < n && !touches(circles[static_cast<std::size_t>(i)])) ++i;
        kept.assign(circles.begin(), circles.begin() + i);
      }
      if (kept.size() >= 4) circles = kept;
    };
    trim_face(face_le, true);
    trim_face(face_te, false);
    // Replace a medial end by the fitted centre when the edge is round and the centre is
    // consistent with the axis (inside the end circle's reach).
    auto replace = [&](const Edge& e, bool front) {
      if (e.shape == EdgeShape::blunt && e.face > 0) return;  // a face, not a circle: see trim_face
      const bool round = e.shape == EdgeShape::round || options.edge == EdgeModel::round;
      const InscribedCircle& end = front ? medial.front() : medial.back();
      // A circle much larger than the end's inscribed circle fits a flank, not the edge; on
      // an edge that is not circular the fitted centre moves with the arc taken.
      if (!round || !e.circular || (e.center - end.center).norm() > e.radius || e.radius > 3 * end.radius) return;
      const Eigen::Vector2d d = front ? d_le : d_te;
      std::vector<InscribedCircle> kept;
      // Medial circles close to the centre touch the profile near the edge-arc junction,
      // where the spline's curvature jump ripples: leaving out those within 0.3 edge radii
      // keeps the end tangent truer (wider gaps let the fit's end slope drift instead).
      for (const auto& c : circles)
        if ((c.center - e.center).dot(d) < -0.3 * e.radius) kept.push_back(c);
      // A centre that would swallow half the axis fits a flank (a nose that is not
      // circular), not the edge: the medial end stays.
      if (kept.size() < std::max<std::size_t>(4, circles.size() / 2)) return;
      InscribedCircle tip;
      tip.center = e.center;
      tip.radius = e.radius;
      tip.left = tip.right = e.point;
      tip.t_left = tip.t_right = e.t;
      // The medial branch can stop well short of the edge centre (pruned at a noise bump
      // on a thin edge's flank); bridged by the axis spline alone, the line there bulges
      // off the axis. Across a gap longer than the end circle's radius, march inscribed
      // circles from the branch's end toward the centre, each from the last one's contacts.
      std::vector<InscribedCircle> bridge;
      {
        const InscribedCircle& from = front ? kept.front() : kept.back();
        const Eigen::Vector2d to = e.center - 0.3 * e.radius * d;
        const double gap = (to - from.center).norm();
        if (gap > from.radius) {
          const Eigen::Vector2d dir = (to - from.center) / gap;
          const Eigen::Vector2d n = left_normal(front ? Eigen::Vector2d(-dir) : dir);
          const double step = 0.25 * std::min(from.radius, e.radius);
          InscribedCircle last = from;
          for (double u = step; u < gap; u += step) {
            // From the last circle's contacts, else (a contact that jumps past a bump ends
            // the branch there) from the profile's nearest samples on either side.
            const Eigen::Vector2d q = from.center + u * dir;
            InscribedCircle c;
            if (!circle_on_normal(pr, q, n, &last, c) || (c.center - q).norm() > 0.5 * c.radius ||
                (c.center - e.center).dot(d) >= -0.3 * e.radius)
              break;
            bridge.push_back(c);
            last = c;
          }
        }
      }
      if (front) {
        kept.insert(kept.begin(), bridge.rbegin(), bridge.rend());
        kept.insert(kept.begin(), tip);
      } else {
        kept.insert(kept.end(), bridge.begin(), bridge.end());
        kept.push_back(tip);
      }
      circles = kept;
    };
    replace(le, true);
    replace(te, false);
    std::vector<Eigen::Vector2d> c;
    for (const auto& x : circles) c.push_back(x.center);
    ax = make_axis(c, 1e-8);
  }
  // Final edge points from the final tangents. On a round edge whose circle was fitted to
  // the measured points, the point is where the tangent meets that circle: a spline cuts a
  // tight edge a few micrometres inside its points (chords of the compressor preset came
  // out 1.9 um short at the mean, up to 10.8 um), the circle through them does not.
  std::tie(res.le_tangent, res.te_tangent) = tangents(circles);
  {
    auto point = [&](const InscribedCircle& end, const Eigen::Vector2d& d, Edge& e) {
      double t = 0;
      if (ray_hit(pr, end.center, d, t)) e.point = pr.fast.jet(t).point, e.t = t;
      else if (e.face == 0) throw Error("camber: the camber line's end tangent does not meet the profile");
      else return;
      if (!e.on_points || !e.circular || e.face > 0 || e.shape != EdgeShape::round || !(e.radius > 0)) return;
      // |end + s d - c| = R, the far root (the ray starts inside the circle).
      const Eigen::Vector2d w = end.center - e.center;
      const double b = w.dot(d), q = b * b - (w.squaredNorm() - e.radius * e.radius);
      if (!(q >= 0)) return;
      const Eigen::Vector2d on_circle = end.center + (-b + std::sqrt(q)) * d;
      if ((on_circle - e.point).norm() <= 0.1 * e.radius) e.point = on_circle;
    };
    point(circles.front(), -res.le_tangent, le);
    point(circles.back(), res.te_tangent, te);
  }
  if (options.edge == EdgeModel::automatic) {
    if (le.shape != EdgeShape::round) le.radius = 0;
    if (te.shape != EdgeShape::round) te.radius = 0;
  }
  res.le = le;
  res.te = te;
  ma.circles = circles;
  ma.curve = ax.spline;
  res.medial = ma;

  // Sampled camber line: straight extensions plus the axis; axis points are snapped onto
  // the exact medial axis by solving their inscribed circle.
  const ArcTable table(ax.spline, 4 * static_cast<int>(circles.size()));
  res.ext_le = (le.point - circles.front().center).norm();
  res.ext_te = (te.point - circles.back().center).norm();
  res.length = res.ext_le + table.length() + res.ext_te;
  const int count = std::max(options.samples, 3);
  std::size_t hint = 0;
  for (int i = 0; i < count; ++i) {
    const double s = res.length * i / (count - 1);
    Eigen::Vector2d p;
    double r;
    if (s <= res.ext_le) {
      p = le.point + s * res.le_tangent;
      r = circles.front().radius;
    } else if (s >= res.length - res.ext_te) {
      p = te.point - (res.length - s) * res.te_tangent;
      r = circles.back().radius;
    } else {
      const double t = table.param(s - res.ext_le);
      p = ax.spline.point(t);
      const Eigen::Vector2d n = left_normal(ax.spline.derivative(t, 1).normalized());
      while (hint + 1 < circles.size() &&
             (circles[hint + 1].center - p).norm() < (circles[hint].center - p).norm())
        ++hint;
      // The fitted edge centres carry no contacts: guess from a medial neighbour.
      std::size_t g = hint;
      if (circles[g].t_left == circles[g].t_right) g = g == 0 ? 1 : g - 1;
      InscribedCircle c;
      if (solve_circle(pr.fast, p, n, circles[g].t_left, circles[g].t_right, pr.scale, c) &&
          valid_circle(pr, n, c, nullptr) && (c.center - p).norm() < 0.5 * c.radius) {
        p = c.center;
        r = c.radius;
      } else {
        // Near a fitted edge centre the medial branch may stop short: interpolate.
        const std::size_t k = std::min(hint + 1, circles.size() - 1), k0 = k == 0 ? 0 : k - 1;
        const double span = (circles[k].center - circles[k0].center).norm();
        const double w = std::clamp((p - circles[k0].center).norm() / std::max(span, 1e-300), 0.0, 1.0);
        r = (1 - w) * circles[k0].radius + w * circles[k].radius;
      }
    }
    res.points.push_back(p);
    res.s.push_back(s);
    res.radius.push_back(r);
    if (s > res.ext_le && s < res.length - res.ext_te) {
      const double off = r - pr.sample_distance(p);
      if (off > res.off_axis) res.off_axis = off, res.off_axis_s = s;
    }
  }

  // Thickest circle: the widest station refined by golden-section search on the axis.
  {
    int k = 0;
    for (std::size_t i = 0; i < circles.size(); ++i)
      if (circles[i].radius > circles[k].radius) k = static_cast<int>(i);
    auto param_of = [&](const Eigen::Vector2d& q) {
      // Axis parameter nearest q among a fine scan of the table.
      double best = ax.a, dist = std::numeric_limits<double>::infinity();
      for (std::size_t i = 0; i < table.t.size(); ++i) {
        const double e = (ax.spline.point(table.t[i]) - q).norm();
        if (e < dist) dist = e, best = table.t[i];
      }
      return best;
    };
    const InscribedCircle& lo_c = circles[std::max(k - 1, 0)];
    const InscribedCircle& hi_c = circles[std::min<std::size_t>(k + 1, circles.size() - 1)];
    double a = param_of(lo_c.center), b = param_of(hi_c.center);
    if (a > b) std::swap(a, b);
    a = std::max(a - (b - a), ax.a);
    b = std::min(b + (b - a), ax.b);
    InscribedCircle best = circles[k];
    auto radius_at = [&](double t) {
      InscribedCircle c;
      const Eigen::Vector2d n = left_normal(ax.spline.derivative(t, 1).normalized());
      if (solve_circle(pr.fast, ax.spline.point(t), n, best.t_left, best.t_right, pr.scale, c) &&
          valid_circle(pr, n, c, nullptr)) {
        if (c.radius > best.radius) best = c;
        return c.radius;
      }
      return -1.0;
    };
    const double g = 0.5 * (std::sqrt(5.0) - 1);
    double x1 = b - g * (b - a), x2 = a + g * (b - a);
    double f1 = radius_at(x1), f2 = radius_at(x2);
    for (int it = 0; it < 80 && b - a > 1e-12 * pr.scale; ++it) {
      if (f1 > f2) {
        b = x2, x2 = x1, f2 = f1;
        x1 = b - g * (b - a);
        f1 = radius_at(x1);
      } else {
        a = x1, x1 = x2, f1 = f2;
        x2 = a + g * (b - a);
        f2 = radius_at(x2);
      }
    }
    res.thickest = best;
    res.thickest_s = res.ext_le + table.arc(param_of(best.center));
    // Polish: the foot of best.center on the axis.
    double t = param_of(best.center);
    for (int it = 0; it < 20; ++it) {
      const Eigen::Vector2d d1 = ax.spline.derivative(t, 1), d2 = ax.spline.derivative(t, 2);
      const Eigen::Vector2d e = ax.spline.point(t) - best.center;
      const double step = e.dot(d1) / (d1.squaredNorm() + e.dot(d2));
      t = std::clamp(t - step, ax.a, ax.b);
      if (std::abs(step) < 1e-15 * (ax.b - ax.a)) break;
    }
    res.thickest_s = res.ext_le + table.arc(t);
  }

  // Pressure side = the concave side of the camber line: opposite to its bulge from the chord.
  const Eigen::Vector2d chord = (te.point - le.point).normalized();
  double bulge = 0;
  for (const auto& p : res.points) bulge += cross(chord, p - le.point);
  res.pressure_side = bulge > 0 ? -1 : 1;
  return res;
}

std::vector<ThicknessStation> thickness_stations(const BSpline& profile, const CamberResult& camber,
                                                 const std::vector<double>& fractions) {
  const Profile pr(profile, 1000);
  const Axis ax(camber.medial.curve);
  const ArcTable table(ax.spline, 4 * static_cast<int>(camber.medial.circles.size()));
  const auto& circles = camber.medial.circles;
  std::vector<ThicknessStation> out;
  for (double f : fractions) {
    if (!(f >= 0 && f <= 1))
      throw Error("params: thickness station " + std::to_string(f) + " is outside [0, 1]");
    ThicknessStation st;
    st.fraction = f;
    st.s = f * camber.length;
    InscribedCircle c;
    bool solved = false;
    if (st.s > camber.ext_le && st.s < camber.length - camber.ext_te) {
      const double t = table.param(st.s - camber.ext_le);
      const Eigen::Vector2d p = ax.spline.point(t);
      const Eigen::Vector2d n = left_normal(ax.spline.derivative(t, 1).normalized());
      std::size_t g = 0;
      double best = std::numeric_limits<double>::infinity();
      for (std::size_t k = 0; k < circles.size(); ++k)
        if (circles[k].t_left != circles[k].t_right && (circles[k].center - p).norm() < best)
          best = (circles[k].center - p).norm(), g = k;
      solved = solve_circle(pr.fast, p, n, circles[g].t_left, circles[g].t_right, pr.scale, c) &&
               valid_circle(pr, n, c, nullptr) && (c.center - p).norm() < 0.5 * c.radius;
      if (!solved) c.center = p;
    } else {
      c.center = st.s <= camber.ext_le ? Eigen::Vector2d(camber.le.point + st.s * camber.le_tangent)
                                       : Eigen::Vector2d(camber.te.point - (camber.length - st.s) * camber.te_tangent);
    }
    if (solved) {
      st.thickness = 2 * c.radius;
    } else {
      // On an extension (or where no circle fits): the width across the camber normal.
      const Eigen::Vector2d d = st.s <= camber.ext_le ? camber.le_tangent : camber.te_tangent;
      double tl = 0, tr = 0;
      if (!ray_hit(pr, c.center, left_normal(d), tl) || !ray_hit(pr, c.center, -left_normal(d), tr))
        throw Error("params: the camber normal at station " + std::to_string(f) + " misses the profile");
      c.left = pr.fast.jet(tl).point;
      c.right = pr.fast.jet(tr).point;
      st.thickness = (c.left - c.right).norm();
    }
    st.point = c.center;
    st.pressure = camber.pressure_side > 0 ? c.left : c.right;
    st.suction = camber.pressure_side > 0 ? c.right : c.left;
    out.push_back(st);
  }
  return out;
}

}  // namespace section

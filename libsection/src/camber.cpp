// SPDX-License-Identifier: GPL-3.0-or-later
#include "section/camber.h"

#include "detail/axis_curve.h"
#include "detail/coverage.h"
#include "detail/camber_line.h"
#include "detail/edge_fit.h"
#include "detail/inscribed.h"
#include "detail/sampled_profile.h"
#include "section/error.h"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <memory>
#include <string>
#include <tuple>
#include <utility>

namespace section {

using detail::ArcLengthTable;
using detail::AxisCurve;
using detail::cross;
using detail::Face;
using detail::left_normal;
using detail::pi;
using detail::SampledProfile;

namespace {

// The medial branch's length along its centres and its widest circle.
struct BranchSize {
  double length = 0, widest = 0;
};

// Blade-likeness: a circle or a square has a medial axis about as long as it is wide.
BranchSize blade_size(const std::vector<InscribedCircle>& circles, const CamberOptions& options) {
  BranchSize b;
  for (std::size_t k = 0; k < circles.size(); ++k) {
    if (k) b.length += (circles[k].center - circles[k - 1].center).norm();
    b.widest = std::max(b.widest, circles[k].radius);
  }
  if (b.length < options.min_slenderness * 2 * b.widest)
    throw Error("camber: the profile is not blade-like: its medial axis (" + std::to_string(b.length) +
                ") is shorter than " + std::to_string(options.min_slenderness) +
                " times its largest inscribed diameter (" + std::to_string(2 * b.widest) + ")");
  return b;
}

InscribedCircle reversed(InscribedCircle c) {
  std::swap(c.left, c.right);
  std::swap(c.t_left, c.t_right);
  return c;
}

// Orders the branch from LE to TE: the LE is the end farther along le_direction when
// given, else the blunter end when the other is sharp (its last circle under sharp_ratio
// of the largest diameter, the other's le_bluntness times it or more: the last circles of
// two round ends vary too much with pruning to compare), else the end nearer the thickest
// circle.
void orient(std::vector<InscribedCircle>& circles, const CamberOptions& options, CamberResult& res) {
  double length = 0, before = 0, widest = 0;
  for (std::size_t k = 1; k < circles.size(); ++k) {
    length += (circles[k].center - circles[k - 1].center).norm();
    if (circles[k].radius > widest) widest = circles[k].radius, before = length;
  }
  bool flip = before > 0.5 * length;
  const double r0 = circles.front().radius, r1 = circles.back().radius;
  if (options.le_direction.norm() > 0) {
    res.le_by_direction = true;
    flip = circles.back().center.dot(options.le_direction) > circles.front().center.dot(options.le_direction);
  } else if (options.le_bluntness > 0 && std::min(r0, r1) < options.sharp_ratio * 2 * widest &&
             std::max(r0, r1) >= options.le_bluntness * std::min(r0, r1)) {
    res.le_by_bluntness = true;
    flip = r1 > r0;
  }
  if (flip) {
    std::reverse(circles.begin(), circles.end());
    for (auto& c : circles) c = reversed(c);
  }
}

// A noisy edge lets the medial branch run on past the edge circle's centre, chasing
// curvature bumps toward the tip with ever closer contacts: trims the end circles whose
// contacts subtend less than 2 x edge_prune degrees (the true edge centre sees its two
// contacts 180 degrees minus the wedge angle apart).
void prune_ends(std::vector<InscribedCircle>& circles, double edge_prune) {
  auto spread = [](const InscribedCircle& c) {
    const Eigen::Vector2d a = c.left - c.center, b = c.right - c.center;
    return 0.5 * std::acos(std::clamp(a.dot(b) / (a.norm() * b.norm()), -1.0, 1.0)) * 180 / pi;
  };
  while (circles.size() > 8 && spread(circles.front()) < edge_prune) circles.erase(circles.begin());
  while (circles.size() > 8 && spread(circles.back()) < edge_prune) circles.pop_back();
}

// Unit tangent (toward the TE end of `circles`) at one end of the chain of their centres:
// cubic least squares over the centres within `span` (arc length along them) of that end,
// each weighted by its circle's fit_weight (those on a hole's bridge count less or not).
// The axis spline's own end slope follows the last few centres, whose contacts lie where a
// measured profile is noisiest (the edge-arc junction); a fit over a longer stretch
// averages that noise and still follows the camber's curvature. Zero when fewer than 6
// centres of weight count. `degree` 4: the quartic that tells how far the cubic is from
// the camber (fit_model).
Eigen::Vector2d end_tangent(const std::vector<InscribedCircle>& circles, bool front, double span,
                            int degree = 3) {
  const detail::EndSpan e = detail::end_span(circles, front, span);
  const std::vector<const InscribedCircle*>& p = e.circles;
  const std::vector<double>& s = e.s;
  if (p.empty()) return Eigen::Vector2d::Zero();
  Eigen::MatrixXd A(p.size(), degree + 1), B(p.size(), 2);
  for (std::size_t i = 0; i < p.size(); ++i) {
    const double x = s[i] / s.back(), w = std::sqrt(p[i]->fit_weight);
    double power = w;
    for (int k = 0; k <= degree; ++k, power *= x) A(i, k) = power;
    B.row(i) = w * p[i]->center.transpose();
  }
  const Eigen::MatrixXd X = A.colPivHouseholderQr().solve(B);
  const Eigen::Vector2d d = X.row(1).transpose();
  if (!(d.norm() > 0)) return Eigen::Vector2d::Zero();
  return (front ? 1.0 : -1.0) * d.normalized();
}

// The camber directions (toward the TE) at both ends of `circles`: fitted over
// tangent_span of the axis length (see end_tangent), else the axis spline's end slopes.
std::pair<Eigen::Vector2d, Eigen::Vector2d> end_tangents(const AxisCurve& ax,
                                                         const std::vector<InscribedCircle>& circles,
                                                         double tangent_span, double axis_length) {
  std::pair<Eigen::Vector2d, Eigen::Vector2d> t{ax.tangent(ax.a), ax.tangent(ax.b)};
  if (tangent_span > 0) {
    const double span = tangent_span * axis_length;
    const Eigen::Vector2d a = end_tangent(circles, true, span), b = end_tangent(circles, false, span);
    if (a.norm() > 0) t.first = a;
    if (b.norm() > 0) t.second = b;
  }
  return t;
}

// How far the end directions (res's tangents, the cubics of end_tangents) move when the
// cubic becomes a quartic over the same span: a cubic follows a curvature that changes
// linearly, and a camber turning fast and unevenly near an edge leaves it biased there (a
// twisted compressor tip: 0.96 degrees at the TE on the exact profile, the quartic 0.01).
// checks.h's inlet_fit and outlet_fit. Where the cubic had too few points, so has the
// quartic: 0.
void fit_model(const std::vector<InscribedCircle>& circles, double span, CamberResult& res) {
  if (!(span > 0)) return;
  const Eigen::Vector2d qa = end_tangent(circles, true, span, 4), qb = end_tangent(circles, false, span, 4);
  auto angle = [](const Eigen::Vector2d& u, const Eigen::Vector2d& v) {
    return u.norm() > 0 && v.norm() > 0 ? std::abs(std::atan2(cross(u, v), u.dot(v))) * 180 / pi : 0.0;
  };
  res.le_fit_model = angle(res.le_tangent, qa);
  res.te_fit_model = angle(res.te_tangent, qb);
  res.tangent_span_length = span;
}

// A blunt end: the medial branch runs into a corner of the face; the circles that touch
// the face belong to that corner branch and are dropped (everything from the first one,
// coming from the other end, that touches it), so the camber line ends where the branch
// forks and is extended along its tangent to the face.
void trim_at_face(std::vector<InscribedCircle>& circles, const Face& face, bool front) {
  if (!face.found) return;
  auto touches = [&](const InscribedCircle& c) {
    return (c.center - face.mid).norm() < 2 * face.width &&
           (face.mid - c.center).dot(face.normal) <= c.radius * 1.02;
  };
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
}

// The medial branch can stop well short of the edge centre (pruned at a noise bump on a
// thin edge's flank); bridged by the axis spline alone, the line there bulges off the
// axis. Across a gap longer than the end circle `from`'s radius: inscribed circles marched
// from it toward the centre of edge e (outward along d), each from the last one's
// contacts, else (a contact that jumps past a bump ends the branch there) from the
// profile's nearest samples on either side. In order from `from` outward.
std::vector<InscribedCircle> bridge_to_centre(const SampledProfile& pr, const InscribedCircle& from,
                                              const Edge& e, const Eigen::Vector2d& d, bool front) {
  std::vector<InscribedCircle> bridge;
  const Eigen::Vector2d to = e.center - 0.3 * e.radius * d;
  const double gap = (to - from.center).norm();
  if (!(gap > from.radius)) return bridge;
  const Eigen::Vector2d dir = (to - from.center) / gap;
  const Eigen::Vector2d n = left_normal(front ? Eigen::Vector2d(-dir) : dir);
  const double step = 0.25 * std::min(from.radius, e.radius);
  InscribedCircle last = from;
  for (double u = step; u < gap; u += step) {
    const Eigen::Vector2d q = from.center + u * dir;
    InscribedCircle c;
    if (!detail::circle_on_normal(pr, q, n, &last, c) || (c.center - q).norm() > 0.5 * c.radius ||
        (c.center - e.center).dot(d) >= -0.3 * e.radius)
      break;
    bridge.push_back(c);
    last = c;
  }
  return bridge;
}

// Replaces a medial end (`end`, outward along d) by the fitted centre of edge e when the
// edge is round and the centre consistent with the axis (inside the end circle's reach).
void end_at_centre(const SampledProfile& pr, std::vector<InscribedCircle>& circles, const Edge& e,
                   const InscribedCircle& end, const Eigen::Vector2d& d, bool front,
                   const CamberOptions& options) {
  if (e.shape == EdgeShape::blunt && e.face > 0) return;  // a face, not a circle: see trim_at_face
  if (e.shape == EdgeShape::sharp) return;                // a vertex, not a circle
  const bool round = e.shape == EdgeShape::round || options.edge == EdgeModel::round;
  // A circle much larger than the end's inscribed circle fits a flank, not the edge; on
  // an edge that is not circular the fitted centre moves with the arc taken.
  if (!round || !e.circular) return;
  // The medial end may have run on past the centre into a finger the spline left at the
  // tip (a small end circle): the axis still passes through the edge circle when one of
  // its circles is nearly it, and the run-on is dropped below.
  const auto nearly_edge = [&e](const InscribedCircle& c) {
    return (c.center - e.center).norm() <= 0.25 * e.radius &&
           std::abs(c.radius - e.radius) <= 0.25 * e.radius;
  };
  const bool consistent = (e.center - end.center).norm() <= e.radius && e.radius <= 3 * end.radius;
  if (!consistent && std::none_of(circles.begin(), circles.end(), nearly_edge)) return;
  std::vector<InscribedCircle> kept;
  // Medial circles close to the centre touch the profile near the edge-arc junction,
  // where the spline's curvature jump ripples: leaving out those within 0.3 edge radii
  // keeps the end tangent truer (wider gaps let the fit's end slope drift instead).
  // Only this edge's half of the axis is tested: an axis that turns by more than 90
  // degrees brings its other end round beyond the plane through this centre (a twisted
  // tip, inlet 40 and outlet -68 degrees at a stagger of 26), and those are no run-on.
  const std::size_t n = circles.size();
  std::size_t swallowed = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const bool near_half = front ? 2 * i < n : 2 * i >= n;
    if (near_half && (circles[i].center - e.center).dot(d) >= -0.3 * e.radius)
      ++swallowed;
    else
      kept.push_back(circles[i]);
  }
  // A centre that would swallow half the axis fits a flank (a nose that is not
  // circular), not the edge: the medial end stays.
  if (2 * swallowed >= n || kept.size() < 4) return;
  InscribedCircle tip;
  tip.center = e.center;
  tip.radius = e.radius;
  tip.left = tip.right = e.point;
  tip.t_left = tip.t_right = e.t;
  const std::vector<InscribedCircle> bridge =
      bridge_to_centre(pr, front ? kept.front() : kept.back(), e, d, front);
  if (front) {
    kept.insert(kept.begin(), bridge.rbegin(), bridge.rend());
    kept.insert(kept.begin(), tip);
  } else {
    kept.insert(kept.end(), bridge.begin(), bridge.end());
    kept.push_back(tip);
  }
  circles = kept;
}

// The circles of the camber line, LE to TE, and its edges.
struct Ends {
  std::vector<InscribedCircle> circles;
  Edge le, te;
};

// The same centres in the same order, to the bit.
bool same_centres(const std::vector<InscribedCircle>& a, const std::vector<InscribedCircle>& b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i)
    if (std::memcmp(a[i].center.data(), b[i].center.data(), 2 * sizeof(double)) != 0) return false;
  return true;
}

// What detect_edge measures an edge from: the end circle's centre and radius (not its
// contacts) and the outward tangent there.
struct EdgeInput {
  double bits[5] = {};
  EdgeInput() = default;
  EdgeInput(const InscribedCircle& end, const Eigen::Vector2d& d)
      : bits{end.center.x(), end.center.y(), end.radius, d.x(), d.y()} {}
  // The same bits (a signed zero or a NaN told apart): the same edge follows.
  bool same(const EdgeInput& o) const { return std::memcmp(bits, o.bits, sizeof bits) == 0; }
};

// Round edges end at the centre of the circle fitted to the edge arc; the arc depends on
// the end tangent, so tangent -> edge point -> arc -> circle is iterated (3 times). Blunt
// faces are looked for once, on the medial branch as found. `ax` enters as the axis
// through `medial` and leaves as the one through the circles returned.
Ends settle_edges(const SampledProfile& pr, const std::vector<InscribedCircle>& medial, AxisCurve& ax,
                  const BranchSize& size, const CamberOptions& options,
                  const std::vector<Eigen::Vector2d>& measured) {
  const std::vector<InscribedCircle> medial_rev(medial.rbegin(), medial.rend());
  Face face_le, face_te;
  Ends ends{medial, {}, {}};
  EdgeInput last_le, last_te;
  for (int it = 0; it < 3; ++it) {
    const auto tg = end_tangents(ax, ends.circles, options.tangent_span, size.length);
    const Eigen::Vector2d d_le = -tg.first, d_te = tg.second;
    if (it == 0) {
      face_le = detail::blunt_face(pr, medial, d_le, options);
      face_te = detail::blunt_face(pr, medial_rev, d_te, options);
    }
    // An edge depends on its end circle and tangent alone (the rest stays): the same
    // inputs as the last iteration's give the same edge, and at both ends the same
    // circles and axis, so the iteration has settled (a converged round edge whose circle
    // was refitted to the measured points: its centre repeats while its point moves).
    const EdgeInput in_le{ends.circles.front(), d_le}, in_te{ends.circles.back(), d_te};
    const bool same_le = it > 0 && in_le.same(last_le), same_te = it > 0 && in_te.same(last_te);
    if (same_le && same_te) break;
    last_le = in_le, last_te = in_te;
    if (!same_le)
      ends.le =
          detail::detect_edge(pr, ends.circles.front(), d_le, face_le, 2 * size.widest, options, measured);
    if (!same_te)
      ends.te =
          detail::detect_edge(pr, ends.circles.back(), d_te, face_te, 2 * size.widest, options, measured);
    ends.circles = medial;
    trim_at_face(ends.circles, face_le, true);
    trim_at_face(ends.circles, face_te, false);
    end_at_centre(pr, ends.circles, ends.le, medial.front(), d_le, true, options);
    end_at_centre(pr, ends.circles, ends.te, medial.back(), d_te, false, options);
    ax = detail::make_axis(detail::centers(ends.circles), 1e-8);
  }
  return ends;
}

// The final edge point: where the final tangent from the end circle `end` (outward along
// d) meets the profile. On a round, circular edge whose circle was fitted to the measured
// points, where it meets that circle instead: a spline cuts a tight edge a few micrometres
// inside its points, the circle through them does not (docs/CAMBER.md).
void final_edge_point(const SampledProfile& pr, const InscribedCircle& end, const Eigen::Vector2d& d,
                      Edge& e) {
  if (e.vertex) return;  // the vertex is the edge point
  double t = 0;
  if (detail::ray_hit(pr, end.center, d, t))
    e.point = pr.fast.point(t), e.t = t;
  else if (e.face == 0)
    throw Error("camber: the camber line's end tangent does not meet the profile");
  else
    return;
  if (!e.on_points || !e.circular || e.face > 0 || e.shape != EdgeShape::round || !(e.radius > 0)) return;
  // |end + s d - c| = R, the far root (the ray starts inside the circle).
  const Eigen::Vector2d w = end.center - e.center;
  const double b = w.dot(d), q = b * b - (w.squaredNorm() - e.radius * e.radius);
  if (!(q >= 0)) return;
  const Eigen::Vector2d on_circle = end.center + (-b + std::sqrt(q)) * d;
  if ((on_circle - e.point).norm() <= 0.1 * e.radius) e.point = on_circle;
}

// The sampled camber line: `count` points evenly in arc length, on the straight
// extensions or on the axis; axis points are snapped onto the exact medial axis by solving
// their inscribed circle. Near a fitted edge centre, where the medial branch may stop
// short, the radius is interpolated between the circles instead.
void sample_line(const SampledProfile& pr, const AxisCurve& ax, const ArcLengthTable& table,
                 const std::vector<InscribedCircle>& circles, int count, CamberResult& res) {
  std::size_t hint = 0;
  for (int i = 0; i < count; ++i) {
    const double s = res.length * i / (count - 1);
    Eigen::Vector2d p;
    double r;
    if (s <= res.ext_le || s >= res.length - res.ext_te) {
      p = detail::extension_point(res, s);
      r = s <= res.ext_le ? circles.front().radius : circles.back().radius;
    } else {
      const detail::AxisSample a = detail::axis_sample(ax, table, res.ext_le, s);
      p = a.point;
      while (hint + 1 < circles.size() &&
             (circles[hint + 1].center - p).norm() < (circles[hint].center - p).norm())
        ++hint;
      // The fitted edge centres carry no contacts: guess from a medial neighbour.
      std::size_t g = hint;
      if (circles[g].t_left == circles[g].t_right) g = g == 0 ? 1 : g - 1;
      InscribedCircle c;
      if (detail::snap_to_axis(pr, p, a.normal, circles[g], c)) {
        p = c.center;
        r = c.radius;
      } else {
        const std::size_t k = std::min(hint + 1, circles.size() - 1), k0 = k == 0 ? 0 : k - 1;
        const double span = (circles[k].center - circles[k0].center).norm();
        const double w = std::clamp((p - circles[k0].center).norm() / std::max(span, 1e-300), 0.0, 1.0);
        r = (1 - w) * circles[k0].radius + w * circles[k].radius;
      }
    }
    res.points.push_back(p);
    res.s.push_back(s);
    res.radius.push_back(r);
  }
}

// Where the sampled line strays from the medial axis (CamberResult::off_axis): the
// samples between the extensions that lie nearer the profile than their radius says.
void off_axis_check(const SampledProfile& pr, CamberResult& res) {
  for (std::size_t i = 0; i < res.points.size(); ++i) {
    const double s = res.s[i];
    // Only a sample nearer than the radius makes the offset positive: told first without
    // finding the nearest (most samples of the line have none).
    if (s > res.ext_le && s < res.length - res.ext_te && pr.sample_within(res.points[i], res.radius[i])) {
      const double off = res.radius[i] - pr.sample_distance(res.points[i]);
      if (off > res.off_axis) res.off_axis = off, res.off_axis_s = s;
    }
  }
}

// Axis parameter nearest q among the parameters of the arc-length table (`points`: the
// axis at each of them).
double nearest_param(const AxisCurve& ax, const ArcLengthTable& table,
                     const std::vector<Eigen::Vector2d>& points, const Eigen::Vector2d& q) {
  double best = ax.a, dist = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < table.t.size(); ++i) {
    const double e = (points[i] - q).norm();
    if (e < dist) dist = e, best = table.t[i];
  }
  return best;
}

// Golden-section search of [a, b] for the maximum of f, to 1e-12 of `scale`.
template <class F>
void golden_max(double a, double b, double scale, F&& f) {
  const double g = 0.5 * (std::sqrt(5.0) - 1);
  double x1 = b - g * (b - a), x2 = a + g * (b - a);
  double f1 = f(x1), f2 = f(x2);
  for (int it = 0; it < 80 && b - a > 1e-12 * scale; ++it) {
    if (f1 > f2) {
      b = x2, x2 = x1, f2 = f1;
      x1 = b - g * (b - a);
      f1 = f(x1);
    } else {
      a = x1, x1 = x2, f1 = f2;
      x2 = a + g * (b - a);
      f2 = f(x2);
    }
  }
}

// The foot of q on the axis (Newton from the parameter t).
double foot_on_axis(const AxisCurve& ax, double t, const Eigen::Vector2d& q) {
  for (int it = 0; it < 20; ++it) {
    Eigen::Vector2d jet[3];  // point and derivatives, from one evaluation
    ax.spline.derivatives(t, 2, jet);
    const Eigen::Vector2d &d1 = jet[1], &d2 = jet[2];
    const Eigen::Vector2d e = jet[0] - q;
    const double step = e.dot(d1) / (d1.squaredNorm() + e.dot(d2));
    t = std::clamp(t - step, ax.a, ax.b);
    if (std::abs(step) < 1e-15 * (ax.b - ax.a)) break;
  }
  return t;
}

// The thickest circle: the widest of `circles` refined by golden-section search on the
// axis between its neighbours (widened by their spacing), and its arc length from the LE.
void thickest_circle(const SampledProfile& pr, const AxisCurve& ax, const ArcLengthTable& table,
                     const std::vector<InscribedCircle>& circles, CamberResult& res) {
  int k = 0;
  for (std::size_t i = 0; i < circles.size(); ++i)
    if (circles[i].radius > circles[k].radius) k = static_cast<int>(i);
  const InscribedCircle& lo_c = circles[std::max(k - 1, 0)];
  const InscribedCircle& hi_c = circles[std::min<std::size_t>(k + 1, circles.size() - 1)];
  // The axis at the table's parameters, evaluated once for the three searches.
  std::vector<Eigen::Vector2d> points(table.t.size());
  for (std::size_t i = 0; i < table.t.size(); ++i) points[i] = ax.spline.point(table.t[i]);
  double a = nearest_param(ax, table, points, lo_c.center), b = nearest_param(ax, table, points, hi_c.center);
  if (a > b) std::swap(a, b);
  a = std::max(a - (b - a), ax.a);
  b = std::min(b + (b - a), ax.b);
  InscribedCircle best = circles[k];
  golden_max(a, b, pr.scale, [&](double t) {
    InscribedCircle c;
    Eigen::Vector2d jet[2];
    ax.spline.derivatives(t, 1, jet);
    const Eigen::Vector2d n = left_normal(jet[1].normalized());
    if (detail::solve_circle(pr.fast, jet[0], n, best.t_left, best.t_right, pr.scale, c) &&
        detail::valid_circle(pr, n, c, nullptr)) {
      if (c.radius > best.radius) best = c;
      return c.radius;
    }
    return -1.0;
  });
  res.thickest = best;
  res.thickest_s =
      res.ext_le + table.arc(foot_on_axis(ax, nearest_param(ax, table, points, best.center), best.center));
}

// +1 when the pressure side lies left of the LE-to-TE direction, -1 right: the pressure
// side is the concave side of the camber line, opposite to its bulge from the chord.
int pressure_side(const CamberResult& res) {
  const Eigen::Vector2d chord = (res.te.point - res.le.point).normalized();
  double bulge = 0;
  for (const auto& p : res.points) bulge += cross(chord, p - res.le.point);
  return bulge > 0 ? -1 : 1;
}

}  // namespace

namespace detail {

AxisSample axis_sample(const AxisCurve& ax, const ArcLengthTable& table, double ext_le, double s) {
  AxisSample a;
  a.t = table.param(s - ext_le);
  Eigen::Vector2d jet[2];  // point and first derivative, from one evaluation
  ax.spline.derivatives(a.t, 1, jet);
  a.point = jet[0];
  a.normal = left_normal(jet[1].normalized());
  return a;
}

Eigen::Vector2d extension_point(const CamberResult& camber, double s) {
  return s <= camber.ext_le ? Eigen::Vector2d(camber.le.point + s * camber.le_tangent)
                            : Eigen::Vector2d(camber.te.point - (camber.length - s) * camber.te_tangent);
}

}  // namespace detail

CamberResult camber_line(const BSpline& profile, const CamberOptions& options,
                         const std::vector<Eigen::Vector2d>& measured) {
  detail::check_options(options);
  detail::check_profile_degree(profile);
  return detail::camber_line(SampledProfile(profile, options.medial.samples), options, measured, nullptr);
}

namespace detail {

CamberResult camber_line(const SampledProfile& pr, const CamberOptions& options,
                         const std::vector<Eigen::Vector2d>& measured, std::unique_ptr<CamberAxis>* axis) {
  CamberResult res;
  res.orientation = pr.sigma;
  AxisCurve medial_curve;
  MedialAxis ma = detail::medial_axis(pr, options.medial, &medial_curve);  // (the same samples)
  std::vector<InscribedCircle> medial = ma.circles;
  const BranchSize size = blade_size(medial, options);
  prune_ends(medial, options.edge_prune);
  orient(medial, options, res);
  // The medial axis ends with the axis through its own circles: the same centres (no end
  // pruned, the order kept) would give that axis again.
  AxisCurve ax = same_centres(medial, ma.circles) ? std::move(medial_curve)
                                                  : detail::make_axis(detail::centers(medial), 1e-8);
  Ends ends = settle_edges(pr, medial, ax, size, options, measured);
  if (options.tangent_span > 0)
    detail::weigh_bridged(pr.fast, measured, 2 * options.tangent_span * size.length,
                          options.end_hole * size.length, options.thickness_hole_spacings, ends.circles);
  const std::vector<InscribedCircle>& circles = ends.circles;
  std::tie(res.le_tangent, res.te_tangent) = end_tangents(ax, circles, options.tangent_span, size.length);
  fit_model(circles, options.tangent_span * size.length, res);
  final_edge_point(pr, circles.front(), -res.le_tangent, ends.le);
  final_edge_point(pr, circles.back(), res.te_tangent, ends.te);
  for (Edge* e : {&ends.le, &ends.te})
    if (e->shape == EdgeShape::sharp ||
        (options.edge == EdgeModel::automatic && e->shape != EdgeShape::round))
      e->radius = e->radius_sigma = 0;
  res.le = ends.le;
  res.te = ends.te;
  ma.circles = circles;
  ma.curve = ax.spline;
  res.medial = ma;

  const ArcLengthTable table(ax.f, 4 * static_cast<int>(circles.size()));
  res.ext_le = (res.le.point - circles.front().center).norm();
  res.ext_te = (res.te.point - circles.back().center).norm();
  res.length = res.ext_le + table.length() + res.ext_te;
  sample_line(pr, ax, table, circles, std::max(options.samples, 3), res);
  off_axis_check(pr, res);
  thickest_circle(pr, ax, table, circles, res);
  res.pressure_side = pressure_side(res);
  if (axis) *axis = std::make_unique<CamberAxis>(CamberAxis{ax, table});
  return res;
}

}  // namespace detail

}  // namespace section

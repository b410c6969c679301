// SPDX-License-Identifier: GPL-3.0-or-later
#include "section/checks.h"

#include "detail/flanks.h"
#include "detail/sampled_profile.h"
#include "detail/section_checks.h"
#include "section/error.h"

#include <Eigen/Cholesky>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <string>

namespace section {

using detail::cross;
using detail::degrees;
using detail::pi;
using detail::SampledProfile;

const char* check_name(Check check) {
  for (const auto& c : check_names)
    if (c.check == check) return c.name;
  return "unknown";
}

namespace {

// True when the space-separated `list` holds the word `word`.
bool lists(const char* list, const char* word) {
  const std::size_t n = std::strlen(word);
  for (const char* p = std::strstr(list, word); p; p = std::strstr(p + 1, word))
    if ((p == list || p[-1] == ' ') && (p[n] == ' ' || p[n] == '\0')) return true;
  return false;
}

// The columns that are the same whichever end is the LE.
constexpr const char* either_end = "chord camber_length max_thickness area caliper_chord centroid wall";

}  // namespace

CheckBits flags_mask(double value) {
  return value > 0 && value < std::ldexp(1.0, check_count) ? static_cast<CheckBits>(value) : 0;
}

std::string check_names_text(CheckBits flags, const char* separator) {
  if (!separator) throw Error("checks: check_names_text needs a separator, not a null pointer");
  std::string out;
  for (const auto& c : check_names)
    if (flags & bit(c.check)) out += (out.empty() ? "" : separator) + std::string(c.name);
  return out;
}

CheckBits checks_flagging(CheckBits flags, const char* column) {
  if (!column) throw Error("checks: checks_flagging needs a column name, not a null pointer");
  CheckBits out = 0;
  for (const auto& c : check_names) {
    if (!(flags & bit(c.check))) continue;
    const bool flagged =
        c.check == Check::units || c.check == Check::registration || c.check == Check::airfoil ? true
        : c.check == Check::le_choice ? !lists(either_end, column)
                                      : lists(c.columns, column);
    if (flagged) out |= bit(c.check);
  }
  return out;
}

namespace {

// Distance from q to the profile: the nearest sample's segment, refined by Newton on the
// exact curve (the foot point), and whether q lies inside (crossings of a ray along +u).
struct Foot {
  double distance = 0;
  bool inside = false;
};

Foot foot(const SampledProfile& pr, const Eigen::Vector2d& q) {
  Foot f;
  f.inside = detail::inside_samples(pr, q);
  const double t = detail::foot_parameter(pr, q, pr.ts[pr.nearest(q)]);
  f.distance = std::min((pr.fast.point(pr.fast.locate(t)) - q).norm(), pr.sample_distance(q));
  return f;
}

// Extent of the profile along the unit direction e (its samples, refined by Newton at the
// two extremes).
double extent(const SampledProfile& pr, const Eigen::Vector2d& e) {
  int lo = 0, hi = 0;
  const int n = static_cast<int>(pr.samples.size());
  for (int i = 1; i < n; ++i) {
    if (pr.samples[i].dot(e) > pr.samples[hi].dot(e)) hi = i;
    if (pr.samples[i].dot(e) < pr.samples[lo].dot(e)) lo = i;
  }
  auto refine = [&](int i, double sign) {
    double t = pr.ts[i], best = sign * pr.samples[i].dot(e);
    const double h = pr.period / n;
    detail::PiecewiseCurve::Cursor at;  // Newton's steps are short: the span before is tried first
    for (int it = 0; it < 30; ++it) {
      const detail::CurveJet j = pr.fast.jet(pr.fast.locate(t, at));
      const double g = sign * j.d1.dot(e), dg = sign * j.d2.dot(e);
      if (!(dg < 0)) break;
      const double step = std::clamp(g / dg, -h, h);
      t -= step;
      best = std::max(best, sign * pr.fast.point(pr.fast.locate(t, at)).dot(e));
      if (std::abs(step) < 1e-14 * pr.period) break;
    }
    return best;
  };
  return refine(hi, 1) + refine(lo, -1);
}

// The point of the sampled camber line at arc length s (linear between samples).
Eigen::Vector2d camber_at(const CamberResult& c, double s) {
  const auto it = std::lower_bound(c.s.begin(), c.s.end(), s);
  if (it == c.s.begin()) return c.points.front();
  if (it == c.s.end()) return c.points.back();
  const std::size_t k = static_cast<std::size_t>(it - c.s.begin());
  const double w = (s - c.s[k - 1]) / std::max(c.s[k] - c.s[k - 1], 1e-300);
  return (1 - w) * c.points[k - 1] + w * c.points[k];
}

struct Checker {
  const SampledProfile& pr;
  const CamberResult& camber;
  const SectionParams& params;
  const CheckOptions& options;
  double tol;  // a distance that is off
  SectionCheck out;

  void fail(Check c, double value, double limit) {
    out.flags |= bit(c);
    out.findings.push_back({c, value, limit});
  }

  // A round edge measured by a circle (not a vertex, a face, or radius 0).
  static bool has_circle(const Edge& e) {
    return e.shape == EdgeShape::round && !e.vertex && !(e.face > 0) && e.radius > 0;
  }

  // A round edge's circle: inside the blade, and on the profile over its arc.
  void edge_circle(const Edge& e, Check c) {
    if (!has_circle(e)) return;
    const Foot f = foot(pr, e.center);
    const double pass = f.inside ? e.radius - f.distance : e.radius + f.distance;
    const double limit = options.noise_factor * std::max(options.noise, e.fit_rms) + options.floor * pr.scale;
    if (pass > limit) return fail(c, pass, limit);
    const double short_by = e.circular ? arc_shortfall(e, c == Check::le_radius) : 0;  // else flagged as such
    if (short_by > options.arc_shortfall)
      fail(c == Check::le_radius ? Check::le_circle : Check::te_circle, short_by, options.arc_shortfall);
    if (!(options.noise > 0) || !e.circular) return;  // not circular: flagged as such (le_circle)
    double worst = 0;
    const double span = e.arc_t1 - e.arc_t0;  // the walks from the edge point, unwrapped
    for (int i = 0; i <= 60; ++i)
      worst =
          std::max(worst, std::abs((pr.fast.point(e.arc_t0 + span * i / 60) - e.center).norm() - e.radius));
    const double arc_limit =
        2 * options.noise_factor * std::max({options.noise, 1e-4 * e.radius, e.sampling});
    if (worst > arc_limit) fail(c, worst, arc_limit);
  }

  // A round edge's radius that its points cannot fix to the tolerance: twice its spread
  // over the tolerance's share of it (docs/CAMBER.md, "Checks"). The spread: the standard
  // error of the circle fitted on the measured points, taken or not (R +- 2 sigma holds the
  // truth about 19 times in 20); else, under 8 points on the arc, the noise (the circle
  // rests on the curve through a handful of points, each off by about the noise). Checked
  // when the circle passed the others (one finding a check).
  void edge_spread(const Edge& e, Check c) {
    if (out.flags & bit(c)) return;
    if (!has_circle(e)) return;
    const double tolerance =
        c == Check::le_radius ? options.le_radius_tolerance : options.te_radius_tolerance;
    // Under 8 measured points on the arc: the spread a circle fitted on them would have at
    // the points' noise, from where they lie (a TE of 0.22 mm with 4 of them was reported
    // 17 % small, flagged by no spread when the noise alone stood for it), and at least the
    // noise. The circle then rests on the curve between them: where that arc strays from its
    // circle by more than the noise (its fit rms), the curve between the points is that
    // uncertain, not the points alone (a 0.29 mm LE with 4 points, the arc 3.2 um off its
    // circle at 2 um of noise, was 3.85 % small, unflagged). With the noise unknown (0) the
    // spread is not judged, as before.
    const double spread = detail::edge_spread(e, options.noise);
    if (!(tolerance > 0) || !(spread > 0) || !(2 * spread > tolerance * e.radius)) return;
    out.flags |= bit(c);
    out.findings.push_back({c, 2 * spread, tolerance * e.radius, true});
  }

  // Degrees by which a round edge's arc falls short of the profile's turning between its
  // flanks (taken from the arc's ends to `reach` beyond): a circle tangent to its flanks
  // subtends all of it, 180 deg less the wedge; one fitted to a bump or finger the spline
  // left at the tip subtends little more than the core it grew from.
  double arc_shortfall(const Edge& e, bool le) const {
    const int n = static_cast<int>(pr.samples.size());
    // Past the whole edge even when the circle fits a finger: twice the blade's inscribed
    // radius 5 % of the camber length in from the edge point.
    const double s = le ? 0.05 * camber.length : 0.95 * camber.length;
    const auto at_s = std::lower_bound(camber.s.begin(), camber.s.end(), s);
    const double inside = at_s == camber.s.end() ? 0 : camber.radius[std::size_t(at_s - camber.s.begin())];
    const double reach = 2 * std::max(e.radius, inside);
    Eigen::Vector2d travel[2];  // the profile's direction along each flank (in t)
    for (int side = 0; side < 2; ++side) {
      const Eigen::Vector2d end = pr.fast.point(pr.wrap(side ? e.arc_t1 : e.arc_t0));
      const int at = pr.nearest(end);
      int k = 1, i = at;
      for (; k < n / 4 && (pr.samples[i] - end).norm() < reach; ++k) i = ((at + (side ? k : -k)) % n + n) % n;
      if (k >= n / 4) return 0;  // flanks longer than a quarter of the profile: no wedge to compare
      travel[side] = (side ? pr.samples[i] - end : end - pr.samples[i]).normalized();
    }
    // Under 180 deg on converging or parallel flanks; diverging ones (over 180) are never short.
    const double turning = std::acos(std::clamp(travel[0].dot(travel[1]), -1.0, 1.0)) * 180 / pi;
    return turning - e.arc;
  }

  void edge_point(const Edge& e, Check c, Check vertex) {
    const double d = foot(pr, e.point).distance;
    const double limit = options.noise_factor * options.noise + options.floor * pr.scale;
    if (!e.vertex) {
      if (d > limit) fail(c, d, limit);
      return;
    }
    // A sharp edge's vertex is where its flanks meet, off the fitted curve's rounding of
    // the corner. Its flanks meet at a wedge of 2a: a shift of the profile by `limit` moves
    // the vertex by limit / sin(a) along the edge (a thin wedge: far); and the flanks taken
    // farther out (2-6 % of the camber length, beyond camber's 1-4 % of the profile's
    // size) must meet where these did.
    const double sine = detail::wedge_sine(pr, e.point, options.vertex_reach * camber.length);
    double off = sine > 0 ? limit / sine : 0;
    const detail::FlankVertex farther =
        detail::flank_meeting(pr, e.point, options.vertex_reach * camber.length,
                              3 * options.vertex_reach * camber.length, options.noise);
    // (Counted where its lines' and parabolas' meetings agree to better than half that.)
    const double apart = (farther.point - e.point).norm();
    if (farther.found && apart > 2 * farther.models_apart) off = std::max(off, apart);
    if (off > 2 * limit) fail(vertex, off, 2 * limit);
  }

  // How far the profile near an edge reaches beyond its edge point along the camber's
  // outward end direction `out` (0 when the point is the end, as on a circle met along
  // its radius); limit: the edge's fit (a nose that is not circular), a face's half width.
  void edge_end(const Edge& e, const Eigen::Vector2d& out_dir, double& gap, double& limit) const {
    const double reach = params.max_thickness + e.radius + e.face;
    gap = 0;
    for (const auto& p : pr.samples)
      if ((p - e.point).norm() < reach) gap = std::max(gap, (p - e.point).dot(out_dir));
    // A vertex lies off the fitted curve's tip, the curve's rounding or overshoot of the
    // corner (te_vertex checks the vertex itself).
    limit = options.noise_factor * std::max(options.noise, e.fit_rms) + options.floor * pr.scale +
            0.5 * e.face + (e.vertex ? (pr.fast.point(e.t) - e.point).norm() : 0);
  }

  // The chord: its edge points at the ends of the profile (a point up a flank makes it
  // short), the chord stated their distance (a params row edited, or made by other code,
  // is not this profile's), and the caliper chord the profile's extent along its line.
  void chord() {
    double gap_le = 0, gap_te = 0, limit_le = 0, limit_te = 0;
    edge_end(camber.le, -camber.le_tangent, gap_le, limit_le);
    edge_end(camber.te, camber.te_tangent, gap_te, limit_te);
    const double stated = std::abs(params.chord - (params.te_point - params.le_point).norm());
    // The largest excess over its limit, if any (a chord that is not a number: flagged).
    const double excess_le = gap_le - limit_le, excess_te = gap_te - limit_te;
    if (!(stated <= tol) && (std::isnan(stated) || stated - tol >= std::max(excess_le, excess_te))) {
      fail(Check::chord, stated, tol);
    } else if (excess_le > excess_te) {
      if (gap_le > limit_le) fail(Check::chord, gap_le, limit_le);
    } else if (gap_te > limit_te) {
      fail(Check::chord, gap_te, limit_te);
    }
    const double a = params.caliper_stagger * pi / 180;
    const double caliper_gap = std::abs(extent(pr, {std::cos(a), std::sin(a)}) - params.caliper_chord);
    if (caliper_gap > tol) fail(Check::caliper, caliper_gap, tol);
  }

  // The profile's own uncertainty: a fit with about as many coefficients as points follows
  // their noise (its rms then hides it), and every length measured on it carries it; the
  // thickness its two sides' at the thickest circle's contacts.
  void noise(std::size_t coefficients) {
    if (!(options.points > 0) || !(options.points_noise > 0)) return;
    const double share = std::min(1.0, double(coefficients) / options.points);
    const double sigma = std::max(options.points_noise, options.noise);
    double stray = options.noise_factor * sigma * std::sqrt(share);
    // The thickness's own standard error (its two contacts' shares: value_sigmas).
    if (!options.point_params.empty() && camber.thickest.radius > 0)
      stray = std::max(stray, options.noise_factor * out.sigmas.max_thickness);
    const double limit = options.accuracy * pr.scale;
    if (stray > limit) fail(Check::noise, stray, limit);
  }

  // Each value whose standard errors (value_sigmas of them) exceed its tolerance.
  void value_noise() {
    const double k = options.value_sigmas;
    if (!(k > 0)) return;
    const ValueSigmas& s = out.sigmas;
    const double chord = params.chord;
    const auto judge = [&](Check c, double sigma, double tolerance) {
      if (k * sigma > tolerance) fail(c, k * sigma, tolerance);
    };
    judge(Check::chord_noise, s.chord, options.chord_tolerance * chord);
    judge(Check::thickness_noise, s.max_thickness, options.thickness_tolerance * chord);
    judge(Check::inlet_noise, s.inlet_angle, options.angle_tolerance);
    judge(Check::outlet_noise, s.outlet_angle, options.angle_tolerance);
  }

  // A section that is no airfoil: a platform's, a root block's or a fixture's (a plate, a
  // box) measured as a blade gives a chord and a thickness no check of its edges doubts.
  void airfoil() {
    const double t = params.max_thickness;
    const double ratio = t / std::max(params.chord, 1e-300);
    if (!(ratio <= options.airfoil_thickness)) return fail(Check::airfoil, ratio, options.airfoil_thickness);
    const double faces = std::min(camber.le.face, camber.te.face) / std::max(t, 1e-300);
    if (faces > options.airfoil_face) fail(Check::airfoil, faces, options.airfoil_face);
  }

  // The end direction extrapolated from the camber line's two chords nearest the edge
  // (`sign` +1 from the LE inward, -1 from the TE), against the reported end tangent.
  void end_angle(double reported, double s0, double sign, Check c) {
    const double l = options.tangent_length * camber.length;
    if (!(l > 0)) return;
    const Eigen::Vector2d p0 = camber_at(camber, s0), p1 = camber_at(camber, s0 + sign * l),
                          p2 = camber_at(camber, s0 + 2 * sign * l);
    // Directions toward the TE.
    const double a1 = degrees(sign * (p1 - p0)), a2 = degrees(sign * (p2 - p1));
    const double turn = detail::wrap_degrees(a1 - a2);
    const double expected = detail::wrap_degrees(a1 + 0.5 * turn);
    const double noise = options.noise_factor * options.noise / l * 180 / pi;
    // A constant curvature extrapolates exactly; a quarter of the turning allows its change.
    const double limit = std::max(options.angle_floor, 0.25 * std::abs(turn)) + noise;
    const double off = std::abs(detail::wrap_degrees(reported - expected));
    if (off > limit) fail(c, off, limit);
  }

  // The end direction against the fit that gave it: where a quartic over the same span
  // turns it by more than fit_model plus the tilt the noise gives over that span, the
  // cubic's own shape set the angle, not the camber line. An edge that is not circular
  // has its angle flagged already (le_circle, te_circle: the axis bends within the nose).
  void end_fit(const Edge& e, double model, Check c) {
    const double span = camber.tangent_span_length;
    if (!(span > 0) || !e.circular) return;
    const double limit = options.fit_model + options.noise_factor * options.noise / span * 180 / pi;
    if (model > limit) fail(c, model, limit);
  }
};

// Options a NaN or a negative value would turn off without a word: every check silenced.
void check_options(const CheckOptions& o) {
  const double values[] = {o.noise,           o.points_noise,
                           o.points,          o.accuracy,
                           o.noise_factor,    o.floor,
                           o.tangent_length,  o.angle_floor,
                           o.fit_model,       o.vertex_reach,
                           o.arc_shortfall,   o.airfoil_thickness,
                           o.airfoil_face,    o.value_sigmas,
                           o.chord_tolerance, o.thickness_tolerance,
                           o.angle_tolerance, o.noise_correlation};
  for (double v : values)
    if (!(v >= 0) || !std::isfinite(v)) throw Error("checks: an option is negative or not finite");
}

}  // namespace

PointsNoise points_noise(const BSpline& profile, const std::vector<Eigen::Vector2d>& points) {
  for (std::size_t i = 0; i < points.size(); ++i)
    if (!points[i].allFinite()) throw Error("checks: point " + std::to_string(i) + " is not finite");
  if (points.size() < 12) return {};
  return detail::points_noise(SampledProfile(profile, detail::check_samples), points);
}

SectionCheck check_section(const BSpline& profile, const CamberResult& camber, const SectionParams& params,
                           const CheckOptions& options) {
  check_options(options);
  return detail::check_section(SampledProfile(profile, detail::check_samples), camber, params, options);
}

namespace detail {

PointsNoise points_noise(const SampledProfile& pr, const std::vector<Eigen::Vector2d>& points) {
  std::size_t n = points.size();
  if (n < 12) return {};
  // The points in the profile's order (by their nearest sample's parameter).
  std::vector<std::pair<double, std::size_t>> all(n);
  int at = 0;
  for (std::size_t i = 0; i < n; ++i) {
    at = pr.nearest(points[i], at);
    all[i] = {pr.ts[static_cast<std::size_t>(at)], i};
  }
  std::sort(all.begin(), all.end());
  // Points much closer than the mean spacing share their noise (a grid cut between its
  // lines gives two points per cell, both interpolated from the same vertices): one is kept.
  double perimeter = 0;
  for (std::size_t i = 0; i < pr.samples.size(); ++i)
    perimeter += (pr.samples[(i + 1) % pr.samples.size()] - pr.samples[i]).norm();
  const double least = 0.5 * perimeter / double(n);
  std::vector<std::pair<double, std::size_t>> order;
  for (const auto& p : all)
    if (order.empty() || (points[p.second] - points[order.back().second]).norm() >= least) order.push_back(p);
  n = order.size();
  if (n < 12) return {};
  std::vector<double> scatter;
  scatter.reserve(n);
  detail::PiecewiseCurve::Cursor span_at;  // in order: the span before is tried first
  for (std::size_t k = 0; k < n; ++k) {
    const std::size_t i = order[k].second;
    const detail::CurveJet j = pr.fast.jet(pr.fast.locate(order[k].first, span_at));
    const Eigen::Vector2d along = j.d1.normalized(), normal = detail::left_normal(along);
    // The quadratic y(x) through the four neighbours (x along the profile's tangent, y
    // along its normal), predicted at the point: the residual over its standard deviation
    // in units of the noise (1 + the prediction's variance).
    Eigen::Matrix3d a = Eigen::Matrix3d::Zero();
    Eigen::Vector3d b = Eigen::Vector3d::Zero();
    for (const long off : {-2L, -1L, 1L, 2L}) {
      const Eigen::Vector2d d = points[order[std::size_t((long(k + n) + off) % long(n))].second] - points[i];
      const Eigen::Vector3d row(1, d.dot(along), d.dot(along) * d.dot(along));
      a += row * row.transpose();
      b += row * d.dot(normal);
    }
    const Eigen::LDLT<Eigen::Matrix3d> ldlt(a);
    const Eigen::Vector3d c = ldlt.solve(b), e0 = ldlt.solve(Eigen::Vector3d::UnitX());
    if (ldlt.info() != Eigen::Success || !c.allFinite() || !(e0.x() > 0) || e0.x() > 100) continue;
    scatter.push_back(std::abs(c.x()) / std::sqrt(1 + e0.x()));
  }
  if (scatter.size() < 8) return {};
  std::nth_element(scatter.begin(), scatter.begin() + long(scatter.size() / 2), scatter.end());
  std::vector<double> params;
  for (const auto& p : order) params.push_back(p.first);
  return {1.4826 * scatter[scatter.size() / 2], double(n), std::move(params)};
}

SectionCheck check_section(const SampledProfile& pr, const CamberResult& camber, const SectionParams& params,
                           const CheckOptions& options) {
  Checker k{pr, camber, params, options, options.noise_factor * options.noise + options.floor * pr.scale, {}};
  k.edge_circle(camber.le, Check::le_radius);
  k.edge_circle(camber.te, Check::te_radius);
  k.edge_spread(camber.le, Check::le_radius);
  k.edge_spread(camber.te, Check::te_radius);
  k.edge_point(camber.le, Check::le_point, Check::le_vertex);
  k.edge_point(camber.te, Check::te_point, Check::te_vertex);
  k.chord();
  k.end_angle(params.inlet_angle, camber.ext_le, 1, Check::inlet_angle);
  k.end_angle(params.outlet_angle, camber.length - camber.ext_te, -1, Check::outlet_angle);
  k.end_fit(camber.le, camber.le_fit_model, Check::inlet_fit);
  k.end_fit(camber.te, camber.te_fit_model, Check::outlet_fit);
  k.out.sigmas = detail::value_sigmas(pr, camber, params, options);
  k.noise(pr.curve.control.size());
  k.value_noise();
  k.airfoil();
  std::sort(k.out.findings.begin(), k.out.findings.end(),
            [](const Finding& a, const Finding& b) { return bit(a.check) < bit(b.check); });
  return k.out;
}

}  // namespace detail

}  // namespace section

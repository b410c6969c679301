// SPDX-License-Identifier: GPL-3.0-or-later
// compare: a measured section against its nominal; the steps are in compare_*.cpp.
#include "section/compare.h"

#include "compare_steps.h"
#include "io/text.h"
#include "section/error.h"
#include "section/units.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <deque>
#include <cmath>
#include <numeric>
#include <string>

namespace section {

namespace {

using compare::Block;
using compare::Geometry;
constexpr double degree = 3.14159265358979323846 / 180;

void check(const CompareOptions& o) {
  if (!(o.edge_zone > 0 && o.edge_zone < 0.5))
    throw Error("compare: the edge zone must lie between 0 and 0.5 of the chord");
  if (!(o.hole >= 0) || !(o.hole_spacings > 0) || !(o.hole_floor >= 0) ||
      !std::isfinite(o.outlier_distance) || !(o.outlier_floor >= 0))
    throw Error(
        "compare: the hole length, hole spacings and outlier distances must be finite and not negative");
  for (double w : o.fit.weights)
    if (!(w >= 0) || !std::isfinite(w))
      throw Error("compare: the zone weights must be finite and not negative");
  if (o.fit.method == FitMethod::weighted &&
      o.fit.weights[1] + o.fit.weights[2] + o.fit.weights[3] + o.fit.weights[4] <= 0)
    throw Error("compare: a weighted fit needs a zone of weight above 0");
  if (!(o.fit.direction.norm() > 0) || !std::isfinite(o.fit.direction.norm()))
    throw Error("compare: the fit's direction must be a finite vector other than 0");
  // INT_MAX iterations with a convergence of 0 ran for hours.
  if (o.fit.max_iterations < 1 || o.fit.max_iterations > 10000 || !(o.fit.convergence >= 0) ||
      !std::isfinite(o.fit.convergence))
    throw Error("compare: the fit's iterations must be 1 to 10000, its convergence 0 or more and finite");
}

int freedoms(FitFreedom f) {
  switch (f) {
    case FitFreedom::none:
      return 0;
    case FitFreedom::translation_along:
    case FitFreedom::rotation:
      return 1;
    case FitFreedom::translation:
      return 2;
    default:
      return 3;
  }
}

// The local move (angle, u, v) each fit parameter makes, for a motion in the basis (e1, e2).
Eigen::Matrix<double, 3, Eigen::Dynamic> selection(FitFreedom f, const Eigen::Vector2d& direction) {
  Eigen::Matrix<double, 3, Eigen::Dynamic> s(3, freedoms(f));
  if (f == FitFreedom::all) s.setIdentity();
  if (f == FitFreedom::translation) s << 0, 0, 1, 0, 0, 1;
  if (f == FitFreedom::translation_along) s << 0, direction.normalized();
  if (f == FitFreedom::rotation) s << 1, 0, 0;
  return s;
}

Eigen::Vector2d mean(const std::vector<Eigen::Vector2d>& p) {
  Eigen::Vector2d m(0, 0);
  for (const auto& q : p) m += q;
  return p.empty() ? m : Eigen::Vector2d(m / static_cast<double>(p.size()));
}

void check_points(const std::vector<Eigen::Vector2d>& measured, int dof) {
  for (std::size_t i = 0; i < measured.size(); ++i)
    if (!std::isfinite(measured[i].x()) || !std::isfinite(measured[i].y()))
      throw Error("compare: measured point " + std::to_string(i) + " is not finite");
    else if (!(measured[i].cwiseAbs().maxCoeff() <=
               detail::max_coordinate))  // squared distances overflowed from 1e154
      throw Error("compare: measured point " + std::to_string(i) + " has a coordinate beyond +-1e15");
  if (measured.size() < static_cast<std::size_t>(std::max(dof + 1, 3)))
    throw Error("compare: " + std::to_string(measured.size()) + " measured points; at least " +
                std::to_string(std::max(dof + 1, 3)) + " are needed");
}

// Outliers of a placed block: isolated points farther from the nominal than the distance
// (automatic: 6 noise sigmas, at least the floor), by fitspline's rule.
std::vector<char> outliers(const Block& b, const CompareOptions& o, double& distance) {
  std::vector<char> out(b.points.size(), 0);
  distance = 0;
  if (o.outlier_distance < 0 || b.points.size() < 5) return out;
  fit::Feet f = b.feet;
  for (std::size_t i = 0; i < f.signed_distance.size(); ++i) f.signed_distance[i] = b.deviation(i);
  const std::vector<double> ones(b.points.size(), 1.0);
  distance =
      o.outlier_distance > 0 ? o.outlier_distance : std::max(o.outlier_floor, 6 * fit::noise_sigma(f, ones));
  const std::vector<double> w = fit::outlier_weights(f, b.moved, distance);
  for (std::size_t i = 0; i < w.size(); ++i) out[i] = w[i] > 0 ? 0 : 1;
  return out;
}

// Leaves the points marked `out` out of a placed block; the others keep their feet, which
// the placing tracks (no full search again).
void leave_out(Block& b, const std::vector<char>& out) {
  std::vector<std::size_t> index(out.size());
  std::vector<Eigen::Vector2d> kept;
  fit::Feet feet;
  for (std::size_t k = 0; k < out.size(); ++k) {
    index[k] = kept.size();
    if (out[k]) continue;
    kept.push_back(b.points[k]);
    feet.t.push_back(b.feet.t[k]);
  }
  for (std::size_t k : b.feet.order)
    if (!out[k]) feet.order.push_back(index[k]);
  feet.signed_distance.assign(kept.size(), 0);
  b.points = std::move(kept);
  b.feet = std::move(feet);
  b.place();
}

// The fit of the blocks (all points placed at the start), outliers left out after a first
// least-squares fit; `out[b]` marks block b's outliers, `distance[b]` the distance used.
compare::FitRun best_fit(std::vector<Block>& blocks, const CompareOptions& o,
                         std::vector<std::vector<char>>& out, std::vector<double>& distance) {
  compare::FitRun run = fit_least_squares(blocks, o.fit);
  out.assign(blocks.size(), {});
  distance.assign(blocks.size(), 0);
  bool any = false;
  for (std::size_t i = 0; i < blocks.size(); ++i) {
    out[i] = outliers(blocks[i], o, distance[i]);
    if (std::find(out[i].begin(), out[i].end(), 1) == out[i].end()) continue;
    any = true;
    leave_out(blocks[i], out[i]);
  }
  auto add = [&](const compare::FitRun& r) {
    run.iterations += r.iterations;
    run.converged = run.converged && r.converged;
  };
  if (any) add(fit_least_squares(blocks, o.fit));
  if (o.fit.method == FitMethod::weighted) {
    for (Block& b : blocks) b.zone_weight.assign(o.fit.weights.begin(), o.fit.weights.end());
    add(fit_least_squares(blocks, o.fit));
  } else if (o.fit.method == FitMethod::minimum_zone) {
    add(fit_minimum_zone(blocks, o.fit));
  }
  return run;
}

double median_spacing(std::vector<double> s, double perimeter) {
  if (s.size() < 2) return 0;
  std::vector<double> gaps;
  for (std::size_t i = 0; i < s.size(); ++i)
    gaps.push_back(i + 1 < s.size() ? s[i + 1] - s[i] : s[0] + perimeter - s[i]);
  return fit::median(gaps);
}

// Zone results of the deviations after the fit: extremes, form, coverage.
void measure_zones(const Geometry& g, const CompareOptions& o, SectionComparison& c) {
  std::vector<double> s;
  for (const PointDeviation& p : c.points)
    if (!p.outlier) s.push_back(g.position(p.t));
  std::sort(s.begin(), s.end());
  c.hole = o.hole > 0 ? o.hole : std::max(o.hole_floor, o.hole_spacings * median_spacing(s, g.perimeter));
  for (int z = 0; z < zone_count; ++z) {
    ZoneResult& r = c.zones[z];
    r = ZoneResult{};
    bool first = true;
    for (const PointDeviation& p : c.points) {
      if (p.outlier || (z != 0 && static_cast<int>(p.zone) != z)) continue;
      r.min = first ? p.after : std::min(r.min, p.after);
      r.max = first ? p.after : std::max(r.max, p.after);
      first = false;
      ++r.points;
    }
    r.form = r.max - r.min;
    const auto [a, b] = g.interval(static_cast<Zone>(z));
    r.length = b - a;
    const auto lo = std::lower_bound(s.begin(), s.end(), a), hi = std::lower_bound(s.begin(), s.end(), b);
    if (lo == hi) {
      r.unmeasured = r.length;
    } else if (z == 0) {
      r.unmeasured = s.front() + g.perimeter - s.back();
      for (std::size_t i = 1; i < s.size(); ++i) r.unmeasured = std::max(r.unmeasured, s[i] - s[i - 1]);
    } else {
      r.unmeasured = std::max(*lo - a, b - *(hi - 1));
      for (auto it = lo + 1; it < hi; ++it) r.unmeasured = std::max(r.unmeasured, *it - *(it - 1));
    }
    r.measured = r.points > 0 && r.unmeasured <= c.hole;
  }
}

// A section's results from its block after the fit: every point (outliers included) at the
// final motion, before and after, and the zones.
SectionComparison results(const Geometry& g, const std::vector<Eigen::Vector2d>& measured,
                          const Block& fitted, const fit::Feet& before, const std::vector<char>& out,
                          const CompareOptions& o) {
  SectionComparison c;
  // Every point at the final motion, its foot tracked from the fit's (an outlier's from
  // before the fit): no full search again.
  Block all = fitted;
  if (fitted.points.size() != measured.size()) {
    all.points = measured;
    all.feet.t = before.t;
    all.feet.signed_distance.assign(measured.size(), 0);
    for (std::size_t i = 0, j = 0; i < measured.size(); ++i)
      if (!out[i]) all.feet.t[i] = fitted.feet.t[j++];
    all.feet.order = before.order;  // nearly sorted: place() sorts it
    all.place();
  }
  c.fit.motion.angle = fitted.angle / degree;
  c.fit.motion.translation = fitted.translation;
  double sb = 0, sa = 0;
  int n = 0;
  for (std::size_t i = 0; i < measured.size(); ++i) {
    PointDeviation p;
    p.point = all.moved[i];
    p.t = all.feet.t[i];
    p.foot = g.pc.point(p.t);
    p.normal = g.normal_at(p.t);
    p.before = g.orientation * before.signed_distance[i];
    p.after = all.deviation(i);
    p.zone = g.zone_at(p.t);
    p.outlier = !out.empty() && out[i];
    c.outliers += p.outlier;
    if (!p.outlier) {
      sb += p.before * p.before;
      sa += p.after * p.after;
      c.fit.max_before = std::max(c.fit.max_before, std::abs(p.before));
      c.fit.max_after = std::max(c.fit.max_after, std::abs(p.after));
      ++n;
    }
    c.points.push_back(p);
  }
  c.fit.rms_before = n ? std::sqrt(sb / n) : 0;
  c.fit.rms_after = n ? std::sqrt(sa / n) : 0;
  measure_zones(g, o, c);
  return c;
}

// compare_section on a nominal's geometry, options and points checked.
SectionComparison compare_on(const Geometry& g, const std::vector<Eigen::Vector2d>& measured,
                             const CompareOptions& options) {
  std::vector<Block> blocks(1);
  Block& b = blocks[0];
  b.nominal = &g;
  b.points = measured;
  b.map = selection(options.fit.freedom, options.fit.direction);
  const bool about = options.fit.freedom == FitFreedom::rotation;
  b.center =
      about ? (std::isfinite(options.fit.center.x()) ? options.fit.center : g.centroid) : mean(measured);
  b.place();
  const fit::Feet before = b.feet;
  std::vector<std::vector<char>> out;
  std::vector<double> distance;
  const compare::FitRun run = best_fit(blocks, options, out, distance);
  SectionComparison c = results(g, measured, blocks[0], before, out[0], options);
  c.fit.iterations = run.iterations;
  c.fit.converged = run.converged;
  c.outlier_distance = distance[0];
  return c;
}

}  // namespace

const char* zone_name(Zone zone) {
  static const char* const names[] = {"whole", "le", "te", "pressure", "suction"};
  const int z = static_cast<int>(zone);
  return z >= 0 && z < 5 ? names[z] : "unknown";
}

Eigen::Vector2d Motion2::apply(const Eigen::Vector2d& p) const {
  const double a = angle * degree;
  return Eigen::Vector2d(std::cos(a) * p.x() - std::sin(a) * p.y(),
                         std::sin(a) * p.x() + std::cos(a) * p.y()) +
         translation;
}

SectionComparison compare_section(const NominalSection& nominal, const std::vector<Eigen::Vector2d>& measured,
                                  const CompareOptions& options) {
  check(options);
  check_points(measured, freedoms(options.fit.freedom));
  const Geometry g(nominal, options.edge_zone);
  return compare_on(g, measured, options);
}

PreparedNominal prepare_nominal(const NominalSection& nominal, const CompareOptions& options) {
  check(options);
  return {std::make_shared<const compare::Prepared>(nominal, options.edge_zone), options.edge_zone};
}

SectionComparison compare_section(const PreparedNominal& nominal,
                                  const std::vector<Eigen::Vector2d>& measured,
                                  const CompareOptions& options) {
  check(options);
  if (!nominal.prepared) throw Error("compare: the nominal has not been prepared (prepare_nominal)");
  if (nominal.edge_zone != options.edge_zone)
    throw Error("compare: the nominal was prepared for an edge zone of " + format_share(nominal.edge_zone) +
                " of the chord, the options ask for " + format_share(options.edge_zone) +
                ": prepare it with the same options");
  check_points(measured, freedoms(options.fit.freedom));
  return compare_on(nominal.prepared->geometry, measured, options);
}

BladeComparison compare_blade(const std::vector<ComparedSection>& sections, const CompareOptions& options) {
  check(options);
  BladeComparison out;
  if (sections.empty()) return out;
  const Frame& f0 = sections.front().frame;
  out.axis = f0.n;
  std::deque<Geometry> geos;  // not moved as it grows: the blocks point at them
  for (const ComparedSection& s : sections) {
    if (!s.nominal || !s.measured)
      throw Error("compare: a section of the blade has no nominal or no measured points");
    if (!s.frame.origin.allFinite() || !s.frame.n.allFinite() || !s.frame.u.allFinite() ||
        !s.frame.v.allFinite())
      throw Error("compare: a section's frame is not finite");
    check_points(*s.measured, freedoms(options.fit.freedom));
    if (std::abs(std::abs(s.frame.n.dot(f0.n)) - 1) > 1e-9)
      throw Error("compare: a whole-blade fit needs parallel section planes");
    geos.emplace_back(*s.nominal, options.edge_zone);
  }
  // The axis point: given, or the mean nominal centroid (rotation), or the mean measured point.
  Eigen::Vector3d c3 = options.fit.center_3d;
  if (!std::isfinite(c3.x())) {
    c3.setZero();
    for (std::size_t i = 0; i < sections.size(); ++i)
      c3 += sections[i].frame.to_world(
          options.fit.freedom == FitFreedom::rotation ? geos[i].centroid : mean(*sections[i].measured));
    c3 /= static_cast<double>(sections.size());
  }
  Eigen::Vector3d d3 = options.fit.direction_3d - options.fit.direction_3d.dot(f0.n) * f0.n;
  if (options.fit.freedom == FitFreedom::translation_along && !(d3.norm() > 1e-12))
    throw Error("compare: the fit's direction is normal to the section planes");
  const auto s = selection(options.fit.freedom, Eigen::Vector2d(d3.dot(f0.u), d3.dot(f0.v)).normalized());
  std::vector<Block> blocks(sections.size());
  std::vector<fit::Feet> before(sections.size());
  for (std::size_t i = 0; i < sections.size(); ++i) {
    const Frame& f = sections[i].frame;
    Eigen::Matrix3d local = Eigen::Matrix3d::Zero();
    local(0, 0) = f.n.dot(f0.n) > 0 ? 1 : -1;
    local.block<2, 2>(1, 1) << f0.u.dot(f.u), f0.v.dot(f.u), f0.u.dot(f.v), f0.v.dot(f.v);
    Block& b = blocks[i];
    b.nominal = &geos[i];
    b.points = *sections[i].measured;
    b.map = local * s;
    b.center = f.to_plane(c3);
    b.place();
    before[i] = b.feet;
  }
  std::vector<std::vector<char>> outs;
  std::vector<double> distance;
  const compare::FitRun run = best_fit(blocks, options, outs, distance);
  for (std::size_t i = 0; i < sections.size(); ++i) {
    out.sections.push_back(results(geos[i], *sections[i].measured, blocks[i], before[i], outs[i], options));
    out.sections.back().fit.iterations = run.iterations;
    out.sections.back().fit.converged = run.converged;
    out.sections.back().outlier_distance = distance[i];
  }
  // The motion in 3D from the first plane's: x -> R x + T with R about the normal.
  const double angle = blocks[0].angle;  // about f0.n, the axis
  const Eigen::Matrix3d r = Eigen::AngleAxisd(angle, f0.n).toRotationMatrix();
  out.angle = angle / degree;
  out.translation = f0.origin - r * f0.origin + f0.direction_to_world(blocks[0].translation);
  FitResult& fr = out.fit;
  fr.motion.angle = out.angle;
  fr.iterations = run.iterations;
  fr.converged = run.converged;
  double sb = 0, sa = 0;
  int n = 0;
  for (const SectionComparison& c : out.sections)
    for (const PointDeviation& p : c.points) {
      if (p.outlier) continue;
      sb += p.before * p.before;
      sa += p.after * p.after;
      fr.max_before = std::max(fr.max_before, std::abs(p.before));
      fr.max_after = std::max(fr.max_after, std::abs(p.after));
      ++n;
    }
  fr.rms_before = n ? std::sqrt(sb / n) : 0;
  fr.rms_after = n ? std::sqrt(sa / n) : 0;
  return out;
}

Verdict verdict(const Tolerance& t, double lowest, double highest, bool measured, double uncertainty) {
  // Limits that are not numbers, or a negative uncertainty, passed every value.
  if (std::isnan(t.low) || std::isnan(t.high) || t.low > t.high)
    throw Error("compare: a tolerance's limits are not numbers or not in order" +
                (t.where.empty() ? std::string() : " (" + t.where + ")"));
  if (uncertainty < 0) throw Error("compare: a negative uncertainty");
  if (lowest > highest) std::swap(lowest, highest);  // a range given the other way round
  const double u = uncertainty > 0 ? uncertainty : 0;
  if (lowest < t.low - u || highest > t.high + u) return Verdict::fail;
  if (!measured || std::isnan(lowest) || std::isnan(highest)) return Verdict::not_measured;
  // An uncertainty that is not a number decides nothing.
  if (std::isnan(uncertainty) || lowest < t.low + u || highest > t.high - u) return Verdict::uncertain;
  return Verdict::pass;
}

const Tolerance* find_tolerance(const std::vector<Tolerance>& tolerances, const std::string& item,
                                int section) {
  const Tolerance* all = nullptr;
  for (const Tolerance& t : tolerances) {
    if (t.item != item) continue;
    if (t.section == section) return &t;
    if (t.section < 0 && !all) all = &t;
  }
  return all;
}

}  // namespace section

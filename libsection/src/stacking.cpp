// SPDX-License-Identifier: GPL-3.0-or-later
// The whole blade from its sections (stacking.h; the definitions: docs/BLADE.md).
#include "section/stacking.h"

#include "section/checks.h"
#include "section/error.h"
#include "section/frame.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <set>
#include <string>

namespace section {

namespace {

constexpr double pi = 3.14159265358979323846;

std::uint32_t bit(StackCheck c) {
  return static_cast<std::uint32_t>(c);
}

// Degrees wrapped into (-180, 180].
double wrapped(double degrees) {
  double a = std::fmod(degrees, 360.0);
  if (a <= -180) a += 360;
  if (a > 180) a -= 360;
  return a;
}

// The stack's coordinates: axial A, tangential T, span S of a 3D point, and back.
struct Axes {
  bool rotor = false;
  Eigen::Vector3d a, t, s;         // planar: the directions; rotor: the axis, t and s at the reference
  Eigen::Vector3d point{0, 0, 0};  // rotor: a point of the axis

  // (A, T, S); rotor: T = radius x angle about the axis from s, positive towards t.
  Eigen::Vector3d coords(const Eigen::Vector3d& p) const {
    if (!rotor) return {p.dot(a), p.dot(t), p.dot(s)};
    const Eigen::Vector3d q = p - point;
    const double axial = q.dot(a);
    const Eigen::Vector3d r = q - axial * a;
    return {axial, r.norm() * std::atan2(r.dot(t), r.dot(s)), r.norm()};
  }
  Eigen::Vector3d world(double axial, double tangential, double span) const {
    if (!rotor) return axial * a + tangential * t + span * s;
    const double angle = span > 0 ? tangential / span : 0.0;
    return point + axial * a + span * (std::cos(angle) * s + std::sin(angle) * t);
  }
  // The angle of `te - le` in (a, t) from a, tangential distances at `radius` (rotor).
  double stagger(const Eigen::Vector3d& le, const Eigen::Vector3d& te, double radius) const {
    const Eigen::Vector3d l = coords(le), e = coords(te);
    const double dt =
        rotor ? radius * (e.y() / std::max(e.z(), 1e-300) - l.y() / std::max(l.z(), 1e-300)) : e.y() - l.y();
    return std::atan2(dt, e.x() - l.x()) * 180 / pi;
  }
};

// The stack's directions: planar from the frames, rotor from the axis and the reference centroid.
Axes axes_of(const std::vector<StackedSection>& sections, const StackedSection& ref,
             const StackingOptions& o) {
  Axes x;
  if (o.rotor) {
    x.rotor = true;
    x.point = o.axis_point;
    x.a = usable_normal(o.axis_direction).normalized();  // 1e200 or 1e-200 long too
    const Eigen::Vector3d q = ref.frame.to_world(ref.params.centroid) - o.axis_point;
    const Eigen::Vector3d r = q - q.dot(x.a) * x.a;
    if (r.norm() < 1e-9 * std::max(1.0, q.norm()))
      throw Error("stacking: the centroid of section " + std::to_string(ref.id) + " lies on the axis");
    x.s = r.normalized();
    x.t = x.s.cross(x.a);
    return x;
  }
  Eigen::Vector3d n = Eigen::Vector3d::Zero();
  for (const auto& sec : sections) n += n.dot(sec.frame.n) < 0 ? Eigen::Vector3d(-sec.frame.n) : sec.frame.n;
  x.s = n.normalized();
  Eigen::Vector3d a = ref.frame.u - ref.frame.u.dot(x.s) * x.s;
  if (a.norm() < 1e-6) a = ref.frame.v - ref.frame.v.dot(x.s) * x.s;
  x.a = a.normalized();
  x.t = x.s.cross(x.a);
  return x;
}

void check_input(const std::vector<StackedSection>& sections, const StackingOptions& o) {
  if (sections.size() < 2)
    throw Error("stacking: " + std::to_string(sections.size()) +
                " section(s) measured: at least 2 are needed for a stacking line");
  if (o.samples < 2 || o.samples > 1000000) throw Error("stacking: samples must be 2 to 1000000");
  if (o.rotor &&
      !(o.axis_direction.stableNorm() > 0 && o.axis_direction.allFinite() && o.axis_point.allFinite()))
    throw Error("stacking: the axis direction must be finite and not zero");
  std::set<int> ids;
  for (const auto& sec : sections) {
    if (!ids.insert(sec.id).second)
      throw Error("stacking: two sections have the id " + std::to_string(sec.id));
    const SectionParams& p = sec.params;
    if (!(p.centroid.allFinite() && p.le_point.allFinite() && p.te_point.allFinite() &&
          std::isfinite(p.chord) && std::isfinite(p.max_thickness) && sec.frame.origin.allFinite() &&
          sec.frame.n.allFinite()))
      throw Error("stacking: section " + std::to_string(sec.id) + " has a value that is not finite");
  }
  if (o.reference >= 0 && !ids.count(o.reference))
    throw Error("stacking: the reference section " + std::to_string(o.reference) + " is not among the " +
                std::to_string(sections.size()) + " sections measured");
}

// An open B-spline through `points` (axial, tangential) at parameters `span` (ascending).
BSpline fit_line(const std::vector<Eigen::Vector2d>& points, const std::vector<double>& span, int control) {
  const int n = static_cast<int>(points.size());
  BSpline shape;
  shape.degree = std::min(3, n - 1);
  shape.closed = false;
  control = std::clamp(control > 0 ? control : std::min(n, 4 + n / 4), shape.degree + 1, n);
  const double s0 = span.front(), s1 = span.back();
  for (int k = 0; k <= shape.degree; ++k) shape.knots.push_back(s0);
  for (int k = 1; k < control - shape.degree; ++k)
    shape.knots.push_back(s0 + (s1 - s0) * k / (control - shape.degree));
  for (int k = 0; k <= shape.degree; ++k) shape.knots.push_back(s1);
  shape.control.assign(static_cast<std::size_t>(control), Eigen::Vector2d::Zero());
  return fit_control_points(points, span, shape);
}

// Bow, axial bow against the line through the hub and tip; the flags of values undefined.
void measure_bow(std::vector<StackedValues>& out, const std::vector<Eigen::Vector3d>& c) {
  const std::size_t h = 0, t = out.size() - 1;
  const bool ends_doubtful = (out[h].flags | out[t].flags) & bit(StackCheck::position);
  for (std::size_t k = 0; k < out.size(); ++k) {
    const double w = (c[k].z() - c[h].z()) / (c[t].z() - c[h].z());
    out[k].bow = c[k].y() - (c[h].y() + w * (c[t].y() - c[h].y()));
    out[k].axial_bow = c[k].x() - (c[h].x() + w * (c[t].x() - c[h].x()));
    out[k].fraction = w;
    if (out.size() < 3 || ends_doubtful) out[k].flags |= bit(StackCheck::bow);
  }
}

// Sections out of order: ids neither ascending nor descending along the span, or two at one span.
void flag_order(std::vector<StackedValues>& out) {
  bool up = true, down = true;
  const double extent = out.back().span - out.front().span;
  for (std::size_t k = 1; k < out.size(); ++k) {
    up = up && out[k].id > out[k - 1].id;
    down = down && out[k].id < out[k - 1].id;
    if (out[k].span - out[k - 1].span <= 1e-9 * extent)
      out[k].flags |= bit(StackCheck::order), out[k - 1].flags |= bit(StackCheck::order);
  }
  if (!up && !down)
    for (auto& v : out) v.flags |= bit(StackCheck::order);
}

// The fitted lines of centroids, LE and TE points (each (A, T, S) by span, hub first),
// the centroids' distances from theirs and the samples.
void fit_lines(StackingResult& r, const Axes& x, const std::array<std::vector<Eigen::Vector3d>, 3>& lines,
               const Eigen::Vector3d& c_ref, const StackingOptions& o) {
  const std::vector<Eigen::Vector3d>& c = lines[0];
  // (A, T) against S, each line through its own points.
  const auto line = [&](const std::vector<Eigen::Vector3d>& pts) {
    std::vector<Eigen::Vector2d> at;
    std::vector<double> s;
    std::vector<std::size_t> order(pts.size());
    for (std::size_t k = 0; k < pts.size(); ++k) order[k] = k;
    std::stable_sort(order.begin(), order.end(), [&](auto i, auto j) { return pts[i].z() < pts[j].z(); });
    for (std::size_t k : order) at.emplace_back(pts[k].x(), pts[k].y()), s.push_back(pts[k].z());
    return fit_line(at, s, o.control_points);
  };
  r.centroid_line = line(c);
  r.le_line = line(lines[1]);
  r.te_line = line(lines[2]);
  for (std::size_t k = 0; k < c.size(); ++k) {
    StackedValues& v = r.sections[k];
    const Eigen::Vector2d on = r.centroid_line.point(c[k].z());
    v.off_line = (x.world(on.x(), on.y(), c[k].z()) - v.centroid).norm();
    if (c.size() < 3 || v.off_line > o.off_line) v.flags |= bit(StackCheck::curve);
  }
  for (int k = 0; k < o.samples; ++k) {
    StackSample smp;
    smp.fraction = double(k) / (o.samples - 1);
    smp.span = c.front().z() + smp.fraction * (c.back().z() - c.front().z());
    const auto at = [&](const BSpline& b) {
      const Eigen::Vector2d p = b.point(smp.span);
      return x.world(p.x(), p.y(), smp.span);
    };
    smp.centroid = at(r.centroid_line), smp.le = at(r.le_line), smp.te = at(r.te_line);
    const Eigen::Vector2d p = r.centroid_line.point(smp.span);
    smp.lean = p.y() - c_ref.y(), smp.sweep = p.x() - c_ref.x();
    r.samples.push_back(smp);
  }
}

}  // namespace

bool params_flagged(CheckBits flags, const char* column) {
  if (!column) throw Error("stacking: params_flagged needs a column name, not a null pointer");
  // (The area centroid rests on the whole profile: le_measured and te_measured list it.)
  return checks_flagging(flags, column) != 0;
}

const char* stack_check_name(StackCheck check) {
  for (const auto& c : stack_check_names)
    if (c.check == check) return c.name;
  return "?";
}

StackingResult stacking(const std::vector<StackedSection>& sections, const StackingOptions& o) {
  check_input(sections, o);
  std::vector<const StackedSection*> by_span;
  for (const auto& sec : sections) by_span.push_back(&sec);
  // The reference fixes the rotor's directions; the span order needs them: the planar
  // directions first, which every frame gives.
  const auto span_of = [&](const StackedSection& sec, const Axes& x) {
    return x.coords(sec.frame.to_world(sec.params.centroid)).z();
  };
  const StackedSection* ref = nullptr;
  for (const auto& sec : sections)
    if (sec.id == o.reference) ref = &sec;
  Axes x = axes_of(sections, ref ? *ref : sections.front(), o);
  std::stable_sort(by_span.begin(), by_span.end(),
                   [&](auto* p, auto* q) { return span_of(*p, x) < span_of(*q, x); });
  if (!ref) ref = by_span.front(), x = axes_of(sections, *ref, o);
  if (!(span_of(*by_span.back(), x) > span_of(*by_span.front(), x)))
    throw Error("stacking: every section lies at one span coordinate: no stacking line");

  StackingResult r;
  r.reference = ref->id;
  r.axial = x.a, r.tangential = x.t, r.span_direction = x.s;
  const Eigen::Vector3d c_ref = x.coords(ref->frame.to_world(ref->params.centroid));
  const auto radius = [&](const StackedSection& sec) {
    return x.coords(sec.frame.to_world(sec.params.centroid)).z();
  };
  const double stagger_ref = x.stagger(ref->frame.to_world(ref->params.le_point),
                                       ref->frame.to_world(ref->params.te_point), radius(*ref));
  std::vector<Eigen::Vector3d> c, le, te;  // (A, T, S) of each line's points, by span
  for (const StackedSection* sec : by_span) {
    const SectionParams& p = sec->params;
    StackedValues v;
    v.id = sec->id;
    v.reference = sec == ref;
    v.centroid = sec->frame.to_world(p.centroid);
    v.le = sec->frame.to_world(p.le_point);
    v.te = sec->frame.to_world(p.te_point);
    c.push_back(x.coords(v.centroid));
    le.push_back(x.coords(v.le));
    te.push_back(x.coords(v.te));
    v.span = c.back().z();
    v.stagger = x.stagger(v.le, v.te, v.span);
    v.twist = wrapped(v.stagger - stagger_ref);
    v.lean = c.back().y() - c_ref.y();
    v.sweep = c.back().x() - c_ref.x();
    v.chord = p.chord;
    v.max_thickness = p.max_thickness;
    const auto flagged = [&](const char* column) {
      return params_flagged(sec->flags, column) || params_flagged(ref->flags, column);
    };
    if (flagged("stagger")) v.flags |= bit(StackCheck::twist);
    if (flagged("centroid")) v.flags |= bit(StackCheck::position);
    if (params_flagged(sec->flags, "le_point")) v.flags |= bit(StackCheck::le);
    if (params_flagged(sec->flags, "te_point")) v.flags |= bit(StackCheck::te);
    if (params_flagged(sec->flags, "chord")) v.flags |= bit(StackCheck::chord);
    if (params_flagged(sec->flags, "max_thickness")) v.flags |= bit(StackCheck::thickness);
    r.sections.push_back(v);
  }
  measure_bow(r.sections, c);
  flag_order(r.sections);

  fit_lines(r, x, {c, le, te}, c_ref, o);
  return r;
}

}  // namespace section

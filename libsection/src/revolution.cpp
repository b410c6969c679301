// SPDX-License-Identifier: GPL-3.0-or-later
// Surfaces of revolution and their unrollings: the exact maps both ways (docs/REVOLUTION.md).
#include "section/revolution.h"

#include "section/error.h"
#include "detail/extent_tails.h"
#include "revolution_map.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

namespace section {

const char* unrolling_name(Unrolling unrolling) {
  switch (unrolling) {
    case Unrolling::cylinder:
      return "cylinder";
    case Unrolling::conformal:
      return "conformal";
    case Unrolling::arclength:
      return "arclength";
  }
  return "?";
}

Unrolling unrolling_named(const std::string& name) {
  for (Unrolling u : {Unrolling::cylinder, Unrolling::conformal, Unrolling::arclength})
    if (name == unrolling_name(u)) return u;
  throw Error("revolution: unknown unrolling '" + name + "' (cylinder, conformal or arclength)");
}

const char* surface_kind_name(SurfaceKind kind) {
  switch (kind) {
    case SurfaceKind::cylinder:
      return "cylinder";
    case SurfaceKind::cone:
      return "cone";
    case SurfaceKind::streamline:
      return "streamline";
  }
  return "?";
}

namespace {

// The axis made unit; throws on a zero or non-finite one.
Eigen::Vector3d unit_axis(const Eigen::Vector3d& axis_point, const Eigen::Vector3d& axis) {
  const double len = axis.norm();
  if (!axis_point.allFinite() || !std::isfinite(len) || !(len > 0))
    throw Error("revolution: the axis needs a finite point and a non-zero direction");
  return axis / len;
}

// The world axis least aligned with the (unit) axis, made normal to it (as make_frame).
Eigen::Vector3d normal_to(const Eigen::Vector3d& n) {
  int k = 0;
  for (int j = 1; j < 3; ++j)
    if (std::abs(n[j]) < std::abs(n[k]) - 1e-12) k = j;
  const Eigen::Vector3d e = Eigen::Vector3d::Unit(k);
  return (e - e.dot(n) * n).normalized();
}

}  // namespace

Revolution cylinder_surface(const Eigen::Vector3d& axis_point, const Eigen::Vector3d& axis, double radius) {
  if (!(radius > 0) || !std::isfinite(radius))
    throw Error("revolution: a cylinder's radius must be positive and finite");
  Revolution s;
  s.kind = SurfaceKind::cylinder;
  s.unrolling = Unrolling::cylinder;
  s.axis_point = axis_point;
  s.axis = unit_axis(axis_point, axis);
  s.reference = normal_to(s.axis);
  s.meridian = {{0, radius}, {1, radius}};  // m = a exactly
  s.r_ref = radius;
  return s;
}

Revolution cone_surface(const Eigen::Vector3d& axis_point, const Eigen::Vector3d& axis,
                        const Eigen::Vector2d& a0r0, const Eigen::Vector2d& a1r1) {
  Revolution s = streamline_surface(axis_point, axis, {a0r0, a1r1});
  s.kind = SurfaceKind::cone;
  return s;
}

Revolution streamline_surface(const Eigen::Vector3d& axis_point, const Eigen::Vector3d& axis,
                              std::vector<Eigen::Vector2d> meridian) {
  Revolution s;
  s.kind = SurfaceKind::streamline;
  s.unrolling = Unrolling::conformal;
  s.axis_point = axis_point;
  s.axis = unit_axis(axis_point, axis);
  s.reference = normal_to(s.axis);
  s.meridian = std::move(meridian);
  return s;
}

void check_surface(const Revolution& s) {
  const auto unit = [](const Eigen::Vector3d& a) { return a.allFinite() && std::abs(a.norm() - 1) < 1e-9; };
  if (!s.axis_point.allFinite() || !unit(s.axis))
    throw Error("revolution: the axis needs a finite point and a unit direction");
  if (!unit(s.reference) || std::abs(s.reference.dot(s.axis)) > 1e-9)
    throw Error("revolution: the reference direction (theta = 0) must be a unit vector normal to the axis");
  if (s.meridian.size() < 2) throw Error("revolution: a meridian needs at least 2 (axial, radius) points");
  for (std::size_t k = 0; k < s.meridian.size(); ++k) {
    const Eigen::Vector2d& q = s.meridian[k];
    if (!q.allFinite() || q.y() < 0)
      throw Error("revolution: meridian point " + std::to_string(k + 1) +
                  " must be finite with a radius of 0 or more");
    if (k > 0 && q == s.meridian[k - 1])
      throw Error("revolution: meridian points " + std::to_string(k) + " and " + std::to_string(k + 1) +
                  " are the same point");
    if (s.unrolling == Unrolling::conformal && !(q.y() > 0))
      throw Error(
          "revolution: the conformal unrolling (integral dm / r) needs radii above 0 along the meridian");
  }
  if (!(s.r_ref > 0) || !std::isfinite(s.r_ref))
    throw Error("revolution: the reference radius r_ref must be positive and finite");
  if (!s.shift.allFinite()) throw Error("revolution: the unrolled shift must be finite");
}

namespace detail {

RevolutionMap::RevolutionMap(const Revolution& surface) : s_(surface) {
  check_surface(s_);
  e2_ = s_.axis.cross(s_.reference);
  const auto& q = s_.meridian;
  m_.assign(1, 0.0);
  mp_.assign(1, 0.0);
  for (std::size_t k = 0; k + 1 < q.size(); ++k) {
    const Eigen::Vector2d d = q[k + 1] - q[k];
    length_.push_back(d.norm());
    t_.push_back(d / length_.back());
    m_.push_back(m_.back() + length_.back());
  }
  for (std::size_t k = 0; k + 1 < q.size(); ++k)
    mp_.push_back(mp_.back() + segment_prime(length_[k], q[k].y(), t_[k].y()));
  // A tree of boxes over the pieces between the two end ones (depth log2(pieces / 4)).
  if (t_.size() > 2) build(1, static_cast<int>(t_.size()) - 1);
}

int RevolutionMap::segment_of(const std::vector<double>& running, double x) const {
  const auto it = std::upper_bound(running.begin() + 1, running.end() - 1, x);
  return static_cast<int>(it - running.begin()) - 1;
}

Eigen::Vector3d RevolutionMap::cylindrical(const Eigen::Vector3d& p) const {
  const Eigen::Vector3d d = p - s_.axis_point;
  const double a = d.dot(s_.axis);
  const Eigen::Vector3d radial = d - a * s_.axis;
  return {a, radial.norm(), std::atan2(radial.dot(e2_), radial.dot(s_.reference))};
}

void RevolutionMap::consider(int k, const Eigen::Vector2d& ar, MeridianFoot& best, double& best_d2,
                             int& best_k) const {
  const int last = static_cast<int>(t_.size()) - 1;
  const Eigen::Vector2d d = ar - s_.meridian[k];
  double x = d.dot(t_[k]);
  bool clamped = false;
  if (k > 0 && x < 0) x = 0, clamped = true;
  if (k < last && x > length_[k]) x = length_[k], clamped = true;
  const Eigen::Vector2d p = s_.meridian[k] + x * t_[k];
  const Eigen::Vector2d off = ar - p;
  const double d2 = off.squaredNorm();
  if (!(d2 < best_d2) && !(d2 == best_d2 && k < best_k)) return;  // ties: the first piece
  best_d2 = d2;
  best_k = k;
  const double cross = t_[k].x() * off.y() - t_[k].y() * off.x();  // left of the meridian: +
  best.m = m_[k] + x;
  best.w = clamped ? std::copysign(std::sqrt(d2), cross) : cross;
  best.ar = clamped && x == 0 ? s_.meridian[k] : p;
}

MeridianFoot RevolutionMap::foot(const Eigen::Vector2d& ar) const {
  MeridianFoot best;
  double best_d2 = std::numeric_limits<double>::infinity();
  int best_k = std::numeric_limits<int>::max();
  const int last = static_cast<int>(t_.size()) - 1;
  consider(0, ar, best, best_d2, best_k);  // the end pieces extend without bound: always looked at
  if (last > 0) consider(last, ar, best, best_d2, best_k);
  if (nodes_.empty()) return best;
  // The pieces between, by their boxes: a box farther than the best foot so far is skipped.
  int stack[64], top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const Node& n = nodes_[std::size_t(stack[--top])];
    if (n.box.squaredExteriorDistance(ar) > best_d2) continue;
    if (n.left < 0) {
      for (int k = n.lo; k < n.hi; ++k) consider(k, ar, best, best_d2, best_k);
    } else if (top + 2 <= 64) {
      // The nearer child first: its foot prunes the other's pieces.
      const bool left_first = nodes_[std::size_t(n.left)].box.squaredExteriorDistance(ar) <=
                              nodes_[std::size_t(n.right)].box.squaredExteriorDistance(ar);
      stack[top++] = left_first ? n.right : n.left;
      stack[top++] = left_first ? n.left : n.right;
    }
  }
  return best;
}

int RevolutionMap::build(int lo, int hi) {
  const int at = static_cast<int>(nodes_.size());
  nodes_.push_back({});
  Node n;
  n.lo = lo;
  n.hi = hi;
  for (int k = lo; k < hi; ++k) {
    n.box.extend(s_.meridian[std::size_t(k)]);
    n.box.extend(s_.meridian[std::size_t(k) + 1]);
  }
  if (hi - lo > 4) {
    const int mid = (lo + hi) / 2;
    n.left = build(lo, mid);
    n.right = build(mid, hi);
  }
  nodes_[std::size_t(at)] = n;
  return at;
}

Eigen::Vector2d RevolutionMap::at(double m) const {
  const int k = segment_of(m_, m);
  return s_.meridian[k] + (m - m_[k]) * t_[k];
}

Eigen::Vector2d RevolutionMap::tangent(double m) const {
  return t_[segment_of(m_, m)];
}

double RevolutionMap::segment_prime(double x, double r, double dr) {
  // The integral of dm / (r + dr m) over [0, x]: log(1 + dr x / r) / dr, x / r when dr = 0.
  const double grow = dr * x / r;
  if (!(grow > -1)) return std::numeric_limits<double>::quiet_NaN();  // at or beyond the apex
  return dr == 0 ? x / r : std::log1p(grow) / dr;
}

double RevolutionMap::m_prime(double m) const {
  const int k = segment_of(m_, m);
  return mp_[k] + segment_prime(m - m_[k], s_.meridian[k].y(), t_[k].y());
}

double RevolutionMap::m_of_prime(double mp) const {
  const int k = segment_of(mp_, mp);
  const double y = mp - mp_[k], r = s_.meridian[k].y(), dr = t_[k].y();
  return m_[k] + (dr == 0 ? y * r : r * std::expm1(dr * y) / dr);
}

Eigen::Vector2d RevolutionMap::unrolled(double m, double theta) const {
  const double rt = s_.r_ref * theta;
  switch (s_.unrolling) {
    case Unrolling::cylinder:
      return Eigen::Vector2d(rt, m) - s_.shift;
    case Unrolling::arclength:
      return Eigen::Vector2d(m, rt) - s_.shift;
    case Unrolling::conformal:
      break;
  }
  return Eigen::Vector2d(s_.r_ref * m_prime(m), rt) - s_.shift;
}

Eigen::Vector2d RevolutionMap::m_theta(const Eigen::Vector2d& uv) const {
  const Eigen::Vector2d p = uv + s_.shift;
  switch (s_.unrolling) {
    case Unrolling::cylinder:
      return {p.y(), p.x() / s_.r_ref};
    case Unrolling::arclength:
      return {p.x(), p.y() / s_.r_ref};
    case Unrolling::conformal:
      break;
  }
  return {m_of_prime(p.x() / s_.r_ref), p.y() / s_.r_ref};
}

Eigen::Vector3d RevolutionMap::point(double m, double theta) const {
  const Eigen::Vector2d ar = at(m);
  return s_.axis_point + ar.x() * s_.axis + ar.y() * (std::cos(theta) * s_.reference + std::sin(theta) * e2_);
}

SurfacePlace RevolutionMap::place(const Eigen::Vector3d& p) const {
  const Eigen::Vector3d c = cylindrical(p);
  const MeridianFoot f = foot(c.head<2>());
  SurfacePlace out;
  out.uv = unrolled(f.m, c.z());
  out.w = f.w;
  out.scale = s_.unrolling == Unrolling::conformal ? s_.r_ref / f.ar.y() : 1.0;
  out.valid = out.uv.allFinite() && std::isfinite(out.w) && std::isfinite(out.scale);
  return out;
}

}  // namespace detail

SurfacePlace surface_place(const Revolution& surface, const Eigen::Vector3d& p) {
  return detail::RevolutionMap(surface).place(p);
}

Eigen::Vector3d surface_point(const Revolution& surface, const Eigen::Vector2d& uv) {
  const detail::RevolutionMap map(surface);
  const Eigen::Vector2d mt = map.m_theta(uv);
  return map.point(mt.x(), mt.y());
}

Eigen::Vector2d surface_uv(const Revolution& surface, const Eigen::Vector3d& p) {
  return surface_place(surface, p).uv;
}

double surface_distance(const Revolution& surface, const Eigen::Vector3d& p) {
  return surface_place(surface, p).w;
}

Frame tangent_frame(const Revolution& surface, const Eigen::Vector2d& uv) {
  const detail::RevolutionMap map(surface);
  const Eigen::Vector2d mt = map.m_theta(uv);
  const Eigen::Vector3d radial =
      std::cos(mt.y()) * surface.reference + std::sin(mt.y()) * surface.axis.cross(surface.reference);
  const Eigen::Vector3d along_theta = surface.axis.cross(radial);
  const Eigen::Vector2d t = map.tangent(mt.x());
  const Eigen::Vector3d along_m = t.x() * surface.axis + t.y() * radial;
  Frame f;
  f.origin = map.point(mt.x(), mt.y());
  f.u = surface.unrolling == Unrolling::cylinder ? along_theta : along_m;
  f.v = surface.unrolling == Unrolling::cylinder ? along_m : along_theta;
  f.n = f.u.cross(f.v);
  return f;
}

Eigen::Vector3d reference_of(const std::vector<Eigen::Vector3d>& points, const Eigen::Vector3d& axis_point,
                             const Eigen::Vector3d& axis) {
  const Eigen::Vector3d n = unit_axis(axis_point, axis), e1 = normal_to(n), e2 = n.cross(e1);
  std::vector<double> theta;
  theta.reserve(points.size());
  for (const auto& p : points) {
    const Eigen::Vector3d d = p - axis_point;
    const double x = d.dot(e1), y = d.dot(e2);
    if ((x != 0 || y != 0) && std::isfinite(x) && std::isfinite(y)) theta.push_back(std::atan2(y, x));
  }
  if (theta.empty()) return e1;
  std::sort(theta.begin(), theta.end());
  // The largest empty gap of angles (the one across +-pi included) holds the branch cut.
  double gap = theta.front() + 2 * M_PI - theta.back(), after = theta.front();
  for (std::size_t k = 1; k < theta.size(); ++k)
    if (theta[k] - theta[k - 1] > gap) gap = theta[k] - theta[k - 1], after = theta[k];
  const double middle = after + 0.5 * (2 * M_PI - gap);  // the middle of the occupied angles
  return std::cos(middle) * e1 + std::sin(middle) * e2;
}

Eigen::Vector2d radius_range(const std::vector<Eigen::Vector3d>& points, const Eigen::Vector3d& axis_point,
                             const Eigen::Vector3d& axis) {
  const Eigen::Vector3d n = unit_axis(axis_point, axis);
  if (points.empty()) throw Error("revolution: no points to take the radius range of");
  detail::Tails tails;
  for (const auto& p : points) {
    const Eigen::Vector3d d = p - axis_point;
    tails.add((d - d.dot(n) * n).norm());
  }
  const PartExtent e = detail::trimmed_extent(tails);
  return {e.lo, e.hi};
}

}  // namespace section

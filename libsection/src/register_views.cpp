// SPDX-License-Identifier: GPL-3.0-or-later
#include "section/register_views.h"
#include "section/units.h"

#include "detail/flann_nearest.h"
#include "section/error.h"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <deque>
#include <memory>
#include <string>

namespace section {

namespace {

// Every k-th point, k chosen so that at most `limit` are kept.
std::vector<Eigen::Vector3d> evenly(const std::vector<Eigen::Vector3d>& points, std::size_t limit) {
  const std::size_t stride =
      std::max<std::size_t>(1, (points.size() + limit - 1) / std::max<std::size_t>(limit, 1));
  std::vector<Eigen::Vector3d> out;
  out.reserve(points.size() / stride + 1);
  for (std::size_t i = 0; i < points.size(); i += stride) out.push_back(points[i]);
  return out;
}

// A local patch of the reference surface: a frame (origin, tangents, normal) from the
// neighbours' principal axes and the height above it, h = a + b x + c y + d x^2 + e xy +
// f y^2, fitted to the neighbours. A tangent plane alone is biased on a tight edge: a point
// a spacing s along a 0.3 mm edge lies s^2 / 2R (some micrometres) inside its neighbour's
// plane, always on the same side.
struct Patch {
  bool valid = false;
  Eigen::Vector3d origin{0, 0, 0}, e1{0, 0, 0}, e2{0, 0, 0}, n{0, 0, 0};
  Eigen::Matrix<double, 6, 1> h = Eigen::Matrix<double, 6, 1>::Zero();
  double scale = 1;  // local coordinates are divided by it (conditioning)

  // Signed distance of q along the normal from the patch, and its gradient in q.
  double residual(const Eigen::Vector3d& q, Eigen::Vector3d& gradient) const {
    const Eigen::Vector3d r = q - origin;
    const double x = e1.dot(r) / scale, y = e2.dot(r) / scale, z = n.dot(r);
    const double height = h(0) + h(1) * x + h(2) * y + h(3) * x * x + h(4) * x * y + h(5) * y * y;
    const double hx = (h(1) + 2 * h(3) * x + h(4) * y) / scale, hy = (h(2) + h(4) * x + 2 * h(5) * y) / scale;
    gradient = n - hx * e1 - hy * e2;
    return z - height;
  }
};

// The reference view: a kd-tree over its points and the surface patch at each, fitted
// when a pair first needs it (most of the reference is never paired).
class Reference {
public:
  Reference(std::vector<Eigen::Vector3d> points, int neighbours)
      : points_(std::move(points)),
        neighbours_(std::min<int>(neighbours, static_cast<int>(points_.size()))),
        index_(points_),
        slot_(points_.size(), -1) {}

  // Nearest reference point of each query within `radius` (index, squared distance; -1
  // where none): a bounded search, as most of a view lies far from the other.
  void nearest(const std::vector<Eigen::Vector3d>& queries, double radius, std::vector<int>& index,
               std::vector<double>& d2) const {
    index_.nearest_within(queries, radius, index, d2);
  }

  // The patch around point i; invalid where the neighbourhood is not a surface (an edge
  // seen from one side, a corner, too few points).
  const Patch& patch(int i) {
    const std::size_t s = static_cast<std::size_t>(i);
    if (slot_[s] >= 0) return patches_[static_cast<std::size_t>(slot_[s])];
    // A deque: references handed out stay valid as patches are added.
    slot_[s] = static_cast<int>(patches_.size());
    Patch& pa = patches_.emplace_back();
    if (neighbours_ < 10) return pa;
    std::vector<int> idx(static_cast<std::size_t>(neighbours_));
    std::vector<double> d2(static_cast<std::size_t>(neighbours_));
    index_.k_nearest(points_[s], neighbours_, idx.data(), d2.data());
    Eigen::Vector3d mean = Eigen::Vector3d::Zero();
    for (int j : idx) mean += points_[static_cast<std::size_t>(j)];
    mean /= neighbours_;
    Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
    for (int j : idx) {
      const Eigen::Vector3d r = points_[static_cast<std::size_t>(j)] - mean;
      cov += r * r.transpose();
    }
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(cov);
    const Eigen::Vector3d ev = eig.eigenvalues();  // ascending
    // A surface: the spread across it well below the spread along it, both ways.
    if (!(ev(1) > 0) || !(ev(0) < 0.1 * ev(1))) return pa;
    pa.origin = mean;
    pa.n = eig.eigenvectors().col(0).normalized();
    pa.e1 = eig.eigenvectors().col(2).normalized();
    pa.e2 = pa.n.cross(pa.e1);
    pa.scale = std::sqrt(ev(2) / neighbours_);
    Eigen::Matrix<double, 6, 6> ata = Eigen::Matrix<double, 6, 6>::Zero();
    Eigen::Matrix<double, 6, 1> atb = Eigen::Matrix<double, 6, 1>::Zero();
    for (int j : idx) {
      const Eigen::Vector3d r = points_[static_cast<std::size_t>(j)] - mean;
      const double x = pa.e1.dot(r) / pa.scale, y = pa.e2.dot(r) / pa.scale;
      Eigen::Matrix<double, 6, 1> row;
      row << 1, x, y, x * x, x * y, y * y;
      ata += row * row.transpose();
      atb += row * pa.n.dot(r);
    }
    const Eigen::LDLT<Eigen::Matrix<double, 6, 6>> ldlt(ata);
    Eigen::Matrix<double, 6, 1> h = ldlt.solve(atb);
    // Neighbours nearly on a line (a scan row) do not fix the cross terms: a plane then.
    if (ldlt.info() != Eigen::Success || !h.allFinite() ||
        !(ldlt.vectorD().minCoeff() > 1e-6 * ldlt.vectorD().maxCoeff()))
      h.setZero();
    pa.h = h;
    pa.valid = true;
    return pa;
  }

  // Signed distance of reference point i from its own patch (NaN without one): the noise
  // of the reference surface, somewhat below it (the patch was fitted to the point too).
  double own_residual(int i) {
    const Patch& pa = patch(i);
    Eigen::Vector3d gradient;
    return pa.valid ? pa.residual(points_[static_cast<std::size_t>(i)], gradient) : std::nan("");
  }

private:
  std::vector<Eigen::Vector3d> points_;
  int neighbours_;
  detail::NearestPoints<3> index_;
  std::vector<int> slot_;      // index into patches_, -1 = not fitted yet
  std::deque<Patch> patches_;  // only those pairs needed: a few percent of the reference
};

struct Pairs {
  std::vector<Eigen::Vector3d> p, n;  // moved point, gradient of its residual
  std::vector<double> r;              // signed distance from the reference surface patch
  std::vector<int> ref;               // the reference point whose patch that is
};

// Pairs of the moved points with the reference: nearest point within reach, a surface
// patch there, and a distance within `trim` robust sigmas (a pair across a thin part, or
// into another surface, is far from its patch).
Pairs pair_up(Reference& ref, const std::vector<Eigen::Vector3d>& moved, double reach, double trim) {
  std::vector<int> index;
  std::vector<double> d2;
  ref.nearest(moved, reach, index, d2);
  Pairs all;
  for (std::size_t i = 0; i < moved.size(); ++i) {
    if (index[i] < 0 || !(d2[i] <= reach * reach)) continue;
    const Patch& patch = ref.patch(index[i]);
    if (!patch.valid) continue;
    Eigen::Vector3d gradient;
    const double r = patch.residual(moved[i], gradient);
    all.p.push_back(moved[i]);
    all.n.push_back(gradient);
    all.r.push_back(r);
    all.ref.push_back(index[i]);
  }
  if (all.r.empty()) return all;
  std::vector<double> a(all.r.size());
  for (std::size_t i = 0; i < a.size(); ++i) a[i] = std::abs(all.r[i]);
  std::nth_element(a.begin(), a.begin() + static_cast<long>(a.size() / 2), a.end());
  const double sigma = 1.4826 * a[a.size() / 2];
  const double limit = std::max(trim * sigma, 1e-12 * reach);
  Pairs kept;
  for (std::size_t i = 0; i < all.r.size(); ++i)
    if (std::abs(all.r[i]) <= limit) {
      kept.p.push_back(all.p[i]);
      kept.n.push_back(all.n[i]);
      kept.r.push_back(all.r[i]);
      kept.ref.push_back(all.ref[i]);
    }
  return kept;
}

double rms(const std::vector<double>& r) {
  double s = 0;
  for (double x : r) s += x * x;
  return r.empty() ? 0 : std::sqrt(s / r.size());
}

void check_views(const std::vector<Cloud>& views, const RegisterOptions& o) {
  if (views.empty()) throw Error("register_views: no views given");
  if (!(o.reach >= 0) || !std::isfinite(o.reach) || !(o.tolerance > 0) || !(o.trim > 0) ||
      o.neighbours < 10 || !(o.weak >= 0 && o.weak < 1) || !(o.fine_weak >= 0 && o.fine_weak < 1) ||
      o.max_iterations < 1 || o.reference_points < 1 || o.moving_points < 1 ||
      !(o.reach_check == 0 || (o.reach_check > 1 && std::isfinite(o.reach_check))))
    throw Error(
        "register_views: reach must be >= 0, tolerance and trim positive, weak and fine_weak in [0, 1), "
        "neighbours >= 10, iterations and point counts >= 1, reach_check 0 or above 1");
  for (std::size_t v = 0; v < views.size(); ++v)
    for (const auto& p : views[v].points)
      if (!p.allFinite())
        throw Error("register_views: view " + std::to_string(v) + " has a point that is not finite");
}

// Only points near the reference can pair: the rest of the view is left out of the
// iterations (the views are aligned to within the reach already).
void keep_near(const Reference& ref, double reach, std::vector<Eigen::Vector3d>& moving) {
  std::vector<int> index;
  std::vector<double> d2;
  ref.nearest(moving, 2 * reach, index, d2);
  std::size_t kept = 0;
  for (std::size_t i = 0; i < moving.size(); ++i)
    if (index[i] >= 0 && d2[i] <= 4 * reach * reach) moving[kept++] = moving[i];
  moving.resize(kept);
}

// One ICP step: the rigid motion that lowers the pairs' residuals, linearised about their
// centroid (r + n.(w x a) + n.t, a = p - c).
Eigen::Isometry3d icp_step(const Pairs& pairs, double weak, const std::string& who) {
  Eigen::Vector3d c = Eigen::Vector3d::Zero();
  for (const auto& p : pairs.p) c += p;
  c /= static_cast<double>(pairs.p.size());
  Eigen::Matrix<double, 6, 6> ata = Eigen::Matrix<double, 6, 6>::Zero();
  Eigen::Matrix<double, 6, 1> atb = Eigen::Matrix<double, 6, 1>::Zero();
  // Rotations scaled by the pairs' rms extent, so that all six unknowns are lengths.
  double extent = 0;
  for (const auto& p : pairs.p) extent += (p - c).squaredNorm();
  extent = std::sqrt(extent / pairs.p.size());
  if (!(extent > 0)) throw Error(who + ": the registration is degenerate (all pairs at one point)");
  for (std::size_t i = 0; i < pairs.p.size(); ++i) {
    const Eigen::Vector3d a = (pairs.p[i] - c) / extent;
    Eigen::Matrix<double, 6, 1> row;
    row << a.cross(pairs.n[i]), pairs.n[i];
    ata += row * row.transpose();
    atb -= row * pairs.r[i];
  }
  // Directions the shared surface hardly constrains (sliding along the span of a blade
  // whose surface is nearly parallel to it) are left alone rather than fitted to noise:
  // the solve is truncated below `weak` of the strongest direction.
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, 6, 6>> eig(ata);
  const Eigen::Matrix<double, 6, 1> lambda = eig.eigenvalues();
  if (!(lambda(5) > 0) || !lambda.allFinite())
    throw Error(who + ": the registration is degenerate (the shared surface is too simple)");
  Eigen::Matrix<double, 6, 1> x = Eigen::Matrix<double, 6, 1>::Zero();
  for (int k = 0; k < 6; ++k)
    if (lambda(k) > weak * lambda(5))
      x += eig.eigenvectors().col(k) * (eig.eigenvectors().col(k).dot(atb) / lambda(k));
  const Eigen::Vector3d w = x.head<3>() / extent, t = x.tail<3>();
  Eigen::Isometry3d step = Eigen::Isometry3d::Identity();
  if (w.norm() > 0) step.linear() = Eigen::AngleAxisd(w.norm(), w.normalized()).toRotationMatrix();
  step.translation() = c + t - step.linear() * c;
  return step;
}

// The angle a motion turns by, in degrees.
double rotation_degrees(const Eigen::Isometry3d& T) {
  return Eigen::AngleAxisd(T.linear()).angle() * 180 / 3.14159265358979323846;
}

// The rms residual of the points against their own surface patches (every k-th point of
// at most 5 000, NaN-free; 0 without any): a view's noise, somewhat below it (each patch
// was fitted to its point too).
double own_noise(const std::vector<Eigen::Vector3d>& points, int neighbours) {
  if (points.empty()) return 0;
  Reference own(points, neighbours);
  const std::size_t stride = std::max<std::size_t>(1, points.size() / 5000);
  double ss = 0;
  std::size_t n = 0;
  for (std::size_t i = 0; i < points.size(); i += stride) {
    const double r = own.own_residual(static_cast<int>(i));
    if (!std::isnan(r)) ss += r * r, ++n;
  }
  return n > 0 ? std::sqrt(ss / static_cast<double>(n)) : 0.0;
}

// Why the view moved by T does not lie on the reference surface at the points' own scale
// (3 spacings), for the refusal; "" where it does: its pairs there within 4 times the
// surface's own noise (the residuals of the reference points paired, 0.02 spacings at
// least), 3 times the two views' noise together (the view's own residuals too; 0.5
// spacings at most) or 0.3 spacings, rms. A registered view lies within 1.3-2 times the
// surface's noise (0.15 spacings at most, 5 um on 62 um) and 0.82-0.94 times the two views'
// (1.1 for a view 6 times as noisy as the reference, 6.7 times the surface's: refused
// before the second term). A reach wider than the views' misalignment lets points pair
// with another part of the surface (the far side of a thin blade), and the motion then
// slides the view along it, 23-55 times that noise off (0.8-1.8 spacings: pairs at random
// within the 3 spacings, whatever the views' noise: hence the cap) while its pairs at the
// reach look close: 6.8 mm for a 0.015 mm misregistration at a reach of 10 mm. A reach
// shorter than the misalignment moves the view part of the way: 0.375 mm apart at a reach
// of 0.187, 0.08 mm moved, 5.4 times the surface's noise off, 3.75 times the two views'.
std::string off_surface(Reference& ref, const std::vector<Eigen::Vector3d>& moving,
                        const Eigen::Isometry3d& T, double spacing, const RegisterOptions& o) {
  const double tight = 3 * spacing;
  std::vector<Eigen::Vector3d> moved(moving.size());
  for (std::size_t i = 0; i < moving.size(); ++i) moved[i] = T * moving[i];
  const Pairs on = pair_up(ref, moved, tight, o.trim);
  double ss = 0;
  std::size_t n = 0;
  for (int i : on.ref) {
    const double r = ref.own_residual(i);
    if (!std::isnan(r)) ss += r * r, ++n;
  }
  const double noise = std::max(n > 0 ? std::sqrt(ss / static_cast<double>(n)) : 0.0, 0.02 * spacing);
  const double off = rms(on.r);
  if (on.r.size() >= o.min_pairs && off <= std::max(4 * noise, 0.3 * spacing)) return {};
  // The view's own noise (a kd-tree over its points) only where the surface's does not pass it.
  const double view_noise = own_noise(moving, o.neighbours);
  const double both = std::sqrt(noise * noise + view_noise * view_noise);
  if (on.r.size() >= o.min_pairs && off <= std::min(3 * both, 0.5 * spacing)) return {};
  return on.r.size() < o.min_pairs
             ? "only " + std::to_string(on.r.size()) + " of its points lie within " + format_length(tight) +
                   " (3 spacings) of it"
             : "its points within " + format_length(tight) + " (3 spacings) of it lie " + format_length(off) +
                   " rms from it, more than 4 times the surface's noise (" + format_length(noise) +
                   "), 3 times the two views' noise together (" + format_length(both) +
                   "; 0.5 spacings at most) and 0.3 spacings";
}

// " (2.39 mm, 4.08 deg)": how far a motion moves and turns.
std::string motion_text(const Eigen::Isometry3d& T) {
  return " (" + format_length(T.translation().norm()) + ", " + format_angle(rotation_degrees(T)) + ")";
}

// The refusal's advice: what a reach far from the views' misalignment does, either way.
std::string reach_advice(double reach) {
  return ". A reach of " + format_length(reach) +
         " is either less than the views' misalignment (the view then moves part of the way) "
         "or so much more that points pair with another part of the surface: give a reach a "
         "little above the misalignment";
}

// ICP of the points `moving` from T at `reach`, directions constrained under `weak` of the
// best left alone (icp_step): the motion found, its iterations, pairs and rms added to
// `out`. False when fewer than min_pairs points pair (out.pairs says how many).
bool icp(Reference& ref, const std::vector<Eigen::Vector3d>& moving, double reach, double weak,
         const RegisterOptions& o, const std::string& who, Eigen::Isometry3d& T, ViewRegistration& out) {
  std::vector<Eigen::Vector3d> moved(moving.size());
  Pairs pairs;
  for (int it = 0; it <= o.max_iterations; ++it) {
    for (std::size_t i = 0; i < moving.size(); ++i) moved[i] = T * moving[i];
    pairs = pair_up(ref, moved, reach, o.trim);
    out.pairs = pairs.r.size();
    if (pairs.r.size() < o.min_pairs) return false;
    if (out.iterations == 0) out.rms_before = rms(pairs.r);
    out.rms_after = rms(pairs.r);
    if (it == o.max_iterations) break;
    const Eigen::Isometry3d step = icp_step(pairs, weak, who);
    T = step * T;
    ++out.iterations;
    // Converged when the step changes the pairs' plane distances by less than the
    // tolerance (rms); a direction the overlap hardly constrains may still creep.
    double change = 0;
    for (std::size_t i = 0; i < pairs.p.size(); ++i)
      change += std::pow(pairs.n[i].dot(step * pairs.p[i] - pairs.p[i]), 2);
    if (std::sqrt(change / pairs.p.size()) < o.tolerance) break;
  }
  return true;
}

// Moves the view (its points near the reference into `moving`) onto the reference by
// ICP: at the reach with the weak directions of `weak` left alone, then from there at 3
// spacings (or the reach, if shorter) with only those of `fine_weak`. A direction the first
// pass leaves alone may hold a real misalignment: a compressor view 0.25 mm away at a reach
// of 0.3 mm kept 62 um of it in the section plane (a direction constrained at 2 % of the
// best), on the surface and so unflagged; the second pass, its pairs at the points' own
// scale, takes it out. False when too few points pair at the reach (out.pairs says how many).
bool settle(Reference& ref, const std::vector<Eigen::Vector3d>& points, double reach, double spacing,
            const RegisterOptions& o, const std::string& who, std::vector<Eigen::Vector3d>& moving,
            ViewRegistration& out) {
  moving = evenly(points, o.moving_points);
  keep_near(ref, reach, moving);
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  if (!icp(ref, moving, reach, o.weak, o, who, T, out)) return false;
  // Too few pairs at the points' scale: the view is off the surface, as the check says.
  Eigen::Isometry3d fine = T;
  ViewRegistration settled = out;
  if (icp(ref, moving, std::min(reach, 3 * spacing), o.fine_weak, o, who, fine, settled)) {
    T = fine;
    out = settled;
  }
  out.transform = T;
  return true;
}

// The largest distance between a point moved by T and by U.
double farthest_apart(const std::vector<Eigen::Vector3d>& points, const Eigen::Isometry3d& T,
                      const Eigen::Isometry3d& U) {
  double d = 0;
  for (const auto& p : points) d = std::max(d, (T * p - U * p).norm());
  return d;
}

// What a kept motion that could not be confirmed asks of the user.
const char* const confirm_advice =
    "Register again with the views aligned closer, or at another reach: a motion found alike at two reaches, "
    "each a little above the misalignment, can be taken";

// The view registered again from where it lay, at `reach`, into `again`: false where no
// motion leaves it on the reference surface there.
bool found_again(Reference& ref, const std::vector<Eigen::Vector3d>& points, double reach, double spacing,
                 const RegisterOptions& o, const std::string& who, ViewRegistration& again) {
  std::vector<Eigen::Vector3d> moving;
  return settle(ref, points, reach, spacing, o, who, moving, again) &&
         off_surface(ref, moving, again.transform, spacing, o).empty();
}

// Registers one view (settle), then checks it: on the reference surface (off_surface),
// and found again from where the view lay at a second reach where the reach and the motion
// lie far apart. Where the motion moves a point farther than the reach (the views lay about
// the reach apart or more; the pairs at the start could not span it), at `reach_check`
// times the reach: such a motion may settle on the surface and be wrong. Compressor views
// 0.3 mm apart at the default reach of 0.19 mm turned 0.77 deg, a point 0.55 mm off, their
// pairs at 2.9 times the two views' noise (off_surface allows 3); at twice the reach they
// register (5-6 um), the two motions 0.55 mm apart. Where the reach is over 1.25 times the
// motion (and 3 spacings), at 1.25 times the motion: a reach far above the misalignment
// lets points pair with other parts of the surface (turbine views 0.2-0.45 mm apart at 1 mm
// slid 10-86 um along it, on it). Twice the motion, still far above the misalignment, let
// 6 of them slide alike (34-86 um; 1.5 times, 1); a quarter above it leaves the pairs
// their partners and little else. Over 1 024 generated registrations (docs/REGISTRATION.md,
// "Found again at a second reach"), right ones lay within 0.37 spacings of their motion at
// the second reach; half a spacing apart refuses 31 of the 41 wrong ones, none right. Where
// the second reach leaves no motion on the surface (twice the reach on a thin blade: points
// pair across it), it tells nothing: the first stands if it moved the view up to 1.5
// reaches (right ones 1.0-1.1), else it is refused (wrong ones 1.8-3.0: 4 more).
ViewRegistration register_view(Reference& ref, const std::vector<Eigen::Vector3d>& points, double reach,
                               double spacing, const RegisterOptions& o, const std::string& who) {
  std::vector<Eigen::Vector3d> moving;
  ViewRegistration out;
  if (!settle(ref, points, reach, spacing, o, who, moving, out))
    throw Error(who + " shares too little surface with view 0: " + std::to_string(out.pairs) +
                " point pairs within " + format_length(reach) + " (at least " + std::to_string(o.min_pairs) +
                " are needed; are the views roughly aligned?)");
  const std::string off = off_surface(ref, moving, out.transform, spacing, o);
  if (!off.empty())
    throw Error(who + " is left off the reference surface by the motion found" + motion_text(out.transform) +
                ": " + off + reach_advice(reach));
  if (!(o.reach_check > 0)) return out;
  // Over all the view's points: those the sections take, not only those paired.
  const double moved = farthest_apart(points, out.transform, Eigen::Isometry3d::Identity());
  const bool beyond = moved > reach;
  const double sized = std::max(1.25 * moved, 3 * spacing);  // a reach sized to the motion
  const bool near = !beyond && moved > 0.8 * reach;
  if (!beyond && !near && !(sized < reach)) return out;
  const auto moves = [&] {  // how far the motion kept so far moves the view, for the messages
    return "the motion found" + motion_text(out.transform) + " moves its points up to " +
           format_length(moved);
  };
  if (near) {
    // Near the reach a wrong motion may settle on the surface: compressor views 0.33 mm apart
    // at 0.5 mm turned 0.8 deg and came 0.59 mm off, a point moved 0.84-0.92 reaches. At
    // 0.8 reaches they register; but that reach lies below a right motion there, and views
    // 0.45 mm apart, right, turned alike at it (7 of 1 792): a motion found alike at 0.8
    // reaches is taken, any other kept and said to be unconfirmed, not refused.
    ViewRegistration again;
    const double narrower = 0.8 * reach;
    const bool alike = found_again(ref, points, narrower, spacing, o, who, again) &&
                       farthest_apart(points, out.transform, again.transform) <= 0.5 * spacing;
    if (!alike)
      out.caution = moves() + ", nearly as far as the reach (" + format_length(reach) + "), and at " +
                    format_length(narrower) +
                    " it is not found again: unconfirmed, it may have slid and turned the view along the "
                    "surface. " +
                    confirm_advice;
    return out;
  }
  const double second = beyond ? o.reach_check * reach : sized;
  ViewRegistration again;
  if (!found_again(ref, points, second, spacing, o, who, again)) {
    if (moved <= 1.5 * reach) {
      out.caution = moves() + " at a reach of " + format_length(reach) + ", and at " + format_length(second) +
                    " no motion leaves it on the reference surface: unconfirmed. " + confirm_advice;
      return out;
    }
    throw Error(who + ": " + moves() + ", more than 1.5 times the reach (" + format_length(reach) +
                "), and at " + format_length(second) +
                " no motion leaves it on the reference surface: the views' misalignment is above the "
                "reach, and the motion may be wrong: give a reach a little above the misalignment");
  }
  const double apart = farthest_apart(points, out.transform, again.transform);
  if (apart > 0.5 * spacing)
    throw Error(who + ": the motion found depends on the reach: at " + format_length(reach) +
                motion_text(out.transform) + ", at " + format_length(second) + motion_text(again.transform) +
                ", the view's points up to " + format_length(apart) + " apart (more than half the spacing, " +
                format_length(0.5 * spacing) + "); either may be wrong, both lie on the surface. " +
                (beyond
                     ? std::string("The views' misalignment is near the reach or above it")
                     : "The reach is far above the views' misalignment, and points pair with other parts of "
                       "the surface") +
                ": give a reach a little above the misalignment");
  // The two agree: the motion of the reach sized to it is kept (where the first moved the
  // view beyond its reach, 10-17 um off against under 7 at twice the reach, 201 views).
  return again;
}

}  // namespace

RegisterResult register_views(const std::vector<Cloud>& views, const RegisterOptions& o) {
  check_views(views, o);
  RegisterResult result;
  result.views.resize(views.size());
  if (views.size() == 1) return result;
  const std::vector<Eigen::Vector3d>& ref_points = views[0].points;
  if (ref_points.size() < std::max<std::size_t>(o.min_pairs, 5))
    throw Error("register_views: the reference view (view 0) has " + std::to_string(ref_points.size()) +
                " points, too few to register onto");
  const double spacing = mean_spacing(ref_points);
  const double reach = o.reach > 0 ? o.reach : 3 * spacing;
  if (!(reach > 0))
    throw Error("register_views: the reference view's points coincide: no surface to register onto");
  Reference ref(evenly(ref_points, o.reference_points), o.neighbours);
  for (std::size_t v = 1; v < views.size(); ++v)
    result.views[v] =
        register_view(ref, views[v].points, reach, spacing, o, "register_views: view " + std::to_string(v));
  return result;
}

std::string describe(const ViewRegistration& r, const std::string& name) {
  const Eigen::Vector3d t = r.transform.translation();
  const double degrees = rotation_degrees(r.transform);
  char buf[512];
  std::snprintf(
      buf, sizeof buf,
      " translation=%.6g,%.6g,%.6g rotation=%.6g pairs=%zu rms_before=%.6g rms_after=%.6g iterations=%d",
      t.x(), t.y(), t.z(), degrees, r.pairs, r.rms_before, r.rms_after, r.iterations);
  return "register view=" + name + buf + (r.caution.empty() ? "" : " unconfirmed=1");
}

Cloud merge_views(const std::vector<Cloud>& views, const RegisterResult& registration) {
  if (registration.views.size() != views.size())
    throw Error("merge_views: " + std::to_string(views.size()) + " views but " +
                std::to_string(registration.views.size()) + " registrations");
  Cloud out;
  std::size_t total = 0;
  for (const auto& v : views) total += v.points.size();
  out.points.reserve(total);
  for (std::size_t k = 0; k < views.size(); ++k) {
    const Eigen::Isometry3d& T = registration.views[k].transform;
    for (const auto& p : views[k].points) out.points.push_back(T * p);
  }
  return out;
}

}  // namespace section

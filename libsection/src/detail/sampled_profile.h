// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// A closed blade profile with dense samples, shared by the camber stages (medial axis,
// edges, camber line, thickness stations): the samples give initial guesses and global
// checks, the piecewise form the exact evaluations.
#include "detail/piecewise_curve.h"
#include "section/bspline.h"

#include <Eigen/Core>

#include <cmath>
#include <vector>

namespace section::detail {

constexpr double pi = 3.14159265358979323846;

/// The normal left of direction d (d turned a quarter counterclockwise).
inline Eigen::Vector2d left_normal(const Eigen::Vector2d& d) {
  return {-d.y(), d.x()};
}
/// The angle of d in degrees from +u, in (-180, 180].
inline double degrees(const Eigen::Vector2d& d) {
  return std::atan2(d.y(), d.x()) * 180 / pi;
}
/// An angle in degrees wrapped into (-180, 180].
inline double wrap_degrees(double a) {
  a = std::fmod(a, 360);
  if (a > 180) a -= 360;
  if (a <= -180) a += 360;
  return a;
}
/// The z component of a x b.
inline double cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return a.x() * b.y() - a.y() * b.x();
}

/// A closed profile and `count` (at least 64) samples evenly in parameter.
struct SampledProfile {
  const BSpline& curve;
  PiecewiseCurve fast;
  double t0 = 0, period = 1;
  double sigma = 1;  ///< +1 counterclockwise, -1 clockwise
  double scale = 1;  ///< bounding-box diagonal of the samples
  std::vector<Eigen::Vector2d> samples;
  std::vector<double> ts;  ///< parameter of each sample
  double step = 0;         ///< largest distance between consecutive samples, rounded up
  /// A circle holding a run of consecutive samples, its radius widened by a million
  /// times the rounding of the distances to them (see sample_within).
  struct Run {
    Eigen::Vector2d center;
    double reach;
  };
  /// The segment from a run's first sample to its last (a + t ab, 0 <= t <= 1), and the
  /// run's largest distance from it widened as a Run's radius: tighter than a circle
  /// where the profile is nearly straight.
  struct Segment {
    Eigen::Vector2d a, ab;
    double inverse_length2;  ///< 1 / |ab|^2, 0 for a point
    double reach;
  };
  /// Runs of run_samples samples (the last may be shorter), and runs of long_run of those
  /// (48 samples): sample_within passes over the runs far from q at once (none: it
  /// compares every sample). The sizes give the fewest instructions on blade profiles.
  std::vector<Segment> runs;
  std::vector<Run> long_runs;
  static constexpr std::size_t run_samples = 12, long_run = 4;

  /// Throws section::Error `camber: ...` when `c` is open, too short or degenerate.
  SampledProfile(const BSpline& c, int count);
  /// The same with `f`, c's piecewise form, already made (one for every sampling of c);
  /// `with_runs` false leaves out the runs, for a profile sample_within is not asked of.
  SampledProfile(const BSpline& c, PiecewiseCurve f, int count, bool with_runs = true);

  double wrap(double t) const { return t0 + std::fmod(std::fmod(t - t0, period) + period, period); }
  /// Parameter distance going forward (in the curve's direction) from a to b.
  double forward(double a, double b) const { return fast.forward(a, b); }
  /// Index of the first sample nearest q.
  int nearest(const Eigen::Vector2d& q) const;
  /// The same, sooner when the sample `hint` lies near q (the last one found, for points
  /// in order along the profile).
  int nearest(const Eigen::Vector2d& q, int hint) const;
  /// Nearest sample on the side of the line through q that `n` points to; -1 when none.
  int nearest_on_side(const Eigen::Vector2d& q, const Eigen::Vector2d& n) const;
  /// Distance from q to the nearest sample.
  double sample_distance(const Eigen::Vector2d& q) const;
  /// True when a sample is nearer q than r: sample_distance(q) < r, told without finding
  /// the nearest (at the first such sample, skipping the runs that lie r or more away).
  bool sample_within(const Eigen::Vector2d& q, double r) const;
  /// Outward unit normal at t.
  Eigen::Vector2d outward(double t) const {
    const Eigen::Vector2d d = fast.jet(t).d1.normalized();
    return sigma * Eigen::Vector2d(d.y(), -d.x());
  }
  /// Curvature at t, positive where the profile is convex.
  double convexity(double t) const {
    const CurveJet j = fast.jet(t);
    return sigma * cross(j.d1, j.d2) / std::pow(j.d1.norm(), 3);
  }
};

/// Whether q lies inside the closed polygon (crossings of a ray along +u).
bool inside_polygon(const std::vector<Eigen::Vector2d>& polygon, const Eigen::Vector2d& q);

/// Whether q lies inside the polygon of the profile's samples.
inline bool inside_samples(const SampledProfile& pr, const Eigen::Vector2d& q) {
  return inside_polygon(pr.samples, q);
}

/// The parameter of q's foot on the profile (the nearest point of the curve near `t`):
/// Newton on the exact curve from t, each step at most one sample's parameter long.
double foot_parameter(const SampledProfile& pr, const Eigen::Vector2d& q, double t);

/// First crossing of the ray m + lambda d (lambda > 0) with the profile: its parameter in
/// `t_hit`. False when the ray misses.
bool ray_hit(const SampledProfile& pr, const Eigen::Vector2d& m, const Eigen::Vector2d& d, double& t_hit);

}  // namespace section::detail

// SPDX-License-Identifier: GPL-3.0-or-later
#include "section/cavity.h"

#include "detail/flann_nearest.h"
#include "detail/sampled_profile.h"
#include "section/error.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

namespace section {

namespace {

// The loop's samples, evenly around it, tested against the profile's polygon: where the
// curves cross, some lie inside and some outside; a crossing between them leaves the
// least distance 0, which the wall then tells.
constexpr int kPlaceTests = 32;

// A stretch of the profile: from parameter `from` forward by `length` (the whole profile
// when `whole`).
struct Stretch {
  bool whole = true;
  double from = 0, length = 0;
};

// t, or the stretch's nearer end when t lies beyond it.
double clamped(const detail::SampledProfile& pr, double t, const Stretch& s) {
  if (s.whole) return t;
  const double u = pr.forward(s.from, t);
  if (u <= s.length) return t;
  return u - s.length < pr.period - u ? s.from + s.length : s.from;
}

// The least distance between the two curves near samples i of `loop` and j of `profile`:
// alternate feet (each curve's nearest point to the other's; the profile's kept on
// stretch `s`), from those samples, until the parameters settle. Converges where the two
// curves are closest, their normals along the segment between the feet (or at an end of
// the stretch).
void refine(const detail::SampledProfile& profile, const detail::SampledProfile& loop, int i, int j,
            const Stretch& s, CavityWall& best) {
  double tl = loop.ts[static_cast<std::size_t>(i)], tp = profile.ts[static_cast<std::size_t>(j)];
  Eigen::Vector2d pl = loop.fast.point(loop.fast.locate(tl)),
                  pp = profile.fast.point(profile.fast.locate(tp));
  for (int it = 0; it < 200; ++it) {
    const double np = clamped(profile, detail::foot_parameter(profile, pl, tp), s);
    pp = profile.fast.point(profile.fast.locate(np));
    const double nl = detail::foot_parameter(loop, pp, tl);
    pl = loop.fast.point(loop.fast.locate(nl));
    const bool settled =
        std::abs(np - tp) <= 1e-13 * profile.period && std::abs(nl - tl) <= 1e-13 * loop.period;
    tp = np, tl = nl;
    if (settled) break;
  }
  const double d = (pp - pl).norm();
  if (d < best.wall) {
    best.wall = d;
    best.profile_t = profile.wrap(tp), best.cavity_t = loop.wrap(tl);
    best.profile_point = pp, best.cavity_point = pl;
  }
}

// The least wall between the loop and the profile's samples `on` (every one when empty),
// refined on the curves within `s`, with its thin stretch; `sampled` is the least sampled
// distance.
CavityWall least_wall(const detail::SampledProfile& pr, const detail::SampledProfile& lp,
                      const std::vector<std::size_t>& on, const Stretch& s, double thin, double& sampled) {
  const std::size_t n = lp.samples.size();
  // Each loop sample's nearest profile sample.
  std::vector<int> near;
  if (on.empty()) {
    near = detail::NearestPoints<2>(pr.samples).nearest(lp.samples);
  } else {
    std::vector<Eigen::Vector2d> samples;
    for (std::size_t j : on) samples.push_back(pr.samples[j]);
    near = detail::NearestPoints<2>(samples).nearest(lp.samples);
    for (int& j : near) j = static_cast<int>(on[static_cast<std::size_t>(j)]);
  }
  std::vector<double> d(n);
  for (std::size_t i = 0; i < n; ++i)
    d[i] = (pr.samples[static_cast<std::size_t>(near[i])] - lp.samples[i]).norm();
  const std::size_t at = static_cast<std::size_t>(std::min_element(d.begin(), d.end()) - d.begin());
  sampled = d[at];
  CavityWall w;
  w.wall = sampled;
  w.cavity_t = lp.ts[at], w.cavity_point = lp.samples[at];
  w.profile_t = pr.ts[static_cast<std::size_t>(near[at])],
  w.profile_point = pr.samples[static_cast<std::size_t>(near[at])];
  // The sampled distance is off the curves' by less than a sample step on either: each
  // local minimum that close to the least is refined (the walls either side of a channel).
  const double slack = pr.step + lp.step;
  for (std::size_t i = 0; i < n; ++i) {
    const double before = d[(i + n - 1) % n], after = d[(i + 1) % n];
    if (d[i] <= before && d[i] <= after && d[i] <= sampled + slack)
      refine(pr, lp, static_cast<int>(i), near[i], s, w);
  }
  for (std::size_t i = 0; i < n; ++i)
    if (d[i] <= (1 + thin) * w.wall) w.thin.push_back({lp.ts[i], pr.ts[static_cast<std::size_t>(near[i])]});
  return w;
}

void check_curves(const BSpline& profile, const BSpline& loop, const CavityOptions& options) {
  if (options.samples < 256)
    throw Error("cavity: at least 256 samples are needed, got " + std::to_string(options.samples));
  if (!(options.thin >= 0) || !std::isfinite(options.thin))
    throw Error("cavity: the thin stretch's fraction must be 0 or more");
  if (!profile.closed || !loop.closed) throw Error("cavity: the profile and the loop must be closed curves");
}

// How many of kPlaceTests samples evenly around the loop lie inside the profile.
int inside_tests(const detail::SampledProfile& pr, const detail::SampledProfile& lp) {
  const std::size_t n = lp.samples.size();
  int inside = 0;
  for (int k = 0; k < kPlaceTests; ++k)
    inside += detail::inside_samples(pr, lp.samples[n * static_cast<std::size_t>(k) / kPlaceTests]);
  return inside;
}

}  // namespace

Cavity measure_cavity(const BSpline& profile, const BSpline& loop, const CavityOptions& options) {
  check_curves(profile, loop, options);
  // The loop's samples a quarter of the profile's: a cavity is a fraction of its length,
  // and the wall is refined on the curves.
  const detail::SampledProfile pr(profile, options.samples), lp(loop, options.samples / 4);
  Cavity c;
  const std::size_t n = lp.samples.size();
  // About the first sample: a loop far from the origin keeps its centroid's digits.
  const Eigen::Vector2d o = lp.samples[0];
  Eigen::Vector2d moment(0, 0);
  double about = 0;  // twice the area, about o
  for (std::size_t i = 0; i < n; ++i) {
    const Eigen::Vector2d& a = lp.samples[i];
    const Eigen::Vector2d& b = lp.samples[(i + 1) % n];
    c.area += detail::cross(a, b);
    const double twice = detail::cross(a - o, b - o);
    about += twice;
    moment += twice * (a + b - 2 * o);
    c.length += (b - a).norm();
  }
  c.centroid = about != 0 ? Eigen::Vector2d(o + moment / (3 * about)) : o;
  c.area = 0.5 * std::abs(c.area);
  const int inside = inside_tests(pr, lp);
  if (inside == 0) return c;  // outside (or around the profile)
  c.place = LoopPlace::crossing;
  if (inside < kPlaceTests) return c;
  double least = 0;
  CavityWall w = least_wall(pr, lp, {}, Stretch{}, options.thin, least);
  c.wall = w.wall;
  c.profile_point = w.profile_point, c.cavity_point = w.cavity_point;
  c.profile_t = w.profile_t, c.cavity_t = w.cavity_t;
  // Touching, or crossing between the samples tested.
  if (!(c.wall > 1e-12 * pr.scale) || !(least > 0)) {
    c.wall = 0;
    return c;
  }
  c.place = LoopPlace::inside;
  c.thin = std::move(w.thin);
  return c;
}

std::array<CavityWall, 2> side_walls(const BSpline& profile, const BSpline& loop, double t0, double t1,
                                     const CavityOptions& options) {
  check_curves(profile, loop, options);
  if (!std::isfinite(t0) || !std::isfinite(t1)) throw Error("cavity: the sides' parameters must be finite");
  const detail::SampledProfile pr(profile, options.samples), lp(loop, options.samples / 4);
  if (inside_tests(pr, lp) < kPlaceTests)
    throw Error("cavity: the loop does not lie inside the profile, so it has no walls to measure");
  // The same point within rounding parts nothing (not the whole profile from one side).
  const double apart = pr.forward(pr.wrap(t0), pr.wrap(t1)), tiny = 1e-9 * pr.period;
  if (!(apart > tiny && apart < pr.period - tiny))
    throw Error("cavity: the sides' parameters part no stretch of the profile (" + std::to_string(t0) +
                " and " + std::to_string(t1) + ")");
  std::array<CavityWall, 2> walls;
  for (int k = 0; k < 2; ++k) {
    Stretch s;
    s.whole = false;
    s.from = pr.wrap(k == 0 ? t0 : t1);
    s.length = k == 0 ? apart : pr.period - apart;
    std::vector<std::size_t> on;
    for (std::size_t j = 0; j < pr.ts.size(); ++j)
      if (pr.forward(s.from, pr.ts[j]) <= s.length) on.push_back(j);
    if (on.empty())
      throw Error("cavity: the side from parameter " + std::to_string(s.from) +
                  " holds no sample of the profile");
    double least = 0;
    walls[static_cast<std::size_t>(k)] = least_wall(pr, lp, on, s, options.thin, least);
  }
  return walls;
}

}  // namespace section

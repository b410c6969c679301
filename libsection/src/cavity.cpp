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

// The least distance between the two curves near samples i of `loop` and j of `profile`:
// alternate feet (each curve's nearest point to the other's), from those samples, until
// the parameters settle. Converges where the two curves are closest, their normals along
// the segment between the feet.
void refine(const detail::SampledProfile& profile, const detail::SampledProfile& loop, int i, int j,
            Cavity& best) {
  double tl = loop.ts[static_cast<std::size_t>(i)], tp = profile.ts[static_cast<std::size_t>(j)];
  Eigen::Vector2d pl = loop.fast.point(loop.fast.locate(tl)),
                  pp = profile.fast.point(profile.fast.locate(tp));
  for (int it = 0; it < 200; ++it) {
    const double np = detail::foot_parameter(profile, pl, tp);
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

}  // namespace

Cavity measure_cavity(const BSpline& profile, const BSpline& loop, const CavityOptions& options) {
  if (options.samples < 256)
    throw Error("cavity: at least 256 samples are needed, got " + std::to_string(options.samples));
  if (!(options.thin >= 0) || !std::isfinite(options.thin))
    throw Error("cavity: the thin stretch's fraction must be 0 or more");
  if (!profile.closed || !loop.closed) throw Error("cavity: the profile and the loop must be closed curves");
  // The loop's samples a quarter of the profile's: a cavity is a fraction of its length,
  // and the wall is refined on the curves.
  const detail::SampledProfile pr(profile, options.samples), lp(loop, options.samples / 4);
  Cavity c;
  const std::size_t n = lp.samples.size();
  for (std::size_t i = 0; i < n; ++i) {
    const Eigen::Vector2d& a = lp.samples[i];
    const Eigen::Vector2d& b = lp.samples[(i + 1) % n];
    c.area += detail::cross(a, b);
    c.length += (b - a).norm();
  }
  c.area = 0.5 * std::abs(c.area);
  int inside = 0;
  for (int k = 0; k < kPlaceTests; ++k)
    inside += detail::inside_samples(pr, lp.samples[n * static_cast<std::size_t>(k) / kPlaceTests]);
  if (inside == 0) return c;  // outside (or around the profile)
  c.place = LoopPlace::crossing;
  if (inside < kPlaceTests) return c;
  // Each loop sample's nearest profile sample.
  const std::vector<int> near = detail::NearestPoints<2>(pr.samples).nearest(lp.samples);
  std::vector<double> d(n);
  for (std::size_t i = 0; i < n; ++i)
    d[i] = (pr.samples[static_cast<std::size_t>(near[i])] - lp.samples[i]).norm();
  const std::size_t at = static_cast<std::size_t>(std::min_element(d.begin(), d.end()) - d.begin());
  const double least = d[at];
  c.wall = least;
  c.cavity_t = lp.ts[at], c.cavity_point = lp.samples[at];
  c.profile_t = pr.ts[static_cast<std::size_t>(near[at])],
  c.profile_point = pr.samples[static_cast<std::size_t>(near[at])];
  // The sampled distance is off the curves' by less than a sample step on either: each
  // local minimum that close to the least is refined (the walls either side of a channel).
  const double slack = pr.step + lp.step;
  for (std::size_t i = 0; i < n; ++i) {
    const double before = d[(i + n - 1) % n], after = d[(i + 1) % n];
    if (d[i] <= before && d[i] <= after && d[i] <= least + slack)
      refine(pr, lp, static_cast<int>(i), near[i], c);
  }
  // Touching, or crossing between the samples tested.
  if (!(c.wall > 1e-12 * pr.scale) || !(least > 0)) {
    c.wall = 0;
    return c;
  }
  c.place = LoopPlace::inside;
  for (std::size_t i = 0; i < n; ++i)
    if (d[i] <= (1 + options.thin) * c.wall)
      c.thin.push_back({lp.ts[i], pr.ts[static_cast<std::size_t>(near[i])]});
  return c;
}

}  // namespace section

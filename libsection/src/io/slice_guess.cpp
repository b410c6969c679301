// SPDX-License-Identifier: GPL-3.0-or-later
#include "io/slice_guess.h"

#include "section/cloud.h"
#include "section/io/cloud_io.h"
#include "detail/slice_steps.h"
#include "io/reservoir.h"

#include <cmath>

namespace section::detail {

namespace {

// Whether the sections of a scan likely get a band (band_half_width at least a slab): its
// slabs hold fewer than 1 / (2 band_spacing) points per mm of profile. The density from
// the peek's mean nearest-neighbour spacing d at full density, that of random points
// (1 / (4 d^2) per mm^2); a scan in even rows is denser for its d, and likely gets none.
// A guess for speed only: the sections are the same either way.
bool band_likely(double spacing, double slab, const SliceOptions& options) {
  if (!(options.band_spacing > 0) || !(spacing > 0)) return false;
  const double per_length = slab * 0.25 / (spacing * spacing);
  return 0.5 / options.band_spacing >= 0.75 * per_length;
}

}  // namespace

// The guess for slice_file: planes from the extent of 4096 points read here and there
// (peek_cloud: binary PLY files only), the slab from their spacing scaled to the full
// density as pass 1 scales its sample's. Inactive when the points kept around the
// guessed planes would be a large part of the cloud, or when pass 1 samples the whole
// cloud: a second read of at most 50 000 points costs less than the first look's spacing
// (at 10 000 points, 1.6 M instructions against 17 M).
Guess guess_planes(const std::string& path, const PlaneSpec& spec, const SliceOptions& options,
                   const CloudReadOptions& read) {
  Guess guess;
  if (peek_cloud(path, 1, read).total <= detail::Reservoir::size) return guess;
  const CloudPeek peek = peek_cloud(path, 4096, read);
  if (peek.points.size() < 256) return guess;
  const PartExtent seen = extent_along(peek.points, spec.normal);
  guess.screen_lo = seen.lo - 0.02 * (seen.hi - seen.lo);
  guess.screen_hi = seen.hi + 0.02 * (seen.hi - seen.lo);
  // The mean spacing at full density (the band's guess needs it, and the slab when not given).
  const double spacing =
      options.slab == 0 || options.band_spacing > 0
          ? section::mean_spacing(peek.points) * std::sqrt(double(peek.points.size()) / double(peek.total))
          : 0;
  double slab = options.slab;
  if (slab == 0) slab = spacing / 0.47;
  if (!(slab > 0) || !std::isfinite(slab)) return guess;
  // The peek's extent, its strays left out (as the pass's): along the normal of --count
  // once, not again for each plane (20 planes took 1 % of slice at 1 M points).
  const auto extent_of = [&](const Eigen::Vector3d& normal, double& lo, double& hi) {
    const PartExtent e = normal == spec.normal ? seen : extent_along(peek.points, normal);
    lo = e.lo;
    hi = e.hi;
  };

  // Measured on generated blades: the peek's spacing is 3-18 % above the one pass 1
  // finds, its extent within 0.025 mm of 60 mm. Planes spread over the extent move by up
  // to the extent's error once it is known; explicit planes stay. The slabs are kept, and
  // the band's points where a band is likely (below); the points beside a plane that a
  // section with a gap needs are read again for it.
  double shift = 0;
  if (spec.count > 0) {
    double lo, hi;
    extent_of(spec.normal, lo, hi);
    if (!(hi > lo)) return guess;
    shift = std::max(1e-3 * (hi - lo), 2 * slab);
    guess.planes = spread(spec.normal, lo, hi, spec.count);
  } else {
    guess.planes = spec.planes;
  }
  const auto share_of = [&](double half_width) {
    double share = 0;
    for (const auto& p : guess.planes) {
      double lo, hi;
      extent_of(p.normal, lo, hi);
      share += hi > lo ? 2 * half_width / (hi - lo) : 1;
    }
    return share;
  };
  // The band's points too, when the sections likely get a band: on such a scan (0.25-1 M
  // points) the read of the file for the points beside the planes is spared, and fewer are
  // held than that read gathers (they reach as far as the gap fill's reach). Else the slabs
  // alone, while they are at most half the cloud (else pass 2 is cheaper).
  const double band = band_likely(spacing, slab, options) ? 1.5 * detail::band_reach(options, slab) : 0;
  guess.half_width = std::max(1.5 * 0.5 * slab, band) + shift;
  guess.band = band > 0;
  double share = share_of(guess.half_width);
  if (guess.band && !(share <= std::max(0.75, share_of(detail::fill_reach(options, slab))))) {
    guess.half_width = 1.5 * 0.5 * slab + shift;
    guess.band = false;
    share = share_of(guess.half_width);
  }
  if (!(share <= 0.5) && !guess.band) return guess;
  guess.share = share;
  guess.groups = detail::group_planes(guess.planes, 2 * guess.half_width);
  guess.kept.resize(guess.planes.size());
  guess.active = true;
  return guess;
}

}  // namespace section::detail

// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// slice_file's guess: the planes and slab from a first look at a cloud file, and the points
// pass 1 keeps around them (io/slice_file.cpp).
#include "section/frame.h"
#include "section/io/slice_file.h"
#include "section/slice.h"
#include "detail/slab_scan.h"

#include <Eigen/Core>

#include <algorithm>
#include <cmath>
#include <string>
#include <limits>
#include <vector>

namespace section::detail {

// Planes (and slab) guessed from a first look at a cloud file (peek_cloud), and the points
// kept around them while pass 1 of slice_file reads the file.
struct Guess {
  bool active = false;                    // false: no guess; pass 2 reads the file again
  std::vector<Plane> planes;              // the guessed planes
  double half_width = 0;                  // points within this of a guessed plane are kept
  bool band = false;                      // half_width holds the band's reach (band_reach) too
  double share = 0;                       // estimated share of the points kept
  std::vector<detail::SlabGroup> groups;  // the guessed planes with slabs 2 half_width wide
  // Per guessed plane, blocks of the points kept, in file order (blocks are moved in as
  // the threads collect them, not copied).
  std::vector<std::vector<std::vector<Eigen::Vector3d>>> kept;
  // The first look's extent along the normal (its strays left out), widened by 2 % each
  // way: pass 1 keeps the offsets beyond it for the part's extent (detail::Tails' limits).
  // None (every offset a candidate) when there was no first look.
  double screen_lo = std::numeric_limits<double>::infinity();
  double screen_hi = -std::numeric_limits<double>::infinity();

  // Appends q to the list in `out` of each guessed plane within half_width of it; `tests`
  // are those of `groups` (made once for a loop over points: see detail::SlabTests).
  void keep(const Eigen::Vector3d& q, const std::vector<detail::SlabTests>& tests,
            std::vector<std::vector<Eigen::Vector3d>>& out) const {
    for (const detail::SlabTests& t : tests) keep_at(q, t.n.dot(q), t, out);
  }
  // keep for one group's test, n . q = s known.
  void keep_at(const Eigen::Vector3d& q, double s, const detail::SlabTests& t,
               std::vector<std::vector<Eigen::Vector3d>>& out) const {
    if (t.far_from_slabs(s)) return;
    for (std::size_t k = t.first_at_least(s - half_width); k < t.planes && t.offset[k] <= s + half_width; ++k)
      out[t.plane[k]].push_back(q);
  }

  // True when every point the slab test of `found` (slab width `slab`) can take was kept:
  // each found plane lies close enough to its guess. `largest` bounds the points'
  // coordinates (the exact slab test's tolerance).
  bool covers(const std::vector<Plane>& found, double slab, double largest) const {
    return holds(found, 0.5 * slab, slab, largest);
  }

  // True when the points kept hold every point within `reach` of each found plane: the
  // band's points need no read of the file then.
  bool covers_band(const std::vector<Plane>& found, double reach, double largest) const {
    return band && reach > 0 && holds(found, reach, reach, largest);
  }

private:
  // Whether each found plane has its guess's normal and lies within half_width - `half` of
  // it, less three times the tolerance of a test `width` wide on coordinates up to `largest`.
  bool holds(const std::vector<Plane>& found, double half, double width, double largest) const {
    if (found.size() != planes.size()) return false;
    const double tol = 1e-12 * (std::max(2 * largest, width) + 1) * (1 + 1e-6);
    const double need = half + 3 * tol;
    for (std::size_t k = 0; k < found.size(); ++k) {
      const Frame f = make_frame(found[k].origin, found[k].normal),
                  g = make_frame(planes[k].origin, planes[k].normal);
      if (!(f.n == g.n)) return false;
      const double shift = std::abs(f.n.dot(found[k].origin) - g.n.dot(planes[k].origin));
      if (!(shift + need <= half_width)) return false;
    }
    return true;
  }
};

// The guess for slice_file: planes from the extent of 4096 points read here and there
// (peek_cloud: binary PLY files only), the slab from their spacing scaled to the full
// density as pass 1 scales its sample's. Inactive when the points kept around the
// guessed planes would be a large part of the cloud, or when pass 1 samples the whole
// cloud: a second read of at most 50 000 points costs less than the first look's spacing
// (at 10 000 points, 1.6 M instructions against 17 M).
Guess guess_planes(const std::string& path, const PlaneSpec& spec, const SliceOptions& options,
                   const CloudReadOptions& read);

}  // namespace section::detail

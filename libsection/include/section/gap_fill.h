// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// @file gap_fill.h
/// Filling a section's gaps with scan points from beside the plane. Where the slab has a
/// gap (a hole, a sparse thin edge), points a few tenths of a millimetre above and below
/// the plane are carried onto it along the section's drift with height, fitted near the
/// gap as a constant in-plane velocity V: p at height z goes to p - z V (docs/MORPHOLOGY.md).
#include "section/morphology.h"

#include <Eigen/Core>
#include <cstddef>
#include <vector>

namespace section {

/// Options of fill_gaps (lengths in the cloud's units).
struct GapFillOptions {
  double reach = 0;                  ///< farthest distance of the points used from the plane; 0 = 12 slabs
  double min_gap = 3;                ///< slab widths: longer steps between ordered points are gaps to fill
  double min_gap_fraction = 0.0025;  ///< ... if also longer than this fraction of the profile's length
  int min_support = 24;              ///< points beside a gap needed to fit its drift
};

/// What fill_gaps returns.
struct GapFillResult {
  MorphologyResult filled;      ///< the ordered loops with the carried points inserted into their gaps
  std::size_t points = 0;       ///< carried points; their input indices are first_index, first_index + 1, ...
  std::vector<double> offsets;  ///< each one's signed distance from the plane before it was carried
  int gaps = 0;                 ///< gaps longer than the threshold
  int gaps_filled = 0;          ///< gaps that received points
  double largest_gap = 0;       ///< length of the longest gap found
  double max_offset = 0;        ///< largest |offset| among the carried points
};

/// The reach fill_gaps uses for a slab: options.reach, or 12 slab widths when it is 0.
double gap_fill_reach(const GapFillOptions& options, double slab);

/// Throws section::Error naming the option when `options` are out of range.
void check_gap_fill_options(const GapFillOptions& options);

/// Fills the gaps of the profile (loop 0) of `ordered` (what order_section made of the
/// slab points) from `nearby`: points of the scan near the plane as (u, v, signed distance from
/// the plane), in any order. `slab` is the slab width used. The slab's own points keep
/// their order; carried points go between the two ends of their gap, in order along it,
/// with input indices from `first_index` on (normals there: rough, from the gap's middle).
/// A gap whose drift cannot be fitted (too few points beside it) stays as it is.
/// Deterministic for given inputs.
GapFillResult fill_gaps(const MorphologyResult& ordered, const std::vector<Eigen::Vector3d>& nearby,
                        double slab, std::size_t first_index, const GapFillOptions& options = {});

}  // namespace section

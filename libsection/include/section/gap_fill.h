#pragma once
/// @file gap_fill.h
/// Filling a section's gaps with scan points from beside the plane. A slab of width d
/// holds only the points within d/2 of the plane; where the scan is sparse (a thin edge at
/// low density) or has a hole, the slab leaves a gap although the scan holds points a few
/// tenths of a millimetre above and below. Those points lie on the section of their own
/// height, which drifts with the height (lean, sweep, twist): near a gap the drift is
/// fitted as a constant in-plane velocity V (mm per mm of height) from the points beside
/// the gap against the slab's own points, and each point p at height z above the plane is
/// carried to p - z V. Carried points go only where the slab has none.
#include "section/morphology.h"

#include <Eigen/Core>
#include <cstddef>
#include <vector>

namespace section {

/// Options of fill_gaps (lengths in the cloud's units).
struct GapFillOptions {
  double reach = 0;       ///< farthest distance from the plane of the points used; 0 = 12 slab widths
  double min_gap = 3;     ///< slab widths: a gap between consecutive ordered points longer than this is filled
  double min_gap_fraction = 0.0025;  ///< and longer than this fraction of the profile's length (0.25 mm on a 100 mm profile)
  int min_support = 24;   ///< points beside a gap needed to fit its drift; fewer leave the gap as it is
};

/// What fill_gaps returns.
struct GapFillResult {
  MorphologyResult filled;              ///< the ordered loops with the carried points inserted into their gaps
  std::size_t points = 0;               ///< carried points; their input indices are first_index, first_index + 1, ...
  std::vector<double> offsets;          ///< each one's signed distance from the plane before it was carried, by index
  int gaps = 0;                         ///< gaps longer than the threshold
  int gaps_filled = 0;                  ///< gaps that received points
  double largest_gap = 0;               ///< length of the longest gap found
  double max_offset = 0;                ///< largest |offset| among the carried points
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
GapFillResult fill_gaps(const MorphologyResult& ordered, const std::vector<Eigen::Vector3d>& nearby, double slab,
                        std::size_t first_index, const GapFillOptions& options = {});

}  // namespace section

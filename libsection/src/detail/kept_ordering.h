// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// An ordering kept for more points: slice orders its drift-corrected band on the loops its
// slab's ordering found, instead of rasterising the band again (src/morphology.cpp).
#include "section/morphology.h"

#include <memory>
#include <optional>
#include <vector>

namespace section::detail {

/// What order_section found (its passes' rasters and fills, the loops' boundaries, the
/// cell): enough to order other points lying along the same loops. Opaque.
struct KeptOrdering;

struct OrderedKept {
  MorphologyResult result;                   ///< as order_section returns it
  std::shared_ptr<const KeptOrdering> kept;  ///< what ordered it
};

/// order_section, keeping what it found.
OrderedKept order_section_kept(const std::vector<Eigen::Vector2d>& points, const MorphologyOptions& options);

/// `points`, lying along the loops of `kept` (a denser sampling of the same profile), in
/// order on those loops: each point joins the loop nearest to it within the outlier
/// distance, ordered by its foot, spikes dropped, normals from the kept fills, the skeleton
/// (options.skeleton) that of the kept loop 0. Empty, the points to be ordered afresh,
/// when the kept loop 0 closed only at a dilation over 32 cells (it bridges holes away from
/// the profile, where denser points may lie), or when the loops do not hold the points:
/// more than 2 dropped beyond those the kept ordering dropped, or a loop left with too few.
std::optional<MorphologyResult> order_beside(const KeptOrdering& kept,
                                             const std::vector<Eigen::Vector2d>& points,
                                             const MorphologyOptions& options);

/// Adds the skeleton of the kept loop 0 to `result`, the ordering that kept it (which left
/// the skeleton out through skeleton_if).
void add_skeleton(const KeptOrdering& kept, MorphologyResult& result);

}  // namespace section::detail

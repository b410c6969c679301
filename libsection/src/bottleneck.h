// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The bottleneck (widest path) from the raster's border over a distance transform
// (src/raster.h), on spans with gaps.
#include "raster.h"

namespace section::morph {

/// For every cell, the largest t such that a 4-connected path from the raster border
/// reaches it through cells with d2 >= t (the bottleneck of the widest path): the cell is
/// outside the band of radius r exactly when b2 > r^2. Bucket queue over the (clamped,
/// integer) keys: O(cells). With `spans` (those of distance_transform, d2 = cap off
/// them and on their gaps), the cells off the spans get cap, their value, without a visit,
/// and each gap's cells the level of the first path into it, by rows.
Buffer<int> bottleneck(const Raster& r, const Buffer<int>& d2, int cap, Buffer<int>& next,
                       const Spans* spans = nullptr);

}  // namespace section::morph

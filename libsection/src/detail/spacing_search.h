// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// sampling_of's kd-tree and nearest distances, kept so that mean_spacing of a cloud the
// sampling held whole does not build a second tree and search its points again
// (src/sampling.cpp, src/cloud.cpp).
#include "section/sampling.h"
#include "detail/flann_nearest.h"

#include <cstddef>
#include <memory>
#include <vector>

namespace section::detail {

/// What sampling_of searched over all of a cloud's points: its kd-tree over them and, for
/// each point, the squared distance mean_spacing takes from the point's 3 nearest (the
/// second, else the third, where nonzero; 0 where neither is), -1 for a point not searched.
/// Empty (no tree) unless the points are a dense scan and sampling_of looked at all of them
/// (only a dense scan's slab is its mean spacing).
struct SpacingSearch {
  std::unique_ptr<NearestPoints<3>> tree;
  std::vector<double> nearest_d2;
};

/// Refuses a cloud built in memory with a point the cloud readers refuse: not finite, or a
/// coordinate beyond +-1e15 (whose squares overflow; one point at 1e20 made the raster
/// exceed its cells). Names the point.
void check_points(const std::vector<Eigen::Vector3d>& points);

/// sampling_of(points, normal, options), its searches kept in `search`.
Sampling sampling_of(const std::vector<Eigen::Vector3d>& points, const Eigen::Vector3d& normal,
                     const SamplingOptions& options, SpacingSearch& search);

/// mean_spacing(points, sample), bit for bit, from `search` where it holds these points (the
/// same tree, and the 3 nearest of a point are the first 3 of the 17 or 24 nearest
/// sampling_of searched, with the same squared distances: both are FLANN's exact search).
double mean_spacing(const std::vector<Eigen::Vector3d>& points, const SpacingSearch& search,
                    std::size_t sample = 5000);

}  // namespace section::detail

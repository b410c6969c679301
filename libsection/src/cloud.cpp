// SPDX-License-Identifier: GPL-3.0-or-later
#include "section/cloud.h"

#include "detail/flann_nearest.h"
#include "detail/spacing_search.h"

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

namespace section {

namespace {

// The median distance from q of the m points `subset` (every (m / q)-th) to their nearest
// other distinct point, by their nearest in `index` (the first nonzero of the 2 after the
// point itself), or from `known` (SpacingSearch's nearest_d2) where a point's are known.
double median_nearest(const detail::NearestPoints<3>& index, const std::vector<Eigen::Vector3d>& subset,
                      std::size_t q, const std::vector<double>& known) {
  const std::size_t m = subset.size();
  std::vector<double> dists;
  dists.reserve(q);
  int idx[3];
  double d2[3] = {0, 0, 0};  // kept across queries, as FLANN leaves the entries it does not find
  for (std::size_t i = 0; i < q; ++i) {
    const std::size_t at = (i * m) / q;
    if (!known.empty() && known[at] >= 0) {
      if (known[at] > 0) dists.push_back(std::sqrt(known[at]));
      continue;
    }
    // The first 2 of the 3 nearest are the 2 nearest (as in sampling_of's near_of): the
    // third is needed only past a copy of the point.
    index.k_nearest(subset[at], 2, idx, d2);
    if (!(d2[1] > 0)) index.k_nearest(subset[at], 3, idx, d2);
    for (int j = 1; j < 3; ++j)
      if (d2[j] > 0) {
        dists.push_back(std::sqrt(d2[j]));
        break;
      }
  }
  if (dists.empty()) return 0;
  std::nth_element(dists.begin(), dists.begin() + std::ptrdiff_t(dists.size() / 2), dists.end());
  return dists[dists.size() / 2];
}

}  // namespace

double mean_spacing(const std::vector<Eigen::Vector3d>& points, std::size_t sample) {
  const std::size_t n = points.size();
  if (n < 2) return 0;
  sample = std::max<std::size_t>(sample, 100);
  // A random subset of a surface scan is a sparser surface scan: its nearest-neighbour
  // distance grows as 1/sqrt(fraction), which scales the estimate back.
  std::size_t m = std::min(n, sample * 10);
  std::vector<Eigen::Vector3d> subset;
  subset.reserve(m);
  std::mt19937_64 rng(12345);
  if (m == n) {
    subset = points;
  } else {
    for (std::size_t i = 0; i < m; ++i) subset.push_back(points[rng() % n]);
  }
  const detail::NearestPoints<3> index(subset);
  double d = median_nearest(index, subset, std::min(m, sample), {});
  if (m < n) d *= std::sqrt(double(m) / double(n)) / 0.47;  // Poisson median NN = 0.47/sqrt(density)
  return d;
}

namespace detail {

double mean_spacing(const std::vector<Eigen::Vector3d>& points, const SpacingSearch& search,
                    std::size_t sample) {
  const std::size_t n = points.size();
  sample = std::max<std::size_t>(sample, 100);
  // Where mean_spacing would search a random subset, or these are not the points searched.
  if (!search.tree || search.nearest_d2.size() != n || n > sample * 10)
    return section::mean_spacing(points, sample);
  return median_nearest(*search.tree, points, std::min(n, sample), search.nearest_d2);
}

}  // namespace detail

}  // namespace section

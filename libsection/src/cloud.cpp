// SPDX-License-Identifier: GPL-3.0-or-later
#include "section/cloud.h"

#include "detail/flann_nearest.h"

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

namespace section {

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
  const std::size_t q = std::min(m, sample);
  std::vector<double> dists;
  dists.reserve(q);
  int idx[3];
  double d2[3] = {0, 0, 0};  // kept across queries, as FLANN leaves the entries it does not find
  for (std::size_t i = 0; i < q; ++i) {
    index.k_nearest(subset[(i * m) / q], 3, idx, d2);
    for (int j = 1; j < 3; ++j)
      if (d2[j] > 0) {
        dists.push_back(std::sqrt(d2[j]));
        break;
      }
  }
  if (dists.empty()) return 0;
  std::nth_element(dists.begin(), dists.begin() + dists.size() / 2, dists.end());
  double d = dists[dists.size() / 2];
  if (m < n) d *= std::sqrt(double(m) / double(n)) / 0.47;  // Poisson median NN = 0.47/sqrt(density)
  return d;
}

}  // namespace section

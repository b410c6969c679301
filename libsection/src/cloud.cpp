#include "section/cloud.h"

#include <flann/flann.hpp>

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
  std::vector<double> data;
  std::size_t m = std::min(n, sample * 10);
  data.reserve(m * 3);
  std::mt19937_64 rng(12345);
  if (m == n) {
    for (const auto& p : points) data.insert(data.end(), {p.x(), p.y(), p.z()});
  } else {
    for (std::size_t i = 0; i < m; ++i) {
      const auto& p = points[rng() % n];
      data.insert(data.end(), {p.x(), p.y(), p.z()});
    }
  }
  flann::Matrix<double> dataset(data.data(), m, 3);
  flann::Index<flann::L2<double>> index(dataset, flann::KDTreeSingleIndexParams(12));
  index.buildIndex();
  const std::size_t q = std::min(m, sample);
  std::vector<double> dists;
  dists.reserve(q);
  std::vector<int> idx(3);
  std::vector<double> d2(3);
  for (std::size_t i = 0; i < q; ++i) {
    const std::size_t k = (i * m) / q;
    flann::Matrix<double> query(&data[k * 3], 1, 3);
    flann::Matrix<int> mi(idx.data(), 1, 3);
    flann::Matrix<double> md(d2.data(), 1, 3);
    index.knnSearch(query, mi, md, 3, flann::SearchParams(flann::FLANN_CHECKS_UNLIMITED));
    for (int j = 1; j < 3; ++j)
      if (d2[j] > 0) { dists.push_back(std::sqrt(d2[j])); break; }
  }
  if (dists.empty()) return 0;
  std::nth_element(dists.begin(), dists.begin() + dists.size() / 2, dists.end());
  double d = dists[dists.size() / 2];
  if (m < n) d *= std::sqrt(double(m) / double(n)) / 0.47;  // Poisson median NN = 0.47/sqrt(density)
  return d;
}

}  // namespace section

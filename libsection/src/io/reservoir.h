// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The uniform random sample slice_file takes of a cloud file as it reads it (its spacing).
#include <Eigen/Core>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <random>
#include <vector>

namespace section::detail {

// A uniform random sample of the points read, 50000 at most (reservoir sampling by skips,
// Li's algorithm L: random numbers only for the points taken, O(k log(n / k)) of them,
// instead of one per point).
class Reservoir {
public:
  static constexpr std::size_t size = 50000;
  Reservoir() {
    w_ = std::exp(std::log(u01()) / size);
    skip();
  }
  // Offers the next `count` points of the file.
  void take(const Eigen::Vector3d* p, std::size_t count) {
    for (std::size_t i = 0; i < count && points.size() < size; ++i) points.push_back(p[i]);
    for (; next_ < seen_ + count; skip())
      points[std::uniform_int_distribution<std::size_t>(0, size - 1)(rng_)] = p[next_ - seen_];
    seen_ += count;
  }
  std::vector<Eigen::Vector3d> points;

private:
  double u01() { return std::max(unit_(rng_), 1e-300); }
  void skip() {
    next_ += std::size_t(std::floor(std::log(u01()) / std::log1p(-w_))) + 1;
    w_ *= std::exp(std::log(u01()) / size);
  }
  std::mt19937_64 rng_{12345};
  std::uniform_real_distribution<double> unit_{0.0, 1.0};
  double w_ = 0;
  std::size_t next_ = size - 1;  // index of the next point to take once the sample is full
  std::size_t seen_ = 0;
};

}  // namespace section::detail

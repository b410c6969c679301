// SPDX-License-Identifier: GPL-3.0-or-later
#include "detail/flann_nearest.h"

#include "section/error.h"

#include <flann/flann.hpp>

namespace section::detail {

template <int Dim>
struct NearestPoints<Dim>::Impl {
  std::vector<double> coords;  // row-major copy: FLANN keeps a pointer to it
  // The kd-tree itself (flann::Index would make it so too), so that k_nearest can search it
  // without knnSearch's copies and allocations per query.
  std::unique_ptr<flann::KDTreeSingleIndex<flann::L2<double>>> index;
};

namespace {

template <int Dim>
std::vector<double> row_major(const std::vector<Eigen::Matrix<double, Dim, 1>>& points) {
  std::vector<double> out(points.size() * Dim);
  for (std::size_t i = 0; i < points.size(); ++i)
    for (int k = 0; k < Dim; ++k) out[Dim * i + k] = points[i][k];
  return out;
}

}  // namespace

template <int Dim>
NearestPoints<Dim>::NearestPoints(const std::vector<Point>& points, int leaf_size) : impl_(new Impl) {
  if (points.empty()) throw Error("nearest: no points to search");
  impl_->coords = row_major<Dim>(points);
  flann::Matrix<double> data(impl_->coords.data(), points.size(), Dim);
  impl_->index = std::make_unique<flann::KDTreeSingleIndex<flann::L2<double>>>(
      data, flann::KDTreeSingleIndexParams(leaf_size));
  impl_->index->buildIndex();
}

template <int Dim>
NearestPoints<Dim>::~NearestPoints() = default;

template <int Dim>
std::vector<int> NearestPoints<Dim>::nearest(const std::vector<Point>& queries) const {
  std::vector<int> result(queries.size(), 0);
  if (queries.empty()) return result;
  std::vector<double> q = row_major<Dim>(queries);
  std::vector<double> dist(queries.size());
  flann::Matrix<double> qm(q.data(), queries.size(), Dim);
  flann::Matrix<int> im(result.data(), queries.size(), 1);
  flann::Matrix<double> dm(dist.data(), queries.size(), 1);
  flann::SearchParams params(flann::FLANN_CHECKS_UNLIMITED);
  params.cores = 1;
  impl_->index->knnSearch(qm, im, dm, 1, params);
  return result;
}

template <int Dim>
void NearestPoints<Dim>::nearest_within(const std::vector<Point>& queries, double radius,
                                        std::vector<int>& index, std::vector<double>& d2) const {
  std::vector<double> q = row_major<Dim>(queries);
  index.assign(queries.size(), -1);
  d2.assign(queries.size(), 0);
  flann::Matrix<double> qm(q.data(), queries.size(), Dim);
  flann::Matrix<int> im(index.data(), queries.size(), 1);
  flann::Matrix<double> dm(d2.data(), queries.size(), 1);
  flann::SearchParams params(flann::FLANN_CHECKS_UNLIMITED);
  params.cores = 0;
  params.max_neighbors = 1;
  impl_->index->radiusSearch(qm, im, dm, static_cast<float>(radius * radius), params);
}

template <int Dim>
void NearestPoints<Dim>::k_nearest(const Point& q, int k, int* index, double* d2) const {
  double coords[Dim];
  for (int i = 0; i < Dim; ++i) coords[i] = q[i];
  const flann::SearchParams params(flann::FLANN_CHECKS_UNLIMITED);
  constexpr int few = 64;  // at most this many: knnSearch's own search, straight (no heap under 250)
  if (k > few) {
    flann::Matrix<double> qm(coords, 1, Dim);
    flann::Matrix<int> im(index, 1, static_cast<std::size_t>(k));
    flann::Matrix<double> dm(d2, 1, static_cast<std::size_t>(k));
    impl_->index->knnSearch(qm, im, dm, k, params);
    return;
  }
  flann::KNNSimpleResultSet<double> found(static_cast<std::size_t>(k));
  impl_->index->findNeighbors(found, coords, params);
  std::size_t at[few];
  const std::size_t n = std::min(found.size(), static_cast<std::size_t>(k));
  found.copy(at, d2, n);
  for (std::size_t j = 0; j < n; ++j) index[j] = static_cast<int>(at[j]);
}

template class NearestPoints<2>;
template class NearestPoints<3>;

}  // namespace section::detail

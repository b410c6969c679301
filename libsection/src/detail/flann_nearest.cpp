#include "detail/flann_nearest.h"

#include "section/error.h"

#include <flann/flann.hpp>

namespace section::detail {

struct NearestPoints::Impl {
  std::vector<double> coords;  // row-major copy: FLANN keeps a pointer to it
  std::unique_ptr<flann::Index<flann::L2<double>>> index;
};

NearestPoints::NearestPoints(const std::vector<Eigen::Vector2d>& points) : impl_(new Impl) {
  if (points.empty()) throw Error("nearest: no points to search");
  impl_->coords.resize(points.size() * 2);
  for (std::size_t i = 0; i < points.size(); ++i) {
    impl_->coords[2 * i] = points[i].x();
    impl_->coords[2 * i + 1] = points[i].y();
  }
  flann::Matrix<double> data(impl_->coords.data(), points.size(), 2);
  impl_->index = std::make_unique<flann::Index<flann::L2<double>>>(
      data, flann::KDTreeSingleIndexParams(10));
  impl_->index->buildIndex();
}

NearestPoints::~NearestPoints() = default;

std::vector<int> NearestPoints::nearest(const std::vector<Eigen::Vector2d>& queries) const {
  std::vector<int> result(queries.size(), 0);
  if (queries.empty()) return result;
  std::vector<double> q(queries.size() * 2);
  for (std::size_t i = 0; i < queries.size(); ++i) {
    q[2 * i] = queries[i].x();
    q[2 * i + 1] = queries[i].y();
  }
  std::vector<double> dist(queries.size());
  flann::Matrix<double> qm(q.data(), queries.size(), 2);
  flann::Matrix<int> im(result.data(), queries.size(), 1);
  flann::Matrix<double> dm(dist.data(), queries.size(), 1);
  flann::SearchParams params(flann::FLANN_CHECKS_UNLIMITED);
  params.cores = 1;
  impl_->index->knnSearch(qm, im, dm, 1, params);
  return result;
}

}  // namespace section::detail

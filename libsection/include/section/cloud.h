// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// @file cloud.h
/// Point clouds in memory (their readers and writers: io/cloud_io.h).
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstddef>
#include <vector>

namespace section {

/// An unordered 3D point cloud, in the units of its file.
struct Cloud {
  std::vector<Eigen::Vector3d> points;  ///< the points
};

/// Mean spacing of a cloud: the median distance from a point to its nearest neighbour,
/// estimated on at most `sample` points. 0 for fewer than two distinct points.
double mean_spacing(const std::vector<Eigen::Vector3d>& points, std::size_t sample = 5000);

}  // namespace section

// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// @file mesh.h
/// Triangle meshes in memory (their readers and writers: io/mesh_io.h).
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <vector>

namespace section {

/// An indexed triangle mesh; polygons are split into triangles on reading.
struct Mesh {
  std::vector<Eigen::Vector3d> vertices;      ///< vertex positions
  std::vector<std::array<int, 3>> triangles;  ///< vertex indices, counterclockwise seen from outside
};

}  // namespace section

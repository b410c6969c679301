// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The library's only doors to CGAL: its headers stay inside src/detail/cgal_*.cpp.
#include "section/mesh.h"

#include <Eigen/Core>
#include <functional>
#include <vector>

namespace section::detail {

/// Exact sign of the orientation of q against the plane through a, b, c (CGAL's
/// orientation predicate): +1 on the side of (b - a) x (c - a), -1 opposite, 0 on it.
int orientation(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                const Eigen::Vector3d& q);

/// The intersection polylines of one plane: a closed polyline repeats its first point at the end.
using PlaneCut = std::vector<std::vector<Eigen::Vector3d>>;

/// Intersection polylines of a triangle mesh with planes (CGAL::Polygon_mesh_slicer), handed
/// to `each(i, cut)` plane by plane, in order, as each is cut. The mesh's triangle indices
/// must lie within its vertices (check_mesh, detail/slice_steps.h).
void mesh_slices(const Mesh& mesh, const std::vector<Eigen::Vector3d>& origins,
                 const std::vector<Eigen::Vector3d>& normals,
                 const std::function<void(std::size_t, PlaneCut&&)>& each);

}  // namespace section::detail

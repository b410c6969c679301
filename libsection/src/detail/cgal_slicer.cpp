// SPDX-License-Identifier: GPL-3.0-or-later
#include "detail/cgal.h"

#include "section/error.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/orient_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Polygon_mesh_slicer.h>
#include <CGAL/Surface_mesh.h>

namespace section::detail {

void mesh_slices(const Mesh& mesh, const std::vector<Eigen::Vector3d>& origins,
                 const std::vector<Eigen::Vector3d>& normals,
                 const std::function<void(std::size_t, PlaneCut&&)>& each) {
  using K = CGAL::Exact_predicates_inexact_constructions_kernel;
  using SM = CGAL::Surface_mesh<K::Point_3>;
  namespace PMP = CGAL::Polygon_mesh_processing;

  std::vector<K::Point_3> points;
  points.reserve(mesh.vertices.size());
  for (const auto& v : mesh.vertices) points.emplace_back(v.x(), v.y(), v.z());
  std::vector<std::vector<std::size_t>> polygons;
  polygons.reserve(mesh.triangles.size());
  for (const auto& t : mesh.triangles) {                         // (indices checked by check_mesh)
    if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2]) continue;  // degenerate: cuts nothing
    polygons.push_back({std::size_t(t[0]), std::size_t(t[1]), std::size_t(t[2])});
  }
  if (polygons.empty()) throw Error("slice: the mesh has no non-degenerate triangles");
  // Scanner exports are not always manifold: orienting the soup splits what must be split.
  PMP::orient_polygon_soup(points, polygons);
  SM sm;
  PMP::polygon_soup_to_polygon_mesh(points, polygons, sm);

  CGAL::Polygon_mesh_slicer<SM, K> slicer(sm);
  for (std::size_t i = 0; i < origins.size(); ++i) {
    const auto& o = origins[i];
    const auto& n = normals[i];
    std::vector<std::vector<K::Point_3>> polylines;
    slicer(K::Plane_3(K::Point_3(o.x(), o.y(), o.z()), K::Vector_3(n.x(), n.y(), n.z())),
           std::back_inserter(polylines));
    PlaneCut cut;
    for (const auto& pl : polylines) {
      std::vector<Eigen::Vector3d> line;
      line.reserve(pl.size());
      for (const auto& p : pl) line.emplace_back(p.x(), p.y(), p.z());
      cut.push_back(std::move(line));
    }
    each(i, std::move(cut));
  }
}

}  // namespace section::detail

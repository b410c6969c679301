// SPDX-License-Identifier: GPL-3.0-or-later
#include "detail/cgal_medial_axis.h"

#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_face_base_with_info_2.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <vector>

namespace section::detail {

namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
struct FaceInfo {
  int nesting = -1;  // constraints crossed from the infinite face; odd = inside
  int index = -1;    // index among the inside faces
};
using Vb = CGAL::Triangulation_vertex_base_with_info_2<int, K>;
using Fbi = CGAL::Triangulation_face_base_with_info_2<FaceInfo, K>;
using Fb = CGAL::Constrained_triangulation_face_base_2<K, Fbi>;
using Tds = CGAL::Triangulation_data_structure_2<Vb, Fb>;
// Exact_predicates_tag: a self-touching polygon gets intersection vertices, not an abort.
using Cdt = CGAL::Constrained_Delaunay_triangulation_2<K, Tds, CGAL::Exact_predicates_tag>;

// Nesting levels by flood fill across unconstrained edges, as in CGAL's polygon
// triangulation example: level 0 outside, 1 inside the polygon.
void mark_domains(Cdt& cdt) {
  for (auto f = cdt.all_faces_begin(); f != cdt.all_faces_end(); ++f) f->info().nesting = -1;
  std::vector<Cdt::Face_handle> frontier{cdt.infinite_face()};
  std::vector<Cdt::Edge> border;
  int level = 0;
  while (!frontier.empty()) {
    std::vector<Cdt::Face_handle> queue = frontier;
    frontier.clear();
    while (!queue.empty()) {
      const Cdt::Face_handle f = queue.back();
      queue.pop_back();
      if (f->info().nesting != -1) continue;
      f->info().nesting = level;
      for (int i = 0; i < 3; ++i) {
        const Cdt::Face_handle n = f->neighbor(i);
        if (n->info().nesting != -1) continue;
        if (cdt.is_constrained(Cdt::Edge(f, i)))
          frontier.push_back(n);
        else
          queue.push_back(n);
      }
    }
    ++level;
  }
}

// Points first (spatially sorted, fast), then the polygon edges as constraints: on a
// dense sampling nearly all of them are Delaunay edges already and only get marked.
// False, with no constraints marked, when the points all lie on one line: such a
// triangulation has no faces, and its edges no neighbours to mark across.
bool triangulate(const std::vector<Eigen::Vector2d>& polygon, Cdt& cdt) {
  const int n = static_cast<int>(polygon.size());
  std::vector<std::pair<K::Point_2, int>> points;
  points.reserve(n);
  for (int i = 0; i < n; ++i) points.emplace_back(K::Point_2(polygon[i].x(), polygon[i].y()), i);
  cdt.insert(points.begin(), points.end());
  if (cdt.dimension() < 2) return false;
  std::vector<Cdt::Vertex_handle> vertex(n);
  for (auto v = cdt.finite_vertices_begin(); v != cdt.finite_vertices_end(); ++v) vertex[v->info()] = v;
  for (int i = 0; i < n; ++i)  // duplicates share the vertex kept
    if (vertex[i] == Cdt::Vertex_handle()) vertex[i] = cdt.insert(points[i].first);
  for (int i = 0; i < n; ++i) {
    const auto a = vertex[i], b = vertex[(i + 1) % n];
    if (a == b) continue;
    Cdt::Face_handle f;
    int k = 0;
    if (cdt.is_edge(a, b, f, k)) {
      f->set_constraint(k, true);
      f->neighbor(k)->set_constraint(cdt.mirror_index(f, k), true);
    } else {
      cdt.insert_constraint(a, b);
    }
  }
  mark_domains(cdt);
  return true;
}

// The dual tree of the inside triangles: a node per triangle at its circumcentre, with
// its distance to the corners, joined across the unconstrained shared edges (at most
// three per node: kept in place, not as a vector per node).
struct DualTree {
  std::vector<Eigen::Vector2d> node;
  std::vector<double> radius;
  std::vector<std::array<int, 3>> adjacent;
  std::vector<int> degree;
};

// A near-degenerate triangle whose circumcentre leaves the polygon's bounding box is
// placed at its centroid instead so that it cannot stretch the longest path.
DualTree dual_tree(const std::vector<Eigen::Vector2d>& polygon, Cdt& cdt) {
  Eigen::Vector2d low = polygon[0], high = polygon[0];
  for (const auto& p : polygon) {
    low = low.cwiseMin(p);
    high = high.cwiseMax(p);
  }
  DualTree tree;
  std::vector<Cdt::Face_handle> faces;
  faces.reserve(cdt.number_of_faces());
  tree.node.reserve(cdt.number_of_faces());
  tree.radius.reserve(cdt.number_of_faces());
  for (auto f = cdt.finite_faces_begin(); f != cdt.finite_faces_end(); ++f) {
    if (f->info().nesting % 2 != 1) continue;
    Eigen::Vector2d p[3];
    for (int i = 0; i < 3; ++i) p[i] = {f->vertex(i)->point().x(), f->vertex(i)->point().y()};
    const Eigen::Vector2d centroid = (p[0] + p[1] + p[2]) / 3;
    const K::Point_2 cc =
        CGAL::circumcenter(f->vertex(0)->point(), f->vertex(1)->point(), f->vertex(2)->point());
    Eigen::Vector2d c(cc.x(), cc.y());
    if (!std::isfinite(c.x()) || !std::isfinite(c.y()) || (c.array() < low.array()).any() ||
        (c.array() > high.array()).any())
      c = centroid;
    f->info().index = static_cast<int>(faces.size());
    faces.push_back(f);
    tree.node.push_back(c);
    tree.radius.push_back(std::min({(c - p[0]).norm(), (c - p[1]).norm(), (c - p[2]).norm()}));
  }
  tree.adjacent.resize(faces.size());
  tree.degree.assign(faces.size(), 0);
  for (std::size_t k = 0; k < faces.size(); ++k)
    for (int i = 0; i < 3; ++i) {
      const Cdt::Face_handle nb = faces[k]->neighbor(i);
      if (cdt.is_infinite(nb) || nb->info().nesting % 2 != 1) continue;
      if (cdt.is_constrained(Cdt::Edge(faces[k], i))) continue;
      tree.adjacent[k][std::size_t(tree.degree[k]++)] = nb->info().index;
    }
  return tree;
}

// Longest path of the dual tree: farthest node from the widest triangle, then the
// farthest node from that one (exact on a tree); its nodes from that end back.
std::vector<int> longest_path(const DualTree& tree) {
  const int m = static_cast<int>(tree.node.size());
  std::vector<double> distance(m);
  std::vector<int> parent(m);
  auto farthest = [&](int start) {
    std::fill(distance.begin(), distance.end(), -1.0);
    std::fill(parent.begin(), parent.end(), -1);
    std::vector<int> stack{start};
    distance[start] = 0;
    int best = start;
    while (!stack.empty()) {
      const int k = stack.back();
      stack.pop_back();
      if (distance[k] > distance[best]) best = k;
      for (int a = 0; a < tree.degree[std::size_t(k)]; ++a)
        if (const int j = tree.adjacent[std::size_t(k)][std::size_t(a)]; distance[j] < 0) {
          distance[j] = distance[k] + (tree.node[j] - tree.node[k]).norm();
          parent[j] = k;
          stack.push_back(j);
        }
    }
    return best;
  };
  const int widest =
      static_cast<int>(std::max_element(tree.radius.begin(), tree.radius.end()) - tree.radius.begin());
  const int a = farthest(widest);
  std::vector<int> path;
  for (int k = farthest(a); k != -1; k = parent[k]) path.push_back(k);
  return path;
}

}  // namespace

MedialSeed medial_axis_seed(const std::vector<Eigen::Vector2d>& polygon) {
  MedialSeed seed;
  if (polygon.size() < 3) return seed;
  Cdt cdt;
  if (!triangulate(polygon, cdt)) return seed;
  const DualTree tree = dual_tree(polygon, cdt);
  seed.triangles = static_cast<int>(tree.node.size());
  if (tree.node.empty()) return seed;
  for (int k : longest_path(tree)) {
    seed.points.push_back(tree.node[k]);
    seed.radius.push_back(tree.radius[k]);
  }
  return seed;
}

}  // namespace section::detail

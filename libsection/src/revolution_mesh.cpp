// SPDX-License-Identifier: GPL-3.0-or-later
// Slicing a mesh by surfaces of revolution: each crossing edge cut where the signed
// distance from the surface is 0, the triangles' pieces linked into loops (docs/REVOLUTION.md).
#include "section/revolution.h"

#include "section/error.h"
#include "detail/local_origin.h"
#include "detail/slice_steps.h"
#include "revolution_map.h"

#include <array>
#include <cmath>
#include <map>
#include <utility>

namespace section {

namespace {

using Edge = std::pair<int, int>;  // vertex indices, lower first

// The point of edge (a, b) where w changes sign (w(a) < 0 <= w(b) or the other way):
// bisection in the edge parameter until the interval stops shrinking.
Eigen::Vector3d crossing(const detail::RevolutionMap& map, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                         double wa) {
  if (wa == 0) return a;
  double lo = 0, hi = 1;
  const bool a_below = wa < 0;
  for (int it = 0; it < 200; ++it) {
    const double mid = 0.5 * (lo + hi);
    if (!(mid > lo && mid < hi)) break;
    const double w = map.foot(map.cylindrical(a + mid * (b - a)).head<2>()).w;
    ((w < 0) == a_below ? lo : hi) = mid;
  }
  const double t = 0.5 * (lo + hi);
  return a + t * (b - a);
}

// The cut of a mesh by one surface: closed polylines (each ending on its first point) and
// open ones (a mesh not closed there).
std::vector<std::vector<Eigen::Vector3d>> cut_mesh(const Mesh& mesh, const detail::RevolutionMap& map) {
  std::vector<double> w(mesh.vertices.size());
  for (std::size_t i = 0; i < w.size(); ++i) w[i] = map.foot(map.cylindrical(mesh.vertices[i]).head<2>()).w;
  const auto below = [&](int i) { return w[std::size_t(i)] < 0; };  // w = 0 counts as above
  std::map<Edge, int> node;                                         // a crossing edge -> its point
  std::vector<Eigen::Vector3d> point;                               // the crossing points
  std::vector<std::array<int, 2>> link;                             // each point's (up to) two neighbours
  const auto node_of = [&](int i, int j) {
    const Edge e{std::min(i, j), std::max(i, j)};
    const auto [it, added] = node.emplace(e, int(point.size()));
    if (added) {
      point.push_back(crossing(map, mesh.vertices[std::size_t(e.first)], mesh.vertices[std::size_t(e.second)],
                               w[std::size_t(e.first)]));
      link.push_back({-1, -1});
    }
    return it->second;
  };
  const auto join = [&](int p, int q) {
    for (int x : {p, q}) {
      auto& l = link[std::size_t(x)];
      (l[0] < 0 ? l[0] : l[1]) = x == p ? q : p;
    }
  };
  for (const auto& t : mesh.triangles) {
    std::array<int, 2> ends{-1, -1};
    int found = 0;
    for (int k = 0; k < 3 && found < 2; ++k) {
      const int i = t[k], j = t[(k + 1) % 3];
      if (below(i) != below(j)) ends[found++] = node_of(i, j);
    }
    if (found == 2) join(ends[0], ends[1]);
  }
  // Walk the links: each point has two on a closed mesh; a chain from an end is open.
  std::vector<char> seen(point.size(), 0);
  std::vector<std::vector<Eigen::Vector3d>> lines;
  const auto walk = [&](int start) {
    std::vector<Eigen::Vector3d> line;
    int prev = -1, at = start;
    while (at >= 0 && !seen[std::size_t(at)]) {
      seen[std::size_t(at)] = 1;
      if (line.empty() || line.back() != point[std::size_t(at)]) line.push_back(point[std::size_t(at)]);
      const auto& l = link[std::size_t(at)];
      const int next = l[0] != prev ? l[0] : l[1];
      prev = at;
      at = next;
    }
    if (at == start && line.size() > 1) line.push_back(line.front());
    lines.push_back(std::move(line));
  };
  for (std::size_t p = 0; p < point.size(); ++p)
    if (!seen[p] && (link[p][0] < 0 || link[p][1] < 0)) walk(int(p));  // open chains from an end
  for (std::size_t p = 0; p < point.size(); ++p)
    if (!seen[p]) walk(int(p));
  return lines;
}

}  // namespace

SliceResult slice(const Mesh& mesh, const std::vector<Revolution>& surfaces, const SliceOptions&,
                  const SectionSink& sink) {
  detail::check_mesh(mesh);
  const std::vector<Revolution> given = detail::with_references(surfaces, mesh.vertices);
  SliceResult result;
  result.points = mesh.vertices.size();
  result.sections.resize(given.size());
  for (std::size_t k = 0; k < given.size(); ++k) {
    Revolution surface = given[k];
    const bool mean_radius = !(surface.r_ref > 0);
    if (mean_radius) surface.r_ref = 1;  // the cut does not depend on it
    const auto lines = cut_mesh(mesh, detail::RevolutionMap(surface));
    if (mean_radius) {
      double sum = 0;
      std::size_t count = 0;
      const detail::RevolutionMap unit(surface);
      for (const auto& line : lines)
        for (const auto& p : line) sum += unit.cylindrical(p).y(), ++count;
      if (count > 0 && sum > 0) surface.r_ref = sum / double(count);
    }
    SectionSlice& s = result.sections[k];
    s.id = static_cast<int>(k);
    const detail::RevolutionMap map(surface);
    std::vector<Eigen::Vector2d> cut;
    for (const auto& line : lines)
      for (const auto& p : line) cut.push_back(map.place(p).uv);
    surface.shift += detail::local_origin(cut);
    const detail::RevolutionMap shifted(surface);
    detail::mesh_loops(
        lines, [&](const Eigen::Vector3d& p) { return shifted.place(p).uv; }, s);
    if (s.error.empty() && s.morphology.loops.empty()) s.error = "the surface does not cut the mesh";
    s.frame = surface_frame(surface);
    if (sink) sink(s);
  }
  return result;
}

}  // namespace section

// SPDX-License-Identifier: GPL-3.0-or-later
// slice on a mesh: each plane's exact cut (CGAL's slicer) as the section's loops; a mesh
// open at the plane (a scan's mesh with a hole) has its cut points ordered as a cloud's.
#include "section/slice.h"

#include "detail/cgal.h"
#include "detail/local_origin.h"
#include "detail/slice_steps.h"
#include "section/error.h"
#include "section/morphology.h"

#include <algorithm>
#include <functional>
#include <string>
#include <vector>

namespace section {

namespace {

// A cut polyline that closes on itself (its last point its first).
bool closes(const std::vector<Eigen::Vector3d>& line) {
  return line.size() >= 4 && (line.front() - line.back()).norm() <= 1e-12 * (1 + line.front().norm());
}

// The longest step between consecutive points of a closed loop.
double longest_step(const std::vector<Eigen::Vector2d>& points) {
  double longest = 0;
  for (std::size_t k = 0; k < points.size(); ++k)
    longest = std::max(longest, (points[(k + 1) % points.size()] - points[k]).norm());
  return longest;
}

// A mesh open at the plane (a scan's mesh with a hole there) cuts into open polylines, and
// the section was refused. Their points are ordered as a cloud's slab: the morphology
// bridges the hole, and the later stages flag what rests on the bridge (an edge, the
// thickest circle) as they do a scan's hole.
void bridge_open_cut(const std::vector<std::vector<Eigen::Vector3d>>& lines, std::size_t open,
                     const std::function<Eigen::Vector2d(const Eigen::Vector3d&)>& to_plane,
                     SectionSlice& s) {
  const std::string what = std::to_string(open) +
                           " open intersection polyline(s): the mesh is not closed around "
                           "this plane";
  std::vector<Eigen::Vector2d> points;
  for (const auto& line : lines) {
    for (std::size_t k = 0; k + (closes(line) ? 1 : 0) < line.size(); ++k)
      points.push_back(to_plane(line[k]));
  }
  try {
    s.morphology = order_section(points, MorphologyOptions{});
  } catch (const Error& e) {
    s.morphology = {};
    s.error = what + ", and its cut points do not close into a loop (" + e.what() + ")";
    return;
  }
  s.slab_points = points.size();
  s.open_polylines = open;
  s.bridged = longest_step(s.morphology.loops.front().points);
}

}  // namespace

namespace detail {

void mesh_loops(const std::vector<std::vector<Eigen::Vector3d>>& lines,
                const std::function<Eigen::Vector2d(const Eigen::Vector3d&)>& to_plane, SectionSlice& s) {
  std::vector<Loop> loops;
  std::size_t open = 0;
  for (const auto& line : lines) {
    if (!closes(line)) {
      ++open;
      continue;
    }
    Loop loop;
    for (std::size_t k = 0; k + 1 < line.size(); ++k) loop.points.push_back(to_plane(line[k]));
    double area = 0, length = 0;
    const std::size_t n = loop.points.size();
    for (std::size_t k = 0; k < n; ++k) {
      const auto& a = loop.points[k];
      const auto& b = loop.points[(k + 1) % n];
      area += 0.5 * (a.x() * b.y() - b.x() * a.y());
      length += (b - a).norm();
    }
    if (area < 0) {
      std::reverse(loop.points.begin(), loop.points.end());
      area = -area;
    }
    loop.area = area;
    loop.length = length;
    loop.normals.resize(n);
    for (std::size_t k = 0; k < n; ++k) {
      const Eigen::Vector2d t = loop.points[(k + 1) % n] - loop.points[(k + n - 1) % n];
      const Eigen::Vector2d nrm(t.y(), -t.x());
      loop.normals[k] = nrm.norm() > 0 ? Eigen::Vector2d(nrm.normalized()) : Eigen::Vector2d(0, 0);
    }
    loop.boundary = loop.points;
    loops.push_back(std::move(loop));
    s.slab_points += n;
  }
  std::stable_sort(loops.begin(), loops.end(), [](const Loop& a, const Loop& b) { return a.area > b.area; });
  s.morphology.loops = std::move(loops);
  if (open > 0) bridge_open_cut(lines, open, to_plane, s);
}

}  // namespace detail

SliceResult slice(const Mesh& mesh, const std::vector<Plane>& planes, const SliceOptions& options,
                  const SectionSink& sink) {
  detail::check_planes(planes);
  detail::check_mesh(mesh);
  std::vector<Eigen::Vector3d> origins, normals;
  for (const auto& p : planes) {
    origins.push_back(p.origin);
    normals.push_back(p.normal.normalized());
  }
  SliceResult result;
  result.points = mesh.vertices.size();
  result.slab = 0;
  result.sections.resize(planes.size());
  detail::mesh_slices(mesh, origins, normals, [&](std::size_t i, detail::PlaneCut&& plane_cut) {
    SectionSlice& s = result.sections[i];
    s.id = static_cast<int>(i);
    s.frame = make_frame(planes[i].origin, planes[i].normal);
    // Far from the plane's origin, the frame's origin moves near the cut (small (u, v)).
    std::vector<Eigen::Vector2d> cut;
    for (const auto& line : plane_cut)
      for (const auto& p : line) cut.push_back(s.frame.to_plane(p));
    const Eigen::Vector2d local = detail::local_origin(cut);
    if (local != Eigen::Vector2d::Zero()) s.frame.origin = s.frame.to_world(local);
    detail::mesh_loops(
        plane_cut, [&](const Eigen::Vector3d& p) { return s.frame.to_plane(p); }, s);
    if (s.error.empty() && s.morphology.loops.empty()) s.error = "the plane does not cut the mesh";
    if (sink) sink(s);
  });
  return result;
}

}  // namespace section

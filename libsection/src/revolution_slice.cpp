// SPDX-License-Identifier: GPL-3.0-or-later
// Slicing a cloud by surfaces of revolution: the cloud unrolled onto each surface, then cut
// by the plane w = 0 as slice(Cloud, planes) cuts it (docs/REVOLUTION.md).
#include "section/revolution.h"

#include "section/error.h"
#include "revolution_map.h"
#include "detail/spacing_search.h"

#include <algorithm>
#include <cstdio>
#include <string>
#include <cmath>
#include <memory>
#include <new>

namespace section {

namespace {

// The surface with its r_ref filled from the points when 0: the mean radius of the feet of
// the points nearest to the surface.
Revolution completed(Revolution s, const std::vector<Eigen::Vector3d>& points) {
  if (s.r_ref > 0) return s;
  s.r_ref = 1;  // w and the feet do not depend on it
  const detail::RevolutionMap map(s);
  std::vector<std::pair<double, double>> near;  // |w|, foot radius
  near.reserve(points.size());
  for (const auto& p : points) {
    const detail::MeridianFoot f = map.foot(map.cylindrical(p).head<2>());
    if (std::isfinite(f.w)) near.emplace_back(std::abs(f.w), f.ar.y());
  }
  const std::size_t k = std::min(near.size(), std::max<std::size_t>(16, near.size() / 200));
  if (k == 0) throw Error("slice: no points to choose the surface's reference radius from");
  std::nth_element(near.begin(), near.begin() + (k - 1), near.end());
  double sum = 0;
  for (std::size_t i = 0; i < k; ++i) sum += near[i].second;
  s.r_ref = sum / static_cast<double>(k);
  if (!(s.r_ref > 0)) throw Error("slice: the points nearest to the surface lie on the axis (give --r-ref)");
  return s;
}

// The points as (u, v, w scale) of the surface; those where the map is undefined left out.
Cloud unrolled_cloud(const detail::RevolutionMap& map, const std::vector<Eigen::Vector3d>& points) {
  Cloud out;
  out.points.reserve(points.size());
  for (const auto& p : points) {
    const SurfacePlace q = map.place(p);
    if (q.valid) out.points.emplace_back(q.uv.x(), q.uv.y(), q.w * q.scale);
  }
  return out;
}

// Why a surface between sparse rows takes none, in the surface's terms (slice_rows speaks of
// planes and heights): the rows' distances from it (their radii for a cylinder).
std::string between_rows(const Revolution& surface, const Sampling& sampling) {
  double below = -INFINITY, above = INFINITY;
  for (const auto& row : sampling.rows) {
    if (row.height < 0) below = std::max(below, row.height);
    if (row.height > 0) above = std::min(above, row.height);
  }
  const bool cylinder = surface.kind == SurfaceKind::cylinder;
  const double r = cylinder ? surface.meridian[0].y() : 0;
  const auto place = [&](double w) {
    char buf[64];
    std::snprintf(buf, sizeof buf, cylinder ? "r = %.6g" : "w = %.6g", r + w);
    return std::string(buf);
  };
  std::string where = std::isfinite(below) && std::isfinite(above)
                          ? "between the rows at " + place(below) + " and " + place(above)
                      : std::isfinite(below) ? "beyond the last row, at " + place(below)
                      : std::isfinite(above) ? "before the first row, at " + place(above)
                                             : "off every row";
  return std::string("the ") + surface_kind_name(surface.kind) +
         (cylinder ? " r = " + place(0).substr(4) : "") + " lies " + where + " (" +
         std::to_string(sampling.rows.size()) +
         " sparse rows of points, each a section's worth): no section is made between rows; cut through a "
         "row (slice --axis with no radius cuts each row at constant radius on its cylinder)";
}

}  // namespace

Frame surface_frame(const Revolution& surface) {
  Frame f = tangent_frame(surface, {0, 0});
  f.surface = std::make_shared<const Revolution>(surface);
  return f;
}

namespace detail {

std::vector<Revolution> with_references(const std::vector<Revolution>& surfaces,
                                        const std::vector<Eigen::Vector3d>& points) {
  if (surfaces.empty()) throw Error("slice: no surfaces given");
  std::vector<Revolution> out = surfaces;
  Eigen::Vector3d reference = Eigen::Vector3d::Zero();
  for (auto& s : out) {
    if (!s.reference.isZero()) continue;
    if (reference.isZero()) reference = reference_of(points, s.axis_point, s.axis);
    s.reference = reference;
  }
  return out;
}

}  // namespace detail

SliceResult slice(const Cloud& cloud, const std::vector<Revolution>& surfaces, const SliceOptions& options,
                  const SectionSink& sink, const SamplingSink& on_sampling) {
  if (cloud.points.empty()) throw Error("slice: the cloud has no points");
  detail::check_points(cloud.points);
  const std::vector<Revolution> given = detail::with_references(surfaces, cloud.points);
  SliceResult result;
  result.points = cloud.points.size();
  result.sections.resize(given.size());
  for (std::size_t k = 0; k < given.size(); ++k) {
    SectionSlice& section = result.sections[k];
    Revolution surface = completed(given[k], cloud.points);
    const detail::RevolutionMap map(surface);
    const Cloud unrolled = unrolled_cloud(map, cloud.points);
    try {
      SliceResult one = slice(unrolled, {Plane{}}, options);
      section = std::move(one.sections[0]);
      if (section.slab_points == 0 && one.sampling.kind == SamplingKind::rows && !section.error.empty())
        section.error = between_rows(surface, one.sampling);
      if (k == 0) {
        result.slab = one.slab;
        result.sampling = std::move(one.sampling);
      }
    } catch (const std::bad_alloc&) {
      throw;
    } catch (const Error& e) {
      section.error = e.what();
    }
    // The plane's frame moved to the section (local_origin): the shift of its (u, v).
    surface.shift += section.frame.origin.head<2>();
    section.id = static_cast<int>(k);
    section.frame = surface_frame(surface);
    if (k == 0 && on_sampling && options.slab == 0) on_sampling(result.sampling);
    if (sink) sink(section);
  }
  return result;
}

std::vector<double> row_radii(const std::vector<Eigen::Vector3d>& points, const Eigen::Vector3d& axis_point,
                              const Eigen::Vector3d& axis, const SamplingOptions& options) {
  if (points.size() < 8) throw Error("slice: too few points to find rows at constant radius");
  std::vector<double> radius;
  Revolution probe = cylinder_surface(axis_point, axis, 1);
  const detail::RevolutionMap unit(probe);
  for (const auto& p : points) radius.push_back(unit.cylindrical(p).y());
  std::nth_element(radius.begin(), radius.begin() + radius.size() / 2, radius.end());
  const double median = radius[radius.size() / 2];
  if (!(median > 0)) throw Error("slice: the points lie on the axis");
  probe = cylinder_surface(axis_point, axis, median);
  probe.reference = reference_of(points, axis_point, axis);
  const Cloud unrolled = unrolled_cloud(detail::RevolutionMap(probe), points);
  SamplingOptions all = options;  // a row is a section only with all its points
  all.max_points = std::max(all.max_points, unrolled.points.size());
  const Sampling sampling = sampling_of(unrolled.points, Eigen::Vector3d::UnitZ(), all);
  if (sampling.kind != SamplingKind::rows)
    throw Error("slice: no radius given, and the points are not rows at constant radius but " +
                sampling.describe() + " (across the radius): give --radius or --count");
  std::vector<double> out;
  for (const auto& row : sampling.rows) out.push_back(median + row.height);
  return out;
}

}  // namespace section

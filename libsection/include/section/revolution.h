// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// @file revolution.h
/// Surfaces of revolution about a machine axis (cylinders, cones, meridional streamlines),
/// their unrollings onto a developed plane and the exact maps both ways; slicing a cloud
/// or a mesh by them (docs/REVOLUTION.md).
///
/// A point P has axial position a = (P - axis_point) . axis, radius r (its distance from the
/// axis) and angle theta about the axis (right-handed, 0 along `reference`). The surface is
/// the meridian, a polyline of (a, r) points swept about the axis; m is the arc length along
/// it from its first point (its end segments extend as straight lines), w the signed
/// distance from it in the (a, r) half-plane, positive on the left of its direction (outward
/// for a meridian running along +axis). The unrolled (u, v) of a point on the surface:
///   cylinder:   (r_ref theta, m)                  (a cylinder's m is its axial position)
///   arclength:  (m, r_ref theta)                  (true lengths along m, and along theta at r_ref)
///   conformal:  (r_ref m', r_ref theta), m' = integral dm / r  (angle-true: the turbomachinery
///               (m', theta) plane, scaled by r_ref so that lengths stay in mm near r = r_ref)
/// minus `shift`.
#include "section/cloud.h"
#include "section/mesh.h"
#include "section/slice.h"

#include <Eigen/Core>
#include <string>
#include <vector>

namespace section {

/// What a surface of revolution is (the frames table's `surface` code in brackets).
enum class SurfaceKind {
  cylinder = 1,   ///< constant radius
  cone = 2,       ///< a straight meridian
  streamline = 3  ///< a meridional polyline
};

/// How a surface is unrolled onto its developed plane (the frames table's `unrolling` code).
enum class Unrolling {
  cylinder = 1,   ///< (r_ref theta, m)
  conformal = 2,  ///< (r_ref m', r_ref theta)
  arclength = 3   ///< (m, r_ref theta)
};

/// The name of an unrolling ("cylinder", "conformal", "arclength") and back; the latter
/// throws section::Error on an unknown name.
const char* unrolling_name(Unrolling unrolling);
Unrolling unrolling_named(const std::string& name);
/// The name of a kind ("cylinder", "cone", "streamline").
const char* surface_kind_name(SurfaceKind kind);

/// A surface of revolution and its unrolling: everything that maps a section's (u, v) to 3D.
struct Revolution {
  SurfaceKind kind = SurfaceKind::cylinder;              ///< what it is (names it; the maps use the meridian)
  Unrolling unrolling = Unrolling::cylinder;             ///< how it is unrolled
  Eigen::Vector3d axis_point = Eigen::Vector3d::Zero();  ///< a point of the axis: a = 0
  Eigen::Vector3d axis = Eigen::Vector3d::UnitZ();       ///< the axis direction (unit)
  Eigen::Vector3d reference =
      Eigen::Vector3d::UnitX();           ///< theta = 0 (unit, normal to the axis; 0 = chosen when slicing)
  std::vector<Eigen::Vector2d> meridian;  ///< (a, r) points, >= 2, r >= 0, neighbours apart
  double r_ref = 0;                       ///< mm, the unrolled plane's reference radius (> 0)
  Eigen::Vector2d shift{0, 0};            ///< unrolled coordinates of (u, v) = (0, 0)
};

/// The cylinder of radius `radius` (> 0) about the axis; its m is the axial position a.
Revolution cylinder_surface(const Eigen::Vector3d& axis_point, const Eigen::Vector3d& axis, double radius);
/// The cone through the meridional points (a0, r0) and (a1, r1) (apart, radii >= 0).
Revolution cone_surface(const Eigen::Vector3d& axis_point, const Eigen::Vector3d& axis,
                        const Eigen::Vector2d& a0r0, const Eigen::Vector2d& a1r1);
/// The surface swept by a meridional polyline of (a, r) points.
Revolution streamline_surface(const Eigen::Vector3d& axis_point, const Eigen::Vector3d& axis,
                              std::vector<Eigen::Vector2d> meridian);

/// Checks a surface (finite, unit axis and reference, a meridian of >= 2 distinct points with
/// r >= 0, r_ref > 0; the conformal unrolling also needs r > 0 along the meridian); throws
/// section::Error saying what is wrong.
void check_surface(const Revolution& surface);

/// A point's place relative to a surface.
struct SurfacePlace {
  Eigen::Vector2d uv{0, 0};  ///< unrolled coordinates of its foot on the surface (minus shift)
  double w = 0;              ///< signed distance from the surface, in the meridional half-plane
  double scale = 1;          ///< mm of the unrolled plane per mm of the surface across m (conformal: r_ref/r)
  bool valid = false;        ///< false where the map is undefined (conformal beyond the apex r = 0)
};

/// Where a 3D point lies: its foot's unrolled coordinates and its distance from the surface.
/// Exact inverse of surface_point for points on the surface (round trip ~1e-15 relative).
SurfacePlace surface_place(const Revolution& surface, const Eigen::Vector3d& p);

/// The 3D point of unrolled coordinates uv (on the surface).
Eigen::Vector3d surface_point(const Revolution& surface, const Eigen::Vector2d& uv);

/// The unit tangents of u and v and the normal u x v at unrolled coordinates uv: the
/// tangent plane there (the frames table's origin, u, v, n of a section on the surface).
Frame tangent_frame(const Revolution& surface, const Eigen::Vector2d& uv);

/// The frame of a section on `surface`: its tangent frame at (0, 0) carrying the surface.
Frame surface_frame(const Revolution& surface);

/// The reference direction (theta = 0) that puts `points` about theta = 0: the middle of
/// the angles they cover about the axis, opposite the largest empty gap of angles (so the
/// branch cut theta = +-pi falls in it, between blades of a whole rotor); with no point off
/// the axis, the world axis least aligned with `axis`.
Eigen::Vector3d reference_of(const std::vector<Eigen::Vector3d>& points, const Eigen::Vector3d& axis_point,
                             const Eigen::Vector3d& axis);

/// Least and largest radius of `points` about the axis, the few far from the rest left out
/// (strays, as extent_along in section/slice.h).
Eigen::Vector2d radius_range(const std::vector<Eigen::Vector3d>& points, const Eigen::Vector3d& axis_point,
                             const Eigen::Vector3d& axis);

/// Radii of the rows of points at constant radius (sparse rows, as a CMM measures a rotor):
/// each row's mean radius, lowest first. Throws section::Error when the points are not rows
/// at constant radius about the axis (it says what they are).
std::vector<double> row_radii(const std::vector<Eigen::Vector3d>& points, const Eigen::Vector3d& axis_point,
                              const Eigen::Vector3d& axis, const SamplingOptions& options = {});

/// Slices a cloud by surfaces of revolution: each point mapped to (u, v, w) of the surface
/// (w times its scale), then the plane w = 0 of those cut as slice(Cloud, planes) cuts a
/// cloud (slab or rows as they lie, band, gap fill), so a shell around the surface is what
/// a slab is around a plane. A surface's r_ref of 0 is chosen from the points nearest to it
/// (their mean radius); a zero reference from reference_of. Each section's frame carries its
/// surface (Frame::surface) with the shift to its points. Throws section::Error for bad
/// surfaces or options; a section that fails carries its error. `sink` and `on_sampling` as
/// slice(Cloud, planes)'s: each section as it is done, and (with slab 0) the sampling of the
/// first surface's shell before any section.
SliceResult slice(const Cloud& cloud, const std::vector<Revolution>& surfaces,
                  const SliceOptions& options = {}, const SectionSink& sink = {},
                  const SamplingSink& on_sampling = {});

/// Slices a mesh by surfaces of revolution exactly: each triangle edge that crosses the
/// surface is cut where the signed distance w is 0 (bisection to the last bit), each
/// triangle's two cuts joined, the pieces linked into closed loops and unrolled (loop 0 the
/// largest, counterclockwise in (u, v)). r_ref 0 = the mean radius of the cut. `sink`, when
/// set, receives each section as it is done.
SliceResult slice(const Mesh& mesh, const std::vector<Revolution>& surfaces, const SliceOptions& options = {},
                  const SectionSink& sink = {});

}  // namespace section

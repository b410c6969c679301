// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// @file frame.h
/// A section plane's frame: maps in-plane (u, v) coordinates to 3D (x, y, z) and back; a
/// section on a surface of revolution maps its unrolled (u, v) through the surface.
#include <Eigen/Core>
#include <Eigen/Geometry>

#include <memory>

namespace section {

struct Revolution;  // section/revolution.h
/// The 3D point of unrolled coordinates uv on a surface (revolution.h).
Eigen::Vector3d surface_point(const Revolution& surface, const Eigen::Vector2d& uv);
/// Unrolled coordinates of a point's foot on a surface, and its signed distance from it.
Eigen::Vector2d surface_uv(const Revolution& surface, const Eigen::Vector3d& p);
double surface_distance(const Revolution& surface, const Eigen::Vector3d& p);

/// Orthonormal right-handed frame of a section plane: u x v = n. For a section on a surface
/// of revolution (`surface` set), (u, v) are its unrolled coordinates and origin, u, v, n
/// the tangent plane at (0, 0); to_world, to_plane and height go through the surface.
struct Frame {
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();  ///< a point of the plane
  Eigen::Vector3d u = Eigen::Vector3d::UnitX();      ///< first in-plane axis (unit)
  Eigen::Vector3d v = Eigen::Vector3d::UnitY();      ///< second in-plane axis (unit)
  Eigen::Vector3d n = Eigen::Vector3d::UnitZ();      ///< plane normal (unit)
  std::shared_ptr<const Revolution> surface;         ///< the surface of revolution; null: the plane

  /// 3D point of in-plane coordinates (u, v).
  Eigen::Vector3d to_world(const Eigen::Vector2d& p) const {
    return surface ? surface_point(*surface, p) : Eigen::Vector3d(origin + p.x() * u + p.y() * v);
  }
  /// 3D direction of an in-plane direction (on a surface: in the tangent plane at (0, 0)).
  Eigen::Vector3d direction_to_world(const Eigen::Vector2d& d) const { return d.x() * u + d.y() * v; }
  /// In-plane coordinates of the orthogonal projection of a 3D point.
  Eigen::Vector2d to_plane(const Eigen::Vector3d& p) const {
    if (surface) return surface_uv(*surface, p);
    const Eigen::Vector3d d = p - origin;
    return {d.dot(u), d.dot(v)};
  }
  /// Signed distance of a 3D point from the plane along n.
  double height(const Eigen::Vector3d& p) const {
    return surface ? surface_distance(*surface, p) : (p - origin).dot(n);
  }
};

/// `normal` scaled by its largest component where its squared length over- or underflows
/// (1e308 or 1e-200 long: every use of it would read it as infinite or zero), else as it is.
Eigen::Vector3d usable_normal(const Eigen::Vector3d& normal);

/// The frame of the plane through `origin` with normal `normal` (need not be unit length,
/// nor of a length whose square is a normal number: see usable_normal).
/// u is the projection of a world axis set by the normal's largest component (x before y
/// before z on ties): x for a normal mostly along z or y, y for one mostly along x. So a
/// normal of +z gives u = +x, v = +y, and every normal near one world axis gets the same u:
/// the sections of a blade cut on slightly different normals (rows fitted one by one, planes
/// along a curved stacking line) are measured in frames that agree (their angles compare).
/// Throws section::Error on a zero or non-finite normal.
Frame make_frame(const Eigen::Vector3d& origin, const Eigen::Vector3d& normal);

}  // namespace section

// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// @file extras/generate_rotor.h
/// Synthetic rotor blades whose sections are designed on surfaces of revolution (cylinders or
/// cones about the machine axis), with exact ground truth: the section designed at span
/// height z lies on surface(z) in its unrolled coordinates, so the surface's cut of the
/// blade is exactly that design (docs/GENERATOR.md, docs/REVOLUTION.md).
#include "section/cloud.h"
#include "section/extras/generate.h"
#include "section/mesh.h"
#include "section/revolution.h"

#include <Eigen/Core>

namespace section {

/// A rotor: a blade's section designs laid on nested surfaces of revolution. The section of
/// height z in [0, span] lies on the surface whose meridian passes through (a, r) = (0,
/// hub_radius + z) at `cone_angle` to the axis, unrolled with r_ref = hub_radius + z, the
/// design's (u, v) its unrolled coordinates (theta = 0 along `reference`).
struct RotorDesign {
  BladeDesign blade;                                     ///< the section designs by height z
  double hub_radius = 200;                               ///< mm, the radius of the section z = 0 at a = 0
  double cone_angle = 0;                                 ///< degrees, the meridians' slope; 0 = cylinders
  Unrolling unrolling = Unrolling::cylinder;             ///< how the designs lie on the surfaces
  Eigen::Vector3d axis_point = Eigen::Vector3d::Zero();  ///< a point of the machine axis (a = 0)
  Eigen::Vector3d axis = Eigen::Vector3d::UnitX();       ///< the machine axis (unit)
  Eigen::Vector3d reference = Eigen::Vector3d::UnitZ();  ///< theta = 0 (unit, normal to the axis)

  /// The surface of the section designed at height z (a cylinder when cone_angle is 0).
  Revolution surface(double z) const;
  /// The 3D point of design coordinates (u, v) at height z: on surface(z).
  Eigen::Vector3d to_world(const Eigen::Vector3d& uvz) const;
};

/// A compressor-like rotor on cylinders (cylinder unrolling) and the same on cones of 20
/// degrees (conformal unrolling): the designs of compressor_blade().
RotorDesign cylinder_rotor();
RotorDesign cone_rotor(Unrolling unrolling = Unrolling::conformal);

/// The rotor's points of a planar blade's points (u, v, z) each carried onto surface(z):
/// generate_scan, generate_rows or generate_grid of rotor.blade give the rotor's scan,
/// rows on its surfaces (rows at constant radius on cylinders), or grid.
Cloud rotor_cloud(const RotorDesign& rotor, const Cloud& planar);

/// generate_mesh of rotor.blade carried onto the surfaces (each ring on its surface).
Mesh rotor_mesh(const RotorDesign& rotor, int profile_points = 400, int layers = 60);

}  // namespace section

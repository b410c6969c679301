// SPDX-License-Identifier: GPL-3.0-or-later
// Rotor blades designed on surfaces of revolution (extras/generate_rotor.h): the planar
// blade's points carried onto the surfaces, section by section.
#include "section/extras/generate_rotor.h"

#include "section/error.h"

#include <cmath>

namespace section {

Revolution RotorDesign::surface(double z) const {
  const double r0 = hub_radius + z;
  if (!(r0 > 0)) throw Error("generate_rotor: the section at z = " + std::to_string(z) + " has no radius");
  const double slope = std::tan(cone_angle * M_PI / 180);
  Revolution s = cone_angle == 0 ? cylinder_surface(axis_point, axis, r0)
                                 : cone_surface(axis_point, axis, {0, r0}, {1, r0 + slope});
  s.unrolling = unrolling;
  s.reference = reference;
  s.r_ref = r0;
  return s;
}

Eigen::Vector3d RotorDesign::to_world(const Eigen::Vector3d& uvz) const {
  return surface_point(surface(uvz.z()), uvz.head<2>());
}

RotorDesign cylinder_rotor() {
  RotorDesign r;
  r.blade = compressor_blade();
  return r;
}

RotorDesign cone_rotor(Unrolling unrolling) {
  RotorDesign r;
  r.blade = compressor_blade();
  r.cone_angle = 20;
  r.unrolling = unrolling;
  return r;
}

Cloud rotor_cloud(const RotorDesign& rotor, const Cloud& planar) {
  Cloud out;
  out.points.reserve(planar.points.size());
  for (const auto& p : planar.points) out.points.push_back(rotor.to_world(p));
  return out;
}

Mesh rotor_mesh(const RotorDesign& rotor, int profile_points, int layers) {
  Mesh mesh = generate_mesh(rotor.blade, profile_points, layers);
  for (auto& v : mesh.vertices) v = rotor.to_world(v);
  return mesh;
}

}  // namespace section

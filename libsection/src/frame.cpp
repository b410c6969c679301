// SPDX-License-Identifier: GPL-3.0-or-later
#include "section/frame.h"

#include "section/error.h"

#include <cmath>

namespace section {

Eigen::Vector3d usable_normal(const Eigen::Vector3d& normal) {
  const double largest = normal.cwiseAbs().maxCoeff();
  if (std::isnormal(normal.squaredNorm()) || !(largest > 0) || !std::isfinite(largest)) return normal;
  return normal / largest;
}

Frame make_frame(const Eigen::Vector3d& origin, const Eigen::Vector3d& given) {
  const Eigen::Vector3d normal = usable_normal(given);  // 1e300 or 1e-200 long too
  const double length = normal.norm();
  if (!std::isfinite(length) || length == 0 || !origin.allFinite())
    throw Error("frame: a section plane needs a finite origin and a non-zero normal");
  Frame f;
  f.origin = origin;
  f.n = normal / length;
  // The world axis least aligned with n gives a u that is stable and familiar (+z -> u = +x).
  int axis = 0;
  for (int k = 1; k < 3; ++k)
    if (std::abs(f.n[k]) < std::abs(f.n[axis]) - 1e-12) axis = k;
  Eigen::Vector3d e = Eigen::Vector3d::Zero();
  e[axis] = 1;
  f.u = (e - e.dot(f.n) * f.n).normalized();
  f.v = f.n.cross(f.u);
  return f;
}

}  // namespace section

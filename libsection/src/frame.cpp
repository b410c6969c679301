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
  // The world axis by n's largest component gives a familiar u (+z -> u = +x) that does not
  // turn with small tilts: the axis least aligned with n, used before, swapped between x and
  // y as a normal near z tilted one way or the other (rows' fitted planes: stagger -105, -30
  // and -139 deg on one smoothly twisted blade).
  int largest = 0;
  for (int k = 1; k < 3; ++k)
    if (std::abs(f.n[k]) > std::abs(f.n[largest])) largest = k;
  const int axis = largest == 0 ? 1 : 0;
  Eigen::Vector3d e = Eigen::Vector3d::Zero();
  e[axis] = 1;
  f.u = (e - e.dot(f.n) * f.n).normalized();
  f.v = f.n.cross(f.u);
  return f;
}

}  // namespace section

// SPDX-License-Identifier: GPL-3.0-or-later
#include "detail/cgal.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

namespace section::detail {

int orientation(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                const Eigen::Vector3d& q) {
  using K = CGAL::Exact_predicates_inexact_constructions_kernel;
  using P = K::Point_3;
  return static_cast<int>(CGAL::orientation(P(a.x(), a.y(), a.z()), P(b.x(), b.y(), b.z()),
                                            P(c.x(), c.y(), c.z()), P(q.x(), q.y(), q.z())));
}

}  // namespace section::detail

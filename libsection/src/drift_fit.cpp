// SPDX-License-Identifier: GPL-3.0-or-later
#include "drift_fit.h"

namespace section::drift {

Reference reference_of(const MorphologyResult& ordered) {
  Reference r;
  for (std::size_t l = 0; l < ordered.loops.size(); ++l) {
    const Loop& loop = ordered.loops[l];
    const int base = int(r.point.size()), n = int(loop.points.size());
    for (int k = 0; k < n; ++k) {
      r.point.push_back(loop.points[std::size_t(k)]);
      r.normal.push_back(std::size_t(k) < loop.normals.size() ? loop.normals[std::size_t(k)] : Vec::Zero());
      r.loop.push_back(int(l));
      r.next.push_back(base + (k + 1) % n);
      r.prev.push_back(base + (k + n - 1) % n);
    }
  }
  return r;
}

bool span_beside(const Reference& ref, const Grid& ref_grid, const Vec& c, double slab, double gap_min,
                 int& k, Vec& pk, Vec& n) {
  k = ref_grid.nearest(c, 3 * slab);
  if (k < 0) return false;
  pk = ref.point[std::size_t(k)];
  const int a = ref.next[std::size_t(k)], b = ref.prev[std::size_t(k)];
  const bool forward =
      (c - ref.point[std::size_t(a)]).squaredNorm() <= (c - ref.point[std::size_t(b)]).squaredNorm();
  int m = forward ? a : b;
  // Points that (nearly) coincide make no span: a band carries rows scanned at the same
  // places along the profile onto one another. Step on to the first that stands apart.
  for (int step = 0; step < 8 && (ref.point[std::size_t(m)] - pk).norm() < 0.05 * slab && m != k; ++step)
    m = forward ? ref.next[std::size_t(m)] : ref.prev[std::size_t(m)];
  const Vec t = ref.point[std::size_t(m)] - pk;
  const double len = t.norm();
  if (!(len > 0) || len > gap_min) return false;
  const double along = (c - pk).dot(t) / (len * len);
  if (along < -0.25 || along > 1.25) return false;
  n = Vec(t.y() / len, -t.x() / len);
  if (n.dot(ref.normal[std::size_t(k)]) < 0) n = -n;
  return true;
}

double gap_length(const GapFillOptions& options, double slab, double profile_length) {
  return std::max(options.min_gap * slab, options.min_gap_fraction * profile_length);
}

double profile_length(const MorphologyResult& ordered) {
  return ordered.loops.empty() ? 0.0 : ordered.loops[0].length;
}

void near_plane(const std::vector<Eigen::Vector3d>& nearby, double limit, std::vector<Vec>& uv,
                std::vector<double>& dz) {
  uv.reserve(uv.size() + nearby.size());  // at most all of them: no copies as the lists grow
  dz.reserve(dz.size() + nearby.size());
  for (const auto& p : nearby)
    if (p.allFinite() && std::abs(p.z()) <= limit) {
      uv.emplace_back(p.x(), p.y());
      dz.push_back(p.z());
    }
}

}  // namespace section::drift

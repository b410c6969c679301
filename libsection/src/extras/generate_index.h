// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// Nearest-segment search over a polyline, for locate() and camber_distance() (generate.h);
// internal to section_extras.
#include "generate_section.h"

#include <cstddef>
#include <limits>
#include <memory>
#include <vector>

namespace section {
namespace detail {

/// Bounding-box tree over consecutive runs of a polyline's segments (the curve is
/// spatially coherent, so index ranges make tight boxes): nearest-segment queries in
/// O(log n) for points near or far.
struct PolylineIndex {
  static constexpr int leaf = 8;              // segments per leaf
  std::size_t count = 0;                      // number of points the index was built for
  bool closed = false;                        // last point joins the first
  Eigen::Vector2d first{0, 0}, middle{0, 0};  // fingerprint: the index belongs to these points
  int leaves = 1;                             // leaf nodes are [leaves, 2 leaves)
  std::vector<Eigen::Vector2d> lo, hi;        // node boxes; node 1 is the root, children 2i, 2i+1
  // The exact profile, when the index belongs to SectionTruth::profile: where each vertex
  // lies on which piece, so locate() can refine the foot on the true curve.
  bool exact = false;
  gen::Section section;
  std::vector<int> piece;      // per vertex
  std::vector<double> lambda;  // per vertex
};

namespace gen {

/// The index of polyline `pts` (closed: the last point joins the first).
std::shared_ptr<PolylineIndex> build_index(const std::vector<Vector2d>& pts, bool closed);

/// Whether `idx` was built for these points (not for an edited copy of them).
bool indexes(const PolylineIndex* idx, const std::vector<Vector2d>& pts, bool closed);

/// The foot of q on segment ab: its parameter t in [0, 1] and squared distance.
struct SegmentFoot {
  double t = 0, d2 = 0;
};
inline SegmentFoot segment_foot(const Vector2d& a, const Vector2d& b, const Vector2d& q) {
  const Vector2d ab = b - a;
  const double l2 = ab.squaredNorm();
  const double t = l2 > 0 ? std::clamp((q - a).dot(ab) / l2, 0.0, 1.0) : 0.0;
  return {t, (a + t * ab - q).squaredNorm()};
}

struct Nearest {
  std::size_t segment = 0;
  double t = 0, d2 = std::numeric_limits<double>::infinity();
};

/// The segment of `pts` nearest to q, through `idx` when it indexes `pts`, else by brute force.
Nearest nearest(const std::vector<Vector2d>& pts, bool closed, const PolylineIndex* idx, const Vector2d& q);

}  // namespace gen
}  // namespace detail
}  // namespace section

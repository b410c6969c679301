// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// Slab scanning, shared by slice(Cloud) (src/slice.cpp) and slice_file (src/io/slice_file.cpp):
// which points of a cloud lie in the slab of each section plane, or near it, in cloud order.
#include "section/frame.h"
#include "section/slice.h"

#include <Eigen/Core>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace section::detail {

// One slab boundary plane, defined exactly by three points with double coordinates.
struct Boundary {
  Eigen::Vector3d a, b, c;
};

/// The planes that share one normal, with their slabs.
struct SlabGroup {
  Eigen::Vector3d n;           // unit normal shared by the group
  std::vector<int> plane;      // plane ids, sorted by offset
  std::vector<double> offset;  // n . origin, sorted
  std::vector<Boundary> lower, upper;
  // Buckets over n . q: first[b] is near the first offset >= the bucket's keys, so that the
  // search for the first candidate plane starts next to it.
  double key0 = 0, inv_width = 0;
  std::vector<std::size_t> first;
  // Buckets over n . q itself, `near_width` wide from near0: near[b] is false when no slab
  // comes within a bucket of bucket b, so that its points are passed over at once.
  double near0 = 0, near_width = 0, inv_near = 0;
  std::vector<char> near;

  /// True when n . q = s lies in a bucket with no slab within a bucket of it.
  bool far_from_slabs(double s) const;

  /// The index of the first offset >= key (std::lower_bound's answer), from the bucket's
  /// guess and a few steps.
  std::size_t first_at_least(double key) const;
};

/// What the per-point tests of a SlabGroup read, copied out of it once for a loop over
/// points: read through the group, every point loaded its vectors' bounds again and
/// converted their sizes (any append could have changed them, for all the compiler knew).
struct SlabTests {
  explicit SlabTests(const SlabGroup& g)
      : n(g.n),
        near0(g.near0),
        inv_near(g.inv_near),
        near_width(g.near_width),
        near_count(double(g.near.size())),
        near(g.near.data()),
        key0(g.key0),
        inv_width(g.inv_width),
        buckets(g.first.size()),
        first(g.first.data()),
        offset(g.offset.data()),
        planes(g.offset.size()),
        plane(g.plane.data()) {}
  Eigen::Vector3d n;
  double near0, inv_near, near_width, near_count;
  const char* near;
  double key0, inv_width;
  std::size_t buckets;
  const std::size_t* first;
  const double* offset;
  std::size_t planes;
  const int* plane;

  /// SlabGroup::far_from_slabs (false when the group has no buckets).
  bool far_from_slabs(double s) const {
    const double x = (s - near0) * inv_near;
    return x >= 0 && x < near_count && !near[std::int64_t(x)];  // x < 2^20: no unsigned guard
  }
  /// SlabGroup::first_at_least.
  std::size_t first_at_least(double key) const {
    const double x = (key - key0) * inv_width;
    std::size_t k = first[x >= 0 ? (x < double(buckets) ? std::size_t(x) : buckets - 1) : 0];
    while (k > 0 && offset[k - 1] >= key) --k;
    while (k < planes && offset[k] < key) ++k;
    return k;
  }
};

inline bool SlabGroup::far_from_slabs(double s) const {
  return SlabTests(*this).far_from_slabs(s);
}
inline std::size_t SlabGroup::first_at_least(double key) const {
  return SlabTests(*this).first_at_least(key);
}

/// The planes grouped by normal (a group's planes share n), sorted by offset, with their
/// slab boundaries (width `slab`) and the buckets that speed up the search.
std::vector<SlabGroup> group_planes(const std::vector<Plane>& planes, double slab);

/// The frame of each plane.
std::vector<Frame> frames_of(const std::vector<Plane>& planes);

/// Splits points[0, count) into parts of at least 64k points, one per thread at most.
std::size_t parts_of(std::size_t count, int threads);

/// Appends the slab points of points[0, count) to `out` (one list per plane), in order.
/// Near a boundary CGAL's exact predicate decides (closed slab).
void add_slab_points(const Eigen::Vector3d* points, std::size_t count, const std::vector<SlabGroup>& groups,
                     const std::vector<Frame>& frame, double slab,
                     std::vector<std::vector<Eigen::Vector2d>>& out);

/// add_slab_points with the chunk split across `threads`; the parts are appended in
/// order, so the result does not depend on the threads.
void add_slab_points_parallel(const Eigen::Vector3d* points, std::size_t count,
                              const std::vector<SlabGroup>& groups, const std::vector<Frame>& frame,
                              double slab, int threads, std::vector<std::vector<Eigen::Vector2d>>& out);

/// Appends to `out` the points of points[0, count) within `reach` of each plane of
/// `groups` (built with a slab of 2 reach) as (u, v, signed distance from the plane), in
/// order, the chunk split across `threads`. A plain double test: these points only fill
/// gaps, no boundary needs to be exact.
void add_near_points_parallel(const Eigen::Vector3d* points, std::size_t count,
                              const std::vector<SlabGroup>& groups, const std::vector<Frame>& frame,
                              double reach, int threads, std::vector<std::vector<Eigen::Vector3d>>& out);

/// The slab points (add_slab_points) and the points within `reach` (add_near_points_parallel)
/// of points[0, count) in one pass, split across threads: n . q once per point, and the
/// chunk read from memory once. `near_groups` are `groups` built with a slab of 2 reach
/// (same normals, same planes, same order).
void add_slab_and_near_points_parallel(const Eigen::Vector3d* points, std::size_t count,
                                       const std::vector<SlabGroup>& groups,
                                       const std::vector<SlabGroup>& near_groups,
                                       const std::vector<Frame>& frame, double slab, double reach,
                                       int threads, std::vector<std::vector<Eigen::Vector2d>>& slabs,
                                       std::vector<std::vector<Eigen::Vector3d>>& near);

}  // namespace section::detail

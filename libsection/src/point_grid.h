// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// Uniform hash grids of the morphology step (src/morphology.cpp): over a subset of 2D points
// (spacing, isolated points) and over the segments of closed polylines (nearest boundary
// foot). Cells are sorted by key and found through an open-addressing table.
#include "detail/segment.h"

#include <Eigen/Core>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

namespace section::morph {

using Vec = Eigen::Vector2d;
using Points = std::vector<Vec>;

/// The key of cell (i, j). Shifted as unsigned: shifting a negative index left is undefined.
inline std::int64_t cell_key(std::int64_t i, std::int64_t j) {
  return static_cast<std::int64_t>((static_cast<std::uint64_t>(i) << 32) ^
                                   (static_cast<std::uint64_t>(j) & 0xffffffffULL));
}

/// The [begin, end) ranges of the occupied cells of a grid in a list sorted by cell key:
/// an open-addressing table, as grid queries look up several cells each (cheaper than
/// std::unordered_map's modulo and node chase).
class CellTable {
public:
  /// `keys` grouped: each run of equal keys is one cell (no key in two runs; the runs in any order).
  explicit CellTable(const std::vector<std::int64_t>& keys);

  /// The range of cell `key`, empty when the cell holds nothing.
  std::pair<std::uint32_t, std::uint32_t> find(std::int64_t key) const {
    for (std::size_t i = home(key);; i = (i + 1) & mask_) {
      const Slot& s = slots_[i];
      if (s.end == 0) return {0, 0};
      if (s.key == key) return {s.begin, s.end};
    }
  }

private:
  struct Slot {
    std::int64_t key = 0;
    std::uint32_t begin = 0, end = 0;  // end 0: a free slot (a cell's range is never empty)
  };
  // Fibonacci hashing: the top shift_ (>= 4) bits of key * 2^64 / phi.
  std::size_t home(std::int64_t key) const {
    return std::size_t((std::uint64_t(key) * 0x9E3779B97F4A7C15ULL) >> (64 - shift_));
  }
  std::vector<Slot> slots_;
  std::size_t mask_ = 0;
  int shift_ = 0;
};

/// A grid over the points `subset` of `points` (held by reference).
class PointGrid {
public:
  PointGrid(const Points& points, const std::vector<std::size_t>& subset, double cell);

  std::int64_t ix(double x) const { return std::int64_t(std::floor(x / cell_)); }
  std::int64_t key_of(const Vec& p) const { return cell_key(ix(p.x()), ix(p.y())); }

  /// Calls f(index) for the points of cell (i, j).
  template <class F>
  void visit(std::int64_t i, std::int64_t j, F&& f) const {
    const auto [begin, end] = cells_.find(cell_key(i, j));
    for (std::uint32_t a = begin; a < end; ++a) f(order_[a]);
  }

  /// Distance from point k to its nearest other point at a positive distance, searching
  /// rings of cells up to `max_ring`; infinity when none is found.
  double nearest(std::size_t k, int max_ring) const;

  /// True when point k has another point (a different index) within `radius` <= cell.
  bool has_neighbour(std::size_t k, double radius) const;

private:
  const Points& points_;
  double cell_;
  std::vector<std::uint32_t> order_;
  CellTable cells_{{}};
};

/// The foot of a point on the nearest boundary segment of any loop.
struct Foot {
  int loop = -1;
  double s = 0;         // arc length of the foot along the loop's boundary
  double distance = 0;  // to the boundary
  Vec normal{0, 0};     // outward normal of the boundary segment
};

/// A grid over the segments of closed polylines (loops), cell >= the search radius.
class SegmentGrid {
public:
  SegmentGrid(const std::vector<const Points*>& loops, double cell);

  double length(int loop) const { return cum_[loop].back(); }

  /// The nearest boundary foot within `cell` of p (loop -1 when none).
  Foot nearest(const Vec& p) const;

private:
  std::int64_t ix(double x) const { return std::int64_t(std::floor(x / cell_)); }
  detail::SegmentFoot foot_on(std::uint64_t id, const Vec& p) const;
  Foot foot(std::uint64_t id, const Vec& p, const detail::SegmentFoot& f) const;
  std::vector<const Points*> loops_;
  double cell_;
  std::vector<std::vector<double>> cum_;
  std::vector<std::uint64_t> ids_;
  CellTable cells_{{}};
};

/// Bounding box of a subset cut at the given quantiles (robust to a few far outliers).
void robust_box(const Points& points, const std::vector<std::size_t>& subset, double q, Vec& lo, Vec& hi);

/// The median distance from a point of `subset` to its nearest neighbour, on at most
/// `sample` of them (0 for fewer than two distinct points), or `floor` when that is larger
/// (known without measuring them all when most lie closer).
double median_spacing(const Points& points, const std::vector<std::size_t>& subset, std::size_t sample,
                      double floor = 0);

}  // namespace section::morph

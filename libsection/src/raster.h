// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The raster of the morphology step (src/morphology.cpp) and the transforms on it: exact
// Euclidean distance transform, boundary trace (the bottleneck: src/bottleneck.h).
#include <Eigen/Core>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <utility>
#include <vector>

namespace section::morph {

using Vec = Eigen::Vector2d;
using Points = std::vector<Vec>;

/// Cell (i, j) has its centre at (x0 + i h, y0 + j h); index j * w + i.
struct Raster {
  int w = 0, h = 0;
  double x0 = 0, y0 = 0, cell = 1;
  std::size_t size() const { return std::size_t(w) * std::size_t(h); }
  Vec to_cell(const Vec& p) const { return {(p.x() - x0) / cell, (p.y() - y0) / cell}; }
  Vec to_world(const Vec& c) const { return {x0 + c.x() * cell, y0 + c.y() * cell}; }
};

/// An allocator that leaves the elements of a resize uninitialised: a raster buffer whose
/// cells are all written before they are read is not zeroed first (a pass over the whole
/// raster, and the touch of every fresh page).
template <class T>
struct NoInit : std::allocator<T> {
  template <class U>
  struct rebind {
    using other = NoInit<U>;
  };
  NoInit() = default;
  template <class U>
  NoInit(const NoInit<U>&) noexcept {}
  template <class U>
  void construct(U* p) noexcept {
    ::new (static_cast<void*>(p)) U;
  }
  template <class U, class... Args>
  void construct(U* p, Args&&... args) {
    ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
  }
};

/// A raster-sized buffer: resize() leaves new cells undefined.
template <class T>
using Buffer = std::vector<T, NoInit<T>>;

/// Raster-sized buffers handed from step to step of one pass: each fresh page costs a page
/// fault (the kernel zeroes it), more than most steps' own work on it.
struct Scratch {
  Buffer<float> f;
  Buffer<int> ints;
  std::vector<std::uint8_t> bytes;
};

/// The cells of each row that may lie within `reach` cells of a seed: columns lo[j]..hi[j]
/// (none when lo[j] > hi[j]). Every cell off them is farther than `reach` from every seed,
/// and so is every cell between it and the raster's border along its row.
/// A span may hold a gap, columns gap_lo[j]..gap_hi[j] (none when gap_lo[j] > gap_hi[j], or
/// when the vectors are empty): from spans_of, cells farther than `reach` from every seed
/// along both axes (a closed profile's interior), strictly inside the span and the spans of
/// the rows above and below, never in the raster's first or last row. Their values are
/// known (at cap), so the transforms skip them: a span is two runs.
struct Spans {
  std::vector<int> lo, hi;
  std::vector<int> gap_lo, gap_hi;
  bool has_gap(int j) const { return !gap_lo.empty() && gap_lo[j] <= gap_hi[j]; }
};

/// The widest gap between the seeds of the rows within a reach of each row k: seed columns
/// a[k] < b[k] of those rows with no seed of those rows between them, at least 2 reach + 2
/// apart (a[k] >= b[k]: none).
struct SeedGaps {
  std::vector<int> a, b;
};

/// The widest gaps of the seed cells `cells` (cell indices, in raster order) over the rows
/// within `reach`.
SeedGaps seed_gaps(const Raster& r, const std::vector<std::size_t>& cells, int reach);

/// Spans of reach `reach` around seeds whose columns in row j run from first[j] to last[j]
/// (first[j] > last[j]: no seed in the row); with `gaps`, the spans' gaps too.
Spans spans_of(const Raster& r, const std::vector<int>& first, const std::vector<int>& last, int reach,
               const SeedGaps* gaps = nullptr);

/// Calls fn(first, end) with the columns of row j's span outside its gap (one or two runs);
/// without spans, the whole row of `w` columns.
template <class Fn>
void for_runs(const Spans* spans, int j, int w, const Fn& fn) {
  if (!spans) {
    fn(0, w);
    return;
  }
  const int lo = spans->lo[j], hi = spans->hi[j];
  if (lo > hi) return;
  if (!spans->has_gap(j)) {
    fn(lo, hi + 1);
    return;
  }
  fn(lo, spans->gap_lo[j]);
  fn(spans->gap_hi[j] + 1, hi + 1);
}

/// The last column of the run from column i (which holds) of the columns before `end` for
/// which holds(column) is true. A gap g0..g1 (none when g0 > g1) that the run reaches at
/// its first column is stepped over, not read: its columns hold.
template <class Holds>
int run_end(int i, int end, int g0, int g1, const Holds& holds) {
  for (;;) {
    const int stop = g0 <= g1 && i < g0 ? std::min(end, g0) : end;
    while (i + 1 < stop && holds(i + 1)) ++i;
    if (g0 > g1 || i + 1 != g0 || g0 >= end) return i;
    i = g1;
  }
}

/// Calls fn(i) for each column i of row j's span whose cell in row k is off row k's span.
template <class Fn>
void each_beside_off_span(const Spans& spans, int j, int k, const Fn& fn) {
  const int lo = spans.lo[j], hi = spans.hi[j], klo = spans.lo[k], khi = spans.hi[k];
  if (klo > khi) {
    for (int i = lo; i <= hi; ++i) fn(i);
    return;
  }
  for (int i = lo; i <= std::min(hi, klo - 1); ++i) fn(i);
  for (int i = std::max(lo, khi + 1); i <= hi; ++i) fn(i);
}

/// Exact squared Euclidean distance (in cells^2) of every cell to the nearest seed cell,
/// clamped to `cap`, and that seed's cell index in `nearest` (-1 when there is no seed).
/// `seed` is 1 at seeds. `base` is added to the cell indices in the parabola arithmetic
/// (see envelope_1d). Between equidistant seeds the one of lower index wins, as in
/// the envelope of the columns. With `spans`, only their cells are computed, and the
/// cells that lie `cap` or farther from every seed may get `cap` and -1: `nearest` is that
/// of the transform without spans wherever the distance is below `cap`. The cells off the
/// spans get `cap` and -1, or with `off_seeds` are seeds themselves (0 and their own
/// index; the distances on the spans are then those of these seeds too). The cells of the
/// spans' gaps must lie `cap` or farther from every seed, and be no seeds: they get `cap`
/// (their column distances are not swept, their rows' envelopes step over them).
/// Uses scratch.f and scratch.ints (not scratch.bytes, which may hold `seed`).
Buffer<int> distance_transform(const Raster& r, const std::vector<std::uint8_t>& seed, int cap, int base,
                               Buffer<int>& nearest, Scratch& scratch, const Spans* spans = nullptr,
                               bool off_seeds = false);

/// floor(x) as an int, for x in the range of int: from a truncation (std::floor is a long
/// sequence without SSE4.1).
inline int floor_int(double x) {
  const int t = int(x);
  return t - (double(t) > x);
}

/// Smallest r with r * r >= x.
int ceil_sqrt(int x);

/// f at cell coordinates c, bilinear between cell centres (clamped to the raster).
double bilinear(const Raster& r, const Buffer<float>& f, const Vec& c);

/// Moore-neighbour trace of the component labelled `label` starting at its first cell in
/// raster order; stops when the first move repeats (Jacob's criterion), so one-cell-wide
/// parts are walked on both sides. Returns cell coordinates.
Points trace(const Raster& r, const Buffer<int>& label, int label_id, std::size_t start);

}  // namespace section::morph

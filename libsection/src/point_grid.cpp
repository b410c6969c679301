// SPDX-License-Identifier: GPL-3.0-or-later
#include "point_grid.h"

#include "detail/segment.h"

#include <algorithm>
#include <cstdlib>
#include <limits>
#include <tuple>
#include <utility>

namespace section::morph {

namespace {

// Groups (key, id) pairs by key, each cell's ids ascending; `ids` gets the ids in that
// order, the table their cells. A query reads only a cell's ids, in their order, so the
// order of the cells is free: when the ids come in non-decreasing order (every grid's
// do), a counting pass by cell keeps each cell's ids as a sort of the pairs would leave
// them, without the sort (its comparisons were most of a grid's making).
template <class Id>
CellTable grouped_cells(std::vector<std::pair<std::int64_t, Id>>& keyed, std::vector<Id>& ids) {
  const std::size_t n = keyed.size();
  std::vector<std::int64_t> keys(n);
  ids.resize(n);
  bool ascending = true;
  for (std::size_t a = 1; a < n && ascending; ++a) ascending = keyed[a - 1].second <= keyed[a].second;
  if (!ascending) {
    std::sort(keyed.begin(), keyed.end());
    for (std::size_t a = 0; a < n; ++a) {
      keys[a] = keyed[a].first;
      ids[a] = keyed[a].second;
    }
    return CellTable(keys);
  }
  // Each pair's cell, numbered in order of first appearance (an open-addressing table),
  // then the cells' starts and the pairs placed in input order.
  std::size_t size = 16;
  while (size < 2 * n) size *= 2;
  const std::size_t mask = size - 1;
  int shift = 0;
  while ((std::size_t(1) << shift) < size) ++shift;
  std::vector<std::uint32_t> slot(size, 0);  // cell number + 1; 0 free
  std::vector<std::int64_t> cell_keys;
  std::vector<std::uint32_t> cell_of(n), start;
  for (std::size_t a = 0; a < n; ++a) {
    const std::int64_t key = keyed[a].first;
    std::size_t i = std::size_t((std::uint64_t(key) * 0x9E3779B97F4A7C15ULL) >> (64 - shift));
    while (slot[i] != 0 && cell_keys[slot[i] - 1] != key) i = (i + 1) & mask;
    if (slot[i] == 0) {
      cell_keys.push_back(key);
      start.push_back(0);
      slot[i] = std::uint32_t(cell_keys.size());
    }
    cell_of[a] = slot[i] - 1;
    ++start[cell_of[a]];
  }
  std::uint32_t at = 0;
  for (std::uint32_t& s : start) at += std::exchange(s, at);
  for (std::size_t a = 0; a < n; ++a) {
    const std::uint32_t to = start[cell_of[a]]++;
    keys[to] = keyed[a].first;
    ids[to] = keyed[a].second;
  }
  return CellTable(keys);
}

}  // namespace

CellTable::CellTable(const std::vector<std::int64_t>& keys) {
  std::size_t cells = 0;
  for (std::size_t a = 0; a < keys.size(); ++a) cells += a == 0 || keys[a] != keys[a - 1];
  std::size_t size = 16;
  while (size < 2 * cells) size *= 2;
  mask_ = size - 1;
  while ((std::size_t(1) << shift_) < size) ++shift_;
  slots_.assign(size, Slot{});
  for (std::size_t a = 0; a < keys.size();) {
    std::size_t b = a;
    while (b < keys.size() && keys[b] == keys[a]) ++b;
    std::size_t i = home(keys[a]);
    while (slots_[i].end != 0) i = (i + 1) & mask_;
    slots_[i] = Slot{keys[a], std::uint32_t(a), std::uint32_t(b)};
    a = b;
  }
}

PointGrid::PointGrid(const Points& points, const std::vector<std::size_t>& subset, double cell)
    : points_(points), cell_(cell) {
  std::vector<std::pair<std::int64_t, std::uint32_t>> keyed;
  keyed.reserve(subset.size());
  for (std::size_t k : subset) keyed.emplace_back(key_of(points[k]), std::uint32_t(k));
  cells_ = grouped_cells(keyed, order_);
}

double PointGrid::nearest(std::size_t k, int max_ring) const {
  const Vec& p = points_[k];
  const std::int64_t ci = ix(p.x()), cj = ix(p.y());
  // p's distance to the sides of its own cell, less a margin for the rounded quotients
  // that placed p and the others in their cells.
  const double x0 = double(ci) * cell_, y0 = double(cj) * cell_;
  const double side = std::min({p.x() - x0, x0 + cell_ - p.x(), p.y() - y0, y0 + cell_ - p.y()});
  const double margin = std::max(0.0, side - 1e-9 * (cell_ + std::abs(p.x()) + std::abs(p.y())));
  double best2 = std::numeric_limits<double>::infinity();
  const auto take = [&](std::uint32_t q) {
    const double d2 = (points_[q] - p).squaredNorm();
    if (d2 > 0 && d2 < best2) best2 = d2;
  };
  for (int ring = 0; ring <= max_ring; ++ring) {
    if (ring == 0) {
      visit(ci, cj, take);
    } else {  // the ring's cells only: its top and bottom rows, then its sides between
      for (std::int64_t i = ci - ring; i <= ci + ring; ++i) {
        visit(i, cj - ring, take);
        visit(i, cj + ring, take);
      }
      for (std::int64_t j = cj - ring + 1; j <= cj + ring - 1; ++j) {
        visit(ci - ring, j, take);
        visit(ci + ring, j, take);
      }
    }
    // Every point of a farther ring is at least `ring` cells and p's margin away (the
    // nearest, so, found: a point as far changes nothing).
    const double reach = ring * cell_ + margin;
    if (best2 <= reach * reach) break;
  }
  return std::sqrt(best2);
}

bool PointGrid::has_neighbour(std::size_t k, double radius) const {
  const Vec& p = points_[k];
  const std::int64_t ci = ix(p.x()), cj = ix(p.y());
  const double r2 = radius * radius;
  bool found = false;
  for (std::int64_t j = cj - 1; j <= cj + 1 && !found; ++j)
    for (std::int64_t i = ci - 1; i <= ci + 1 && !found; ++i)
      visit(i, j, [&](std::uint32_t q) {
        if (q != k && (points_[q] - p).squaredNorm() <= r2) found = true;
      });
  return found;
}

SegmentGrid::SegmentGrid(const std::vector<const Points*>& loops, double cell) : loops_(loops), cell_(cell) {
  cum_.resize(loops.size());
  std::vector<std::pair<std::int64_t, std::uint64_t>> keyed;
  for (std::size_t l = 0; l < loops.size(); ++l) {
    const Points& p = *loops[l];
    auto& cum = cum_[l];
    cum.assign(p.size() + 1, 0.0);
    for (std::size_t i = 0; i < p.size(); ++i) {
      const Vec& a = p[i];
      const Vec& b = p[(i + 1) % p.size()];
      cum[i + 1] = cum[i] + (b - a).norm();
      const std::int64_t i0 = ix(std::min(a.x(), b.x())), i1 = ix(std::max(a.x(), b.x()));
      const std::int64_t j0 = ix(std::min(a.y(), b.y())), j1 = ix(std::max(a.y(), b.y()));
      for (std::int64_t j = j0; j <= j1; ++j)
        for (std::int64_t x = i0; x <= i1; ++x)
          keyed.emplace_back(cell_key(x, j), (std::uint64_t(l) << 32) | i);
    }
  }
  cells_ = grouped_cells(keyed, ids_);
}

Foot SegmentGrid::foot(std::uint64_t id, const Vec& p, const detail::SegmentFoot& f) const {
  const int l = int(id >> 32);
  const std::size_t k = std::size_t(id & 0xffffffffu);
  const Points& q = *loops_[l];
  const Vec e = q[(k + 1) % q.size()] - q[k];
  const double e2 = e.squaredNorm();
  Foot out;
  out.loop = l;
  out.s = cum_[l][k] + f.t * std::sqrt(e2);
  out.distance = std::sqrt(f.d2);
  out.normal = e2 > 0 ? Vec(e.y(), -e.x()) / std::sqrt(e2) : Vec(0, 0);
  return out;
}

detail::SegmentFoot SegmentGrid::foot_on(std::uint64_t id, const Vec& p) const {
  const Points& q = *loops_[int(id >> 32)];
  const std::size_t k = std::size_t(id & 0xffffffffu);
  return detail::segment_foot(q[k], q[(k + 1) % q.size()], p);
}

Foot SegmentGrid::nearest(const Vec& p) const {
  const std::int64_t ci = ix(p.x()), cj = ix(p.y());
  // p's own cell first: a segment outside it lies at least p's distance to the cell's
  // sides away (less a margin for rounding), so a nearer foot there settles it. The
  // 3 x 3 scan below takes the first of equally near feet in its order (cell row by row,
  // then id): among the own cell's segments that is the least (first of the 3 x 3 cells
  // that holds the segment, id), each segment held by the cells its box covers.
  const double x0 = double(ci) * cell_, y0 = double(cj) * cell_;
  const double side = std::min({p.x() - x0, x0 + cell_ - p.x(), p.y() - y0, y0 + cell_ - p.y()});
  const double margin = side - 1e-9 * (cell_ + std::abs(p.x()) + std::abs(p.y()));
  if (margin > 0) {
    const auto [begin, end] = cells_.find(cell_key(ci, cj));
    double best2 = std::min(cell_ * cell_, margin * margin);
    std::size_t won = end;
    std::int64_t won_j = 0, won_i = 0;
    detail::SegmentFoot won_f;
    for (std::size_t a = begin; a < end; ++a) {
      const detail::SegmentFoot f = foot_on(ids_[a], p);
      if (f.d2 > best2 || (f.d2 == best2 && won == end)) continue;
      const Points& q = *loops_[int(ids_[a] >> 32)];
      const std::size_t k = std::size_t(ids_[a] & 0xffffffffu);
      const Vec& u = q[k];
      const Vec& v = q[(k + 1) % q.size()];
      const std::int64_t j = std::max(ix(std::min(u.y(), v.y())), cj - 1);
      const std::int64_t i = std::max(ix(std::min(u.x(), v.x())), ci - 1);
      if (f.d2 == best2 && std::make_tuple(j, i, ids_[a]) > std::make_tuple(won_j, won_i, ids_[won]))
        continue;
      best2 = f.d2, won = a, won_j = j, won_i = i, won_f = f;
    }
    if (won != end) return foot(ids_[won], p, won_f);
  }
  // The foot made once, of the nearest segment (not of each nearer one on the way).
  const std::uint64_t none = ~std::uint64_t(0);
  std::uint64_t best = none;
  detail::SegmentFoot best_f;
  best_f.d2 = cell_ * cell_;
  for (std::int64_t j = cj - 1; j <= cj + 1; ++j)
    for (std::int64_t i = ci - 1; i <= ci + 1; ++i) {
      const auto [begin, end] = cells_.find(cell_key(i, j));
      for (std::size_t a = begin; a < end; ++a) {
        const detail::SegmentFoot f = foot_on(ids_[a], p);
        if (f.d2 < best_f.d2) best = ids_[a], best_f = f;
      }
    }
  return best == none ? Foot{} : foot(best, p, best_f);
}

void robust_box(const Points& points, const std::vector<std::size_t>& subset, double q, Vec& lo, Vec& hi) {
  std::vector<double> xs, ys;
  xs.reserve(subset.size());
  ys.reserve(subset.size());
  for (std::size_t k : subset) {
    xs.push_back(points[k].x());
    ys.push_back(points[k].y());
  }
  const auto at = [](std::vector<double>& v, double f) {
    const std::size_t i = std::min(v.size() - 1, std::size_t(f * double(v.size() - 1) + 0.5));
    std::nth_element(v.begin(), v.begin() + i, v.end());
    return v[i];
  };
  lo = {at(xs, q), at(ys, q)};
  hi = {at(xs, 1 - q), at(ys, 1 - q)};
}

double median_spacing(const Points& points, const std::vector<std::size_t>& subset, std::size_t sample,
                      double floor) {
  if (subset.size() < 2) return std::max(0.0, floor);
  Vec lo, hi;
  robust_box(points, subset, 0.005, lo, hi);
  const double diag = (hi - lo).norm();
  if (!(diag > 0)) {
    robust_box(points, subset, 0, lo, hi);
    if (!((hi - lo).norm() > 0)) return std::max(0.0, floor);
  }
  // Section points lie along curves: about n / 2 cells along a curve of length ~2 diag
  // would hold one point each; n^0.75 keeps a few points per cell on dense sections.
  const double cell = std::max(diag, (hi - lo).norm()) / std::pow(double(subset.size()), 0.75);
  const PointGrid grid(points, subset, cell);
  const std::size_t step = std::max<std::size_t>(1, subset.size() / std::max<std::size_t>(1, sample));
  // The median is the (size / 2)-th of at most `queries` distances: once queries / 2 + 1
  // lie within the floor, it does too (a band's points, 5 times as close as its cell).
  const std::size_t queries = (subset.size() + step - 1) / step;
  std::size_t within = 0;
  std::vector<double> d;
  for (std::size_t a = 0; a < subset.size(); a += step) {
    const double x = grid.nearest(subset[a], 64);
    if (std::isfinite(x)) d.push_back(x);
    within += x <= floor;
    if (floor > 0 && within > queries / 2) return floor;
  }
  if (d.empty()) return std::max(0.0, floor);
  std::nth_element(d.begin(), d.begin() + d.size() / 2, d.end());
  return std::max(d[d.size() / 2], floor);
}

}  // namespace section::morph

// SPDX-License-Identifier: GPL-3.0-or-later
// Nearest-segment search over a polyline: see generate_index.h.
#include "generate_index.h"

namespace section::detail::gen {

std::shared_ptr<PolylineIndex> build_index(const std::vector<Vector2d>& pts, bool closed) {
  auto idx = std::make_shared<PolylineIndex>();
  const std::size_t n = pts.size();
  idx->count = n;
  idx->closed = closed;
  if (n == 0) return idx;
  idx->first = pts.front();
  idx->middle = pts[n / 2];
  const std::size_t nseg = closed ? n : n - 1;
  const std::size_t nleaf = std::max<std::size_t>(1, (nseg + PolylineIndex::leaf - 1) / PolylineIndex::leaf);
  int leaves = 1;
  while (std::size_t(leaves) < nleaf) leaves *= 2;
  idx->leaves = leaves;
  const double inf = std::numeric_limits<double>::infinity();
  idx->lo.assign(std::size_t(2 * leaves), Vector2d(inf, inf));
  idx->hi.assign(std::size_t(2 * leaves), Vector2d(-inf, -inf));
  for (std::size_t i = 0; i < nseg; ++i) {
    const std::size_t node = std::size_t(leaves) + i / PolylineIndex::leaf;
    for (const Vector2d& p : {pts[i], pts[(i + 1) % n]}) {
      idx->lo[node] = idx->lo[node].cwiseMin(p);
      idx->hi[node] = idx->hi[node].cwiseMax(p);
    }
  }
  for (int node = leaves - 1; node >= 1; --node) {
    idx->lo[std::size_t(node)] = idx->lo[std::size_t(2 * node)].cwiseMin(idx->lo[std::size_t(2 * node + 1)]);
    idx->hi[std::size_t(node)] = idx->hi[std::size_t(2 * node)].cwiseMax(idx->hi[std::size_t(2 * node + 1)]);
  }
  return idx;
}

bool indexes(const PolylineIndex* idx, const std::vector<Vector2d>& pts, bool closed) {
  const std::size_t n = pts.size();
  return idx && n > 0 && idx->count == n && idx->closed == closed && idx->first == pts.front() &&
         idx->middle == pts[n / 2];
}

namespace {

void test_segment(const std::vector<Vector2d>& pts, std::size_t i, const Vector2d& q, Nearest& best) {
  const SegmentFoot f = segment_foot(pts[i], pts[(i + 1) % pts.size()], q);
  if (f.d2 < best.d2) best = {i, f.t, f.d2};
}

}  // namespace

Nearest nearest(const std::vector<Vector2d>& pts, bool closed, const PolylineIndex* idx, const Vector2d& q) {
  Nearest best;
  const std::size_t n = pts.size();
  if (n == 0) return best;
  if (n == 1) return {0, 0, (pts[0] - q).squaredNorm()};
  const std::size_t nseg = closed ? n : n - 1;
  if (!indexes(idx, pts, closed)) {
    for (std::size_t i = 0; i < nseg; ++i) test_segment(pts, i, q, best);
    return best;
  }
  auto box_d2 = [&](int node) {
    const Vector2d& lo = idx->lo[std::size_t(node)];
    const Vector2d& hi = idx->hi[std::size_t(node)];
    const double dx = std::max({lo.x() - q.x(), 0.0, q.x() - hi.x()});
    const double dy = std::max({lo.y() - q.y(), 0.0, q.y() - hi.y()});
    return dx * dx + dy * dy;
  };
  // Box distance, ties (query inside both boxes) broken by distance to the box centre.
  auto key = [&](int c) {
    const double d = box_d2(c);
    return d > 0
               ? d
               : -1.0 / (1.0 + (0.5 * (idx->lo[std::size_t(c)] + idx->hi[std::size_t(c)]) - q).squaredNorm());
  };
  int stack[64];
  int top = 0;
  stack[top++] = 1;
  while (top > 0) {
    const int node = stack[--top];
    if (box_d2(node) >= best.d2) continue;
    if (node >= idx->leaves) {
      const std::size_t i0 = std::size_t(node - idx->leaves) * PolylineIndex::leaf;
      const std::size_t i1 = std::min(nseg, i0 + PolylineIndex::leaf);
      for (std::size_t i = i0; i < i1; ++i) test_segment(pts, i, q, best);
      continue;
    }
    const int l = 2 * node, r = 2 * node + 1;
    const bool left_first = key(l) < key(r);
    stack[top++] = left_first ? r : l;  // the nearer child on top of the stack
    stack[top++] = left_first ? l : r;
  }
  return best;
}

}  // namespace section::detail::gen

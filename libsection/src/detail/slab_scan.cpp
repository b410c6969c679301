// SPDX-License-Identifier: GPL-3.0-or-later
#include "detail/slab_scan.h"

#include "detail/cgal.h"
#include "detail/parallel.h"

#include <algorithm>
#include <cmath>
#include <thread>

namespace section::detail {

std::vector<SlabGroup> group_planes(const std::vector<Plane>& planes, double slab) {
  std::vector<SlabGroup> groups;
  for (int i = 0; i < static_cast<int>(planes.size()); ++i) {
    const Frame f = make_frame(planes[i].origin, planes[i].normal);
    SlabGroup* g = nullptr;
    for (auto& candidate : groups)
      if (candidate.n == f.n) g = &candidate;
    if (!g) {
      groups.emplace_back();
      groups.back().n = f.n;
      g = &groups.back();
    }
    g->plane.push_back(i);
  }
  for (auto& g : groups) {
    std::vector<std::pair<double, int>> order;
    for (int id : g.plane) order.emplace_back(g.n.dot(planes[id].origin), id);
    std::sort(order.begin(), order.end());
    g.plane.clear();
    for (const auto& [o, id] : order) {
      g.plane.push_back(id);
      g.offset.push_back(o);
      const Frame f = make_frame(planes[id].origin, planes[id].normal);
      const Eigen::Vector3d lo = f.origin - 0.5 * slab * f.n, hi = f.origin + 0.5 * slab * f.n;
      g.lower.push_back({lo, lo + f.u, lo + f.v});
      g.upper.push_back({hi, hi + f.u, hi + f.v});
    }
    const std::size_t nb = 4 * g.offset.size() + 4;
    const double a = g.offset.front() - slab, b = g.offset.back() + slab;
    g.key0 = a;
    g.inv_width = b > a ? double(nb) / (b - a) : 0;
    g.first.resize(nb);
    for (std::size_t k = 0; k < nb; ++k) {
      const double key = g.inv_width > 0 ? a + double(k) / g.inv_width : a;
      g.first[k] = std::lower_bound(g.offset.begin(), g.offset.end(), key) - g.offset.begin();
    }
    // Buckets a sixteenth of the narrowest gap between planes (or of the slab) wide, an
    // eighth of the slab at most, so that most of the space between slabs is in buckets far
    // from them (a slab's near buckets reach a bucket or two beyond it); 2^19 at most.
    double gap = 0;
    for (std::size_t k = 1; k < g.offset.size(); ++k) {
      const double d = g.offset[k] - g.offset[k - 1];
      if (d > 0 && (gap == 0 || d < gap)) gap = d;
    }
    const double half = 0.5 * slab, pad = std::max(4 * slab, g.offset.back() - g.offset.front());
    const double from = g.offset.front() - half - pad, to = g.offset.back() + half + pad;
    const double width =
        std::max(std::min(std::max(gap, slab) / 16, slab / 8), (to - from) / double(1 << 19));
    const double buckets = (to - from) / width;
    const std::size_t nn = buckets > 0 && buckets < double(1 << 20) ? std::size_t(buckets) + 1 : 0;
    g.near0 = from;
    g.near_width = nn ? (to - from) / double(nn) : 0;
    if (nn && g.near_width > 0 && std::isfinite(g.near_width)) {
      g.inv_near = 1 / g.near_width;
      g.near.assign(nn, 0);
      for (std::size_t b = 0; b < nn; ++b) {
        const double from = g.near0 + (double(b) - 1) * g.near_width - half,
                     to = g.near0 + (double(b) + 2) * g.near_width + half;
        const auto at = std::lower_bound(g.offset.begin(), g.offset.end(), from);
        g.near[b] = at != g.offset.end() && *at <= to;
      }
    }
  }
  return groups;
}

std::vector<Frame> frames_of(const std::vector<Plane>& planes) {
  std::vector<Frame> frame;
  for (const auto& p : planes) frame.push_back(make_frame(p.origin, p.normal));
  return frame;
}

namespace {

// Appends q to the list of every plane of `g` whose slab contains it (s = g.n . q).
inline void add_if_in_slab(const Eigen::Vector3d& q, double s, const SlabGroup& g, const SlabTests& t,
                           const std::vector<Frame>& frame, double slab,
                           std::vector<std::vector<Eigen::Vector2d>>& out) {
  const double half = 0.5 * slab;
  const std::size_t np = t.planes;
  // The first plane whose slab can contain q, then its neighbours while they can.
  const double scale = std::max({std::abs(q.x()), std::abs(q.y()), std::abs(q.z()), std::abs(s), slab});
  const double tol = 1e-12 * (scale + 1);
  std::size_t k = t.first_at_least(s - half - tol);
  for (; k < np && t.offset[k] <= s + half + tol; ++k) {
    const double above_lower = s - (t.offset[k] - half);
    const double below_upper = (t.offset[k] + half) - s;
    bool inside;
    if (above_lower > tol && below_upper > tol) {
      inside = true;
    } else {
      // Near a boundary the double test cannot decide: the exact predicate does.
      const Boundary& lo = g.lower[k];
      const Boundary& hi = g.upper[k];
      inside = orientation(lo.a, lo.b, lo.c, q) >= 0 && orientation(hi.a, hi.b, hi.c, q) <= 0;
    }
    if (inside) out[t.plane[k]].push_back(frame[t.plane[k]].to_plane(q));
  }
}

// True when q (s = g.n . q) is in a bucket of `g` with no slab near it and its rounding
// tolerance (add_if_in_slab) is below half a bucket (the rest of a bucket covers it): no
// slab can contain it.
inline bool far_from_every_slab(const Eigen::Vector3d& q, double s, const SlabTests& t, double slab) {
  if (!t.far_from_slabs(s)) return false;
  const double scale = std::max({std::abs(q.x()), std::abs(q.y()), std::abs(q.z()), std::abs(s), slab});
  return 1e-12 * (scale + 1) < 0.5 * t.near_width;
}

// Appends (u, v, signed distance from the plane) of q to the list of every plane of `g`
// within `reach` of it (s = g.n . q; `g` built with a slab of 2 reach).
inline void add_if_near(const Eigen::Vector3d& q, double s, const SlabTests& t,
                        const std::vector<Frame>& frame, double reach,
                        std::vector<std::vector<Eigen::Vector3d>>& out) {
  if (t.far_from_slabs(s)) return;
  for (std::size_t k = t.first_at_least(s - reach); k < t.planes && t.offset[k] <= s + reach; ++k) {
    const Eigen::Vector2d uv = frame[t.plane[k]].to_plane(q);
    out[t.plane[k]].emplace_back(uv.x(), uv.y(), s - t.offset[k]);
  }
}

// add(points, count, out) with the chunk split across threads; each part collects into
// its own lists and the parts are appended in order, so the result does not depend on
// the threads.
template <class T, class Add>
void add_parallel(const Eigen::Vector3d* points, std::size_t count, int threads,
                  std::vector<std::vector<T>>& out, const Add& add) {
  const std::size_t parts = parts_of(count, threads);
  if (parts == 1) return add(points, count, out);
  std::vector<std::vector<std::vector<T>>> local(parts, std::vector<std::vector<T>>(out.size()));
  parallel_for(parts, threads, [&](std::size_t t) {
    const std::size_t a = count * t / parts, b = count * (t + 1) / parts;
    add(points + a, b - a, local[t]);
  });
  for (const auto& part : local)
    for (std::size_t k = 0; k < out.size(); ++k) out[k].insert(out[k].end(), part[k].begin(), part[k].end());
}

// add_near_points_parallel on one part; every point is kept (docs/MORPHOLOGY.md, gap filling).
void add_near_points(const Eigen::Vector3d* points, std::size_t count, const std::vector<SlabGroup>& groups,
                     const std::vector<Frame>& frame, double reach,
                     std::vector<std::vector<Eigen::Vector3d>>& out) {
  // The tests on the heap, not in the frame: held in registers, they were saved and
  // restored around every near point's appends (a call may grow a list), which cost more
  // than reading them from memory each point.
  std::vector<SlabTests> tests;
  for (const SlabGroup& g : groups) tests.emplace_back(g);
  for (const SlabTests& t : tests)
    for (std::size_t i = 0; i < count; ++i) add_if_near(points[i], t.n.dot(points[i]), t, frame, reach, out);
}

}  // namespace

void add_slab_points(const Eigen::Vector3d* points, std::size_t count, const std::vector<SlabGroup>& groups,
                     const std::vector<Frame>& frame, double slab,
                     std::vector<std::vector<Eigen::Vector2d>>& out) {
  for (const SlabGroup& g : groups) {
    const SlabTests t(g);
    for (std::size_t i = 0; i < count; ++i) {
      const double s = t.n.dot(points[i]);
      if (!far_from_every_slab(points[i], s, t, slab)) add_if_in_slab(points[i], s, g, t, frame, slab, out);
    }
  }
}

std::size_t parts_of(std::size_t count, int threads) {
  const std::size_t workers =
      threads > 0 ? std::size_t(threads) : std::max(1u, std::thread::hardware_concurrency());
  return std::max<std::size_t>(1, std::min(workers, count / 65536));
}

void add_slab_points_parallel(const Eigen::Vector3d* points, std::size_t count,
                              const std::vector<SlabGroup>& groups, const std::vector<Frame>& frame,
                              double slab, int threads, std::vector<std::vector<Eigen::Vector2d>>& out) {
  add_parallel(points, count, threads, out, [&](const Eigen::Vector3d* p, std::size_t n, auto& o) {
    add_slab_points(p, n, groups, frame, slab, o);
  });
}

void add_near_points_parallel(const Eigen::Vector3d* points, std::size_t count,
                              const std::vector<SlabGroup>& groups, const std::vector<Frame>& frame,
                              double reach, int threads, std::vector<std::vector<Eigen::Vector3d>>& out) {
  add_parallel(points, count, threads, out, [&](const Eigen::Vector3d* p, std::size_t n, auto& o) {
    add_near_points(p, n, groups, frame, reach, o);
  });
}

void add_slab_and_near_points_parallel(const Eigen::Vector3d* points, std::size_t count,
                                       const std::vector<SlabGroup>& groups,
                                       const std::vector<SlabGroup>& near_groups,
                                       const std::vector<Frame>& frame, double slab, double reach,
                                       int threads, std::vector<std::vector<Eigen::Vector2d>>& slabs,
                                       std::vector<std::vector<Eigen::Vector3d>>& near) {
  const std::size_t parts = parts_of(count, threads);
  std::vector<std::vector<std::vector<Eigen::Vector2d>>> local_slabs(
      parts, std::vector<std::vector<Eigen::Vector2d>>(slabs.size()));
  std::vector<std::vector<std::vector<Eigen::Vector3d>>> local_near(
      parts, std::vector<std::vector<Eigen::Vector3d>>(near.size()));
  parallel_for(parts, threads, [&](std::size_t t) {
    const std::size_t a = count * t / parts, b = count * (t + 1) / parts;
    for (std::size_t gi = 0; gi < groups.size(); ++gi) {
      const SlabGroup& g = groups[gi];
      const SlabTests gt(g), nt(near_groups[gi]);
      for (std::size_t i = a; i < b; ++i) {
        const Eigen::Vector3d& q = points[i];
        const double s = gt.n.dot(q);
        if (!far_from_every_slab(q, s, gt, slab)) add_if_in_slab(q, s, g, gt, frame, slab, local_slabs[t]);
        add_if_near(q, s, nt, frame, reach, local_near[t]);
      }
    }
  });
  for (std::size_t t = 0; t < parts; ++t) {
    for (std::size_t k = 0; k < slabs.size(); ++k)
      slabs[k].insert(slabs[k].end(), local_slabs[t][k].begin(), local_slabs[t][k].end());
    for (std::size_t k = 0; k < near.size(); ++k)
      near[k].insert(near[k].end(), local_near[t][k].begin(), local_near[t][k].end());
  }
}

}  // namespace section::detail

#include "section/slice.h"

#include "section/error.h"
#include "section/io/cloud_io.h"
#include "section/io/slice_file.h"
#include "detail/cgal.h"
#include "detail/parallel.h"

#include <algorithm>
#include <cstdio>
#include <cmath>
#include <map>
#include <mutex>
#include <numeric>
#include <optional>
#include <random>
#include <thread>

namespace section {

std::vector<Plane> planes_at(const Eigen::Vector3d& normal, const std::vector<double>& offsets) {
  const double len = normal.norm();
  if (!(len > 0) || !std::isfinite(len)) throw Error("slice: the plane normal must be finite and non-zero");
  std::vector<Plane> planes;
  for (double o : offsets) {
    if (!std::isfinite(o)) throw Error("slice: plane offsets must be finite");
    planes.push_back({o * normal / len, normal});
  }
  return planes;
}

std::vector<Plane> planes_across(const std::vector<Eigen::Vector3d>& points, const Eigen::Vector3d& normal,
                                 int count) {
  const double len = normal.norm();
  if (!(len > 0) || !std::isfinite(len)) throw Error("slice: the plane normal must be finite and non-zero");
  if (count < 1) throw Error("slice: --count must be at least 1");
  if (points.empty()) throw Error("slice: no points to spread planes over");
  const Eigen::Vector3d n = normal / len;
  double lo = INFINITY, hi = -INFINITY;
  for (const auto& p : points) {
    const double s = n.dot(p);
    lo = std::min(lo, s);
    hi = std::max(hi, s);
  }
  std::vector<double> offsets;
  for (int k = 0; k < count; ++k) offsets.push_back(lo + (hi - lo) * (k + 1) / (count + 1));
  return planes_at(normal, offsets);
}

namespace {

// One slab boundary plane, defined exactly by three points with double coordinates.
struct Boundary {
  Eigen::Vector3d a, b, c;
};

struct SlabGroup {
  Eigen::Vector3d n;                 // unit normal shared by the group
  std::vector<int> plane;            // plane ids, sorted by offset
  std::vector<double> offset;        // n . origin, sorted
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
  bool far_from_slabs(double s) const {
    const double x = (s - near0) * inv_near;
    return x >= 0 && x < double(near.size()) && !near[std::size_t(x)];
  }

  /// The index of the first offset >= key (std::lower_bound's answer), from the bucket's
  /// guess and a few steps.
  std::size_t first_at_least(double key) const {
    const double x = (key - key0) * inv_width;
    const std::size_t nb = first.size();
    std::size_t k = first[x >= 0 ? (x < double(nb) ? std::size_t(x) : nb - 1) : 0];
    while (k > 0 && offset[k - 1] >= key) --k;
    while (k < offset.size() && offset[k] < key) ++k;
    return k;
  }
};

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
    // Buckets a sixteenth of the narrowest gap between planes (or of the slab) wide, so
    // that most of the space between slabs is in buckets far from them.
    double gap = 0;
    for (std::size_t k = 1; k < g.offset.size(); ++k) {
      const double d = g.offset[k] - g.offset[k - 1];
      if (d > 0 && (gap == 0 || d < gap)) gap = d;
    }
    const double half = 0.5 * slab, pad = std::max(4 * slab, g.offset.back() - g.offset.front());
    const double from = g.offset.front() - half - pad, to = g.offset.back() + half + pad;
    const double buckets = (to - from) / (std::max(gap, slab) / 16);
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

}  // namespace

namespace {

// Appends q to the list of every plane of `g` whose slab contains it (s = g.n . q).
inline void add_if_in_slab(const Eigen::Vector3d& q, double s, const SlabGroup& g, const std::vector<Frame>& frame,
                           double slab, std::vector<std::vector<Eigen::Vector2d>>& out) {
  const double half = 0.5 * slab;
  const std::size_t np = g.offset.size();
  // The first plane whose slab can contain q, then its neighbours while they can.
  const double scale = std::max({std::abs(q.x()), std::abs(q.y()), std::abs(q.z()), std::abs(s), slab});
  const double tol = 1e-12 * (scale + 1);
  std::size_t k = g.first_at_least(s - half - tol);
  for (; k < np && g.offset[k] <= s + half + tol; ++k) {
    const double above_lower = s - (g.offset[k] - half);
    const double below_upper = (g.offset[k] + half) - s;
    bool inside;
    if (above_lower > tol && below_upper > tol) {
      inside = true;
    } else {
      // Near a boundary the double test cannot decide: the exact predicate does.
      const Boundary& lo = g.lower[k];
      const Boundary& hi = g.upper[k];
      inside = detail::orientation(lo.a, lo.b, lo.c, q) >= 0 && detail::orientation(hi.a, hi.b, hi.c, q) <= 0;
    }
    if (inside) out[g.plane[k]].push_back(frame[g.plane[k]].to_plane(q));
  }
}

// True when q (s = g.n . q) is in a bucket of `g` with no slab near it and its rounding
// tolerance (add_if_in_slab) is below half a bucket (the rest of a bucket covers it): no
// slab can contain it.
inline bool far_from_every_slab(const Eigen::Vector3d& q, double s, const SlabGroup& g, double slab) {
  if (g.near.empty() || !g.far_from_slabs(s)) return false;
  const double scale = std::max({std::abs(q.x()), std::abs(q.y()), std::abs(q.z()), std::abs(s), slab});
  return 1e-12 * (scale + 1) < 0.5 * g.near_width;
}

// Appends (u, v, signed distance from the plane) of q to the list of every plane of `g`
// within `reach` of it (s = g.n . q; `g` built with a slab of 2 reach).
inline void add_if_near(const Eigen::Vector3d& q, double s, const SlabGroup& g, const std::vector<Frame>& frame,
                        double reach, std::vector<std::vector<Eigen::Vector3d>>& out) {
  if (!g.near.empty() && g.far_from_slabs(s)) return;
  const std::size_t np = g.offset.size();
  for (std::size_t k = g.first_at_least(s - reach); k < np && g.offset[k] <= s + reach; ++k) {
    const Eigen::Vector2d uv = frame[g.plane[k]].to_plane(q);
    out[g.plane[k]].emplace_back(uv.x(), uv.y(), s - g.offset[k]);
  }
}

// Appends the slab points of points[0, count) to `out` (one list per plane), in order.
void add_slab_points(const Eigen::Vector3d* points, std::size_t count, const std::vector<SlabGroup>& groups,
                     const std::vector<Frame>& frame, double slab, std::vector<std::vector<Eigen::Vector2d>>& out) {
  for (const SlabGroup& g : groups)
    for (std::size_t i = 0; i < count; ++i) {
      const double s = g.n.dot(points[i]);
      if (!far_from_every_slab(points[i], s, g, slab)) add_if_in_slab(points[i], s, g, frame, slab, out);
    }
}

// Splits points[0, count) into parts of at least 64k points, one per thread at most.
std::size_t parts_of(std::size_t count, int threads) {
  const std::size_t workers = threads > 0 ? std::size_t(threads) : std::max(1u, std::thread::hardware_concurrency());
  return std::max<std::size_t>(1, std::min(workers, count / 65536));
}

// add(points, count, out) with the chunk split across threads; each part collects into
// its own lists and the parts are appended in order, so the result does not depend on
// the threads.
template <class T, class Add>
void add_parallel(const Eigen::Vector3d* points, std::size_t count, int threads, std::vector<std::vector<T>>& out,
                  const Add& add) {
  const std::size_t parts = parts_of(count, threads);
  if (parts == 1) return add(points, count, out);
  std::vector<std::vector<std::vector<T>>> local(parts, std::vector<std::vector<T>>(out.size()));
  detail::parallel_for(parts, threads, [&](std::size_t t) {
    const std::size_t a = count * t / parts, b = count * (t + 1) / parts;
    add(points + a, b - a, local[t]);
  });
  for (const auto& part : local)
    for (std::size_t k = 0; k < out.size(); ++k) out[k].insert(out[k].end(), part[k].begin(), part[k].end());
}

void add_slab_points_parallel(const Eigen::Vector3d* points, std::size_t count, const std::vector<SlabGroup>& groups,
                              const std::vector<Frame>& frame, double slab, int threads,
                              std::vector<std::vector<Eigen::Vector2d>>& out) {
  add_parallel(points, count, threads, out, [&](const Eigen::Vector3d* p, std::size_t n, auto& o) {
    add_slab_points(p, n, groups, frame, slab, o);
  });
}

// Appends to `out` the points of points[0, count) within `reach` of each plane of
// `groups` (built with a slab of 2 reach) as (u, v, signed distance from the plane), in
// order. A plain double test: these points only fill gaps, no boundary needs to be exact.
// (Keeping a quarter of them, by a hash, cut the 20 M point pipe by 0.7 s but cost the
// generated compressor sections several targets: they are all kept.)
void add_near_points(const Eigen::Vector3d* points, std::size_t count, const std::vector<SlabGroup>& groups,
                     const std::vector<Frame>& frame, double reach, std::vector<std::vector<Eigen::Vector3d>>& out) {
  for (const SlabGroup& g : groups)
    for (std::size_t i = 0; i < count; ++i) add_if_near(points[i], g.n.dot(points[i]), g, frame, reach, out);
}

void add_near_points_parallel(const Eigen::Vector3d* points, std::size_t count, const std::vector<SlabGroup>& groups,
                              const std::vector<Frame>& frame, double reach, int threads,
                              std::vector<std::vector<Eigen::Vector3d>>& out) {
  add_parallel(points, count, threads, out, [&](const Eigen::Vector3d* p, std::size_t n, auto& o) {
    add_near_points(p, n, groups, frame, reach, o);
  });
}

// The slab points (add_slab_points) and the points within `reach` (add_near_points) of
// points[0, count) in one pass, split across threads: n . q once per point, and the
// chunk read from memory once. `near_groups` are `groups` built with a slab of 2 reach
// (same normals, same planes, same order).
void add_slab_and_near_points_parallel(const Eigen::Vector3d* points, std::size_t count,
                                       const std::vector<SlabGroup>& groups, const std::vector<SlabGroup>& near_groups,
                                       const std::vector<Frame>& frame, double slab, double reach, int threads,
                                       std::vector<std::vector<Eigen::Vector2d>>& slabs,
                                       std::vector<std::vector<Eigen::Vector3d>>& near) {
  const std::size_t parts = parts_of(count, threads);
  std::vector<std::vector<std::vector<Eigen::Vector2d>>> local_slabs(parts, std::vector<std::vector<Eigen::Vector2d>>(slabs.size()));
  std::vector<std::vector<std::vector<Eigen::Vector3d>>> local_near(parts, std::vector<std::vector<Eigen::Vector3d>>(near.size()));
  detail::parallel_for(parts, threads, [&](std::size_t t) {
    const std::size_t a = count * t / parts, b = count * (t + 1) / parts;
    for (std::size_t gi = 0; gi < groups.size(); ++gi) {
      const SlabGroup& g = groups[gi];
      const SlabGroup& ng = near_groups[gi];
      for (std::size_t i = a; i < b; ++i) {
        const Eigen::Vector3d& q = points[i];
        const double s = g.n.dot(q);
        if (!far_from_every_slab(q, s, g, slab)) add_if_in_slab(q, s, g, frame, slab, local_slabs[t]);
        add_if_near(q, s, ng, frame, reach, local_near[t]);
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

// How far from the plane the points beside it are kept: the fill's reach and the band's
// drift fit (drift_band); 0 when neither runs.
double fill_reach(const SliceOptions& options, double slab) {
  const double fill = options.fill_gaps ? gap_fill_reach(options.fill, slab) : 0;
  const double band = options.band_spacing > 0
                         ? std::max({2 * std::max(0.5, options.band_max), options.band_sparse_max, 3.0}) * slab
                         : 0;
  return std::max(fill, band);
}

void check_band_options(const SliceOptions& options) {
  if (!(options.band_spacing >= 0) || !std::isfinite(options.band_spacing))
    throw Error("slice: the band spacing must be zero or positive and finite");
  if (!(options.band_max >= 0.5) || !std::isfinite(options.band_max))
    throw Error("slice: the band's largest half width must be at least 0.5 slab widths");
  if (!(options.band_sparse_max >= 0) || !std::isfinite(options.band_sparse_max))
    throw Error("slice: the band's half width beside sparse stretches must be zero or positive and finite");
}

std::vector<Frame> frames_of(const std::vector<Plane>& planes) {
  std::vector<Frame> frame;
  for (const auto& p : planes) frame.push_back(make_frame(p.origin, p.normal));
  return frame;
}

void check_slab(double slab) {
  if (!(slab >= 0) || !std::isfinite(slab)) throw Error("slice: the slab width must be finite and not negative");
}

}  // namespace

std::vector<std::vector<Eigen::Vector2d>> slab_points(const std::vector<Eigen::Vector3d>& points,
                                                      const std::vector<Plane>& planes, double slab) {
  check_slab(slab);
  std::vector<std::vector<Eigen::Vector2d>> out(planes.size());
  add_slab_points(points.data(), points.size(), group_planes(planes, slab), frames_of(planes), slab, out);
  return out;
}

namespace {

void check_planes(const std::vector<Plane>& planes) {
  if (planes.empty()) throw Error("slice: no section planes given");
  for (const auto& p : planes)
    if (!p.origin.allFinite() || !p.normal.allFinite() || !(p.normal.norm() > 0))
      throw Error("slice: every section plane needs a finite origin and a non-zero normal");
}

}  // namespace

namespace {

// Hands finished sections to a callback in plane order, from one thread at a time,
// without holding up the threads that finish sections meanwhile.
class InOrder {
public:
  InOrder(std::size_t count, const SectionSink& sink) : done_(count, 0), sink_(sink) {}
  void finished(std::size_t i, const std::vector<SectionSlice>& sections) {
    if (!sink_) return;
    {
      std::lock_guard<std::mutex> lock(mutex_);
      done_[i] = 1;
      if (handing_) return;  // the thread handing sections over takes this one too
      handing_ = true;
    }
    while (true) {
      std::size_t k;
      {
        std::lock_guard<std::mutex> lock(mutex_);
        if (next_ == done_.size() || !done_[next_]) {
          handing_ = false;
          return;
        }
        k = next_++;
      }
      sink_(sections[k]);
    }
  }

private:
  std::mutex mutex_;
  std::vector<char> done_;
  std::size_t next_ = 0;
  bool handing_ = false;
  const SectionSink& sink_;
};

// The points beside plane i (fill_reach) as (u, v, signed distance), asked for only when
// a section has a band to build or a gap to fill.
using NearFn = std::function<std::vector<Eigen::Vector3d>(std::size_t i)>;

// Orders the slab points of every plane into loops, sections in parallel, and fills the
// profile's gaps from the near points; frees each section's points once done and hands
// it to `sink` in plane order.
void order_slabs(std::vector<std::vector<Eigen::Vector2d>>& slabs, const NearFn& near_of,
                 const std::vector<Plane>& planes, double slab, const SliceOptions& options, SliceResult& result,
                 const SectionSink& sink = {}) {
  result.sections.resize(planes.size());
  InOrder in_order(planes.size(), sink);
  detail::parallel_for(planes.size(), options.threads, [&](std::size_t i) {
    SectionSlice& s = result.sections[i];
    s.id = static_cast<int>(i);
    s.frame = make_frame(planes[i].origin, planes[i].normal);
    s.slab_points = slabs[i].size();
    try {
      if (slabs[i].empty()) throw Error("no points in the slab (the plane misses the part?)");
      s.morphology = order_section(slabs[i], options.morphology);
      std::size_t first = slabs[i].size();
      std::optional<std::vector<Eigen::Vector3d>> near_points;
      const auto near = [&]() -> const std::vector<Eigen::Vector3d>& {
        if (!near_points) near_points = near_of ? near_of(i) : std::vector<Eigen::Vector3d>{};
        return *near_points;
      };
      if (options.band_spacing > 0 && !s.morphology.loops.empty()) {
        const Loop& profile = s.morphology.loops[0];
        const double half = band_half_width(profile.points.size(), profile.length, slab, options.band_spacing,
                                            options.band_max);
        // A band less than twice as wide as the slab is not worth a second ordering and
        // the later stages' time for its points (the slab is dense enough then).
        if (half >= slab && !near().empty()) {
          std::vector<Eigen::Vector2d> band =
              drift_band(s.morphology, near(), slab, half, options.band_spacing, options.band_sparse_max * slab);
          if (band.size() > slabs[i].size()) {
            // A band that cannot be ordered leaves the slab's ordering as it is.
            try {
              s.morphology = order_section(band, options.morphology);
              first = band.size();
              s.band_points = band.size();
              s.band_half_width = half;
            } catch (const Error&) {
            }
          }
        }
      }
      // The points beside the plane only for a profile with gaps (the look for gaps
      // needs none of them, and fill_gaps finds none then).
      if (options.fill_gaps && fill_gaps(s.morphology, {}, slab, first, options.fill).gaps > 0 && !near().empty()) {
        GapFillResult r = fill_gaps(s.morphology, near(), slab, first, options.fill);
        s.morphology = std::move(r.filled);
        r.filled = MorphologyResult{};
        s.fill = std::move(r);
      }
    } catch (const std::exception& e) {
      s.error = e.what();
    }
    std::vector<Eigen::Vector2d>().swap(slabs[i]);
    in_order.finished(i, result.sections);
  });
}

}  // namespace

SliceResult slice(const Cloud& cloud, const std::vector<Plane>& planes, const SliceOptions& options) {
  check_planes(planes);
  if (options.fill_gaps) check_gap_fill_options(options.fill);
  check_band_options(options);
  if (cloud.points.empty()) throw Error("slice: the cloud has no points");
  SliceResult result;
  result.points = cloud.points.size();
  result.slab = options.slab;
  if (result.slab == 0) {
    result.slab = mean_spacing(cloud.points);
    if (!(result.slab > 0))
      throw Error("slice: cannot estimate the point spacing (fewer than two distinct points); give the slab width");
  }
  if (!(result.slab > 0) || !std::isfinite(result.slab)) throw Error("slice: the slab width must be positive and finite");
  auto slabs = slab_points(cloud.points, planes, result.slab);
  const double reach = fill_reach(options, result.slab);
  const auto near_groups = reach > 0 ? group_planes(planes, 2 * reach) : std::vector<SlabGroup>{};
  const auto frame = frames_of(planes);
  // Every plane's near points in one pass over the cloud, made when a section first asks.
  std::vector<std::vector<Eigen::Vector3d>> near(planes.size());
  std::once_flag near_made;
  const NearFn near_of = [&](std::size_t i) {
    std::call_once(near_made, [&] {
      if (reach > 0)
        add_near_points_parallel(cloud.points.data(), cloud.points.size(), near_groups, frame, reach, 1, near);
    });
    return std::move(near[i]);
  };
  order_slabs(slabs, near_of, planes, result.slab, options, result);
  return result;
}

namespace {

// Planes (and slab) guessed from a first look at a cloud file (peek_cloud), and the points
// kept around them while pass 1 of slice_file reads the file.
struct Guess {
  bool active = false;                             // false: no guess; pass 2 reads the file again
  std::vector<Plane> planes;                       // the guessed planes
  double half_width = 0;                           // points within this of a guessed plane are kept
  double share = 0;                                // estimated share of the points kept
  std::vector<SlabGroup> groups;                   // the guessed planes with slabs 2 half_width wide
  // Per guessed plane, blocks of the points kept, in file order (blocks are moved in as
  // the threads collect them, not copied).
  std::vector<std::vector<std::vector<Eigen::Vector3d>>> kept;

  // Appends q to the list in `out` of each guessed plane within half_width of it.
  void keep(const Eigen::Vector3d& q, std::vector<std::vector<Eigen::Vector3d>>& out) const {
    for (const SlabGroup& g : groups) {
      const double s = g.n.dot(q);
      if (!g.near.empty() && g.far_from_slabs(s)) continue;
      for (std::size_t k = g.first_at_least(s - half_width); k < g.offset.size() && g.offset[k] <= s + half_width; ++k)
        out[g.plane[k]].push_back(q);
    }
  }

  // True when every point the slab test of `found` (slab width `slab`) can take was kept:
  // each found plane lies close enough to its guess. `largest` bounds the points'
  // coordinates (the exact slab test's tolerance).
  bool covers(const std::vector<Plane>& found, double slab, double largest) const {
    if (found.size() != planes.size()) return false;
    const double tol = 1e-12 * (std::max(2 * largest, slab) + 1) * (1 + 1e-6);
    const double need = 0.5 * slab + 3 * tol;
    for (std::size_t k = 0; k < found.size(); ++k) {
      const Frame f = make_frame(found[k].origin, found[k].normal), g = make_frame(planes[k].origin, planes[k].normal);
      if (!(f.n == g.n)) return false;
      const double shift = std::abs(f.n.dot(found[k].origin) - g.n.dot(planes[k].origin));
      if (!(shift + need <= half_width)) return false;
    }
    return true;
  }
};

// read_cloud_chunks_parallel with a result per chunk: `scan(points, count, threads)` makes
// it on a worker thread, `take(result, points, count)` receives it in file order.
template <class Scan, class Take>
std::size_t scan_chunks(const std::string& path, const CloudReadOptions& read, const Scan& scan, const Take& take) {
  using Result = decltype(scan(static_cast<const Eigen::Vector3d*>(nullptr), std::size_t(0), 1));
  std::mutex mutex;
  std::map<std::size_t, Result> made;  // by chunk, from scan to take
  return read_cloud_chunks_parallel(
      path,
      [&](std::size_t chunk, const Eigen::Vector3d* p, std::size_t count, int threads) {
        Result r = scan(p, count, threads);
        std::lock_guard<std::mutex> lock(mutex);
        made[chunk] = std::move(r);
      },
      [&](std::size_t chunk, const Eigen::Vector3d* p, std::size_t count) {
        Result r;
        {
          std::lock_guard<std::mutex> lock(mutex);
          auto at = made.find(chunk);
          r = std::move(at->second);
          made.erase(at);
        }
        take(r, p, count);
      },
      read);
}

// The points within `reach` of each plane in the file, as (u, v, signed distance), in file
// order (add_near_points), chunks read side by side.
std::vector<std::vector<Eigen::Vector3d>> read_near_points(const std::string& path, const std::vector<Plane>& planes,
                                                           double reach, const CloudReadOptions& read) {
  const auto groups = group_planes(planes, 2 * reach);
  const auto frame = frames_of(planes);
  std::vector<std::vector<Eigen::Vector3d>> near(planes.size());
  scan_chunks(
      path, read,
      [&](const Eigen::Vector3d* p, std::size_t count, int threads) {
        std::vector<std::vector<Eigen::Vector3d>> f(planes.size());
        add_near_points_parallel(p, count, groups, frame, reach, threads, f);
        return f;
      },
      [&](std::vector<std::vector<Eigen::Vector3d>>& f, const Eigen::Vector3d*, std::size_t) {
        for (std::size_t k = 0; k < planes.size(); ++k) near[k].insert(near[k].end(), f[k].begin(), f[k].end());
      });
  return near;
}

// The guess for slice_file: planes from the extent of 4096 points read here and there
// (peek_cloud: binary PLY files only), the slab from their spacing scaled to the full
// density as pass 1 scales its sample's. Inactive when the points kept around the
// guessed planes would be a large part of the cloud.
Guess guess_planes(const std::string& path, const PlaneSpec& spec, const SliceOptions& options,
                   const CloudReadOptions& read) {
  Guess guess;
  const CloudPeek peek = peek_cloud(path, 4096, read);
  if (peek.points.size() < 256) return guess;
  double slab = options.slab;
  if (slab == 0) slab = mean_spacing(peek.points) * std::sqrt(double(peek.points.size()) / double(peek.total)) / 0.47;
  if (!(slab > 0) || !std::isfinite(slab)) return guess;
  const auto extent_along = [&](const Eigen::Vector3d& normal, double& lo, double& hi) {
    const Eigen::Vector3d n = normal.normalized();
    lo = INFINITY;
    hi = -INFINITY;
    for (const auto& p : peek.points) {
      lo = std::min(lo, n.dot(p));
      hi = std::max(hi, n.dot(p));
    }
  };
  // Measured on generated blades: the peek's spacing is 3-18 % above the one pass 1
  // finds, its extent within 0.025 mm of 60 mm. Planes spread over the extent move by up
  // to the extent's error once it is known; explicit planes stay. Only the slabs are
  // kept: the points beside a plane, which a section with a gap or a band needs, are
  // read again for it (rare on dense scans, where the guess pays).
  double shift = 0;
  if (spec.count > 0) {
    double lo, hi;
    extent_along(spec.normal, lo, hi);
    if (!(hi > lo)) return guess;
    shift = std::max(1e-3 * (hi - lo), 2 * slab);
    std::vector<double> offsets;
    for (int k = 0; k < spec.count; ++k) offsets.push_back(lo + (hi - lo) * (k + 1) / (spec.count + 1));
    guess.planes = planes_at(spec.normal, offsets);
  } else {
    guess.planes = spec.planes;
  }
  guess.half_width = 1.5 * 0.5 * slab + shift;
  // Worth it while the kept points are at most half the cloud (else pass 2 is cheaper).
  double share = 0;
  for (const auto& p : guess.planes) {
    double lo, hi;
    extent_along(p.normal, lo, hi);
    share += hi > lo ? 2 * guess.half_width / (hi - lo) : 1;
  }
  if (!(share <= 0.5)) return guess;
  guess.share = share;
  guess.groups = group_planes(guess.planes, 2 * guess.half_width);
  guess.kept.resize(guess.planes.size());
  guess.active = true;
  return guess;
}

}  // namespace

SliceResult slice_file(const std::string& path, const PlaneSpec& spec, const SliceOptions& options,
                       const CloudReadOptions& read, const SectionSink& sink) {
  check_slab(options.slab);
  if (options.fill_gaps) check_gap_fill_options(options.fill);
  check_band_options(options);
  if (spec.count > 0 && (!spec.normal.allFinite() || !(spec.normal.norm() > 0)))
    throw Error("slice: the plane normal must be finite and non-zero");
  if (spec.count == 0) check_planes(spec.planes);
  if (path == "-") {
    // A pipe cannot be read twice: hold the cloud.
    const Cloud cloud = read_cloud(path, read);
    const auto planes = spec.count > 0 ? planes_across(cloud.points, spec.normal, spec.count) : spec.planes;
    SliceResult result = slice(cloud, planes, options);
    if (sink)
      for (const auto& s : result.sections) sink(s);
    return result;
  }
  // Chunks of at most 64k points (1.5 MB): each stays in a core's cache from its read to its
  // scan, and the workers end the file together.
  CloudReadOptions read_chunks = read;
  read_chunks.chunk_points = std::min<std::size_t>(read.chunk_points, std::size_t(1) << 16);
  if (read_chunks.threads == 0) read_chunks.threads = options.threads;
  std::vector<Plane> planes = spec.planes;
  double slab = options.slab;
  std::size_t total = 0;
  SliceResult result;
  if (spec.count > 0 || slab == 0) {
    // Pass 1: extent along the normal and a uniform random sample (reservoir) for the
    // spacing; mean_spacing scales a subset's spacing back to the full density the same way.
    const Eigen::Vector3d n = spec.normal.normalized();
    // Points near planes guessed from a first look at the file are kept on the way: when
    // the planes and slab found are near enough to the guess, pass 2 is not needed.
    Guess guess = guess_planes(path, spec, options, read);
    double lo = INFINITY, hi = -INFINITY, largest = 0;
    constexpr std::size_t reservoir_size = 50000;
    std::vector<Eigen::Vector3d> reservoir;
    // Reservoir sampling by skips (Li's algorithm L): random numbers only for the points
    // taken, O(k log(n / k)) of them, instead of one per point.
    std::mt19937_64 rng(12345);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    const auto u01 = [&] { return std::max(unit(rng), 1e-300); };
    double w = std::exp(std::log(u01()) / reservoir_size);
    std::size_t next = reservoir_size - 1;  // index of the next point to take once the reservoir is full
    const auto skip = [&] {
      next += std::size_t(std::floor(std::log(u01()) / std::log1p(-w))) + 1;
      w *= std::exp(std::log(u01()) / reservoir_size);
    };
    skip();
    // Chunks are read and scanned side by side (work), and taken in file order (merge):
    // the extent, the points kept around the guess, the reservoir.
    struct Scanned {
      double lo = INFINITY, hi = -INFINITY, big = 0;
      std::vector<std::vector<Eigen::Vector3d>> kept;  // per guessed plane
    };
    total = scan_chunks(
        path, read_chunks,
        [&](const Eigen::Vector3d* p, std::size_t count, int threads) {
          const std::size_t parts = parts_of(count, threads);
          std::vector<Scanned> part(parts);
          detail::parallel_for(parts, threads, [&](std::size_t t) {
            Scanned& r = part[t];
            const std::size_t a = count * t / parts, e = count * (t + 1) / parts;
            if (guess.active) {
              // One pass over the points (a chunk does not stay in the cache for three).
              r.kept.resize(guess.planes.size());
              for (auto& list : r.kept) list.reserve(std::size_t(guess.share * double(e - a) / double(r.kept.size()) * 1.25) + 16);
              for (std::size_t i = a; i < e; ++i) {
                const Eigen::Vector3d& q = p[i];
                const double s = n.x() * q.x() + n.y() * q.y() + n.z() * q.z();
                r.lo = s < r.lo ? s : r.lo;
                r.hi = s > r.hi ? s : r.hi;
                r.big = std::max({r.big, std::abs(q.x()), std::abs(q.y()), std::abs(q.z())});
                guess.keep(q, r.kept);
              }
            } else {
              for (std::size_t i = a; i < e; ++i) {
                const double s = n.x() * p[i].x() + n.y() * p[i].y() + n.z() * p[i].z();
                r.lo = s < r.lo ? s : r.lo;
                r.hi = s > r.hi ? s : r.hi;
              }
            }
          });
          // The parts of a chunk as one, in order.
          Scanned whole;
          whole.kept.resize(guess.active ? guess.planes.size() : 0);
          for (auto& r : part) {
            whole.lo = std::min(whole.lo, r.lo);
            whole.hi = std::max(whole.hi, r.hi);
            whole.big = std::max(whole.big, r.big);
            for (std::size_t k = 0; k < whole.kept.size(); ++k) {
              if (whole.kept[k].empty())
                whole.kept[k] = std::move(r.kept[k]);
              else
                whole.kept[k].insert(whole.kept[k].end(), r.kept[k].begin(), r.kept[k].end());
            }
          }
          return whole;
        },
        [&](Scanned& r, const Eigen::Vector3d* p, std::size_t count) {
          lo = std::min(lo, r.lo);
          hi = std::max(hi, r.hi);
          largest = std::max(largest, r.big);
          for (std::size_t k = 0; k < r.kept.size(); ++k)
            if (!r.kept[k].empty()) guess.kept[k].push_back(std::move(r.kept[k]));
          if (slab != 0) return;
          for (std::size_t i = 0; i < count && reservoir.size() < reservoir_size; ++i) reservoir.push_back(p[i]);
          for (; next < total + count; skip())
            reservoir[std::uniform_int_distribution<std::size_t>(0, reservoir_size - 1)(rng)] = p[next - total];
          total += count;
        });
    if (spec.count > 0) {
      std::vector<double> offsets;
      for (int k = 0; k < spec.count; ++k) offsets.push_back(lo + (hi - lo) * (k + 1) / (spec.count + 1));
      planes = planes_at(spec.normal, offsets);
    }
    if (slab == 0) {
      slab = mean_spacing(reservoir);
      if (reservoir.size() < total) slab *= std::sqrt(double(reservoir.size()) / double(total)) / 0.47;
      if (!(slab > 0))
        throw Error("slice: cannot estimate the point spacing (fewer than two distinct points); give the slab width");
    }
    if (!(slab > 0) || !std::isfinite(slab)) throw Error("slice: the slab width must be positive and finite");
    if (guess.active && guess.covers(planes, slab, largest)) {
      // Each plane's slab points from the points kept around its guess: the same points,
      // in the same order, as pass 2 would give.
      std::vector<std::vector<Eigen::Vector2d>> slabs(planes.size());
      const double reach = fill_reach(options, slab);
      detail::parallel_for(planes.size(), options.threads, [&](std::size_t k) {
        const std::vector<Plane> one{planes[k]};
        std::vector<std::vector<Eigen::Vector2d>> slab_k(1);
        const auto slab_groups = group_planes(one, slab);
        const auto frame = frames_of(one);
        for (const auto& block : guess.kept[k]) add_slab_points(block.data(), block.size(), slab_groups, frame, slab, slab_k);
        slabs[k] = std::move(slab_k[0]);
        std::vector<std::vector<Eigen::Vector3d>>().swap(guess.kept[k]);
      });
      // A plane's near points, when its section asks: from a pass over the file for every
      // plane, made once, when a section first asks.
      std::vector<std::vector<Eigen::Vector3d>> near(planes.size());
      std::once_flag near_read;
      const NearFn near_of = [&](std::size_t k) {
        if (!(reach > 0)) return std::vector<Eigen::Vector3d>{};
        std::call_once(near_read, [&] { near = read_near_points(path, planes, reach, read_chunks); });
        return std::move(near[k]);
      };
      result.points = total;
      result.slab = slab;
      result.file_passes = 1;
      order_slabs(slabs, near_of, planes, slab, options, result, sink);
      return result;
    }
  }
  if (!(slab > 0) || !std::isfinite(slab)) throw Error("slice: the slab width must be positive and finite");
  // Pass 2: only the slab points are kept.
  const auto groups = group_planes(planes, slab);
  const auto frame = frames_of(planes);
  std::vector<std::vector<Eigen::Vector2d>> slabs(planes.size());
  std::vector<std::vector<Eigen::Vector3d>> near(planes.size());
  const double reach = fill_reach(options, slab);
  const auto near_groups = reach > 0 ? group_planes(planes, 2 * reach) : std::vector<SlabGroup>{};
  // Chunks are tested side by side and their points appended in file order.
  struct Found {
    std::vector<std::vector<Eigen::Vector2d>> slabs;
    std::vector<std::vector<Eigen::Vector3d>> near;
  };
  result.points = scan_chunks(
      path, read_chunks,
      [&](const Eigen::Vector3d* p, std::size_t count, int threads) {
        Found f{std::vector<std::vector<Eigen::Vector2d>>(planes.size()),
                std::vector<std::vector<Eigen::Vector3d>>(planes.size())};
        if (reach > 0)
          add_slab_and_near_points_parallel(p, count, groups, near_groups, frame, slab, reach, threads, f.slabs, f.near);
        else
          add_slab_points_parallel(p, count, groups, frame, slab, threads, f.slabs);
        return f;
      },
      [&](Found& f, const Eigen::Vector3d*, std::size_t) {
        for (std::size_t k = 0; k < planes.size(); ++k) {
          slabs[k].insert(slabs[k].end(), f.slabs[k].begin(), f.slabs[k].end());
          near[k].insert(near[k].end(), f.near[k].begin(), f.near[k].end());
        }
      });
  result.slab = slab;
  result.file_passes = spec.count > 0 || options.slab == 0 ? 2 : 1;
  order_slabs(slabs, [&](std::size_t i) { return std::move(near[i]); }, planes, slab, options, result, sink);
  return result;
}

SliceResult slice(const Mesh& mesh, const std::vector<Plane>& planes, const SliceOptions& options) {
  check_planes(planes);
  if (mesh.triangles.empty()) throw Error("slice: the mesh has no triangles");
  std::vector<Eigen::Vector3d> origins, normals;
  for (const auto& p : planes) {
    origins.push_back(p.origin);
    normals.push_back(p.normal.normalized());
  }
  const auto cuts = detail::mesh_slices(mesh, origins, normals);
  SliceResult result;
  result.points = mesh.vertices.size();
  result.slab = 0;
  result.sections.resize(planes.size());
  for (std::size_t i = 0; i < planes.size(); ++i) {
    SectionSlice& s = result.sections[i];
    s.id = static_cast<int>(i);
    s.frame = make_frame(planes[i].origin, planes[i].normal);
    std::vector<Loop> loops;
    std::size_t open = 0;
    for (const auto& line : cuts[i]) {
      if (line.size() < 4 || (line.front() - line.back()).norm() > 1e-12 * (1 + line.front().norm())) {
        ++open;
        continue;
      }
      Loop loop;
      for (std::size_t k = 0; k + 1 < line.size(); ++k) loop.points.push_back(s.frame.to_plane(line[k]));
      double area = 0, length = 0;
      const std::size_t n = loop.points.size();
      for (std::size_t k = 0; k < n; ++k) {
        const auto& a = loop.points[k];
        const auto& b = loop.points[(k + 1) % n];
        area += 0.5 * (a.x() * b.y() - b.x() * a.y());
        length += (b - a).norm();
      }
      if (area < 0) {
        std::reverse(loop.points.begin(), loop.points.end());
        area = -area;
      }
      loop.area = area;
      loop.length = length;
      loop.normals.resize(n);
      for (std::size_t k = 0; k < n; ++k) {
        const Eigen::Vector2d t = loop.points[(k + 1) % n] - loop.points[(k + n - 1) % n];
        const Eigen::Vector2d nrm(t.y(), -t.x());
        loop.normals[k] = nrm.norm() > 0 ? Eigen::Vector2d(nrm.normalized()) : Eigen::Vector2d(0, 0);
      }
      loop.boundary = loop.points;
      loops.push_back(std::move(loop));
      s.slab_points += n;
    }
    std::stable_sort(loops.begin(), loops.end(), [](const Loop& a, const Loop& b) { return a.area > b.area; });
    s.morphology.loops = std::move(loops);
    if (open > 0)
      s.error = std::to_string(open) + " open intersection polyline(s): the mesh is not closed around this plane";
    else if (s.morphology.loops.empty())
      s.error = "the plane does not cut the mesh";
  }
  return result;
}

}  // namespace section

// SPDX-License-Identifier: GPL-3.0-or-later
#include "section/slice.h"

#include "section/error.h"
#include "detail/cgal.h"
#include "detail/extent_tails.h"
#include "detail/flann_nearest.h"
#include "detail/kept_ordering.h"
#include "detail/local_origin.h"
#include "detail/parallel.h"
#include "detail/slab_scan.h"
#include "detail/slice_steps.h"
#include "detail/spacing_search.h"
#include "io/text.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <memory>
#include <mutex>
#include <new>
#include <optional>

namespace section {

std::vector<Plane> planes_at(const Eigen::Vector3d& given, const std::vector<double>& offsets) {
  const Eigen::Vector3d normal = usable_normal(given);
  const double len = normal.norm();
  if (!(len > 0) || !std::isfinite(len)) throw Error("slice: the plane normal must be finite and non-zero");
  std::vector<Plane> planes;
  for (double o : offsets) {
    if (!std::isfinite(o)) throw Error("slice: plane offsets must be finite");
    planes.push_back({o * normal / len, normal});
  }
  return planes;
}

std::vector<Plane> detail::spread(const Eigen::Vector3d& normal, double lo, double hi, int count) {
  std::vector<double> offsets;
  for (int k = 0; k < count; ++k) offsets.push_back(lo + (hi - lo) * (k + 1) / (count + 1));
  return planes_at(normal, offsets);
}

namespace {

// The normal planes_across spreads its planes with, its count checked.
Eigen::Vector3d across_normal(const Eigen::Vector3d& given, int count) {
  const Eigen::Vector3d normal = usable_normal(given);
  const double len = normal.norm();
  if (!(len > 0) || !std::isfinite(len)) throw Error("slice: the plane normal must be finite and non-zero");
  if (count < 1 || count > 10000000) throw Error("slice: --count must be 1 to 10000000");
  return normal;
}

}  // namespace

std::vector<Plane> planes_across(const PartExtent& extent, const Eigen::Vector3d& given, int count) {
  return detail::spread(across_normal(given, count), extent.lo, extent.hi, count);
}

std::vector<Plane> planes_across(const std::vector<Eigen::Vector3d>& points, const Eigen::Vector3d& given,
                                 int count) {
  across_normal(given, count);
  if (points.empty()) throw Error("slice: no points to spread planes over");
  return planes_across(extent_along(points, given), given, count);
}

PartExtent extent_along(const std::vector<Eigen::Vector3d>& points, const Eigen::Vector3d& given) {
  const Eigen::Vector3d normal = usable_normal(given);
  const double len = normal.norm();
  if (!(len > 0) || !std::isfinite(len)) throw Error("slice: the plane normal must be finite and non-zero");
  const Eigen::Vector3d n = normal / len;
  detail::Tails tails;
  constexpr std::size_t block = 256;
  double s[block];
  for (std::size_t i0 = 0; i0 < points.size(); i0 += block) {
    const std::size_t m = std::min(block, points.size() - i0);
    for (std::size_t j = 0; j < m; ++j) s[j] = n.dot(points[i0 + j]);
    tails.add(s, m);
  }
  return detail::trimmed_extent(tails);
}

std::vector<std::vector<Eigen::Vector2d>> slab_points(const std::vector<Eigen::Vector3d>& points,
                                                      const std::vector<Plane>& planes, double slab) {
  detail::check_slab(slab);
  std::vector<std::vector<Eigen::Vector2d>> out(planes.size());
  detail::add_slab_points(points.data(), points.size(), detail::group_planes(planes, slab),
                          detail::frames_of(planes), slab, out);
  return out;
}

namespace detail {

void check_planes(const std::vector<Plane>& planes) {
  if (planes.empty()) throw Error("slice: no section planes given");
  for (const auto& p : planes)
    if (!p.origin.allFinite() || !p.normal.allFinite() || !(p.normal.norm() > 0))
      throw Error("slice: every section plane needs a finite origin and a non-zero normal");
}

void check_mesh(const Mesh& mesh) {
  if (mesh.triangles.empty()) throw Error("slice: the mesh has no triangles");
  const std::size_t nv = mesh.vertices.size();
  // What the mesh readers refuse (a mesh built in memory): a vertex at 1e300 cut the plane
  // in a spurious loop, a NaN one in open polylines.
  for (std::size_t v = 0; v < nv; ++v)
    if (!(mesh.vertices[v].cwiseAbs().maxCoeff() <= max_coordinate))
      throw Error("slice: mesh vertex " + std::to_string(v) +
                  " is not finite or lies beyond +-1e15 (a coordinate no mesh file gives)");
  for (const auto& t : mesh.triangles)
    for (int k = 0; k < 3; ++k)
      if (t[k] < 0 || std::size_t(t[k]) >= nv) throw Error("slice: mesh triangle index out of range");
}

void check_slab(double slab) {
  if (!(slab >= 0) || !std::isfinite(slab))
    throw Error("slice: the slab width must be finite and not negative");
}

double band_reach(const SliceOptions& options, double slab) {
  // drift_band reads the points within max(2 half width, 3 slabs, the sparse half width).
  return options.band_spacing > 0
             ? std::max({2 * std::max(0.5, options.band_max), options.band_sparse_max, 3.0}) * slab
             : 0;
}

double fill_reach(const SliceOptions& options, double slab) {
  const double fill = options.fill_gaps ? gap_fill_reach(options.fill, slab) : 0;
  return std::max(fill, band_reach(options, slab));
}

void check_band_options(const SliceOptions& options) {
  if (!(options.band_spacing >= 0) || !std::isfinite(options.band_spacing))
    throw Error("slice: the band spacing must be zero or positive and finite");
  if (!(options.band_max >= 0.5) || !std::isfinite(options.band_max))
    throw Error("slice: the band's largest half width must be at least 0.5 slab widths");
  if (!(options.band_sparse_max >= 0) || !std::isfinite(options.band_sparse_max))
    throw Error("slice: the band's half width beside sparse stretches must be zero or positive and finite");
}

namespace {

// Hands finished sections to a callback in plane order, from one thread at a time,
// without holding up the threads that finish sections meanwhile.
class InOrder {
public:
  InOrder(std::size_t count, const SectionFn& sink) : done_(count, 0), sink_(sink) {}
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
  const SectionFn& sink_;
};

// Drops the exact copies of a point (the first stays), in order: a copy adds nothing, and
// zero distances make the spacings of the later stages zero (every interval a hole).
// True when there were copies. An open-addressed table of the points kept so far finds a
// copy in one probe or two (a sort of the near points cost 5 % of `slice`).
template <class P>
bool drop_copies(std::vector<P>& points) {
  std::size_t size = 16;
  while (size < 2 * points.size()) size *= 2;
  std::vector<std::uint32_t> slot(size, UINT32_MAX);
  const auto home = [&](const P& p) {
    std::uint64_t h = 0;
    for (int k = 0; k < int(P::RowsAtCompileTime); ++k) {
      const double x = p[k] + 0.0;  // -0 and +0 are equal: one hash
      std::uint64_t bits;
      std::memcpy(&bits, &x, sizeof bits);
      h = (h ^ bits) * 0x9E3779B97F4A7C15ULL;
    }
    return std::size_t(h ^ (h >> 29)) & (size - 1);
  };
  std::vector<char> copy(points.size(), 0);
  bool any = false;
  for (std::size_t k = 0; k < points.size(); ++k)
    for (std::size_t h = home(points[k]);; h = (h + 1) & (size - 1)) {
      if (slot[h] == UINT32_MAX) {
        slot[h] = std::uint32_t(k);
        break;
      }
      if (points[slot[h]] == points[k]) {
        copy[k] = 1, any = true;
        break;
      }
    }
  if (!any) return false;
  std::size_t w = 0;
  for (std::size_t k = 0; k < points.size(); ++k)
    if (!copy[k]) points[w++] = points[k];
  points.resize(w);
  return true;
}

// A section that does not close, with what can help: a slab's section a wider slab (the
// ordering's own cell and dilation are no options), a row nothing but more points.
std::string with_hint(const std::string& what, const SectionSlice& s, double slab) {
  if (what.rfind("morphology:", 0) != 0) return what;
  if (s.row >= 0) return what + " (the row's points as they lie: it is too sparse or not closed)";
  char hint[96];
  std::snprintf(hint, sizeof hint, "; a wider slab holds more points (--slab, now %.3g mm)", slab);
  return what + hint;
}

// A loop that holds only part of its section's points: where a tenth of the slab's points
// (8 at least) lie farther than `far` from every loop, the plane cuts the part in an open
// sheet (a radial rotor's blade cut across) or a piece the loop left out, and the loop,
// closed across them, is no profile of the section: throws, saying how many and how far.
void check_loops_hold(const std::vector<Eigen::Vector2d>& points, const MorphologyResult& m, double far) {
  if (m.dropped < 8) return;  // nothing left out, or a few outliers
  std::vector<Eigen::Vector2d> on;
  for (const Loop& loop : m.loops) on.insert(on.end(), loop.points.begin(), loop.points.end());
  if (on.empty()) return;
  const detail::NearestPoints<2> tree(on);
  const std::vector<int> nearest = tree.nearest(points);
  std::size_t off = 0;
  double farthest = 0;
  for (std::size_t k = 0; k < points.size(); ++k) {
    const double d = (points[k] - on[std::size_t(nearest[k])]).norm();
    off += d > far;
    farthest = std::max(farthest, d);
  }
  if (off < 8 || 10 * off < points.size()) return;
  char what[320];
  std::snprintf(what, sizeof what,
                "the loop holds only part of the section: %zu of the slab's %zu points lie farther than "
                "%.3g mm from it (up to %.3g mm); the plane cuts the part in an open sheet, or the loop "
                "closes across a gap: no profile here",
                off, points.size(), far, farthest);
  throw Error(what);
}

// Whether band_half_width will likely ask for a band at least a slab wide: the loop's
// mean spacing at least twice the band spacing, its length guessed as twice the points'
// extent. A guess for speed only (see order_slabs).
bool band_likely(const std::vector<Eigen::Vector2d>& points, const SliceOptions& options) {
  if (!(options.band_spacing > 0) || options.band_max < 1 || points.empty()) return false;
  Eigen::Vector2d lo = points[0], hi = lo;
  for (const auto& p : points) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  return 2 * (hi - lo).maxCoeff() >= 2 * options.band_spacing * double(points.size());
}

// Orders the drift-corrected band of half width `half` beside s's slab ordering into
// s.morphology: on the slab's loops (`kept`, what ordered the slab), or afresh when they do
// not hold the band. False, s as it was, when the band holds no more points than the slab or
// cannot be ordered.
bool order_band(SectionSlice& s, const std::vector<Eigen::Vector3d>& near, std::size_t slab_points,
                double slab, double half, const SliceOptions& options, const detail::KeptOrdering* kept) {
  std::vector<Eigen::Vector2d> band =
      drift_band(s.morphology, near, slab, half, options.band_spacing, options.band_sparse_max * slab);
  drop_copies(band);
  if (band.size() <= slab_points) return false;
  // The band's rows, carried onto the plane, lie close beside one another: their nearest
  // neighbours' spacing, the automatic cell, is far finer than the spacing along the
  // profile on a sparse scan (a 10 k point scan: 0.08 against 0.27 mm, 11 times the cells).
  MorphologyOptions band_options = options.morphology;
  if (!s.morphology.loops.empty()) band_options.min_cell = s.morphology.loops[0].length / double(band.size());
  try {
    std::optional<MorphologyResult> beside;
    if (kept) beside = detail::order_beside(*kept, band, band_options);
    s.morphology = beside ? std::move(*beside) : order_section(band, band_options);
  } catch (const Error&) {
    return false;
  }
  s.band_points = band.size();
  s.band_half_width = half;
  return true;
}

// Orders the slab's points into s.morphology: with `order` when given (nothing kept), else
// by order_section, what made it kept to order a band on its loops.
std::shared_ptr<const detail::KeptOrdering> order_slab(SectionSlice& s,
                                                       const std::vector<Eigen::Vector2d>& slab,
                                                       const OrderFn& order,
                                                       const MorphologyOptions& options) {
  if (order) {
    s.morphology = order(slab, options);
    return nullptr;
  }
  detail::OrderedKept ordered = detail::order_section_kept(slab, options);
  s.morphology = std::move(ordered.result);
  return std::move(ordered.kept);
}

// A section that waits for its near points to fill its gaps (order_slabs): where its
// ordering left off.
struct Waiting {
  bool fill = false;
  Eigen::Vector2d local = Eigen::Vector2d::Zero();  // the origin the section is ordered about
  std::size_t first = 0;                            // fill_gaps' `first`
};

// Plane i's near points about the section's origin `local`, exact copies counted once.
std::vector<Eigen::Vector3d> near_about(const NearFn& near_of, std::size_t i, const Eigen::Vector2d& local) {
  std::vector<Eigen::Vector3d> near = near_of ? near_of(i) : std::vector<Eigen::Vector3d>{};
  drop_copies(near);
  for (auto& q : near) q.head<2>() -= local;
  return near;
}

// A section's near points (near_about), asked for once each: all of them, and those the
// band reads (band_near_of's, when given; else all of them).
struct SectionNear {
  const NearFn& near_of;
  const NearFn& band_near_of;
  std::size_t i;
  Eigen::Vector2d local;
  std::optional<std::vector<Eigen::Vector3d>> points, band_points;

  const std::vector<Eigen::Vector3d>& all() {
    if (!points) points = near_about(near_of, i, local);
    return *points;
  }
  const std::vector<Eigen::Vector3d>& band() {
    if (!band_near_of) return all();
    if (!band_points) band_points = near_about(band_near_of, i, local);
    return *band_points;
  }
};

// Fills the gaps of s's profile from the near points (none: s as it is).
void fill_from(SectionSlice& s, const std::vector<Eigen::Vector3d>& near, double slab, std::size_t first,
               const SliceOptions& options) {
  if (near.empty()) return;
  GapFillResult r = fill_gaps(s.morphology, near, slab, first, options.fill);
  s.morphology = std::move(r.filled);
  r.filled = MorphologyResult{};
  s.fill = std::move(r);
}

// Runs step(); an error ends the section, as its error (out of memory fails the run: a
// section left out for it would pass unnoticed).
template <class Step>
void guarded(SectionSlice& s, double slab, const Step& step) {
  try {
    step();
  } catch (const std::bad_alloc&) {
    throw;
  } catch (const std::exception& e) {
    s.error = with_hint(e.what(), s, slab);
  }
}

// The sections that wait for their near points (order_slabs): their gaps filled from
// them, all asked for at once, then done(i).
template <class Done>
void fill_waiting(const std::vector<Waiting>& waiting, const NearFn& near_of, const NearPrefetch& prefetch,
                  const std::vector<std::vector<Eigen::Vector2d>>& slabs, double slab,
                  const SliceOptions& options, SliceResult& result, const Done& done) {
  std::vector<std::size_t> wanted;
  for (std::size_t i = 0; i < waiting.size(); ++i)
    if (waiting[i].fill) wanted.push_back(i);
  if (wanted.empty()) return;
  prefetch(wanted);
  detail::parallel_for(wanted.size(), options.threads, [&](std::size_t k) {
    const std::size_t i = wanted[k];
    SectionSlice& s = result.sections[i];
    guarded(s, slab, [&] {
      fill_from(s, near_about(near_of, i, waiting[i].local), slab, waiting[i].first, options);
      check_loops_hold(slabs[i], s.morphology, std::max(3 * slab, 10 * s.morphology.cell));
    });
    done(i);
  });
}

}  // namespace

void order_slabs(std::vector<std::vector<Eigen::Vector2d>>& slabs, const NearFn& near_of,
                 const std::vector<Plane>& planes, double slab, const SliceOptions& options,
                 SliceResult& result, const SectionFn& sink, const OrderFn& order,
                 const NearPrefetch& prefetch, const NearFn& band_near_of) {
  result.sections.resize(planes.size());
  InOrder in_order(planes.size(), sink);
  // With `prefetch`, a section with gaps to fill whose near points no band asked for waits
  // until every other is ordered: then the near points of those that wait alone are asked
  // for (one read of a file for a few planes, not every plane's).
  std::vector<Waiting> waiting(planes.size());
  const auto done = [&](std::size_t i) {
    std::vector<Eigen::Vector2d>().swap(slabs[i]);
    in_order.finished(i, result.sections);
  };
  detail::parallel_for(planes.size(), options.threads, [&](std::size_t i) {
    SectionSlice& s = result.sections[i];
    s.id = static_cast<int>(i);
    s.frame = make_frame(planes[i].origin, planes[i].normal);
    const bool copies = drop_copies(slabs[i]);
    s.slab_points = slabs[i].size();
    guarded(s, slab, [&] {
      if (slabs[i].empty())
        throw Error(s.error.empty() ? "no points in the slab (the plane misses the part?)" : s.error);
      if (copies && slabs[i].size() == 1)
        throw Error("morphology: the points are all equal; no loop can be formed");
      // A section far from its plane's origin is ordered about an origin near it (the
      // frame's origin moves there, in the plane): small (u, v) for every later stage.
      const Eigen::Vector2d local = detail::local_origin(slabs[i]);
      if (local != Eigen::Vector2d::Zero()) {
        for (auto& p : slabs[i]) p -= local;
        s.frame.origin = s.frame.to_world(local);
      }
      SectionNear near{near_of, band_near_of, i, local, {}, {}};
      // The band's half width when a band is to be tried, else 0. A band less than twice
      // as wide as the slab is not worth a second ordering and the later stages' time for
      // its points (the slab is dense enough then).
      const auto band_half = [&](const MorphologyResult& m) {
        if (!(options.band_spacing > 0) || m.loops.empty()) return 0.0;
        const Loop& profile = m.loops[0];
        const double half = band_half_width(profile.points.size(), profile.length, slab, options.band_spacing,
                                            options.band_max);
        return half >= slab && !near.band().empty() ? half : 0.0;
      };
      // The slab's ordering is kept to order a band on its loops (no second raster); when a
      // band is likely, it leaves its skeleton out until no band is tried after all.
      MorphologyOptions slab_options = options.morphology;
      if (slab_options.skeleton && !order && band_likely(slabs[i], options))
        slab_options.skeleton_if = [&](const MorphologyResult& m) { return band_half(m) == 0; };
      std::shared_ptr<const detail::KeptOrdering> kept = order_slab(s, slabs[i], order, slab_options);
      std::size_t first = slabs[i].size();
      if (const double half = band_half(s.morphology); half > 0) {
        if (order_band(s, near.band(), slabs[i].size(), slab, half, options, kept.get()))
          first = s.band_points;
        else if (slab_options.skeleton_if)  // the slab's ordering stays: with its skeleton
          detail::add_skeleton(*kept, s.morphology);
      }
      kept.reset();
      near.band_points.reset();
      // The points beside the plane only for a profile with gaps (the look for gaps
      // needs none of them, and fill_gaps finds none then).
      if (options.fill_gaps && fill_gaps(s.morphology, {}, slab, first, options.fill).gaps > 0) {
        if (prefetch && !near.points) {
          waiting[i] = {true, local, first};
          return;
        }
        fill_from(s, near.all(), slab, first, options);
      }
      check_loops_hold(slabs[i], s.morphology, std::max(3 * slab, 10 * s.morphology.cell));
    });
    if (!waiting[i].fill) done(i);
  });
  fill_waiting(waiting, near_of, prefetch, slabs, slab, options, result, done);
}

}  // namespace detail

SliceResult slice(const Cloud& cloud, const std::vector<Plane>& planes, const SliceOptions& options,
                  const SectionSink& sink, const SamplingSink& on_sampling) {
  detail::check_planes(planes);
  if (options.fill_gaps) check_gap_fill_options(options.fill);
  detail::check_band_options(options);
  if (cloud.points.empty()) throw Error("slice: the cloud has no points");
  // (The readers refuse them; a cloud built in memory may hold one: it moved the spacing.)
  detail::check_points(cloud.points);
  SliceResult result;
  result.points = cloud.points.size();
  result.slab = options.slab;
  if (result.slab == 0) {
    detail::SpacingSearch search;
    result.sampling = detail::sample_all(cloud.points, planes[0].normal, options.sampling, search);
    const Sampling& s = result.sampling;
    if (on_sampling) on_sampling(s);
    if (s.kind == SamplingKind::rows) {
      detail::slice_through_rows(cloud.points, planes, options, result, sink);
      return result;
    }
    result.slab = detail::sampled_slab(cloud.points, s, search);
    if (s.kind == SamplingKind::lines && !s.rows.empty() && s.points == cloud.points.size()) {
      detail::slice_between_lines(cloud.points, planes, options, result, sink);
      return result;
    }
  }
  if (!(result.slab > 0) || !std::isfinite(result.slab))
    throw Error("slice: the slab width must be positive and finite");
  auto slabs = slab_points(cloud.points, planes, result.slab);
  const double reach = detail::fill_reach(options, result.slab);
  const auto near_groups =
      reach > 0 ? detail::group_planes(planes, 2 * reach) : std::vector<detail::SlabGroup>{};
  const auto frame = detail::frames_of(planes);
  // Every plane's near points in one pass over the cloud, made when a section first asks.
  std::vector<std::vector<Eigen::Vector3d>> near(planes.size());
  std::once_flag near_made;
  const detail::NearFn near_of = [&](std::size_t i) {
    std::call_once(near_made, [&] {
      if (reach > 0)
        detail::add_near_points_parallel(cloud.points.data(), cloud.points.size(), near_groups, frame, reach,
                                         1, near);
    });
    return std::move(near[i]);
  };
  detail::order_slabs(slabs, near_of, planes, result.slab, options, result, sink);
  return result;
}

}  // namespace section

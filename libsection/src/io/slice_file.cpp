// SPDX-License-Identifier: GPL-3.0-or-later
#include "section/io/slice_file.h"

#include "section/error.h"
#include "section/io/csv.h"
#include "section/io/file.h"
#include "section/io/limits.h"
#include "detail/extent_tails.h"
#include "detail/parallel.h"
#include "io/byte_source.h"
#include "io/text.h"
#include "detail/slab_scan.h"
#include "detail/slice_steps.h"
#include "detail/spacing_search.h"
#include "io/reservoir.h"
#include "io/slice_guess.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <mutex>
#include <numeric>
#include <optional>
#include <random>

namespace section {

namespace {

using detail::Guess;
using detail::guess_planes;
using detail::spread;

// read_cloud_chunks_parallel with a result per chunk: `scan(points, count, threads)` makes
// it on a worker thread, `take(result, points, count)` receives it in file order.
template <class Scan, class Take>
std::size_t scan_chunks(const std::string& path, const CloudReadOptions& read, const Scan& scan,
                        const Take& take, const ChunkFilter& wanted = {}) {
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
      read, wanted);
}

// The points within `reach` of each plane in the file, as (u, v, signed distance), in file
// order (add_near_points), chunks read side by side.
std::vector<std::vector<Eigen::Vector3d>> read_near_points(const std::string& path,
                                                           const std::vector<Plane>& planes, double reach,
                                                           const CloudReadOptions& read,
                                                           detail::HeldBytes& held,
                                                           const ChunkFilter& wanted) {
  const auto groups = detail::group_planes(planes, 2 * reach);
  const auto frame = detail::frames_of(planes);
  std::vector<std::vector<Eigen::Vector3d>> near(planes.size());
  scan_chunks(
      path, read,
      [&](const Eigen::Vector3d* p, std::size_t count, int threads) {
        std::vector<std::vector<Eigen::Vector3d>> f(planes.size());
        detail::add_near_points_parallel(p, count, groups, frame, reach, threads, f);
        return f;
      },
      [&](std::vector<std::vector<Eigen::Vector3d>>& f, const Eigen::Vector3d*, std::size_t) {
        for (std::size_t k = 0; k < planes.size(); ++k) {
          held.add(sizeof(Eigen::Vector3d) * f[k].size());
          near[k].insert(near[k].end(), f[k].begin(), f[k].end());
        }
      },
      wanted);
  return near;
}

// What pass 1 finds in a chunk (or a part of one): the extent along the normal, the
// largest coordinate and the points kept around the guess (per guessed plane).
struct Scanned {
  double lo = INFINITY, hi = -INFINITY, big = 0;
  detail::Tails tails;  // the lowest and highest offsets, for the part's extent without strays
  std::vector<std::vector<Eigen::Vector3d>> kept;
};

// Scans points[a, e) into r.
void scan_part(const Eigen::Vector3d* p, std::size_t a, std::size_t e, const Eigen::Vector3d& n,
               const Guess& guess, Scanned& r) {
  if (guess.active) {
    // One pass over the points (a chunk does not stay in the cache for three).
    r.kept.resize(guess.planes.size());
    for (auto& list : r.kept)
      list.reserve(std::size_t(guess.share * double(e - a) / double(r.kept.size()) * 1.25) + 16);
    // The tests on the heap, as add_near_points' (held in registers, they were saved and
    // restored around every kept point's append); the extent in locals, which an append
    // cannot change (r's could, for all the compiler knew).
    std::vector<detail::SlabTests> tests(guess.groups.begin(), guess.groups.end());
    // Planes along the normal of the extent (--count): the keep test's n . q is the extent's
    // (to the last bits of another order of sums: the kept width's edge is no slab's).
    const bool along = tests.size() == 1 && tests[0].n == n;
    double lo = r.lo, hi = r.hi, big = r.big;
    // In blocks: the extents over a block (no append between them), then its appends.
    constexpr std::size_t block = 256;
    double s[block];
    for (std::size_t i0 = a; i0 < e; i0 += block) {
      const std::size_t m = std::min(block, e - i0);
      const Eigen::Vector3d* q = p + i0;
      double blo = INFINITY, bhi = -INFINITY;
      for (std::size_t j = 0; j < m; ++j) {
        s[j] = n.x() * q[j].x() + n.y() * q[j].y() + n.z() * q[j].z();
        blo = s[j] < blo ? s[j] : blo;
        bhi = s[j] > bhi ? s[j] : bhi;
        big = std::max({big, std::abs(q[j].x()), std::abs(q[j].y()), std::abs(q[j].z())});
      }
      lo = blo < lo ? blo : lo;
      hi = bhi > hi ? bhi : hi;
      r.tails.add(s, m, blo, bhi);
      if (along)
        for (std::size_t j = 0; j < m; ++j) guess.keep_at(q[j], s[j], tests[0], r.kept);
      else
        for (std::size_t j = 0; j < m; ++j) guess.keep(q[j], tests, r.kept);
    }
    r.lo = lo, r.hi = hi, r.big = big;
  } else {
    constexpr std::size_t block = 256;
    double s[block];
    for (std::size_t i0 = a; i0 < e; i0 += block) {
      const std::size_t m = std::min(block, e - i0);
      double blo = INFINITY, bhi = -INFINITY;
      for (std::size_t j = 0; j < m; ++j) {
        const Eigen::Vector3d& q = p[i0 + j];
        s[j] = n.x() * q.x() + n.y() * q.y() + n.z() * q.z();
        blo = s[j] < blo ? s[j] : blo;
        bhi = s[j] > bhi ? s[j] : bhi;
      }
      r.lo = blo < r.lo ? blo : r.lo;
      r.hi = bhi > r.hi ? bhi : r.hi;
      r.tails.add(s, m, blo, bhi);
    }
  }
}

// Scans one chunk, its parts side by side, and joins them in order.
Scanned scan_chunk(const Eigen::Vector3d* p, std::size_t count, int threads, const Eigen::Vector3d& n,
                   const Guess& guess) {
  const std::size_t parts = detail::parts_of(count, threads);
  std::vector<Scanned> part(parts);
  for (Scanned& r : part) r.tails = detail::Tails(64, guess.screen_lo, guess.screen_hi);
  detail::parallel_for(parts, threads, [&](std::size_t t) {
    scan_part(p, count * t / parts, count * (t + 1) / parts, n, guess, part[t]);
  });
  Scanned whole;
  whole.tails = detail::Tails(64, guess.screen_lo, guess.screen_hi);
  whole.kept.resize(guess.active ? guess.planes.size() : 0);
  for (auto& r : part) {
    whole.lo = std::min(whole.lo, r.lo);
    whole.hi = std::max(whole.hi, r.hi);
    whole.big = std::max(whole.big, r.big);
    whole.tails.merge(r.tails);
    for (std::size_t k = 0; k < whole.kept.size(); ++k) {
      if (whole.kept[k].empty())
        whole.kept[k] = std::move(r.kept[k]);
      else
        whole.kept[k].insert(whole.kept[k].end(), r.kept[k].begin(), r.kept[k].end());
    }
  }
  return whole;
}

// What pass 1 found in the whole file.
struct FirstPass {
  double lo = INFINITY, hi = -INFINITY, largest = 0;   // extent along the normal, largest coordinate
  std::size_t total = 0;                               // points
  detail::Reservoir sample;                            // filled when `sampled`
  std::size_t hold = 0;                                // when `sampled`: the first this many points are kept
  std::vector<Eigen::Vector3d> first;                  // those, in file order (their sampling: sampling_of)
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();   // the unit normal the extents are along
  std::vector<std::pair<double, double>> chunk_range;  // per chunk of the file, its extent along it
  detail::Tails tails;                                 // the lowest and highest offsets along it
};

// Pass 1: the extent along the normal and, when `sampled`, a uniform random sample for the
// spacing; the points near the guessed planes are kept in `guess` on the way. Chunks are
// read and scanned side by side, and taken in file order.
void first_pass(const std::string& path, const CloudReadOptions& read, const Eigen::Vector3d& n, bool sampled,
                Guess& guess, FirstPass& pass, detail::HeldBytes& held) {
  pass.normal = n;
  pass.tails = detail::Tails(64, guess.screen_lo, guess.screen_hi);
  pass.total = scan_chunks(
      path, read,
      [&](const Eigen::Vector3d* p, std::size_t count, int threads) {
        return scan_chunk(p, count, threads, n, guess);
      },
      [&](Scanned& r, const Eigen::Vector3d* p, std::size_t count) {
        pass.chunk_range.emplace_back(r.lo, r.hi);
        pass.lo = std::min(pass.lo, r.lo);
        pass.hi = std::max(pass.hi, r.hi);
        pass.tails.merge(r.tails);
        pass.largest = std::max(pass.largest, r.big);
        for (std::size_t k = 0; k < r.kept.size(); ++k) {
          held.add(sizeof(Eigen::Vector3d) * r.kept[k].size());
          if (!r.kept[k].empty()) guess.kept[k].push_back(std::move(r.kept[k]));
        }
        if (!sampled) return;
        pass.sample.take(p, count);
        pass.first.insert(pass.first.end(), p, p + std::min(count, pass.hold - pass.first.size()));
      });
}

// The chunks of the file that may hold points within `reach` of `planes`, from the extents
// pass 1 found (every chunk when a plane's normal is not the one they are along). A hair
// wider than the reach: the near test's arithmetic differs from pass 1's in the last bits.
ChunkFilter chunks_near(const FirstPass& first, const std::vector<Plane>& planes, double reach) {
  std::vector<double> offsets;
  for (const auto& p : planes) {
    const Eigen::Vector3d n = make_frame(p.origin, p.normal).n;
    if (!((n - first.normal).norm() <= 1e-12)) return {};
    offsets.push_back(first.normal.dot(p.origin));
  }
  std::sort(offsets.begin(), offsets.end());
  const double margin = reach + 1e-8 * (first.largest + reach + 1);
  return [&first, offsets, margin](std::size_t chunk) {
    if (chunk >= first.chunk_range.size()) return true;
    const auto [lo, hi] = first.chunk_range[chunk];
    const auto at = std::lower_bound(offsets.begin(), offsets.end(), lo - margin);
    return at != offsets.end() && *at <= hi + margin;
  };
}

// The sections from the points kept around the guessed planes, when the planes found lie
// near enough to them: the same slab points, in the same order, as pass 2 would give.
SliceResult slice_kept(const std::string& path, const std::vector<Plane>& planes, double slab, Guess& guess,
                       const FirstPass& first, const SliceOptions& options,
                       const CloudReadOptions& read_chunks, const SectionSink& sink,
                       detail::HeldBytes& held) {
  std::vector<std::vector<Eigen::Vector2d>> slabs(planes.size());
  const double reach = detail::fill_reach(options, slab);
  // The band's points from those kept too, when they hold them: a hair wider than the band
  // reads, so that no rounding of the near test leaves out a point it reads.
  const double band = detail::band_reach(options, slab) * (1 + 1e-9);
  const bool band_kept = guess.covers_band(planes, band, first.largest);
  std::vector<std::vector<Eigen::Vector3d>> band_near(band_kept ? planes.size() : 0);
  detail::parallel_for(planes.size(), options.threads, [&](std::size_t k) {
    const std::vector<Plane> one{planes[k]};
    std::vector<std::vector<Eigen::Vector2d>> slab_k(1);
    const auto slab_groups = detail::group_planes(one, slab);
    const auto frame = detail::frames_of(one);
    for (const auto& block : guess.kept[k])
      detail::add_slab_points(block.data(), block.size(), slab_groups, frame, slab, slab_k);
    slabs[k] = std::move(slab_k[0]);
    if (band_kept) {
      std::vector<std::vector<Eigen::Vector3d>> near_k(1);
      const auto near_groups = detail::group_planes(one, 2 * band);
      for (const auto& block : guess.kept[k])
        detail::add_near_points_parallel(block.data(), block.size(), near_groups, frame, band, 1, near_k);
      band_near[k] = std::move(near_k[0]);
    }
    std::vector<std::vector<Eigen::Vector3d>>().swap(guess.kept[k]);
  });
  // A plane's near points, when its section asks: from a pass over the file for every
  // plane not read yet, made when a section with a band first asks (its points not kept),
  // or after the ordering for the planes whose sections have gaps to fill (order_slabs'
  // prefetch); a pass reads only the chunks near the planes it reads for (chunks_near).
  std::vector<std::vector<Eigen::Vector3d>> near(planes.size());
  std::vector<char> read(planes.size(), 0);
  std::mutex near_mutex;
  int near_reads = 0;
  const auto read_planes = [&](const std::vector<std::size_t>& which) {
    std::vector<std::size_t> ids;
    std::vector<Plane> some;
    for (std::size_t k : which)
      if (!read[k]) ids.push_back(k), some.push_back(planes[k]);
    if (ids.empty()) return;
    auto got = read_near_points(path, some, reach, read_chunks, held, chunks_near(first, some, reach));
    ++near_reads;
    for (std::size_t m = 0; m < ids.size(); ++m) near[ids[m]] = std::move(got[m]), read[ids[m]] = 1;
  };
  std::vector<std::size_t> every(planes.size());
  std::iota(every.begin(), every.end(), std::size_t(0));
  const detail::NearFn near_of = [&](std::size_t k) {
    if (!(reach > 0)) return std::vector<Eigen::Vector3d>{};
    std::lock_guard<std::mutex> lock(near_mutex);
    if (!read[k]) read_planes(every);
    return std::move(near[k]);
  };
  const detail::NearPrefetch prefetch = [&](const std::vector<std::size_t>& which) {
    if (!(reach > 0)) return;
    std::lock_guard<std::mutex> lock(near_mutex);
    read_planes(which);
  };
  SliceResult result;
  result.points = first.total;
  result.slab = slab;
  detail::NearFn band_near_of;
  if (band_kept) band_near_of = [&](std::size_t k) { return std::move(band_near[k]); };
  detail::order_slabs(slabs, near_of, planes, slab, options, result, sink, {}, prefetch, band_near_of);
  result.file_passes = 1 + near_reads;
  return result;
}

// Pass 2: the slab points and the near points of every plane; chunks are tested side by
// side and their points appended in file order.
SliceResult slice_pass(const std::string& path, const std::vector<Plane>& planes, double slab, int passes,
                       const SliceOptions& options, const CloudReadOptions& read_chunks,
                       const SectionSink& sink, detail::HeldBytes& held) {
  const auto groups = detail::group_planes(planes, slab);
  const auto frame = detail::frames_of(planes);
  std::vector<std::vector<Eigen::Vector2d>> slabs(planes.size());
  std::vector<std::vector<Eigen::Vector3d>> near(planes.size());
  const double reach = detail::fill_reach(options, slab);
  const auto near_groups =
      reach > 0 ? detail::group_planes(planes, 2 * reach) : std::vector<detail::SlabGroup>{};
  struct Found {
    std::vector<std::vector<Eigen::Vector2d>> slabs;
    std::vector<std::vector<Eigen::Vector3d>> near;
  };
  SliceResult result;
  result.points = scan_chunks(
      path, read_chunks,
      [&](const Eigen::Vector3d* p, std::size_t count, int threads) {
        Found f{std::vector<std::vector<Eigen::Vector2d>>(planes.size()),
                std::vector<std::vector<Eigen::Vector3d>>(planes.size())};
        if (reach > 0)
          detail::add_slab_and_near_points_parallel(p, count, groups, near_groups, frame, slab, reach,
                                                    threads, f.slabs, f.near);
        else
          detail::add_slab_points_parallel(p, count, groups, frame, slab, threads, f.slabs);
        return f;
      },
      [&](Found& f, const Eigen::Vector3d*, std::size_t) {
        for (std::size_t k = 0; k < planes.size(); ++k) {
          held.add(sizeof(Eigen::Vector2d) * f.slabs[k].size() + sizeof(Eigen::Vector3d) * f.near[k].size());
          slabs[k].insert(slabs[k].end(), f.slabs[k].begin(), f.slabs[k].end());
          near[k].insert(near[k].end(), f.near[k].begin(), f.near[k].end());
        }
      });
  result.slab = slab;
  result.file_passes = passes;
  detail::order_slabs(
      slabs, [&](std::size_t i) { return std::move(near[i]); }, planes, slab, options, result, sink);
  return result;
}

// The slab from pass 1: a dense scan's spacing from the random sample scaled back to the
// full density (as mean_spacing scales a subset's), unless exact copies inflate that
// density; lines' spacing along the normal (detail::sampled_slab). A sample of every point
// is the points sampling_of searched (the reservoir keeps the first ones in file order).
double sampled_slab(const FirstPass& first, const Sampling& sampling, const detail::SpacingSearch& search) {
  if (sampling.kind == SamplingKind::dense && 100 * sampling.duplicates <= sampling.measured) {
    const std::vector<Eigen::Vector3d>& sample = first.sample.points;
    double slab = sample.size() == first.total && first.first.size() == first.total
                      ? detail::mean_spacing(first.first, search)
                      : mean_spacing(sample);
    if (sample.size() < first.total) slab *= std::sqrt(double(sample.size()) / double(first.total)) / 0.47;
    if (slab > 0) return slab;
  }
  return detail::sampled_slab(first.first, sampling, search);
}

// Sparse rows (the planes through them take them as they lie: detail::slice_through_rows)
// and lines whose rows pass 1 found (interpolated between them: detail::slice_between_lines),
// from the whole cloud in memory (read again when pass 1 kept only its first points).
SliceResult slice_held(const std::string& path, const std::vector<Plane>& planes, const SliceOptions& options,
                       const CloudReadOptions& read, const SectionSink& sink, FirstPass first,
                       Sampling sampling, const SamplingSink& on_sampling) {
  SliceResult result;
  result.points = first.total;
  result.file_passes = 1;
  std::vector<Eigen::Vector3d> points = std::move(first.first);
  if (points.size() < first.total) {
    points = read_cloud(path, read).points;
    detail::SpacingSearch unused;
    sampling = detail::sample_all(points, planes[0].normal, options.sampling, unused);
    result.file_passes = 2;
  }
  result.sampling = std::move(sampling);
  if (on_sampling) on_sampling(result.sampling);
  if (result.sampling.kind == SamplingKind::rows) {
    detail::slice_through_rows(points, planes, options, result, sink);
    return result;
  }
  if (result.sampling.kind == SamplingKind::lines && !result.sampling.rows.empty() &&
      result.sampling.points == points.size()) {
    result.slab = result.sampling.slab;
    detail::slice_between_lines(points, planes, options, result, sink);
    return result;
  }
  // All the points are no rows after all (the first ones looked like rows).
  Cloud cloud{std::move(points)};
  SliceResult lines = slice(cloud, planes, options, sink);
  lines.file_passes = result.file_passes;
  return lines;
}

void check_slab_width(double slab) {
  if (!(slab > 0) || !std::isfinite(slab)) throw Error("slice: the slab width must be positive and finite");
}

// The bytes a section's result holds (its loops and skeleton), for the memory limit.
std::size_t bytes_of(const SectionSlice& s) {
  std::size_t bytes = sizeof(SectionSlice) + 24 * s.morphology.skeleton.size();
  for (const Loop& l : s.morphology.loops)
    bytes += 16 * (l.points.size() + l.normals.size() + l.boundary.size()) + 8 * l.index.size();
  return bytes;
}

}  // namespace

SliceResult slice_file(const std::string& path, const PlaneSpec& spec, const SliceOptions& options,
                       const CloudReadOptions& read, const SectionSink& given_sink,
                       const SamplingSink& on_sampling) {
  detail::check_slab(options.slab);
  if (options.fill_gaps) check_gap_fill_options(options.fill);
  detail::check_band_options(options);
  if (spec.count > 0 && (!spec.normal.allFinite() || !(spec.normal.norm() > 0)))
    throw Error("slice: the plane normal must be finite and non-zero");
  if (spec.count == 0) detail::check_planes(spec.planes);
  if (path == "-") {
    // A pipe cannot be read twice: hold the cloud.
    const Cloud cloud = read_cloud(path, read);
    const PartExtent extent = spec.count > 0 ? extent_along(cloud.points, spec.normal) : PartExtent{};
    const auto planes = spec.count > 0 ? spread(spec.normal, extent.lo, extent.hi, spec.count) : spec.planes;
    SliceResult r = slice(cloud, planes, options, given_sink, on_sampling);
    r.extent = extent;
    return r;
  }
  // The points held for the planes (slabs, the points beside them, the sections made) stay
  // within half the memory limit: about 4 kB a plane before any point, refused at once.
  const std::size_t plane_count = spec.count > 0 ? std::size_t(spec.count) : spec.planes.size();
  detail::HeldBytes held(memory_limit() / 2,
                         "slice: the points held for " + std::to_string(plane_count) +
                             " planes pass the memory limit: give fewer planes, a smaller "
                             "--fill-reach or --band-max, or --no-fill");
  held.add(4096 * plane_count);
  const SectionSink sink = [&](const SectionSlice& s) {
    held.add(bytes_of(s));
    if (given_sink) given_sink(s);
  };
  // Chunks of at most 64k points (1.5 MB): each stays in a core's cache from its read to its
  // scan, and the workers end the file together.
  CloudReadOptions read_chunks = read;
  read_chunks.chunk_points = std::min<std::size_t>(read.chunk_points, std::size_t(1) << 16);
  if (read_chunks.threads == 0) read_chunks.threads = options.threads;
  std::vector<Plane> planes = spec.planes;
  double slab = options.slab;
  Sampling found;
  PartExtent extent;
  if (spec.count > 0 || slab == 0) {
    // Points near planes guessed from a first look at the file are kept on the way: when
    // the planes and slab found are near enough to the guess, pass 2 is not needed.
    Guess guess = guess_planes(path, spec, options, read);
    FirstPass first;
    first.hold = options.sampling.max_points;
    first_pass(path, read_chunks, spec.normal.normalized(), slab == 0, guess, first, held);
    if (spec.count > 0) {
      extent = detail::trimmed_extent(first.tails);
      planes = spread(spec.normal, extent.lo, extent.hi, spec.count);
    }
    if (slab == 0) {
      detail::SpacingSearch search;
      Sampling sampling = detail::sampling_of(first.first, planes[0].normal, options.sampling, search);
      const bool all_held = first.first.size() == first.total;
      if (sampling.kind == SamplingKind::rows ||
          (sampling.kind == SamplingKind::lines && !sampling.rows.empty() && all_held))
        return slice_held(path, planes, options, read, sink, std::move(first), std::move(sampling),
                          on_sampling);
      slab = sampled_slab(first, sampling, search);
      if (on_sampling) on_sampling(sampling);
      found = std::move(sampling);
      found.rows.clear();
    }
    check_slab_width(slab);
    if (guess.active && guess.covers(planes, slab, first.largest)) {
      SliceResult r = slice_kept(path, planes, slab, guess, first, options, read_chunks, sink, held);
      r.sampling = std::move(found);
      r.extent = extent;
      return r;
    }
  }
  check_slab_width(slab);
  SliceResult r = slice_pass(path, planes, slab, spec.count > 0 || options.slab == 0 ? 2 : 1, options,
                             read_chunks, sink, held);
  r.sampling = std::move(found);
  r.extent = extent;
  return r;
}

}  // namespace section

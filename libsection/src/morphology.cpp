// SPDX-License-Identifier: GPL-3.0-or-later
#include "section/morphology.h"

#include "closing.h"
#include "detail/kept_ordering.h"
#include "point_grid.h"
#include "section/error.h"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <optional>
#include <string>
#include <utility>

namespace section {

namespace {

using morph::Foot;
using morph::Pass;
using morph::Points;
using morph::Vec;

/// Drops the points of one ordered loop that stand off the curve of their neighbours along
/// the loop: an outlier close to the profile is in the raster, so the closing passes
/// through it and its distance to the boundary is small; a quadratic fitted to its
/// neighbours along the loop (up to 3 each side within 12 cells, the point left out) shows
/// its offset. Returns the number dropped.
std::size_t drop_spikes(const Points& points, const std::vector<Vec>& normal_at, const Points& boundary,
                        double h, double limit, std::vector<std::pair<double, std::size_t>>& mem) {
  const std::size_t n = mem.size();
  if (n < 8) return 0;
  const double window = 12 * h;
  std::vector<std::uint8_t> drop(n, 0);
  for (std::size_t i = 0; i < n; ++i) {
    const Vec& p = points[mem[i].second];
    const Vec nrm = normal_at[mem[i].second];
    if (nrm.isZero()) continue;
    const Vec t(-nrm.y(), nrm.x());
    Eigen::Matrix3d A = Eigen::Matrix3d::Zero();
    Eigen::Vector3d b = Eigen::Vector3d::Zero();
    int used = 0, left = 0, right = 0;
    for (int side = -1; side <= 1; side += 2)
      for (std::size_t k = 1; k <= 3 && k < n / 2; ++k) {
        const std::size_t j = (i + n + side * std::ptrdiff_t(k)) % n;
        if ((points[mem[j].second] - p).norm() > window) break;
        const Vec d = points[mem[j].second] - p;
        const double x = t.dot(d), y = nrm.dot(d);
        const Eigen::Vector3d row(1, x, x * x);
        A += row * row.transpose();
        b += row * y;
        ++used;
        (side < 0 ? left : right) += 1;
      }
    if (left < 2 || right < 2) continue;  // too few neighbours to judge
    const Eigen::Vector3d c = A.ldlt().solve(b);
    if (std::isfinite(c(0)) && std::abs(c(0)) > limit) drop[i] = 1;
  }
  std::size_t count = 0, w = 0;
  for (std::size_t i = 0; i < n; ++i) {
    if (drop[i]) {
      ++count;
      continue;
    }
    mem[w++] = mem[i];
  }
  mem.resize(w);
  return count;
}

// A loop found by a pass: the component and its boundary.
struct Found {
  int pass = 0;
  int component = 0;  // index into pass.components
  Points boundary;
  double area = 0;
};

// The passes and the loops they found. `footed` are the points of the last grid built
// over `found` (ascending, as the subset) and `feet` their feet on it: that grid is built
// over `found` as the search leaves it, so they are reused when sorting by area leaves
// that order as it is.
struct Search {
  std::vector<Pass> passes;
  std::vector<Found> found;
  std::vector<std::size_t> footed;
  std::vector<Foot> feet;
  // The skeleton made of found loop `skeleton_of` (-1: none kept): it depends on that
  // loop's pass and component only, so an ordering of other points on the same loops
  // (order_beside) takes it as it is.
  int skeleton_of = -1;
  std::vector<Vec> skeleton;
  std::vector<double> skeleton_radius;
};

// Checks the options and points; returns the fewest points a loop needs.
std::size_t check_input(const std::vector<Eigen::Vector2d>& points, const MorphologyOptions& opt) {
  if (points.empty()) throw Error("morphology: no points");
  if (!(opt.cell >= 0) || !std::isfinite(opt.cell))
    throw Error("morphology: cell must be >= 0, got " + morph::num(opt.cell));
  if (opt.max_dilation < 1) throw Error("morphology: max_dilation must be >= 1");
  if (!(opt.outlier_distance >= 0) || !(opt.isolated_distance >= 0))
    throw Error("morphology: outlier_distance and isolated_distance must be >= 0");
  if (!(opt.normal_sigma > 0) || opt.normal_sigma > 10)
    throw Error("morphology: normal_sigma must be in (0, 10] cells");
  const std::size_t min_points = std::max<std::size_t>(3, opt.min_points);
  if (points.size() < min_points)
    throw Error("morphology: " + std::to_string(points.size()) + " points, at least " +
                std::to_string(min_points) + " are needed");
  for (std::size_t k = 0; k < points.size(); ++k)
    if (!points[k].allFinite()) throw Error("morphology: point " + std::to_string(k) + " is not finite");
  return min_points;
}

// The raster cell: opt.cell, or the median spacing coarsened to at most opt.auto_cells
// cells. Refuses an oversized raster before anything is allocated (its size with no
// margin is a lower bound of every pass's raster).
double cell_size(const Points& points, const std::vector<std::size_t>& all, const MorphologyOptions& opt) {
  double h = opt.cell;
  if (h == 0) {
    Vec lo, hi;
    morph::robust_box(points, all, 0.001, lo, hi);
    const Vec ext = hi - lo;
    const double budget_cell =
        std::sqrt(ext.x() * ext.y() / double(std::max<std::size_t>(1, opt.auto_cells)));
    h = morph::median_spacing(points, all, 20000, std::max({budget_cell, 1e-4 * ext.norm(), opt.min_cell}));
    if (!(h > 0)) throw Error("morphology: the points are all equal; no loop can be formed");
  }
  Vec lo = points[0], hi = lo;
  for (const Vec& p : points) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  const double wc = std::floor((hi.x() - lo.x()) / h) + 1, hc = std::floor((hi.y() - lo.y()) / h) + 1;
  if (wc * hc > double(opt.max_cells)) throw morph::raster_too_large(wc, hc, h, opt.max_cells);
  return h;
}

// Points scattered off the surface (a laser's mixed pixels at 0.1-0.2 mm, a reflection's
// ghosts) farther than the outlier distance from the profile closed, on a pass of their own,
// into loops along it of a point every 0.35-2 mm where the scan has one every 0.03: the
// section was then refused for its "other objects". Such a loop, far sparser than the cell
// (the points' median spacing) with its points beside the first pass's loops, is no loop:
// an object of its own (a fixture, a piece the data split off) is scanned as densely as the
// blade.
constexpr double kStraySparser = 5;  // its points' mean spacing over the cell (a scan's density varies 4:1)
constexpr double kStrayReach = 20;   // cells from the first pass's loops ...
constexpr double kStrayShare = 0.8;  // ... within which this share of its points lies

bool strays_beside(const Points& points, const std::vector<std::size_t>& subset, const Points& boundary,
                   const std::vector<const Points*>& first_pass, double reach, double h) {
  const morph::SegmentGrid own({&boundary}, reach), beside(first_pass, kStrayReach * h);
  const double length = own.length(0);  // the closed boundary's, summed as it indexes it
  std::size_t made = 0, near = 0;
  for (const std::size_t k : subset)
    if (own.nearest(points[k]).loop >= 0) {
      ++made;
      near += beside.nearest(points[k]).loop >= 0;
    }
  return made > 0 && length / double(made) > kStraySparser * h && double(near) >= kStrayShare * double(made);
}

// Passes over `subset` until no new loop is found: points far from every loop so far
// are processed again on their own.
void find_loops(const Points& points, std::vector<std::size_t> subset, double h, double outlier,
                std::size_t min_points, const MorphologyOptions& opt, Search& s, MorphologyResult& result) {
  while (subset.size() >= min_points && int(s.found.size()) < opt.max_loops) {
    Pass pass;
    if (!morph::run_pass(points, subset, h, opt, pass)) break;
    if (s.passes.empty()) result.raster_cells = pass.raster.size();
    const std::size_t before = s.found.size();
    // Pointers into s.found: this pass's loops are appended only after the last test
    // against them (an append may move them).
    std::vector<const Points*> first_pass;
    for (const Found& f : s.found)
      if (f.pass == 0) first_pass.push_back(&f.boundary);
    std::vector<Found> made;
    for (std::size_t ci = 0; ci < pass.components.size(); ++ci) {
      const morph::Component& comp = pass.components[ci];
      if (comp.enclosed == 0) continue;
      Found f;
      f.pass = int(s.passes.size());
      f.component = int(ci);
      f.boundary = morph::component_boundary(pass, comp);
      if (f.boundary.size() < 3) continue;
      if (!first_pass.empty() &&
          strays_beside(points, subset, f.boundary, first_pass, std::max(outlier, pass.radius * h), h))
        continue;
      f.area = morph::signed_area(f.boundary);
      made.push_back(std::move(f));
    }
    for (Found& f : made) s.found.push_back(std::move(f));
    s.passes.push_back(std::move(pass));
    if (s.found.size() == before) break;
    std::vector<const Points*> bounds;
    for (const Found& f : s.found) bounds.push_back(&f.boundary);
    const morph::SegmentGrid segs(bounds, outlier);
    s.footed = subset;
    s.feet.clear();
    std::vector<std::size_t> left;
    for (std::size_t k : subset) {
      s.feet.push_back(segs.nearest(points[k]));
      if (s.feet.back().loop < 0) left.push_back(k);
    }
    if (left.size() == subset.size()) break;
    subset.swap(left);
  }
}

// The loop of `found` with its members (arc length, input index) in order.
Loop make_loop(const Points& points, const Found& f, const Pass& pass, int label,
               const std::vector<std::pair<double, std::size_t>>& mem, const std::vector<Vec>& fallback,
               double normal_sigma) {
  Loop loop;
  loop.boundary = f.boundary;
  loop.area = f.area;
  for (std::size_t i = 0; i < f.boundary.size(); ++i)
    loop.length += (f.boundary[(i + 1) % f.boundary.size()] - f.boundary[i]).norm();
  loop.dilation = pass.radius;
  loop.points.reserve(mem.size());
  loop.normals.reserve(mem.size());
  loop.index.reserve(mem.size());
  morph::ImageNormals normals(pass, label, normal_sigma);
  for (const auto& [s, k] : mem) {
    Vec n = normals.at(points[k]);
    if (n.isZero()) n = fallback[k];
    loop.points.push_back(points[k]);
    loop.normals.push_back(n);
    loop.index.push_back(k);
  }
  return loop;
}

// The skeleton of found loop `first` (an index into s.found) into `result`.
void skeleton_of_found(const Search& s, int first, MorphologyResult& result) {
  if (first == s.skeleton_of) {
    result.skeleton = s.skeleton;
    result.skeleton_radius = s.skeleton_radius;
    return;
  }
  const Found& f = s.found[std::size_t(first)];
  const Pass& pass = s.passes[f.pass];
  morph::skeleton_of(pass, pass.components[f.component], result);
}

// The outlier distance at cell h: the option, or 2.5 cells.
double outlier_at(const MorphologyOptions& opt, double h) {
  return opt.outlier_distance > 0 ? opt.outlier_distance : 2.5 * h;
}

// Every input point joins the loop nearest to it, or is dropped; then each loop keeps its
// members in order along it, without spikes, if enough are left. With `feet_known`, the
// feet s.feet of the points s.footed are reused. Returns the index into s.found of loop 0
// (-1: none).
int make_loops(const Points& points, const Search& s, bool feet_known, double h, double outlier,
               std::size_t min_points, const MorphologyOptions& opt, MorphologyResult& result) {
  std::vector<const Points*> bounds;
  for (const Found& f : s.found) bounds.push_back(&f.boundary);
  // Made for the first point whose foot is not known (the slab's are, all but its
  // isolated points').
  std::optional<morph::SegmentGrid> segs;
  const auto nearest = [&](const Vec& p) {
    if (!segs) segs.emplace(bounds, outlier);
    return segs->nearest(p);
  };
  std::vector<std::vector<std::pair<double, std::size_t>>> members(s.found.size());
  std::vector<Vec> fallback(points.size());
  std::size_t dropped = 0;
  const std::size_t footed = feet_known ? s.footed.size() : 0;
  for (std::size_t k = 0, next = 0; k < points.size(); ++k) {
    const bool known = next < footed && s.footed[next] == k;
    const Foot foot = known ? s.feet[next++] : nearest(points[k]);
    if (foot.loop < 0) {
      ++dropped;
      continue;
    }
    members[foot.loop].emplace_back(foot.s, k);
    fallback[k] = foot.normal;
  }
  int first = -1;
  for (std::size_t l = 0; l < s.found.size(); ++l) {
    auto& mem = members[l];
    std::sort(mem.begin(), mem.end());
    dropped += drop_spikes(points, fallback, s.found[l].boundary, h, outlier, mem);
    if (mem.size() < min_points) {
      dropped += mem.size();
      continue;
    }
    const Found& f = s.found[l];
    const Pass& pass = s.passes[f.pass];
    const morph::Component& comp = pass.components[f.component];
    Loop loop = make_loop(points, f, pass, comp.label, mem, fallback, opt.normal_sigma);
    if (result.loops.empty()) {
      result.dilation = pass.radius;
      first = int(l);
    }
    result.loops.push_back(std::move(loop));
  }
  result.dropped = dropped;
  if (first >= 0 && opt.skeleton && (!opt.skeleton_if || opt.skeleton_if(result)))
    skeleton_of_found(s, first, result);
  return first;
}

}  // namespace

namespace detail {

// A loop closed by a dilation wider than this many cells bridges holes in its points, away
// from the profile: denser points beside it are dropped there, and are ordered afresh.
constexpr int kMaxBesideDilation = 32;

struct KeptOrdering {
  Search search;
  double h = 0;
  std::size_t min_points = 0;
  std::size_t loops = 0;  // loops the ordering made
  int first = -1;         // index into search.found of loop 0
  std::size_t raster_cells = 0;
  std::size_t dropped = 0;  // points the ordering left off its loops
  int dilation = 0;         // cells, the radius that closed loop 0
};

}  // namespace detail

namespace {

// order_section, what it found left in `kept`.
MorphologyResult order_into(const std::vector<Eigen::Vector2d>& points, const MorphologyOptions& opt,
                            detail::KeptOrdering& kept) {
  const std::size_t min_points = check_input(points, opt);
  std::vector<std::size_t> all(points.size());
  std::iota(all.begin(), all.end(), std::size_t(0));
  const double h = cell_size(points, all, opt);
  const double outlier = outlier_at(opt, h);
  const double isolated = opt.isolated_distance > 0 ? opt.isolated_distance : 6 * h;

  // Isolated points stay out of the raster so that they cannot make loops or bumps.
  std::vector<std::size_t> subset;
  {
    const morph::PointGrid grid(points, all, isolated);
    for (std::size_t k : all)
      if (grid.has_neighbour(k, isolated)) subset.push_back(k);
  }

  MorphologyResult result;
  result.cell = h;
  Search& s = kept.search;
  find_loops(points, std::move(subset), h, outlier, min_points, opt, s, result);
  if (s.found.empty())
    throw Error("morphology: the " + std::to_string(points.size()) +
                " points do not close into a loop up to a dilation of " + std::to_string(opt.max_dilation) +
                " cells (cell " + morph::num(h) + " mm); the section may be open or too sparse");
  // Largest area first.
  const auto larger = [](const Found& a, const Found& b) { return a.area > b.area; };
  bool feet_known = true;
  if (!std::is_sorted(s.found.begin(), s.found.end(), larger)) {
    std::stable_sort(s.found.begin(), s.found.end(), larger);
    feet_known = false;
  }
  kept.first = make_loops(points, s, feet_known, h, outlier, min_points, opt, result);
  if (result.loops.empty())
    throw Error("morphology: no loop keeps at least " + std::to_string(min_points) + " points");
  if (!result.skeleton.empty()) {  // made of loop kept.first: kept for order_beside
    s.skeleton_of = kept.first;
    s.skeleton = result.skeleton;
    s.skeleton_radius = result.skeleton_radius;
  }
  kept.h = h;
  kept.min_points = min_points;
  kept.loops = result.loops.size();
  kept.raster_cells = result.raster_cells;
  kept.dropped = result.dropped;
  kept.dilation = result.dilation;
  // The feet are of these points only.
  std::vector<std::size_t>().swap(s.footed);
  std::vector<Foot>().swap(s.feet);
  return result;
}

}  // namespace

double spacing_2d(const std::vector<Eigen::Vector2d>& points, std::size_t sample) {
  std::vector<std::size_t> all(points.size());
  std::iota(all.begin(), all.end(), std::size_t(0));
  for (const Vec& p : points)
    if (!p.allFinite()) throw Error("morphology: a point has a non-finite coordinate");
  return morph::median_spacing(points, all, std::max<std::size_t>(1, sample));
}

MorphologyResult order_section(const std::vector<Eigen::Vector2d>& points, const MorphologyOptions& opt) {
  detail::KeptOrdering kept;
  return order_into(points, opt, kept);
}

namespace detail {

OrderedKept order_section_kept(const std::vector<Eigen::Vector2d>& points, const MorphologyOptions& options) {
  auto kept = std::make_shared<KeptOrdering>();
  OrderedKept ordered;
  ordered.result = order_into(points, options, *kept);
  ordered.kept = std::move(kept);
  return ordered;
}

std::optional<MorphologyResult> order_beside(const KeptOrdering& kept,
                                             const std::vector<Eigen::Vector2d>& points,
                                             const MorphologyOptions& options) {
  check_input(points, options);
  if (kept.dilation > kMaxBesideDilation) return std::nullopt;
  // The points' own scale, as order_section would take it: the kept loops must hold them
  // within their own outlier distance, not the kept (coarser) one's.
  std::vector<std::size_t> all(points.size());
  std::iota(all.begin(), all.end(), std::size_t(0));
  const double h = cell_size(points, all, options);
  const double outlier = outlier_at(options, h);
  MorphologyResult result;
  result.cell = kept.h;
  result.raster_cells = kept.raster_cells;
  make_loops(points, kept.search, false, h, outlier, kept.min_points, options, result);
  if (result.loops.size() != kept.loops || result.dropped > kept.dropped + 2) return std::nullopt;
  return result;
}

void add_skeleton(const KeptOrdering& kept, MorphologyResult& result) {
  if (kept.first >= 0) skeleton_of_found(kept.search, kept.first, result);
}

}  // namespace detail

}  // namespace section

// SPDX-License-Identifier: GPL-3.0-or-later
#include "section/sampling.h"

#include "section/error.h"
#include "section/frame.h"
#include "detail/flann_nearest.h"
#include "detail/parallel.h"
#include "detail/spacing_search.h"
#include "io/text.h"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>
#include <numeric>

namespace section {

namespace {

using Vec3 = Eigen::Vector3d;

// Neighbours of a point looked at: the 16 nearest distinct others, from a search for 24
// (exact copies of the point, itself included, are skipped), or for 17 when no other
// point lies on it.
constexpr int wanted = 16, searched = 24;
// The first look: this many points (at most), this many of them measured; a quick look
// measures at least quick_queries of the same points first.
constexpr std::size_t first_look = 50'000, first_queries = 5'000, quick_queries = 1'000;
// Within 45 degrees of the normal a neighbour is above or below; within 30 degrees of the
// plane it is beside, in the same row.
const double above = std::sqrt(0.5), beside = 0.5;

double quantile(std::vector<double> v, double q) {
  if (v.empty()) return 0;
  const std::size_t i = std::min(v.size() - 1, std::size_t(q * double(v.size() - 1) + 0.5));
  std::nth_element(v.begin(), v.begin() + std::ptrdiff_t(i), v.end());
  return v[i];
}

// The distinct neighbours of point i, nearest first (indices into `first`), and whether
// it has an exact copy; with `spacing_d2`, what mean_spacing takes from the point's 3
// nearest (SpacingSearch::nearest_d2).
struct Near {
  int index[searched];
  int count = 0;
  bool copied = false;
};

Near near_of(const detail::NearestPoints<3>& tree, const std::vector<Vec3>& first, std::size_t i,
             double* spacing_d2 = nullptr) {
  int idx[searched];
  double d2[searched];
  std::fill(d2, d2 + searched, -1.0);  // FLANN leaves the entries it does not find
  // The first 17 of FLANN's exact 24 nearest are its 17 nearest, in the same order: the
  // search for fewer visits no cell the larger one does not, and what only the larger one
  // finds lies farther than the smaller one's last. Without a copy of the point they are
  // the point and its 16 nearest distinct others.
  const int most = int(std::min<std::size_t>(searched, first.size()));
  int k = std::min(wanted + 1, most);
  tree.k_nearest(first[i], k, idx, d2);
  if (k < most && !(d2[1] > 0)) {  // a copy of the point: look past it
    k = most;
    tree.k_nearest(first[i], k, idx, d2);
  }
  if (spacing_d2 && k >= 3) *spacing_d2 = d2[1] > 0 ? d2[1] : d2[2] > 0 ? d2[2] : 0;
  Near n;
  for (int j = 0; j < k && n.count < wanted; ++j) {
    if (d2[j] < 0 || idx[j] < 0) continue;
    if (d2[j] == 0) {
      n.copied = n.copied || std::size_t(idx[j]) != i;
      continue;
    }
    n.index[n.count++] = idx[j];
  }
  return n;
}

// The neighbours of point i: those kept (every point's, when measure_spacings measured them
// all) or searched again.
Near near_at(const detail::NearestPoints<3>& tree, const std::vector<Vec3>& first,
             const std::vector<Near>& known, std::size_t i) {
  return known.empty() ? near_of(tree, first, i) : known[i];
}

// Every step-th of m points is measured for at most `queries` of them.
std::size_t step_of(std::size_t m, std::size_t queries) {
  return std::max<std::size_t>(1, m / std::max<std::size_t>(1, queries));
}

// Far from every line the first look draws between a dense scan and the rest (dense
// scans measure 1.04-1.10 and 0.52-0.65 for the two ratios below; lines and rows have
// 1.9 or more and 1, or none) and with no exact copy seen: a sample a fifth the size
// would not cross those lines (docs/SAMPLING.md).
bool plainly_dense(const Sampling& s, const SamplingOptions& options) {
  return s.spacing > 0 && s.duplicates == 0 && s.normal_spacing <= 0.75 * options.anisotropy * s.spacing &&
         s.normal_low < 0.72 * s.normal_high;
}

// The neighbours of every step-th point of `first`, as one look measured them.
struct Look {
  std::size_t step = 0;
  std::vector<Near> near;  // of points 0, step, 2 step, ...
};

// The spacing in the surface and along the normal, medians over every step-th point; the
// neighbours of each point into `look`, taken from `before` (a look on the same tree) where
// it measured the point, and what mean_spacing takes from them into `nearest_d2` (one entry
// a point).
void measure_spacings(const detail::NearestPoints<3>& tree, const std::vector<Vec3>& first, const Vec3& n,
                      std::size_t step, int threads, const Look& before, Sampling& s,
                      std::vector<double>& heights, Look& look, std::vector<double>& nearest_d2) {
  const std::size_t count = (first.size() + step - 1) / step;
  std::vector<double> nearest(count, std::numeric_limits<double>::infinity());
  heights.assign(count, std::numeric_limits<double>::infinity());
  std::vector<char> copied(count, 0);
  look.step = step;
  look.near.assign(count, Near{});
  detail::parallel_for(count, threads, [&](std::size_t q) {
    const std::size_t i = q * step;
    const bool seen = before.step > 0 && i % before.step == 0 && i / before.step < before.near.size();
    const Near& near = look.near[q] =
        seen ? before.near[i / before.step] : near_of(tree, first, i, &nearest_d2[i]);
    copied[q] = near.copied;
    for (int j = 0; j < near.count; ++j) {
      const Vec3 d = first[std::size_t(near.index[j])] - first[i];
      const double length = d.norm(), up = std::abs(d.dot(n));
      nearest[q] = std::min(nearest[q], length);
      if (up >= above * length) heights[q] = std::min(heights[q], up);
    }
  });
  s.measured = count;
  s.duplicates = std::size_t(std::count(copied.begin(), copied.end(), 1));
  std::vector<double> finite;
  for (double x : nearest)
    if (std::isfinite(x)) finite.push_back(x);
  s.spacing = quantile(finite, 0.5);
  s.normal_spacing = quantile(heights, 0.5);
  s.normal_low = quantile(heights, 0.25);
  s.normal_high = quantile(heights, 0.75);
}

std::size_t root(std::vector<std::size_t>& parent, std::size_t a) {
  while (parent[a] != a) a = parent[a] = parent[parent[a]];
  return a;
}

// Pieces of points joined to their neighbours beside them: across the normal (within 30
// degrees of the plane) and within 3 times the point's second nearest neighbour (along a
// row, its neighbours before and after it), so that where a row's points lie sparse a row
// beside it is not joined.
std::vector<std::vector<std::size_t>> pieces(const detail::NearestPoints<3>& tree,
                                             const std::vector<Vec3>& first, const std::vector<Near>& known,
                                             const Vec3& n, int threads) {
  const std::size_t m = first.size();
  std::vector<std::array<int, wanted>> link(m);
  detail::parallel_for((m + 4095) / 4096, threads, [&](std::size_t block) {
    for (std::size_t i = block * 4096; i < std::min(m, (block + 1) * 4096); ++i) {
      const Near near = near_at(tree, first, known, i);
      link[i].fill(-1);
      if (near.count < 2) continue;
      const double reach = 3 * (first[std::size_t(near.index[1])] - first[i]).norm();
      for (int j = 0; j < near.count; ++j) {
        const Vec3 d = first[std::size_t(near.index[j])] - first[i];
        if (std::abs(d.dot(n)) < beside * d.norm() && d.norm() <= reach)
          link[i][std::size_t(j)] = near.index[j];
      }
    }
  });
  std::vector<std::size_t> parent(m);
  std::iota(parent.begin(), parent.end(), std::size_t(0));
  for (std::size_t i = 0; i < m; ++i)
    for (int j : link[i])
      if (j >= 0) parent[root(parent, i)] = root(parent, std::size_t(j));
  std::vector<std::vector<std::size_t>> out;
  std::vector<std::size_t> slot(m, m);
  for (std::size_t i = 0; i < m; ++i) {
    const std::size_t r = root(parent, i);
    if (slot[r] == m) slot[r] = out.size(), out.emplace_back();
    out[slot[r]].push_back(i);
  }
  return out;
}

// The best plane of a row (heights above the plane of `n` fitted as a + b u + c v), its
// spread about it and its size.
PointRow fit_row(std::vector<std::size_t> points, const std::vector<Vec3>& first, const Vec3& n,
                 double flatness) {
  PointRow row;
  row.points = std::move(points);
  const Frame f = make_frame(Vec3::Zero(), n);
  Vec3 centre = Vec3::Zero();
  row.low = INFINITY, row.high = -INFINITY;
  for (std::size_t i : row.points) {
    centre += first[i];
    row.low = std::min(row.low, n.dot(first[i])), row.high = std::max(row.high, n.dot(first[i]));
  }
  centre /= double(row.points.size());
  row.height = n.dot(centre);
  Eigen::Matrix2d a = Eigen::Matrix2d::Zero();
  Eigen::Vector2d b = Eigen::Vector2d::Zero();
  for (std::size_t i : row.points) {
    const Vec3 d = first[i] - centre;
    const Eigen::Vector2d uv(d.dot(f.u), d.dot(f.v));
    a += uv * uv.transpose();
    b += uv * d.dot(n);
  }
  Eigen::Vector2d slope = Eigen::Vector2d::Zero();
  if (std::abs(a.determinant()) > 1e-12 * a.squaredNorm()) slope = a.ldlt().solve(b);
  row.normal = (n - slope.x() * f.u - slope.y() * f.v).normalized();
  row.origin = row.normal.dot(centre) * row.normal;
  const Frame own = make_frame(row.origin, row.normal);
  Eigen::Vector2d lo(INFINITY, INFINITY), hi(-INFINITY, -INFINITY);
  for (std::size_t i : row.points) {
    row.spread = std::max(row.spread, std::abs(own.height(first[i])));
    lo = lo.cwiseMin(own.to_plane(first[i])), hi = hi.cwiseMax(own.to_plane(first[i]));
  }
  row.size = (hi - lo).norm();
  row.planar = row.spread <= flatness * row.size;
  return row;
}

// A smaller piece joins a larger one it lies in (a row split where its spacing jumps):
// their heights overlap and its points lie within twice the larger one's spread (or
// the spacing) of its best plane. Pieces of fewer than 8 points are strays.
std::vector<PointRow> join_pieces(std::vector<std::vector<std::size_t>> parts, const std::vector<Vec3>& first,
                                  const Vec3& n, double spacing, double flatness) {
  std::sort(parts.begin(), parts.end(), [](const auto& a, const auto& b) { return a.size() > b.size(); });
  std::vector<PointRow> rows;
  for (auto& part : parts) {
    if (part.size() < 8) break;
    PointRow piece = fit_row(std::move(part), first, n, flatness);
    PointRow* into = nullptr;
    for (PointRow& row : rows) {
      if (piece.low > row.high || piece.high < row.low) continue;
      const double reach = 2 * std::max(row.spread, spacing);
      bool inside = true;
      for (std::size_t i : piece.points)
        if (!(std::abs(row.normal.dot(first[i] - row.origin)) <= reach)) inside = false;
      if (inside) into = &row;
      if (inside) break;
    }
    if (!into) {
      rows.push_back(std::move(piece));
      continue;
    }
    std::vector<std::size_t> joined = std::move(into->points);
    joined.insert(joined.end(), piece.points.begin(), piece.points.end());
    std::sort(joined.begin(), joined.end());
    *into = fit_row(std::move(joined), first, n, flatness);
  }
  return rows;
}

// Points on levels (a structured grid's lines at constant height, however their spacing
// along a line compares with the gap between lines): the points sorted by height, cut
// where the next height lies over half the lowest quartile `gap` of the heights to a
// neighbour above or below. Empty unless every level is thinner than a quarter of the gaps
// beside it (levels that overlap, such as slanted lines, are left to the pieces).
std::vector<std::vector<std::size_t>> levels_of(const std::vector<Vec3>& first, const Vec3& n, double gap) {
  std::vector<std::size_t> order(first.size());
  std::iota(order.begin(), order.end(), std::size_t(0));
  std::vector<double> h(first.size());
  for (std::size_t i = 0; i < first.size(); ++i) h[i] = n.dot(first[i]);
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return h[a] < h[b]; });
  std::vector<std::vector<std::size_t>> out(1);
  std::vector<std::array<double, 2>> span;  // each level's lowest and highest height
  for (std::size_t k = 0; k < order.size(); ++k) {
    if (k > 0 && h[order[k]] - h[order[k - 1]] > 0.5 * gap) out.emplace_back();
    if (out.back().empty()) span.push_back({h[order[k]], h[order[k]]});
    out.back().push_back(order[k]);
    span.back()[1] = h[order[k]];
  }
  for (std::size_t k = 0; k < out.size(); ++k) {
    const double thick = span[k][1] - span[k][0];
    if (k > 0 && 4 * thick > span[k][0] - span[k - 1][1]) return {};
    if (k + 1 < out.size() && 4 * thick > span[k + 1][0] - span[k][1]) return {};
    std::sort(out[k].begin(), out[k].end());
  }
  return out;
}

// The normal of levels tilted from `n` (a grid's lines at constant height, sliced by planes
// a few degrees off them): the direction across the steps from each of up to `queries`
// points to its nearest neighbour within 6 degrees of the plane (on a level, its neighbour
// along the line), the least eigenvector of their scatter; `n` when that is over 30
// degrees from it.
Vec3 level_normal(const detail::NearestPoints<3>& tree, const std::vector<Vec3>& first,
                  const std::vector<Near>& known, const Vec3& n, const SamplingOptions& options) {
  const std::size_t step = step_of(first.size(), options.queries);
  Eigen::Matrix3d scatter = Eigen::Matrix3d::Zero();
  for (std::size_t i = 0; i < first.size(); i += step) {
    const Near near = near_at(tree, first, known, i);
    for (int j = 0; j < near.count; ++j) {
      const Vec3 d = (first[std::size_t(near.index[j])] - first[i]).normalized();
      if (std::abs(d.dot(n)) >= 0.1) continue;
      scatter += d * d.transpose();
      break;
    }
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(scatter);
  Vec3 m = eig.eigenvectors().col(0);
  if (m.dot(n) < 0) m = -m;
  return m.dot(n) > std::sqrt(0.75) ? m : n;
}

// The rows of the points, when rows of at least 8 points hold 90 % of them and at least
// half of the rows are planar; else none. Points on levels are split by height first:
// along `n`, else along the levels' own normal (level_normal); `only_levels`: no rows
// but levels (points no sparser along the normal than across it are rows only so).
std::vector<PointRow> find_rows(const detail::NearestPoints<3>& tree, const std::vector<Vec3>& first,
                                const std::vector<Near>& known, const Vec3& n, double spacing,
                                double level_gap, bool only_levels, const SamplingOptions& options) {
  std::vector<std::vector<std::size_t>> parts;
  if (level_gap > 0) parts = levels_of(first, n, level_gap);
  // (An infinite gap makes one level along any normal: none is sought.)
  if (level_gap > 0 && std::isfinite(level_gap) && parts.size() < 2)
    parts = levels_of(first, level_normal(tree, first, known, n, options), level_gap);
  std::vector<PointRow> rows;
  if (parts.size() >= 2) {
    // Levels are whole lines: none joins another (tilted ones overlap in height along n).
    for (auto& part : parts)
      if (part.size() >= 8) rows.push_back(fit_row(std::move(part), first, n, options.flatness));
  } else {
    if (only_levels) return {};
    parts = pieces(tree, first, known, n, options.threads);
    if (8 * parts.size() > first.size()) return {};  // mostly strays: no rows
    rows = join_pieces(std::move(parts), first, n, spacing, options.flatness);
  }
  std::size_t covered = 0, planar = 0;
  for (const PointRow& row : rows) covered += row.points.size(), planar += row.planar;
  if (rows.empty() || double(covered) < 0.9 * double(first.size()) || 2 * planar < rows.size()) return {};
  return rows;
}

// Sorted by height: the median gap between neighbours and the slab of lines (the gap that
// nine in ten of them keep within).
void classify_rows(const SamplingOptions& options, Sampling& s) {
  std::sort(s.rows.begin(), s.rows.end(),
            [](const PointRow& a, const PointRow& b) { return a.height < b.height; });
  std::vector<double> gaps, sizes;
  for (std::size_t k = 0; k < s.rows.size(); ++k) {
    sizes.push_back(s.rows[k].size);
    if (k > 0) gaps.push_back(s.rows[k].height - s.rows[k - 1].height);
  }
  s.row_gap = quantile(gaps, 0.5);
  if (gaps.empty() || s.row_gap > options.sparse * quantile(sizes, 0.5)) {
    s.kind = SamplingKind::rows;
    return;
  }
  s.kind = SamplingKind::lines;
  s.slab = quantile(gaps, 0.9);
}

std::string length(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3g", x);
  return buf;
}

}  // namespace

const char* sampling_kind_name(SamplingKind kind) {
  switch (kind) {
    case SamplingKind::lines:
      return "lines";
    case SamplingKind::rows:
      return "rows";
    default:
      return "dense";
  }
}

std::string Sampling::describe() const {
  const std::string along = std::isfinite(normal_spacing)
                                ? ", along the normal " + length(normal_spacing) + " mm"
                                : ", none near above or below";
  const std::string spacings = "spacing " + length(spacing) + " mm" + along;
  const std::string copies = duplicates > 0
                                 ? ", " + std::to_string(duplicates) + " of " + std::to_string(measured) +
                                       " points measured have an exact copy"
                                 : "";
  if (kind == SamplingKind::dense) return "a dense scan (" + spacings + copies + ")";
  if (kind == SamplingKind::lines)
    return "lines of points across the normal (" + spacings +
           (rows.empty() ? ""
                         : ", " + std::to_string(rows.size()) + " lines " + length(row_gap) + " mm apart") +
           copies + "): slab " + length(slab) + " mm";
  if (rows.size() == 1) return "one row of points, a single section (" + spacings + copies + ")";
  return std::to_string(rows.size()) + " rows of points " + length(row_gap) + " mm apart, each a section (" +
         spacings + copies + ")";
}

Sampling sampling_of(const std::vector<Eigen::Vector3d>& points, const Eigen::Vector3d& normal,
                     const SamplingOptions& options) {
  detail::check_points(points);
  detail::SpacingSearch unused;
  return detail::sampling_of(points, normal, options, unused);
}

namespace detail {

void check_points(const std::vector<Eigen::Vector3d>& points) {
  for (std::size_t k = 0; k < points.size(); ++k)
    if (!(points[k].cwiseAbs().maxCoeff() <= max_coordinate))
      throw Error("slice: point " + std::to_string(k) +
                  (points[k].allFinite() ? " lies beyond +-1e15 (a coordinate no cloud file gives)"
                                         : " is not finite"));
}

namespace {

// Lines that do not come apart into rows (slanted, or crossing): the slab bridges the gap
// along the normal that nine in ten points see (0 when none has one).
double lines_slab(const std::vector<double>& heights) {
  std::vector<double> finite;
  for (double h : heights)
    if (std::isfinite(h)) finite.push_back(h);
  return quantile(finite, 0.9);
}

// Options that made no sense: queries 0 took the whole cloud as one slab.
void check_options(const SamplingOptions& options) {
  if (options.queries < 1 || options.max_points < 1)
    throw Error(
        "slice: the sampling needs at least 1 point and 1 query (queries 0 took the whole cloud as one "
        "slab)");
  if (!(options.anisotropy > 1) || !std::isfinite(options.anisotropy) || !(options.sparse > 0) ||
      !(options.flatness > 0) || !std::isfinite(options.sparse) || !std::isfinite(options.flatness))
    throw Error(
        "slice: the sampling's anisotropy must be a finite number above 1, sparse and flatness above 0");
}

Sampling sample_points(const std::vector<Eigen::Vector3d>& points, const Eigen::Vector3d& normal,
                       const SamplingOptions& options, SpacingSearch& search) {
  if (!normal.allFinite() || !(normal.norm() > 0))
    throw Error("slice: the plane normal must be finite and non-zero");
  check_options(options);
  const Vec3 n = normal.normalized();
  const std::size_t all = std::min(points.size(), std::max<std::size_t>(options.max_points, 1));
  // A first look at fewer points, fewer of them measured, settles a dense scan for a
  // fraction of the cost (a small cloud too); the rest only when they are not one, on the
  // same tree when the first look held all the points. A quick look before it, at every
  // fifth of its points (1 000 or more), settles only what is plainly a dense scan. Each
  // look takes the neighbours of the points the look before it measured on the same tree.
  const std::size_t look = std::min(all, first_look);
  const std::size_t first_step = step_of(look, std::min(options.queries, first_queries));
  const bool quick_look = (look + 5 * first_step - 1) / (5 * first_step) >= quick_queries;
  std::unique_ptr<std::vector<Vec3>> first;
  std::unique_ptr<detail::NearestPoints<3>>& tree = search.tree;
  Look before;
  for (const int stage : {0, 1, 2}) {
    const bool quick = stage == 0, partial = stage < 2;
    if (quick && !quick_look) continue;
    const std::size_t m = partial ? look : all;
    Sampling s;
    s.points = m;
    if (m < 2) return s;
    if (!first || first->size() != m) {
      tree.reset();
      first = std::make_unique<std::vector<Vec3>>(points.begin(), points.begin() + std::ptrdiff_t(m));
      tree = std::make_unique<detail::NearestPoints<3>>(*first);
      search.nearest_d2.assign(m, -1);
      before = Look{};
    }
    const std::size_t step = quick ? 5 * first_step : partial ? first_step : step_of(m, options.queries);
    // A first look measuring what the whole one would is the whole one.
    const bool whole = !partial || (!quick && m == all && step == step_of(m, options.queries));
    std::vector<double> heights;
    Look measured;
    measure_spacings(*tree, *first, n, step, options.threads, before, s, heights, measured,
                     search.nearest_d2);
    before = std::move(measured);
    if (quick) {
      if (plainly_dense(s, options)) return s;
      continue;
    }
    // Every point's neighbours when every point was measured.
    const std::vector<Near> none, &known = before.step == 1 ? before.near : none;
    // Heights on levels (the quartiles of the gaps along the normal close together, where
    // a dense scan's spread over a factor of two) wider apart than the spacing are lines
    // too: a slab of the spacing would fall between them.
    // Levels closer than the spacing along them (a chordwise grid's lines, denser in
    // height than along the chord) are lines too when they come apart by height.
    const bool on_levels = s.normal_low >= 0.8 * s.normal_high && s.normal_low > 0;
    const bool levels = on_levels && s.normal_spacing > s.spacing,
               sparse_up = s.normal_spacing > options.anisotropy * s.spacing;
    // Exact copies make the spacing the slab (as the density they inflate cannot give it):
    // a cloud the first look held measures it over all its queries, as it always did.
    const bool copies = 100 * s.duplicates > s.measured && m == all;
    const bool dense = !(s.spacing > 0) || !(on_levels || sparse_up);
    if (dense && (whole || !copies)) return s;
    if (!whole) continue;
    s.kind = SamplingKind::lines;
    s.rows = find_rows(*tree, *first, known, n, s.spacing, on_levels ? s.normal_low : 0,
                       !levels && !sparse_up, options);
    if (!s.rows.empty()) {
      classify_rows(options, s);
      return s;
    }
    if (!levels && !sparse_up) {
      s.kind = SamplingKind::dense;  // close levels that do not come apart: a slab as for a scan
      return s;
    }
    s.slab = lines_slab(heights);
    if (!(s.slab > 0)) s.kind = SamplingKind::dense;
    return s;
  }
  return Sampling{};
}

}  // namespace

Sampling sampling_of(const std::vector<Eigen::Vector3d>& points, const Eigen::Vector3d& normal,
                     const SamplingOptions& options, SpacingSearch& search) {
  search = SpacingSearch{};
  Sampling s = sample_points(points, normal, options, search);
  // Kept for a dense scan's mean spacing alone, and only when it searched every point.
  if (s.kind != SamplingKind::dense || search.nearest_d2.size() != points.size()) search = SpacingSearch{};
  return s;
}

}  // namespace detail

}  // namespace section

// SPDX-License-Identifier: GPL-3.0-or-later
#include "closing.h"

#include "bottleneck.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>

namespace section::morph {

namespace {

void smooth_closed(Points& p, int passes) {
  const std::size_t n = p.size();
  if (n < 3) return;
  Points q(n);
  for (int k = 0; k < passes; ++k) {
    for (std::size_t i = 0; i < n; ++i) q[i] = 0.25 * p[(i + n - 1) % n] + 0.5 * p[i] + 0.25 * p[(i + 1) % n];
    p.swap(q);
  }
}

/// Outward normal of a counterclockwise closed polyline at vertex i.
Vec vertex_normal(const Points& p, std::size_t i) {
  const std::size_t n = p.size();
  const Vec t = p[(i + 1) % n] - p[(i + n - 1) % n];
  const double l = t.norm();
  return l > 0 ? Vec(t.y() / l, -t.x() / l) : Vec(0, 0);
}

bool substantial(long long cells) {
  return cells >= 16;
}

/// The cells of a subset's point means, by raster cell: `slot` of a cell indexes `mean`
/// (-1: no point), the mean of its points in cell coordinates.
struct Seeds {
  std::vector<Vec> mean;
  std::vector<int> slot;         // filled, not a Buffer: uninitialised it raised the peak (0.9 MB at 0.25 M)
  std::vector<int> first, last;  // per row, the first and last column holding a seed
  std::vector<std::size_t> cells;  // the seed cells, in raster order
};

// Places a raster over [lo, hi] with `margin` cells around.
void place_raster(const Vec& lo, const Vec& hi, double h, int margin, std::size_t max_cells, Raster& r) {
  const double wc = std::floor((hi.x() - lo.x()) / h) + 1 + 2.0 * margin;
  const double hc = std::floor((hi.y() - lo.y()) / h) + 1 + 2.0 * margin;
  if (wc * hc > double(max_cells) || wc > 2e9 || hc > 2e9) throw raster_too_large(wc, hc, h, max_cells);
  r.w = int(wc);
  r.h = int(hc);
  r.x0 = lo.x() - margin * h;
  r.y0 = lo.y() - margin * h;
}

// Seeds: cells holding points; each keeps the mean of its points so that distances to
// the points are known to a small fraction of a cell (the raster alone gives half a cell).
void seed_cells(const Points& points, const std::vector<std::size_t>& subset, const Raster& r,
                std::vector<std::uint8_t>& seed, Seeds& seeds) {
  seed.assign(r.size(), 0);
  seeds.slot.assign(r.size(), -1);
  seeds.mean.clear();
  seeds.cells.clear();
  seeds.first.assign(r.h, r.w);
  seeds.last.assign(r.h, -1);
  std::vector<int> count;
  for (std::size_t k : subset) {
    const Vec c = r.to_cell(points[k]);
    const int i = std::clamp(int(std::lround(c.x())), 0, r.w - 1);
    const int j = std::clamp(int(std::lround(c.y())), 0, r.h - 1);
    const std::size_t cell = std::size_t(j) * r.w + i;
    seeds.first[j] = std::min(seeds.first[j], i);
    seeds.last[j] = std::max(seeds.last[j], i);
    if (!seed[cell]) {
      seed[cell] = 1;
      seeds.slot[cell] = int(seeds.mean.size());
      seeds.mean.emplace_back(0, 0);
      seeds.cells.push_back(cell);
      count.push_back(0);
    }
    seeds.mean[seeds.slot[cell]] += c;
    ++count[seeds.slot[cell]];
  }
  for (std::size_t m = 0; m < seeds.mean.size(); ++m) seeds.mean[m] /= count[m];
  std::sort(seeds.cells.begin(), seeds.cells.end());
}

// Calls fn(first, end) with the columns of row j's span (the whole row without spans).
template <class Fn>
void for_spans_of_row(const Spans* band, int j, int w, const Fn& fn) {
  if (!band)
    fn(0, w);
  else if (band->lo[j] <= band->hi[j])
    fn(band->lo[j], band->hi[j] + 1);
}

// Calls fn(first, end) with the cell indices of each row's span (the whole row without
// spans).
template <class Fn>
void for_spans(const Spans* band, int h, int w, const Fn& fn) {
  for (int j = 0; j < h; ++j) {
    const std::size_t row = std::size_t(j) * w;
    for_spans_of_row(band, j, w, [&](int i0, int i1) { fn(row + i0, row + i1); });
  }
}

// The closing radius r_c (cells), 0 when no substantial interior is ever enclosed.
// A cell is enclosed at radius r when b2 <= r^2 < d2: inside the band of radius r but
// not on it. Cells enclosed at some radius (b2 < d2) are the interior of closed
// profiles; each part of an interior closes at its own radius b (the half width of the
// widest gap leading to it), so the closing radius r_c is the radius by which all of
// them have closed. Taking the first radius at which some interior appears instead
// leaves a part of a thin profile open behind a wide hole when the band pinches the
// profile elsewhere first.
int closing_radius(const Buffer<int>& d2, const Buffer<int>& b2, int cap, int rmax, int w,
                   const Spans* band) {
  std::vector<long long> closing_at(rmax + 2, 0);
  // b2 and d2 lie in [0, cap]: their ceil_sqrt from a table (one per interior cell).
  std::vector<int> root(std::size_t(cap) + 1);
  for (int x = 0; x <= cap; ++x) root[x] = ceil_sqrt(x);
  const int *bp = b2.data(), *dp = d2.data(), *rt = root.data();
  long long* at = closing_at.data();
  const auto count = [=](std::size_t c, long long n) {
    const int b = bp[c], d = dp[c];
    if (b >= d) return;
    const int a = std::max(1, rt[b]);
    if (a > rmax || a > rt[d] - 1) return;  // never enclosed at an integer radius <= rmax
    at[a] += n;
  };
  // Off the spans b2 = d2 = cap: nothing to count there. A gap's cells share b2 and d2.
  for (int j = 0, h = int(d2.size() / w); j < h; ++j) {
    const std::size_t row = std::size_t(j) * w;
    for_runs(band, j, w, [&](int i0, int i1) {
      for (std::size_t c = row + i0; c < row + i1; ++c) count(c, 1);
    });
    if (band && band->has_gap(j)) count(row + band->gap_lo[j], band->gap_hi[j] - band->gap_lo[j] + 1);
  }
  long long ever = 0;
  for (const long long n : closing_at) ever += n;
  if (!substantial(ever)) return 0;
  int rc = 0;
  for (long long sum = 0; rc < rmax && sum < ever;) sum += closing_at[++rc];
  return rc;
}

// Each row's cells of the spans from the first to the last that is not outside (none when
// all are): the cells beyond are outside like those off the spans, seeds of the erosion's
// transform (off_seeds) that need no transform of their own. The spans' gaps that are not
// outside are gaps of these: no outside cell lies within radius + 8 of them (run_pass
// keeps the reach at 2 radius + 9 or more), so the transform leaves them at its cap.
Spans inside_spans(const Raster& r, const Spans& band, const std::uint8_t* out) {
  Spans inner;
  inner.lo.assign(r.h, r.w);
  inner.hi.assign(r.h, -1);
  inner.gap_lo.assign(r.h, 1);
  inner.gap_hi.assign(r.h, 0);
  for (int j = 0; j < r.h; ++j) {
    if (band.has_gap(j) && !out[std::size_t(j) * r.w + band.gap_lo[j]]) {
      inner.gap_lo[j] = band.gap_lo[j];
      inner.gap_hi[j] = band.gap_hi[j];
    }
    const std::uint8_t* row = out + std::size_t(j) * r.w;
    int a = band.lo[j], b = band.hi[j];
    while (a <= b && row[a]) ++a;
    while (b >= a && row[b]) --b;
    if (a > b) continue;
    inner.lo[j] = a;
    inner.hi[j] = b;
  }
  return inner;
}

// Erodes the fill back (keeps the cells farther than the radius from the outside) and sets
// pass.g; returns the squared distance of each cell to the outside. With spans, `inner` gets
// their cells that are not outside (inside_spans), which hold the fill.
Buffer<int> erode(Pass& pass, const Buffer<int>& b2, const Buffer<int>& nearest_seed, const Seeds& seeds,
                  int rmax, int base, const Spans* band, Scratch& scratch, Spans& inner) {
  const Raster& r = pass.raster;
  const int rr = pass.radius * pass.radius;
  std::vector<std::uint8_t>& outside = scratch.bytes;
  // Read on the spans only (the cells off them are outside).
  // (Through pointers: a byte written may alias a vector's, for the compiler.)
  const int* b = b2.data();
  std::uint8_t* out = outside.data();
  for_spans(band, r.h, r.w, [&](std::size_t c0, std::size_t c1) {
    for (std::size_t c = c0; c < c1; ++c) out[c] = b[c] > rr;
  });
  const double far = 2.0 * std::max(r.w, r.h) * std::max(r.w, r.h) + 4;
  // On the spans, the distances to the outside only below radius + 8 cells. The outside
  // cell nearest to a non-outside one is within radius + 1 of the points, so deeper g > 6.3
  // (left at rmax + 1): the boundary reads g within a few cells of its zero level, the
  // normals (image_normal) only whether it is above 1/2. (The full raster, without spans,
  // is not pruned: exact everywhere, as it always was.)
  const int cap_out = band ? (pass.radius + 8) * (pass.radius + 8) : int(std::min(far, double(1 << 30)));
  Buffer<int> nearest_out;
  if (band) inner = inside_spans(r, *band, out);
  Buffer<int> out2 =
      distance_transform(r, outside, cap_out, base, nearest_out, scratch, band ? &inner : nullptr, true);

  // The closing's complement is about the union of the empty discs centred on outside
  // cells y, of radius d(y) = distance from y to the nearest point. With y* the outside
  // cell nearest to x, g(x) = |x - y*| - d(y*) is the signed distance of x to that union:
  // its zero level is the boundary to a small fraction of a cell, and it passes through
  // the outermost points.
  const auto exact_d = [&](std::size_t y, int i, int j) {
    const int s = nearest_seed[y];
    if (s < 0) return float(rmax + 1);
    return float((Vec(double(i), double(j)) - seeds.mean[seeds.slot[s]]).norm());
  };
  pass.g = std::move(scratch.f);
  // Off the spans, cells are outside and farther than the reach from every point: their g
  // is read only as below -1.5 (see run_pass).
  std::fill(pass.g.begin(), pass.g.end(), -float(rmax + 1));
  for (int j = 0; j < r.h; ++j) {
    const std::size_t row = std::size_t(j) * r.w;
    // A gap's cells are outside (g as filled: they are no nearer than the reach to a
    // point) or at cap_out (inside_spans).
    if (band && inner.has_gap(j))
      std::fill(pass.g.begin() + std::ptrdiff_t(row + inner.gap_lo[j]),
                pass.g.begin() + std::ptrdiff_t(row + inner.gap_hi[j] + 1), float(rmax + 1));
    for_runs(band, j, r.w, [&](int i0, int i1) {
      // out2 is 0 at the outside cells (their own nearest) only, and cap_out wherever the
      // transform left no nearest.
      const int* o2 = out2.data() + row;
      float* g = pass.g.data() + row;
      for (int i = i0; i < i1; ++i) {
        if (o2[i] >= cap_out) {
          g[i] = float(rmax + 1);
        } else if (o2[i] == 0) {
          g[i] = std::sqrt(float(o2[i])) - exact_d(row + i, i, j);
        } else {
          const int y = nearest_out[row + i];
          g[i] = std::sqrt(float(o2[i])) - exact_d(std::size_t(y), y % r.w, y / r.w);
        }
      }
    });
  }
  return out2;
}

// The runs of fill cells (out2 > r^2) of each row, in raster order, each joined to the
// runs it touches (8-connected) in the row above: `parent` is a union-find forest.
struct Runs {
  std::vector<int> row, first, last, parent;
  int root(int k) {
    while (parent[k] != k) k = parent[k] = parent[parent[k]];
    return k;
  }
};

Runs fill_runs(const Buffer<int>& out2, int rr, const Raster& r, const Spans* band) {
  Runs runs;
  int above = 0, begin = 0;  // the runs of the row above: [above, begin)
  for (int j = 0; j < r.h; ++j) {
    const int start = int(runs.row.size());
    const std::size_t row = std::size_t(j) * r.w;
    // A gap's cells are fill cells (at the transform's cap): stepped over at once.
    const int g0 = band && band->has_gap(j) ? band->gap_lo[j] : 1;
    const int g1 = band && band->has_gap(j) ? band->gap_hi[j] : 0;
    for_spans_of_row(band, j, r.w, [&](int i0, int i1) {
      const int* o2 = out2.data() + row;
      for (int i = i0; i < i1; ++i) {
        if (o2[i] <= rr) continue;
        const int a = i;
        i = run_end(i, i1, g0, g1, [&](int c) { return o2[c] > rr; });
        const int k = int(runs.row.size());
        runs.row.push_back(j);
        runs.first.push_back(a);
        runs.last.push_back(i);
        runs.parent.push_back(k);
        while (above < begin && runs.last[above] < a - 1) ++above;
        for (int m = above; m < begin && runs.first[m] <= i + 1; ++m) {
          const int x = runs.root(m), y = runs.root(k);
          if (x != y) runs.parent[std::max(x, y)] = std::min(x, y);
        }
      }
    });
    above = start;
    begin = int(runs.row.size());
  }
  return runs;
}

// Zeroes the labels that are read: those of the cells next to the fill (trace) and of the
// cells whose g is above -1/2 (image normals). With spans (`inner`, the cells that are
// not outside), both lie on them or one cell beside them: an outside cell lies farther
// than the radius (4 cells or more) from the points' cells, more than 3 from their means,
// and its g is below -3. The other labels are left as they are, never read.
void clear_labels(const Raster& r, const Spans* inner, Buffer<int>& label) {
  if (!inner) {
    std::fill(label.begin(), label.end(), 0);
    return;
  }
  for (int j = 0; j < r.h; ++j) {
    int lo = r.w, hi = -1;
    for (int k = std::max(0, j - 1); k <= std::min(r.h - 1, j + 1); ++k) {
      lo = std::min(lo, inner->lo[k]);
      hi = std::max(hi, inner->hi[k]);
    }
    lo = std::max(0, lo - 1);
    hi = std::min(r.w - 1, hi + 1);
    if (lo <= hi) std::fill_n(label.data() + std::size_t(j) * r.w + lo, hi - lo + 1, 0);
  }
}

// 8-connected components of the fill (out2 > r^2), labelled in raster order of their
// first cell, from the rows' runs of fill cells.
void label_components(const Buffer<int>& out2, const Buffer<int>& b2, const Buffer<int>& d2,
                      const Spans* band, Scratch& scratch, Pass& pass) {
  const Raster& r = pass.raster;
  pass.label = std::move(scratch.ints);
  clear_labels(r, band, pass.label);
  Runs runs = fill_runs(out2, pass.radius * pass.radius, r, band);
  std::vector<int> id(runs.row.size(), -1);  // by root: index into pass.components
  for (std::size_t k = 0; k < runs.row.size(); ++k) {
    const int root = runs.root(int(k));
    const int j = runs.row[k], a = runs.first[k], e = runs.last[k];
    if (id[root] < 0) {
      id[root] = int(pass.components.size());
      Component comp;
      comp.label = id[root] + 1;
      comp.start = std::size_t(j) * r.w + a;
      comp.i0 = r.w;
      comp.j0 = r.h;
      pass.components.push_back(comp);
    }
    Component& comp = pass.components[id[root]];
    const std::size_t row = std::size_t(j) * r.w;
    comp.area += std::size_t(e - a + 1);
    for (std::size_t c = row + a; c <= row + e; ++c) {
      pass.label[c] = comp.label;
      comp.enclosed += b2[c] < d2[c];
    }
    comp.i0 = std::min(comp.i0, a);
    comp.i1 = std::max(comp.i1, e);
    comp.j0 = std::min(comp.j0, j);
    comp.j1 = std::max(comp.j1, j);
  }
  for (auto& comp : pass.components)
    if (!substantial(comp.enclosed)) comp.enclosed = 0;  // an open band or a fragment
}

}  // namespace

std::string num(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", x);
  return buf;
}

Error raster_too_large(double wc, double hc, double h, std::size_t max_cells) {
  return Error("morphology: a raster of " + num(wc) + " x " + num(hc) + " cells (cell " + num(h) +
               " mm) exceeds max_cells " + std::to_string(max_cells) +
               "; a larger cell makes it smaller (slice --cell)");
}

bool run_pass(const Points& points, const std::vector<std::size_t>& subset, double h,
              const MorphologyOptions& opt, Pass& pass) {
  Vec lo = points[subset[0]], hi = lo;
  for (std::size_t k : subset) {
    lo = lo.cwiseMin(points[k]);
    hi = hi.cwiseMax(points[k]);
  }
  const double span_cells = std::max(hi.x() - lo.x(), hi.y() - lo.y()) / h;
  // A radius beyond half the extent cannot close anything a smaller one would not.
  const int rmax = std::max(1, std::min(opt.max_dilation, int(span_cells / 2) + 2));
  // The raster margin. The distance d2 and the bottleneck b2 are exact on any raster that
  // holds the points: outward from a border cell the distance to every point grows, so a
  // border cell's widest path from far away is its own d2. Hence the closing radius does
  // not depend on the margin; the erosion needs the outside cells next to the band, i.e.
  // radius + 2 cells. Start with a small margin and widen it only when the radius needs it:
  // the result is that of a margin of rmax + 2, on a much smaller raster.
  int margin = std::min(rmax, 8) + 2;
  // The reach (cells): a cell farther than `reach` from every point counts as at reach + 1
  // (d2 = cap), and only the rows' spans (the cells within `reach` of the points of the
  // rows within `reach`) are computed: every cell off them is outside. The closing radius
  // (the largest at which some cell closes) is then that of the reach rmax unless some cell
  // closes only beyond `reach`, behind a gap more than 2 reach cells wide: such a cell is
  // not seen (the reach widens to rmax only when nothing closes within it). With 29 cells
  // that takes a gap of 60 cells, which the full reach closes with a radius of 60 or more.
  // The erosion reads the nearest point of the outside cells up to radius + 1 from the
  // points, the boundary (bilinear reads of g) that of those up to 2 radius + 9 (a fill
  // cell next to a non-fill one is within 2 radius + 2 of the points, the boundary moves
  // up to 5.5 cells from it): the reach widens to cover them. At the reach rmax every cell
  // is computed, as without spans.
  int reach = std::min(rmax, 29);
  Raster& r = pass.raster;
  r.cell = h;
  Seeds seeds;
  Buffer<int> nearest_seed, d2, b2;
  Scratch scratch;
  Spans spans;
  const Spans* band = nullptr;
  for (;;) {
    place_raster(lo, hi, h, margin, opt.max_cells, r);
    seed_cells(points, subset, r, scratch.bytes, seeds);
    const SeedGaps gaps = seed_gaps(r, seeds.cells, reach);
    spans = spans_of(r, seeds.first, seeds.last, reach, &gaps);
    band = reach < rmax ? &spans : nullptr;
    const int cap = (reach + 1) * (reach + 1);
    d2 = distance_transform(r, scratch.bytes, cap, rmax + 2 - margin, nearest_seed, scratch, band);
    b2 = bottleneck(r, d2, cap, scratch.ints, band);
    const int rc = closing_radius(d2, b2, cap, reach, r.w, band);
    if (rc == 0 && reach < rmax) {
      reach = rmax;
      continue;
    }
    if (rc == 0) return false;
    pass.closing = rc;
    // Margin: twice the closing radius (at least 4 cells). A disc just able to bridge a gap
    // dips into it by about its radius and may cut a thin trailing edge in two; a disc twice
    // as large dips by a quarter of that.
    pass.radius = std::min(std::max(2 * rc, 4), rmax);
    const int need = std::min(rmax, 2 * pass.radius + 9);
    if (pass.radius + 2 <= margin && need <= reach) break;
    margin = std::max(margin, pass.radius + 2);
    reach = std::max(reach, need);
  }
  Spans inner;
  const Buffer<int> out2 =
      erode(pass, b2, nearest_seed, seeds, rmax, rmax + 2 - margin, band, scratch, inner);
  label_components(out2, b2, d2, band ? &inner : nullptr, scratch, pass);
  return true;
}

Points outline(const Pass& pass, const Component& comp) {
  Points b = trace(pass.raster, pass.label, comp.label, comp.start);
  if (b.size() < 3) return {};
  if (signed_area(b) < 0) std::reverse(b.begin(), b.end());
  smooth_closed(b, 2);
  return b;
}

/// The boundary of one component in world coordinates, counterclockwise: the Moore trace
/// smoothed a little, then each vertex moved along its normal onto the zero level of g.
Points component_boundary(const Pass& pass, const Component& comp) {
  Points b = outline(pass, comp);
  if (b.empty()) return {};
  for (int it = 0; it < 3; ++it) {
    Points moved = b;
    for (std::size_t i = 0; i < b.size(); ++i) {
      const Vec n = vertex_normal(b, i);
      const double shift = std::clamp(bilinear(pass.raster, pass.g, b[i]), -1.5, 1.5);
      moved[i] = b[i] + shift * n;
    }
    b.swap(moved);
  }
  smooth_closed(b, 1);
  for (Vec& p : b) p = pass.raster.to_world(p);
  return b;
}

ImageNormals::ImageNormals(const Pass& pass, int label_id, double sigma)
    : pass_(pass),
      label_(label_id),
      k_(int(std::ceil(3 * sigma))),
      inv_(1 / (2 * sigma * sigma)),
      shrink_(std::exp(-2 * inv_)),
      i0_(std::numeric_limits<int>::min()),
      j0_(0),
      column_(std::size_t(4 * k_ * k_)),
      row_end_(std::size_t(2 * k_)),
      cover_(std::size_t(4 * k_ * k_)) {}

Vec ImageNormals::at(const Vec& p) {
  const Raster& r = pass_.raster;
  const Vec c = r.to_cell(p);
  const int k = k_;
  const int i0 = floor_int(c.x()) - k + 1, j0 = floor_int(c.y()) - k + 1;
  const int n = 2 * k;
  // The offsets p - c of the window's columns and rows (tx, ty) and their weights: with t
  // falling by 1 a step, exp(-t^2 q) is the previous weight times exp((2t - 1) q), whose
  // factor shrinks by exp(-2 q) a step: two exp calls per axis, not one per cell.
  double gx[64], gy[64], tx[64], ty[64];
  const double inv = inv_, shrink = shrink_;
  const auto weights = [&](double t0, double* t, double* g) {
    double w = std::exp(-t0 * t0 * inv), f = std::exp((2 * t0 - 1) * inv), da = 0;
    for (int a = 0; a < n; ++a, da += 1) {  // da = a, exactly
      t[a] = t0 - da;
      g[a] = w;
      w *= f;
      f *= shrink;
    }
  };
  weights(c.x() - i0, tx, gx);
  weights(c.y() - j0, ty, gy);
  // The window clipped to the raster (cells off it are left out).
  const int a0 = std::max(0, -i0), a1 = std::min(n, r.w - i0);
  const int b0 = std::max(0, -j0), b1 = std::min(n, r.h - j0);
  // Summed per coordinate: a Vec built per cell went through the stack, and its packed
  // reload waited on the two stores (the same sums, several times slower).
  double gx_sum = 0, gy_sum = 0;
  int* const column = column_.data();
  int* const row_end = row_end_.data();
  double* const cover = cover_.data();
  if (i0 == i0_ && j0 == j0_) {  // the cells of the window before, in the same order
    for (int b = b0, m = 0; b < b1; ++b) {
      const double gyb = gy[b], tyb = ty[b];
      for (const int end = row_end[b]; m < end; ++m) {
        const int a = column[m];
        const double wgt = cover[m] * gx[a] * gyb;
        gx_sum += wgt * tx[a];
        gy_sum += wgt * tyb;
      }
    }
  } else {
    i0_ = i0;
    j0_ = j0;
    for (int b = b0, m = 0; b < b1; ++b) {
      const std::size_t row = std::size_t(j0 + b) * r.w;
      const int* label = pass_.label.data() + row;
      const float* dist = pass_.g.data() + row;
      for (int a = a0; a < a1; ++a) {
        const int i = i0 + a;
        if (!(dist[i] > -0.5f)) continue;  // no cover (1/2 + g <= 0), whatever the label
        const int l = label[i];
        if (l != label_ && l != 0) continue;
        const double cv = std::min(0.5 + double(dist[i]), 1.0);  // clamp(.., 0, 1): above 0 here
        column[m] = a;
        cover[m++] = cv;
        const double wgt = cv * gx[a] * gy[b];
        gx_sum += wgt * tx[a];
        gy_sum += wgt * ty[b];
      }
      row_end[b] = m;
    }
  }
  const Vec g(gx_sum, gy_sum);
  const double l = g.norm();
  return l > 1e-12 ? Vec(g / l) : Vec(0, 0);
}

double signed_area(const Points& p) {
  double a = 0;
  for (std::size_t i = 0, n = p.size(); i < n; ++i) {
    const Vec& u = p[i];
    const Vec& v = p[(i + 1) % n];
    a += u.x() * v.y() - v.x() * u.y();
  }
  return a / 2;
}

}  // namespace section::morph

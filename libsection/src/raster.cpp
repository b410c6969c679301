// SPDX-License-Identifier: GPL-3.0-or-later
#include "raster.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

namespace section::morph {

namespace {

/// The lower envelope's parabolas: the sample of each (v), where it starts (z, one more)
/// and its height at the origin, f + (q + base)^2 (h, kept so as not to be computed again).
struct Envelope {
  std::vector<int> v;
  std::vector<double> z, h;
  explicit Envelope(int n) : v(n + 1), z(n + 2), h(n + 1) {}
};

/// The height at the origin of sample q's parabola.
inline double fq_of(const float* f, int q, int base) {
  return double(f[q]) + double(q + base) * (q + base);
}

/// Felzenszwalb-Huttenlocher 1D squared distance transform of f (n samples): emit(q0, q1, s,
/// fs) for each run of samples q0..q1 whose nearest sample is s (-1 and fs = `big` when
/// none), fs = f[s]: sample q lies (q - s)^2 + fs from it. By runs, so that what depends on
/// s only is worked out once per run.
/// Samples with f >= `big` (no seed in their column) are left out of the lower envelope:
/// they never win, and the envelope of the others is the same; those before `first` and
/// after `last` must be such samples (they are not read). Positions are q + base, so
/// that the rounding of the parabola intersections, which decides between equidistant
/// seeds, does not depend on where the raster starts (its margin).
template <class Emit>
void envelope_1d(const float* f, int n, int first, int last, float big, int base, Envelope& e,
                 const Emit& emit) {
  const double inf = std::numeric_limits<double>::infinity();
  int* v = e.v.data();
  double* z = e.z.data();
  double* h = e.h.data();
  int k = -1, q = first;
  for (; q <= last; ++q) {  // the first kept sample
    if (!(f[q] < big)) continue;
    k = 0;
    v[0] = q;
    h[0] = fq_of(f, q, base);
    z[0] = -inf;
    break;
  }
  for (++q; q <= last; ++q) {
    if (!(f[q] < big)) continue;
    const double fq = fq_of(f, q, base);
    double s;
    for (;;) {  // s is finite (q > v[k]) and z[0] = -inf: k never drops below 0
      s = (fq - h[k]) / (2.0 * (q - v[k]));
      if (s > z[k]) break;
      --k;
    }
    ++k;
    v[k] = q;
    h[k] = fq;
    z[k] = s;
  }
  z[k + 1] = inf;
  if (k < 0) {
    emit(0, n - 1, -1, double(big));
    return;
  }
  // Parabola k is the lowest for the samples q with z[k] < q + base <= z[k + 1]: up to
  // floor(z[k + 1]) - base, clamped to -1..n - 1.
  const double zlo = double(base), zhi = double(base + n - 1);
  for (int q = 0, k = 0; q < n; ++k) {
    const double zk = z[k + 1];
    int end = n - 1;
    if (zk < zlo) {
      end = -1;
    } else if (zk < zhi) {
      end = floor_int(zk) - base;
    }
    if (q > end) continue;
    emit(q, end, v[k], double(f[v[k]]));
    q = end + 1;
  }
}

/// The least m >= 0 with float(m) * float(m) >= prune (that square grows with m), at most
/// `none`: the column distances pruned are those of m rows or more.
int first_pruned(float prune, int none) {
  if (!(prune < 1e18f)) return none;
  long long m = std::llround(std::sqrt(double(prune)));
  while (m > 0 && float(m - 1) * float(m - 1) >= prune) --m;
  while (float(m) * float(m) < prune) ++m;
  return int(std::min<long long>(m, none));
}

/// The columns' part of distance_transform: row_of holds, on the spans, the row of the
/// nearest seed in the cell's column (when none, a row far off), found by one sweep each way over whole
/// rows (cache friendly), and f its squared distance (1e20 when none or at least `prune`).
/// With off_seeds, the cells off the spans are seeds too.
void column_sweeps(const Raster& r, const std::vector<std::uint8_t>& seed, const Spans* spans, bool off_seeds,
                   float prune, Buffer<int>& row_of, Buffer<float>& f) {
  const int w = r.w, h = r.h;
  // Row k's off-span cells are seeds for the columns of row j's span (k = j -+ 1).
  const auto enter = [&](int j, int k, std::vector<int>& last) {
    if (off_seeds && spans && k >= 0 && k < h)
      each_beside_off_span(*spans, j, k, [&](int i) { last[i] = k; });
  };
  // Branch-free loops over raw pointers (a select, not a branch, per cell). A column with
  // no seed on one side has one `far_row` rows off (cell indices are ints, and the raster's
  // margin makes w > 4, so h < 2^29): farther than every real one, with no select for it.
  const int far_row = 1 << 30;
  std::vector<int> last(w, -far_row);
  for (int j = 0; j < h; ++j) {
    const std::uint8_t* srow = seed.data() + std::size_t(j) * w;
    int* arow = row_of.data() + std::size_t(j) * w;
    int* lrow = last.data();
    enter(j, j - 1, last);
    // The gap's cells are no seeds: `last` passes through them as it is.
    for_runs(spans, j, w, [&](int i0, int i1) {
      for (int i = i0; i < i1; ++i) {
        const int l = srow[i] ? j : lrow[i];
        lrow[i] = l;
        arow[i] = l;
      }
    });
  }
  std::fill(last.begin(), last.end(), far_row);
  const int far = std::min(first_pruned(prune, far_row), far_row / 2);  // every real distance < h
  const float big = 1e20f;
  std::int32_t big_bits;
  std::memcpy(&big_bits, &big, sizeof big_bits);
  for (int j = h - 1; j >= 0; --j) {
    const std::uint8_t* srow = seed.data() + std::size_t(j) * w;
    int* arow = row_of.data() + std::size_t(j) * w;
    int* lrow = last.data();
    float* frow = f.data() + std::size_t(j) * w;
    enter(j, j + 1, last);
    for_runs(spans, j, w, [&](int i0, int i1) {
      for (int i = i0; i < i1; ++i) {
        const int below = srow[i] ? j : lrow[i];
        lrow[i] = below;
        const int above = arow[i];
        // The nearer seed, the one above on a tie (the lower index); a far row when none.
        // Integer selects of this form only, so that the loop is vectorised (GCC keeps a
        // branch for a float compare, or a select of floats).
        const int da = j - above, db = below - j;
        const int s = da <= db ? above : below;
        arow[i] = s;
        // 1e20 from `far` rows on (and when none), by a mask on the float's bits.
        const std::int32_t pruned = -std::int32_t((da <= db ? da : db) >= far);
        const float fs = float(j - s) * float(j - s);
        std::int32_t bits;
        std::memcpy(&bits, &fs, sizeof bits);
        bits = (bits & ~pruned) | (big_bits & pruned);
        std::memcpy(frow + i, &bits, sizeof bits);
      }
    });
    // The gap's cells lie farther than the cap from every seed: pruned (an envelope that
    // runs into the gap reads them; row_of is read at kept samples only).
    if (spans && spans->has_gap(j)) std::fill(frow + spans->gap_lo[j], frow + spans->gap_hi[j] + 1, big);
  }
}

/// The rows' part of distance_transform: the envelope of each row's column distances f
/// (1e20: none, or pruned), into d (clamped to cap) and nearest.
struct RowPass {
  const Raster& r;
  const Buffer<float>& f;
  const Buffer<int>& row_of;
  int cap, base;
  bool prune;
  Buffer<int>& d;
  Buffer<int>& nearest;
  int near = ceil_sqrt(cap);  // (near - 1)^2 < cap <= near^2
  int n = std::max(r.w, r.h);
  Envelope e = Envelope(n);

  // Cells i0..i1 - 1 of row j as seeds (0, their own index) or at cap (none).
  void off(int j, int i0, int i1, bool seeds) {
    const std::size_t row = std::size_t(j) * r.w;
    for (int i = i0; i < i1; ++i) {
      d[row + i] = seeds ? 0 : cap;
      nearest[row + i] = seeds ? int(row + i) : -1;
    }
  }

  // The envelope over cells a..b of row j. It picks the nearest sample exactly (the lowest
  // on a tie): the intersections are quotients of exact integers, correctly rounded, and
  // distinct ones lie far beyond rounding apart. So the envelope of any part of a row that
  // holds a cell's nearest sample gives the cell what the whole row's does.
  // The samples of cells a..b off first..last are pruned.
  void stretch(int j, int a, int b, int first, int last) {
    const std::size_t row = std::size_t(j) * r.w;
    const float big = 1e20f;
    // Locals, not members: the stores to d would otherwise reload them (they may alias,
    // for the compiler) at every run and every cell.
    int* const dc = d.data() + row + a;
    int* const nc = nearest.data() + row + a;
    const int* const of = row_of.data() + row + a;
    const int c = cap, w = r.w;
    envelope_1d(f.data() + row + a, b - a + 1, first - a, last - a, big, base + a, e,
                [=](int q0, int q1, int s, double fs) {
                  if (s < 0) {  // no seed: `big`, beyond cap
                    std::fill(dc + q0, dc + q1 + 1, c);
                    std::fill(nc + q0, nc + q1 + 1, -1);
                    return;
                  }
                  const int to = of[s] * w + a + s;
                  // fs, a kept sample's, is a squared integer: every cell gets `to`.
                  if (c <= (1 << 23)) {
                    // (q - s)^2 + fs in integers: the float below is exact up to 2^23, and beyond it is
                    // at cap (the same values, a third of the instructions). `to` in the same loop: the
                    // runs are short (3-4 cells), a fill of its own costs more than its stores.
                    long long v = (long long)(q0 - s) * (q0 - s) + (long long)(fs), step = 2LL * (q0 - s) + 1;
                    for (int q = q0; q <= q1; ++q, v += step, step += 2) {
                      dc[q] = v < c ? int(v) : c;
                      nc[q] = to;
                    }
                    return;
                  }
                  std::fill(nc + q0, nc + q1 + 1, to);
                  for (int q = q0; q <= q1; ++q) {
                    const double dq = double(q - s);
                    const float o = float(dq * dq + fs);
                    // Squared distances are integers (exact in float below 2^24, and every float above
                    // 2^23 is an integer): rounding is a truncation of x + 0.5.
                    dc[q] = o >= float(c) ? c : int(o + 0.5f);
                  }
                });
  }

  // The first kept sample of row j at column i or after, up to hi (hi + 1: none); the
  // cells of the gap g0..g1 are pruned, and not read.
  int next_kept(const float* frow, int i, int hi, int g0, int g1) const {
    if (i >= g0 && i <= g1) i = g1 + 1;
    const int stop = i < g0 ? std::min(hi, g0 - 1) : hi;
    for (; i <= stop; ++i)
      if (frow[i] < 1e20f) return i;
    return stop < hi ? next_kept(frow, g1 + 1, hi, g0, g1) : hi + 1;
  }

  // Cells lo..hi of row j: the envelope of all unless pruned. Pruned, a kept sample brings
  // below cap only the cells closer than `near` to it: the clusters of kept samples are done
  // apart, each with its cells that close (the envelope of a cluster's samples is the row's
  // there), and the rest is at cap. Cells g0..g1 (a gap of the spans, if g0 <= g1) are
  // pruned samples.
  void part(int j, int lo, int hi, int g0, int g1) {
    if (!prune) {
      stretch(j, lo, hi, lo, hi);
      return;
    }
    const float* frow = f.data() + std::size_t(j) * r.w;
    if (g0 > g1) g0 = g1 = std::numeric_limits<int>::max();  // no gap: never reached
    int done = lo;  // the cells before are written (the clusters' stretches are disjoint)
    for (int i = next_kept(frow, lo, hi, g0, g1); i <= hi;) {
      int last = i;
      for (int k = i + 1, end = std::min(hi, i + 2 * near - 2); k <= end; ++k)
        if (frow[k] < 1e20f) last = k, end = std::min(hi, k + 2 * near - 2);
      const int a = std::max(lo, i - near + 1), b = std::min(hi, last + near - 1);
      off(j, done, a, false);
      stretch(j, a, b, i, last);
      done = b + 1;
      i = next_kept(frow, last + 2 * near - 1, hi, g0, g1);  // the scan above found none before
    }
    off(j, done, hi + 1, false);
  }
};

}  // namespace

SeedGaps seed_gaps(const Raster& r, const std::vector<std::size_t>& cells, int reach) {
  SeedGaps g;
  g.a.assign(r.h, 0);
  g.b.assign(r.h, 0);
  // Only a gap of 2 reach + 2 columns or more leaves a cell to spans_of (which takes reach
  // + 1 off each end), and its 2 reach + 1 empty columns hold a whole block of reach + 1:
  // the seeds of the rows within `reach` (a sliding window) are counted by column and by
  // block, and a row's gaps are looked for about its runs of empty blocks only.
  const std::size_t w = std::size_t(r.w);
  const int bs = reach + 1, blocks = (r.w + bs - 1) / bs;
  std::vector<int> column(w, 0), block(std::size_t(blocks), 0);
  std::size_t in = 0, out = 0;  // cells[out, in): the window's seeds
  for (int k = 0; k < r.h; ++k) {
    for (; in < cells.size() && int(cells[in] / w) <= k + reach; ++in) {
      ++column[cells[in] % w];
      ++block[cells[in] % w / std::size_t(bs)];
    }
    for (; out < in && int(cells[out] / w) < k - reach; ++out) {
      --column[cells[out] % w];
      --block[cells[out] % w / std::size_t(bs)];
    }
    for (int q = 0, widest = 0; q < blocks; ++q) {
      if (block[std::size_t(q)]) continue;
      const int q0 = q;
      while (q + 1 < blocks && !block[std::size_t(q) + 1]) ++q;
      // The seed columns next to the run of empty blocks q0..q (-1, w: none).
      int a = q0 * bs - 1, b = (q + 1) * bs;
      while (a >= 0 && !column[std::size_t(a)]) --a;
      while (b < r.w && !column[std::size_t(b)]) ++b;
      if (a >= 0 && b < r.w && b - a > widest) widest = b - a, g.a[k] = a, g.b[k] = b;
    }
  }
  return g;
}

Spans spans_of(const Raster& r, const std::vector<int>& first, const std::vector<int>& last, int reach,
               const SeedGaps* gaps) {
  Spans s;
  s.lo.assign(r.h, r.w);
  s.hi.assign(r.h, -1);
  // A seed dy rows away is within `reach` of the cells up to e[dy] columns from it: the
  // discs, not their squares (a tenth fewer cells than squares on a blade).
  std::vector<int> e(std::size_t(reach) + 1);
  for (int dy = 0; dy <= reach; ++dy) {
    int x = ceil_sqrt((reach + 1) * (reach + 1) - dy * dy);  // x^2 + dy^2 >= (reach + 1)^2
    e[std::size_t(dy)] = x - 1;
  }
  for (int j = 0; j < r.h; ++j) {
    if (first[j] > last[j]) continue;
    for (int k = std::max(0, j - reach), k1 = std::min(r.h - 1, j + reach); k <= k1; ++k) {
      const int ek = e[std::size_t(std::abs(k - j))];
      s.lo[k] = std::min(s.lo[k], std::max(0, first[j] - ek));
      s.hi[k] = std::max(s.hi[k], std::min(r.w - 1, last[j] + ek));
    }
  }
  if (!gaps) return s;
  // Row k's gap: the columns more than `reach` beyond the widest gap's ends of every row
  // with seeds within `reach` rows (the seeds of row j lie at or before a[j] or at or after
  // b[j]), within the spans of rows k - 1 and k + 1.
  s.gap_lo.assign(r.h, 1);
  s.gap_hi.assign(r.h, 0);
  for (int k = 1; k + 1 < r.h; ++k) {
    const int lo = std::max({s.lo[k] + 1, s.lo[k - 1], s.lo[k + 1], gaps->a[k] + reach + 1});
    const int hi = std::min({s.hi[k] - 1, s.hi[k - 1], s.hi[k + 1], gaps->b[k] - reach - 1});
    if (lo > hi) continue;
    s.gap_lo[k] = lo;
    s.gap_hi[k] = hi;
  }
  return s;
}

Buffer<int> distance_transform(const Raster& r, const std::vector<std::uint8_t>& seed, int cap, int base,
                               Buffer<int>& nearest, Scratch& scratch, const Spans* spans, bool off_seeds) {
  const float big = 1e20f;
  const int w = r.w, h = r.h;
  Buffer<float>& f = scratch.f;
  Buffer<int>& row_of = scratch.ints;
  f.resize(r.size());  // both written in full (on the spans) by the sweeps
  row_of.resize(r.size());
  // With spans, a column's sample at cap or beyond is left out of the rows' envelopes: it
  // brings no cell below cap.
  const bool prune = spans != nullptr;
  column_sweeps(r, seed, spans, off_seeds, prune ? float(cap) : big, row_of, f);
  Buffer<int> d(r.size());  // d and nearest: every cell written below
  nearest.resize(r.size());
  RowPass rows{r, f, row_of, cap, base, prune, d, nearest};
  for (int j = 0; j < h; ++j) {
    const std::size_t row = std::size_t(j) * w;
    int lo = spans ? spans->lo[j] : 0, hi = spans ? spans->hi[j] : w - 1;
    if (spans && off_seeds && lo <= hi) {
      // The off-span cells next to the span are seeds: the row's zeros that bound its runs.
      if (lo > 0) row_of[row + --lo] = j, f[row + lo] = 0;
      if (hi < w - 1) row_of[row + ++hi] = j, f[row + hi] = 0;
    }
    // Cells off the span (seeds or at cap).
    rows.off(j, 0, std::min(lo, w), off_seeds);
    rows.off(j, std::max(lo, hi + 1), w, off_seeds);
    if (lo > hi) continue;
    const bool gap = spans && spans->has_gap(j);
    const int g0 = gap ? spans->gap_lo[j] : 1, g1 = gap ? spans->gap_hi[j] : 0;
    if (!off_seeds) {
      rows.part(j, lo, hi, g0, g1);
      continue;
    }
    // Dense seeds (the erosion's outside): a seed is its own nearest, and the nearest of the
    // cells between two seeds is one of them or between them (see stretch), so only the runs
    // between seeds are transformed, each with the seeds that bound it; the rest costs a write.
    const float* frow = f.data() + row;
    for (int i = lo; i <= hi;) {
      if (frow[i] == 0) {  // a run of seeds (the gap holds none)
        int e = i + 1;
        while (e <= hi && frow[e] == 0) ++e;
        rows.off(j, i, e, true);
        i = e;
        continue;
      }
      // (The gap holds no seed.)
      const int b = run_end(i <= g1 && i >= g0 ? g1 : i, hi + 1, g0, g1, [&](int c) { return frow[c] != 0; });
      rows.part(j, std::max(lo, i - 1), std::min(hi, b + 1), g0, g1);
      i = b + 2;  // b + 1, a seed, was done with the run
    }
  }
  return d;
}

int ceil_sqrt(int x) {
  int s = int(std::sqrt(double(x)));
  while (s * s < x) ++s;
  while (s > 0 && (s - 1) * (s - 1) >= x) --s;
  return s;
}

double bilinear(const Raster& r, const Buffer<float>& f, const Vec& c) {
  const double x = std::clamp(c.x(), 0.0, double(r.w - 1) - 1e-9);
  const double y = std::clamp(c.y(), 0.0, double(r.h - 1) - 1e-9);
  const int i = int(x), j = int(y);
  const double fx = x - i, fy = y - j;
  const std::size_t a = std::size_t(j) * r.w + i;
  return (1 - fy) * ((1 - fx) * f[a] + fx * f[a + 1]) + fy * ((1 - fx) * f[a + r.w] + fx * f[a + r.w + 1]);
}

Points trace(const Raster& r, const Buffer<int>& label, int label_id, std::size_t start) {
  static const int dx[8] = {1, 1, 0, -1, -1, -1, 0, 1};
  static const int dy[8] = {0, 1, 1, 1, 0, -1, -1, -1};
  const auto dir_of = [](int x, int y) {
    for (int k = 0; k < 8; ++k)
      if (dx[k] == x && dy[k] == y) return k;
    return 0;
  };
  const auto fg = [&](int i, int j) {
    return i >= 0 && j >= 0 && i < r.w && j < r.h && label[std::size_t(j) * r.w + i] == label_id;
  };
  const int si = int(start % r.w), sj = int(start / r.w);
  Points out;
  out.emplace_back(si, sj);
  int pi = si, pj = sj, back = 4;  // the west neighbour of the first cell is background
  int first_dir = -1;
  const std::size_t limit = 8 * r.size() + 16;
  for (std::size_t step = 0; step < limit; ++step) {
    int found = -1;
    for (int k = 1; k <= 8; ++k) {
      const int d = (back - k + 16) % 8;
      if (fg(pi + dx[d], pj + dy[d])) {
        found = d;
        break;
      }
    }
    if (found < 0) break;  // a single cell
    if (pi == si && pj == sj) {
      if (first_dir < 0)
        first_dir = found;
      else if (found == first_dir)
        break;
    }
    const int c = (found + 1) % 8;  // last background neighbour checked
    const int qi = pi + dx[found], qj = pj + dy[found];
    back = dir_of(pi + dx[c] - qi, pj + dy[c] - qj);
    pi = qi;
    pj = qj;
    if (pi == si && pj == sj) continue;  // closing back at the start: not stored twice
    out.emplace_back(pi, pj);
  }
  return out;
}

}  // namespace section::morph

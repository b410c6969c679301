#include "section/morphology.h"

#include "section/error.h"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
#include <numeric>
#include <queue>
#include <string>
#include <utility>

namespace section {

namespace {

using Vec = Eigen::Vector2d;
using Points = std::vector<Vec>;

std::string num(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", x);
  return buf;
}

// ---------------------------------------------------------------------------------------
// Uniform hash grid over a subset of points (cells sorted by key, one lookup per cell).

// Shifted as unsigned: shifting a negative cell index left is undefined (UBSan, robustness).
std::int64_t cell_key(std::int64_t i, std::int64_t j) {
  return static_cast<std::int64_t>((static_cast<std::uint64_t>(i) << 32) ^ (static_cast<std::uint64_t>(j) & 0xffffffffULL));
}

/// The [begin, end) ranges of the occupied cells of a grid in a list sorted by cell key:
/// an open-addressing table, as grid queries look up several cells each (cheaper than
/// std::unordered_map's modulo and node chase).
class CellTable {
public:
  /// `keys` sorted; each run of equal keys is one cell.
  explicit CellTable(const std::vector<std::int64_t>& keys) {
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

  /// The range of cell `key`, empty when the cell holds nothing.
  std::pair<std::uint32_t, std::uint32_t> find(std::int64_t key) const {
    for (std::size_t i = home(key);; i = (i + 1) & mask_) {
      const Slot& s = slots_[i];
      if (s.end == 0) return {0, 0};
      if (s.key == key) return {s.begin, s.end};
    }
  }

private:
  struct Slot {
    std::int64_t key = 0;
    std::uint32_t begin = 0, end = 0;  // end 0: a free slot (a cell's range is never empty)
  };
  // Fibonacci hashing: the top shift_ (>= 4) bits of key * 2^64 / phi.
  std::size_t home(std::int64_t key) const {
    return std::size_t((std::uint64_t(key) * 0x9E3779B97F4A7C15ULL) >> (64 - shift_));
  }
  std::vector<Slot> slots_;
  std::size_t mask_ = 0;
  int shift_ = 0;
};

class PointGrid {
public:
  PointGrid(const Points& points, const std::vector<std::size_t>& subset, double cell)
      : points_(points), cell_(cell) {
    std::vector<std::pair<std::int64_t, std::uint32_t>> keyed;
    keyed.reserve(subset.size());
    for (std::size_t k : subset) keyed.emplace_back(key_of(points[k]), std::uint32_t(k));
    std::sort(keyed.begin(), keyed.end());
    std::vector<std::int64_t> keys(keyed.size());
    order_.resize(keyed.size());
    for (std::size_t a = 0; a < keyed.size(); ++a) {
      keys[a] = keyed[a].first;
      order_[a] = keyed[a].second;
    }
    cells_ = CellTable(keys);
  }

  std::int64_t ix(double x) const { return std::int64_t(std::floor(x / cell_)); }
  std::int64_t key_of(const Vec& p) const { return cell_key(ix(p.x()), ix(p.y())); }

  /// Calls f(index) for the points of cell (i, j).
  template <class F> void visit(std::int64_t i, std::int64_t j, F&& f) const {
    const auto [begin, end] = cells_.find(cell_key(i, j));
    for (std::uint32_t a = begin; a < end; ++a) f(order_[a]);
  }

  /// Distance from point k to its nearest other point at a positive distance, searching
  /// rings of cells up to `max_ring`; infinity when none is found.
  double nearest(std::size_t k, int max_ring) const {
    const Vec& p = points_[k];
    const std::int64_t ci = ix(p.x()), cj = ix(p.y());
    double best2 = std::numeric_limits<double>::infinity();
    for (int ring = 0; ring <= max_ring; ++ring) {
      for (std::int64_t j = cj - ring; j <= cj + ring; ++j)
        for (std::int64_t i = ci - ring; i <= ci + ring; ++i) {
          if (std::max(std::abs(i - ci), std::abs(j - cj)) != ring) continue;
          visit(i, j, [&](std::uint32_t q) {
            const double d2 = (points_[q] - p).squaredNorm();
            if (d2 > 0 && d2 < best2) best2 = d2;
          });
        }
      // Every point of a farther ring is at least `ring` cells away.
      if (best2 <= (ring * cell_) * (ring * cell_)) break;
    }
    return std::sqrt(best2);
  }

  /// True when point k has another point (a different index) within `radius` <= cell.
  bool has_neighbour(std::size_t k, double radius) const {
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

private:
  const Points& points_;
  double cell_;
  std::vector<std::uint32_t> order_;
  CellTable cells_{{}};
};

/// Bounding box of a subset cut at the given quantiles (robust to a few far outliers).
void robust_box(const Points& points, const std::vector<std::size_t>& subset, double q,
                Vec& lo, Vec& hi) {
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

double median_spacing(const Points& points, const std::vector<std::size_t>& subset,
                      std::size_t sample) {
  if (subset.size() < 2) return 0;
  Vec lo, hi;
  robust_box(points, subset, 0.005, lo, hi);
  const double diag = (hi - lo).norm();
  if (!(diag > 0)) {
    robust_box(points, subset, 0, lo, hi);
    if (!((hi - lo).norm() > 0)) return 0;
  }
  // Section points lie along curves: about n / 2 cells along a curve of length ~2 diag
  // would hold one point each; n^0.75 keeps a few points per cell on dense sections.
  const double cell = std::max(diag, (hi - lo).norm()) / std::pow(double(subset.size()), 0.75);
  const PointGrid grid(points, subset, cell);
  const std::size_t step = std::max<std::size_t>(1, subset.size() / std::max<std::size_t>(1, sample));
  std::vector<double> d;
  for (std::size_t a = 0; a < subset.size(); a += step) {
    const double x = grid.nearest(subset[a], 64);
    if (std::isfinite(x)) d.push_back(x);
  }
  if (d.empty()) return 0;
  std::nth_element(d.begin(), d.begin() + d.size() / 2, d.end());
  return d[d.size() / 2];
}

// ---------------------------------------------------------------------------------------
// Raster: cell (i, j) has its centre at (x0 + i h, y0 + j h); index j * w + i.

struct Raster {
  int w = 0, h = 0;
  double x0 = 0, y0 = 0, cell = 1;
  std::size_t size() const { return std::size_t(w) * std::size_t(h); }
  Vec to_cell(const Vec& p) const { return {(p.x() - x0) / cell, (p.y() - y0) / cell}; }
  Vec to_world(const Vec& c) const { return {x0 + c.x() * cell, y0 + c.y() * cell}; }
};

/// Felzenszwalb-Huttenlocher 1D squared distance transform of f (n samples) into d.
/// Samples with f >= `big` (no seed in their column) are left out of the lower envelope:
/// they never win, and the envelope of the others is the same. Positions are q + base, so
/// that the rounding of the parabola intersections, which decides between equidistant
/// seeds, does not depend on where the raster starts (its margin).
void envelope_1d(const float* f, int n, float big, int base, float* d, int* arg, std::vector<int>& v,
                 std::vector<double>& z) {
  const double inf = std::numeric_limits<double>::infinity();
  int k = -1;
  for (int q = 0; q < n; ++q) {
    if (!(f[q] < big)) continue;
    const double fq = double(f[q]) + double(q + base) * (q + base);
    if (k < 0) {
      k = 0;
      v[0] = q;
      z[0] = -inf;
      z[1] = inf;
      continue;
    }
    double s;
    for (;;) {
      const int p = v[k];
      s = (fq - (double(f[p]) + double(p + base) * (p + base))) / (2.0 * (q - p));
      if (s > z[k] || k == 0) break;  // z[0] = -inf: k never drops below 0
      --k;
    }
    ++k;
    v[k] = q;
    z[k] = s;
    z[k + 1] = inf;
  }
  if (k < 0) {
    for (int q = 0; q < n; ++q) {
      d[q] = big;
      arg[q] = -1;
    }
    return;
  }
  k = 0;
  for (int q = 0; q < n; ++q) {
    while (z[k + 1] < q + base) ++k;
    const double dq = double(q - v[k]);
    d[q] = float(dq * dq + double(f[v[k]]));
    arg[q] = v[k];
  }
}

/// envelope_1d of f split at its zero samples (seeds in the sample's own cell). A zero
/// sample is its own nearest, and no parabola on one side of it wins on the other (their
/// intersections with it lie at least half a cell away, far beyond rounding), so the
/// envelope of a run between two zeros, zeros included, is the whole row's there, with the
/// same arithmetic. Runs of seeds then cost nothing: most of a raster is outside.
void distance_1d(const float* f, int n, float big, int base, float* d, int* arg, std::vector<int>& v,
                 std::vector<double>& z) {
  for (int a = 0; a < n;) {
    if (f[a] == 0) {
      d[a] = 0;
      arg[a] = a;
      ++a;
      continue;
    }
    int b = a + 1;
    while (b < n && f[b] != 0) ++b;
    const int lo = a > 0 ? a - 1 : 0, hi = b < n ? b + 1 : n;
    envelope_1d(f + lo, hi - lo, big, base + lo, d + lo, arg + lo, v, z);
    for (int q = lo; q < hi; ++q)
      if (arg[q] >= 0) arg[q] += lo;
    a = b;
  }
}

/// Raster-sized buffers handed from step to step of one pass: each fresh page costs a page
/// fault (the kernel zeroes it), more than most steps' own work on it.
struct Scratch {
  std::vector<float> f;
  std::vector<int> ints;
  std::vector<std::uint8_t> bytes;
};

/// Exact squared Euclidean distance (in cells^2) of every cell to the nearest seed cell,
/// clamped to `cap`, and that seed's cell index in `nearest` (-1 when there is no seed).
/// `seed` is 1 at seeds. `base` is added to the cell indices in the parabola arithmetic
/// (see distance_1d). Between equidistant seeds the one of lower index wins, as in
/// the envelope of the columns.
/// Uses scratch.f and scratch.ints (not scratch.bytes, which may hold `seed`).
std::vector<int> distance_transform(const Raster& r, const std::vector<std::uint8_t>& seed, int cap, int base,
                                    std::vector<int>& nearest, Scratch& scratch) {
  const float big = 1e20f;
  const int w = r.w, h = r.h;
  // Columns: with 0/1 seeds the 1D transform is the distance to the nearest seed above or
  // below, found by one sweep each way over whole rows (cache friendly).
  std::vector<float>& f = scratch.f;
  std::vector<int>& row_of = scratch.ints;
  f.resize(r.size());  // both written in full by the sweeps below
  row_of.resize(r.size());
  {
    std::vector<int> last(w, -1);
    for (int j = 0; j < h; ++j) {
      const std::uint8_t* srow = seed.data() + std::size_t(j) * w;
      int* arow = row_of.data() + std::size_t(j) * w;
      for (int i = 0; i < w; ++i) {
        if (srow[i]) last[i] = j;
        arow[i] = last[i];
      }
    }
    std::fill(last.begin(), last.end(), -1);
    for (int j = h - 1; j >= 0; --j) {
      const std::uint8_t* srow = seed.data() + std::size_t(j) * w;
      int* arow = row_of.data() + std::size_t(j) * w;
      float* frow = f.data() + std::size_t(j) * w;
      for (int i = 0; i < w; ++i) {
        if (srow[i]) last[i] = j;
        const int above = arow[i], below = last[i];
        // The seed above wins a tie (the lower index).
        const int s = above < 0 ? below : (below < 0 || j - above <= below - j) ? above : below;
        arow[i] = s;
        frow[i] = s < 0 ? big : float(double(j - s) * double(j - s));
      }
    }
  }
  const int n = std::max(w, h);
  std::vector<int> v(n + 1), arg(n);
  std::vector<double> z(n + 2);
  std::vector<float> out(n);
  std::vector<int> d(r.size());
  nearest.resize(r.size());  // every cell written below
  for (int j = 0; j < h; ++j) {
    const float* row = f.data() + std::size_t(j) * w;
    distance_1d(row, w, big, base, out.data(), arg.data(), v, z);
    for (int i = 0; i < w; ++i) {
      const std::size_t c = std::size_t(j) * w + i;
      // Squared distances are integers (exact in float below 2^24, and every float above
      // 2^23 is an integer): rounding is a truncation of x + 0.5.
      d[c] = out[i] >= float(cap) ? cap : int(out[i] + 0.5f);
      const int si = arg[i];
      nearest[c] = out[i] < 1e19f ? row_of[std::size_t(j) * w + si] * w + si : -1;
    }
  }
  return d;
}

/// For every cell, the largest t such that a 4-connected path from the raster border
/// reaches it through cells with d2 >= t (the bottleneck of the widest path): the cell is
/// outside the band of radius r exactly when b2 > r^2. Bucket queue over the (clamped,
/// integer) keys: O(cells).
std::vector<int> bottleneck(const Raster& r, const std::vector<int>& d2, int cap, std::vector<int>& next) {
  std::vector<int> b2(r.size(), -1);
  // Each bucket is a stack threaded through `next` (a cell enters one bucket, once; its
  // entry is written before it is read).
  std::vector<std::int32_t> head(std::size_t(cap) + 1, -1);
  next.resize(r.size());
  const auto push = [&](std::size_t c) {
    next[c] = head[b2[c]];
    head[b2[c]] = std::int32_t(c);
  };
  const auto seed = [&](int i, int j) {
    const std::size_t c = std::size_t(j) * r.w + i;
    if (b2[c] >= 0) return;
    b2[c] = d2[c];
    push(c);
  };
  for (int i = 0; i < r.w; ++i) {
    seed(i, 0);
    seed(i, r.h - 1);
  }
  for (int j = 0; j < r.h; ++j) {
    seed(0, j);
    seed(r.w - 1, j);
  }
  const std::size_t size = r.size();
  for (int level = cap; level >= 0; --level) {
    while (head[level] >= 0) {
      const std::uint32_t c = std::uint32_t(head[level]);
      head[level] = next[c];
      // Every border cell was seeded above, so a step that wraps to the other side of the
      // raster lands on a cell already set; only steps off its ends need a test.
      const std::size_t nb[4] = {std::size_t(c) - 1, std::size_t(c) + 1, std::size_t(c) - r.w, std::size_t(c) + r.w};
      for (int k = 0; k < 4; ++k) {
        if (nb[k] >= size || b2[nb[k]] >= 0) continue;
        b2[nb[k]] = std::min(level, d2[nb[k]]);
        push(nb[k]);
      }
    }
  }
  return b2;
}

/// Smallest r with r * r >= x.
int ceil_sqrt(int x) {
  int s = int(std::sqrt(double(x)));
  while (s * s < x) ++s;
  while (s > 0 && (s - 1) * (s - 1) >= x) --s;
  return s;
}

double bilinear(const Raster& r, const std::vector<float>& f, const Vec& c) {
  const double x = std::clamp(c.x(), 0.0, double(r.w - 1) - 1e-9);
  const double y = std::clamp(c.y(), 0.0, double(r.h - 1) - 1e-9);
  const int i = int(x), j = int(y);
  const double fx = x - i, fy = y - j;
  const std::size_t a = std::size_t(j) * r.w + i;
  return (1 - fy) * ((1 - fx) * f[a] + fx * f[a + 1]) +
         fy * ((1 - fx) * f[a + r.w] + fx * f[a + r.w + 1]);
}

/// Signed area of a closed polygon (positive counterclockwise).
double signed_area(const Points& p) {
  double a = 0;
  for (std::size_t i = 0, n = p.size(); i < n; ++i) {
    const Vec& u = p[i];
    const Vec& v = p[(i + 1) % n];
    a += u.x() * v.y() - v.x() * u.y();
  }
  return a / 2;
}

void smooth_closed(Points& p, int passes) {
  const std::size_t n = p.size();
  if (n < 3) return;
  Points q(n);
  for (int k = 0; k < passes; ++k) {
    for (std::size_t i = 0; i < n; ++i)
      q[i] = 0.25 * p[(i + n - 1) % n] + 0.5 * p[i] + 0.25 * p[(i + 1) % n];
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

/// Moore-neighbour trace of the component labelled `label` starting at its first cell in
/// raster order; stops when the first move repeats (Jacob's criterion), so one-cell-wide
/// parts are walked on both sides. Returns cell coordinates.
Points trace(const Raster& r, const std::vector<int>& label, int label_id, std::size_t start) {
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

/// Zhang-Suen's deletion test of a foreground cell for each of its 256 neighbourhoods
/// (bit k - 2 holds p_k, clockwise from north) in each of the two sub-steps.
struct ThinTable {
  bool remove[2][256] = {};
  ThinTable() {
    for (int bits = 0; bits < 256; ++bits) {
      int p[10] = {};
      for (int k = 2; k <= 9; ++k) p[k] = (bits >> (k - 2)) & 1;
      const int b = p[2] + p[3] + p[4] + p[5] + p[6] + p[7] + p[8] + p[9];
      int a = 0;
      for (int k = 2; k <= 9; ++k) a += !p[k] && p[k == 9 ? 2 : k + 1];
      const bool ok = b >= 2 && b <= 6 && a == 1;
      remove[0][bits] = ok && p[2] * p[4] * p[6] == 0 && p[4] * p[6] * p[8] == 0;
      remove[1][bits] = ok && p[2] * p[4] * p[8] == 0 && p[2] * p[6] * p[8] == 0;
    }
  }
};

/// Zhang-Suen thinning of a binary image (w x h, 1 = foreground, the outermost rows and
/// columns empty), in place. Only cells next to a deletion are looked at again, so the cost
/// is about the area.
void thin(std::vector<std::uint8_t>& img, int w, int h) {
  static const ThinTable table;
  // Foreground cells are never on the image's frame (the caller leaves it empty), so their
  // neighbours are all inside: fixed offsets, no bounds tests.
  const std::ptrdiff_t W = w;
  const std::ptrdiff_t around[9] = {-W - 1, -W, -W + 1, -1, 0, 1, W - 1, W, W + 1};
  std::vector<std::uint32_t> cand;
  std::vector<std::uint8_t> mark(img.size(), 0);
  for (std::size_t c = 0; c < img.size(); ++c)
    if (img[c] && (!img[c - 1] || !img[c + 1] || !img[c - W] || !img[c + W])) cand.push_back(std::uint32_t(c));
  std::vector<std::uint32_t> del, keep;
  int idle = 0;
  for (int step = 0; idle < 2; step ^= 1) {
    del.clear();
    keep.clear();
    for (std::uint32_t c : cand) {
      if (!img[c]) continue;
      const std::uint8_t* q = img.data() + c;
      const int bits = q[-W] | q[1 - W] << 1 | q[1] << 2 | q[W + 1] << 3 | q[W] << 4 | q[W - 1] << 5 | q[-1] << 6 |
                       q[-W - 1] << 7;
      if (table.remove[step][bits])
        del.push_back(c);
      else
        keep.push_back(c);
    }
    for (std::uint32_t c : del) img[c] = 0;
    idle = del.empty() ? idle + 1 : 0;
    // Next candidates: the surviving ones and the foreground neighbours of deleted cells.
    cand.clear();
    for (std::uint32_t c : keep)
      if (!mark[c]) {
        mark[c] = 1;
        cand.push_back(c);
      }
    for (std::uint32_t c : del)
      for (const std::ptrdiff_t o : around) {
        const std::uint32_t e = std::uint32_t(std::ptrdiff_t(c) + o);
        if (img[e] && !mark[e]) {
          mark[e] = 1;
          cand.push_back(e);
        }
      }
    for (std::uint32_t c : cand) mark[c] = 0;
  }
}

// ---------------------------------------------------------------------------------------
// One pass: raster of a point subset, closing, components.

struct Component {
  int label = 0;
  std::size_t start = 0;     // first cell in raster order
  std::size_t area = 0;      // cells
  std::size_t enclosed = 0;  // cells enclosed by the band at the closing radius
};

struct Pass {
  Raster raster;
  int closing = 0;                   // r_c: radius at which the band closed
  int radius = 0;                    // r: radius used (closing plus one step of margin)
  std::vector<int> label;            // component of the eroded fill, 0 = none
  std::vector<float> g;              // signed distance to the closing's boundary, cells, > 0 inside
  std::vector<Component> components; // index = label - 1
};

/// Builds the raster of `subset`, finds the closing radius and labels the closed fill.
/// Returns false when the band never encloses a substantial interior.
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
  Raster& r = pass.raster;
  r.cell = h;
  std::vector<Vec> mean;
  std::vector<int> slot, nearest_seed, d2, b2;
  Scratch scratch;
  int rc = 0;
  const auto substantial = [](long long cells) { return cells >= 16; };
  for (;;) {
    const double wc = std::floor((hi.x() - lo.x()) / h) + 1 + 2.0 * margin;
    const double hc = std::floor((hi.y() - lo.y()) / h) + 1 + 2.0 * margin;
    if (wc * hc > double(opt.max_cells) || wc > 2e9 || hc > 2e9)
      throw Error("morphology: a raster of " + num(wc) + " x " + num(hc) + " cells (cell " + num(h) +
                  " mm) exceeds max_cells " + std::to_string(opt.max_cells) +
                  "; use a larger cell or raise max_cells");
    r.w = int(wc);
    r.h = int(hc);
    r.x0 = lo.x() - margin * h;
    r.y0 = lo.y() - margin * h;

    // Seeds: cells holding points; each keeps the mean of its points so that distances to
    // the points are known to a small fraction of a cell (the raster alone gives half a cell).
    std::vector<std::uint8_t>& seed = scratch.bytes;
    seed.assign(r.size(), 0);
    slot.assign(r.size(), -1);
    mean.clear();
    std::vector<int> count;
    for (std::size_t k : subset) {
      const Vec c = r.to_cell(points[k]);
      const int i = std::clamp(int(std::lround(c.x())), 0, r.w - 1);
      const int j = std::clamp(int(std::lround(c.y())), 0, r.h - 1);
      const std::size_t cell = std::size_t(j) * r.w + i;
      seed[cell] = 1;
      if (slot[cell] < 0) {
        slot[cell] = int(mean.size());
        mean.emplace_back(0, 0);
        count.push_back(0);
      }
      mean[slot[cell]] += c;
      ++count[slot[cell]];
    }
    for (std::size_t m = 0; m < mean.size(); ++m) mean[m] /= count[m];
    const int cap = (rmax + 1) * (rmax + 1);
    d2 = distance_transform(r, seed, cap, rmax + 2 - margin, nearest_seed, scratch);
    b2 = bottleneck(r, d2, cap, scratch.ints);

    // A cell is enclosed at radius r when b2 <= r^2 < d2: inside the band of radius r but
    // not on it. Cells enclosed at some radius (b2 < d2) are the interior of closed
    // profiles; each part of an interior closes at its own radius b (the half width of the
    // widest gap leading to it), so the closing radius r_c is the radius by which all of
    // them have closed. Taking the first radius at which some
    // interior appears instead leaves a part of a thin profile open behind a wide hole
    // when the band pinches the profile elsewhere first.
    std::vector<long long> closing_at(rmax + 2, 0);
    long long ever = 0;
    // b2 and d2 lie in [0, cap]: their ceil_sqrt from a table (one per interior cell).
    std::vector<int> root(std::size_t(cap) + 1);
    for (int x = 0; x <= cap; ++x) root[x] = ceil_sqrt(x);
    for (std::size_t c = 0; c < r.size(); ++c) {
      if (b2[c] >= d2[c]) continue;
      const int a = std::max(1, root[b2[c]]);
      if (a > rmax || a > root[d2[c]] - 1) continue;  // never enclosed at an integer radius <= rmax
      ++closing_at[a];
      ++ever;
    }
    if (!substantial(ever)) return false;
    rc = 0;
    for (long long sum = 0; rc < rmax && sum < ever;) sum += closing_at[++rc];
    pass.closing = rc;
    // Margin: twice the closing radius (at least 4 cells). A disc just able to bridge a gap
    // dips into it by about its radius and may cut a thin trailing edge in two; a disc twice
    // as large dips by a quarter of that.
    pass.radius = std::min(std::max(2 * rc, 4), rmax);
    if (pass.radius + 2 <= margin) break;
    margin = pass.radius + 2;
  }
  const int rr = pass.radius * pass.radius;

  // Erode the fill back: keep the cells farther than r from the outside.
  std::vector<std::uint8_t>& outside = scratch.bytes;
  for (std::size_t c = 0; c < r.size(); ++c) outside[c] = b2[c] > rr;
  const double far = 2.0 * std::max(r.w, r.h) * std::max(r.w, r.h) + 4;
  const int cap_out = int(std::min(far, double(1 << 30)));
  std::vector<int> nearest_out;
  const std::vector<int> out2 = distance_transform(r, outside, cap_out, rmax + 2 - margin, nearest_out, scratch);

  // The closing's complement is about the union of the empty discs centred on outside
  // cells y, of radius d(y) = distance from y to the nearest point. With y* the outside
  // cell nearest to x, g(x) = |x - y*| - d(y*) is the signed distance of x to that union:
  // its zero level is the boundary to a small fraction of a cell, and it passes through
  // the outermost points.
  const auto exact_d = [&](std::size_t y) {
    const int s = nearest_seed[y];
    if (s < 0) return float(rmax + 1);
    const Vec c(double(y % r.w), double(y / r.w));
    return float((c - mean[slot[s]]).norm());
  };
  pass.g = std::move(scratch.f);  // every cell written below
  for (std::size_t c = 0; c < r.size(); ++c) {
    const int y = nearest_out[c];
    pass.g[c] = y < 0 ? float(rmax + 1) : std::sqrt(float(out2[c])) - exact_d(std::size_t(y));
  }

  // 8-connected components of the fill (out2 > r^2), labelled in raster order of their
  // first cell. `open` marks fill cells not labelled yet (one byte per cell: cheaper to
  // test than out2 and label).
  pass.label = std::move(scratch.ints);
  std::fill(pass.label.begin(), pass.label.end(), 0);
  std::vector<std::uint8_t>& open = scratch.bytes;
  for (std::size_t c = 0; c < r.size(); ++c) open[c] = out2[c] > rr;
  const std::ptrdiff_t W = r.w;
  const std::ptrdiff_t around[8] = {-W - 1, -W, -W + 1, -1, 1, W - 1, W, W + 1};
  std::vector<std::uint32_t> queue;
  for (std::size_t c0 = 0; c0 < r.size(); ++c0) {
    if (!open[c0]) continue;
    Component comp;
    comp.label = int(pass.components.size()) + 1;
    comp.start = c0;
    pass.label[c0] = comp.label;
    open[c0] = 0;
    queue.assign(1, std::uint32_t(c0));
    for (std::size_t q = 0; q < queue.size(); ++q) {
      const std::uint32_t c = queue[q];
      ++comp.area;
      if (b2[c] < d2[c]) ++comp.enclosed;
      const int i = int(c % r.w), j = int(c / r.w);
      if (i > 0 && j > 0 && i + 1 < r.w && j + 1 < r.h) {
        for (const std::ptrdiff_t o : around) {
          const std::size_t e = std::size_t(std::ptrdiff_t(c) + o);
          if (open[e]) {
            open[e] = 0;
            pass.label[e] = comp.label;
            queue.push_back(std::uint32_t(e));
          }
        }
        continue;
      }
      for (int y = std::max(0, j - 1); y <= std::min(r.h - 1, j + 1); ++y)
        for (int x = std::max(0, i - 1); x <= std::min(r.w - 1, i + 1); ++x) {
          const std::size_t e = std::size_t(y) * r.w + x;
          if (open[e]) {
            open[e] = 0;
            pass.label[e] = comp.label;
            queue.push_back(std::uint32_t(e));
          }
        }
    }
    pass.components.push_back(comp);
  }
  for (auto& comp : pass.components)
    if (!substantial(comp.enclosed)) comp.enclosed = 0;  // an open band or a fragment
  return true;
}

/// The boundary of one component in world coordinates, counterclockwise: the Moore trace
/// smoothed a little, then each vertex moved along its normal onto the zero level of g.
Points component_boundary(const Pass& pass, const Component& comp) {
  Points b = trace(pass.raster, pass.label, comp.label, comp.start);
  if (b.size() < 3) return {};
  if (signed_area(b) < 0) std::reverse(b.begin(), b.end());
  smooth_closed(b, 2);
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

// ---------------------------------------------------------------------------------------
// Nearest boundary segment of any loop (grid of segments, cell >= the search radius).

struct Foot {
  int loop = -1;
  double s = 0;         // arc length of the foot along the loop's boundary
  double distance = 0;  // to the boundary
  Vec normal{0, 0};     // outward normal of the boundary segment
};

class SegmentGrid {
public:
  SegmentGrid(const std::vector<const Points*>& loops, double cell) : loops_(loops), cell_(cell) {
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
    std::sort(keyed.begin(), keyed.end());
    std::vector<std::int64_t> keys(keyed.size());
    ids_.resize(keyed.size());
    for (std::size_t a = 0; a < keyed.size(); ++a) {
      keys[a] = keyed[a].first;
      ids_[a] = keyed[a].second;
    }
    cells_ = CellTable(keys);
  }

  double length(int loop) const { return cum_[loop].back(); }

  /// The nearest boundary foot within `cell` of p (loop -1 when none).
  Foot nearest(const Vec& p) const {
    Foot best;
    double best2 = cell_ * cell_;
    const std::int64_t ci = ix(p.x()), cj = ix(p.y());
    for (std::int64_t j = cj - 1; j <= cj + 1; ++j)
      for (std::int64_t i = ci - 1; i <= ci + 1; ++i) {
        const auto [begin, end] = cells_.find(cell_key(i, j));
        for (std::size_t a = begin; a < end; ++a) {
          const int l = int(ids_[a] >> 32);
          const std::size_t k = std::size_t(ids_[a] & 0xffffffffu);
          const Points& q = *loops_[l];
          const Vec& u = q[k];
          const Vec& v = q[(k + 1) % q.size()];
          const Vec e = v - u;
          const double e2 = e.squaredNorm();
          const double t = e2 > 0 ? std::clamp((p - u).dot(e) / e2, 0.0, 1.0) : 0.0;
          const double d2 = (u + t * e - p).squaredNorm();
          if (d2 < best2) {
            best2 = d2;
            best.loop = l;
            best.s = cum_[l][k] + t * std::sqrt(e2);
            best.distance = std::sqrt(d2);
            best.normal = e2 > 0 ? Vec(e.y(), -e.x()) / std::sqrt(e2) : Vec(0, 0);
          }
        }
      }
    return best;
  }

private:
  std::int64_t ix(double x) const { return std::int64_t(std::floor(x / cell_)); }
  std::vector<const Points*> loops_;
  double cell_;
  std::vector<std::vector<double>> cum_;
  std::vector<std::uint64_t> ids_;
  CellTable cells_{{}};
};

/// Outward normal at p from the gradient of the component's filled image blurred by a
/// Gaussian of `sigma` cells: -grad (G * I)(p) is proportional to sum I(c) (p - c) G(p - c).
/// I is the fill anti-aliased with g (coverage clamp(1/2 + g, 0, 1)), so that the
/// direction is not that of the cell staircase.
Vec image_normal(const Pass& pass, int label_id, const Vec& p, double sigma) {
  const Raster& r = pass.raster;
  const Vec c = r.to_cell(p);
  const int k = int(std::ceil(3 * sigma));
  const int i0 = int(std::floor(c.x())) - k + 1, j0 = int(std::floor(c.y())) - k + 1;
  const int n = 2 * k;
  double gx[64], gy[64];
  const double inv = 1 / (2 * sigma * sigma);
  for (int a = 0; a < n; ++a) {
    const double tx = c.x() - (i0 + a), ty = c.y() - (j0 + a);
    gx[a] = std::exp(-tx * tx * inv);
    gy[a] = std::exp(-ty * ty * inv);
  }
  // The window clipped to the raster (cells off it are left out).
  const int a0 = std::max(0, -i0), a1 = std::min(n, r.w - i0);
  const int b0 = std::max(0, -j0), b1 = std::min(n, r.h - j0);
  // Summed per coordinate: a Vec built per cell went through the stack, and its packed
  // reload waited on the two stores (the same sums, several times slower).
  double gx_sum = 0, gy_sum = 0;
  for (int b = b0; b < b1; ++b) {
    const int j = j0 + b;
    const int* label = pass.label.data() + std::size_t(j) * r.w;
    const float* dist = pass.g.data() + std::size_t(j) * r.w;
    for (int a = a0; a < a1; ++a) {
      const int i = i0 + a;
      const int l = label[i];
      if (l != label_id && l != 0) continue;
      const double cover = std::clamp(0.5 + double(dist[i]), 0.0, 1.0);
      if (cover == 0) continue;
      const double wgt = cover * gx[a] * gy[b];
      gx_sum += wgt * (c.x() - i);
      gy_sum += wgt * (c.y() - j);
    }
  }
  const Vec g(gx_sum, gy_sum);
  const double l = g.norm();
  return l > 1e-12 ? Vec(g / l) : Vec(0, 0);
}

/// Skeleton of a component: Zhang-Suen thinning, then the longest path (two Dijkstra
/// searches over the 8-connected skeleton cells), radius = distance to the boundary.
void skeleton_of(const Pass& pass, const Component& comp, MorphologyResult& result) {
  const Raster& r = pass.raster;
  int i0 = r.w, i1 = -1, j0 = r.h, j1 = -1;
  for (int j = 0; j < r.h; ++j)
    for (int i = 0; i < r.w; ++i)
      if (pass.label[std::size_t(j) * r.w + i] == comp.label) {
        i0 = std::min(i0, i);
        i1 = std::max(i1, i);
        j0 = std::min(j0, j);
        j1 = std::max(j1, j);
      }
  if (i1 < 0) return;
  const int w = i1 - i0 + 3, h = j1 - j0 + 3;  // one empty cell around
  std::vector<std::uint8_t> img(std::size_t(w) * h, 0);
  for (int j = j0; j <= j1; ++j)
    for (int i = i0; i <= i1; ++i)
      img[std::size_t(j - j0 + 1) * w + (i - i0 + 1)] = pass.label[std::size_t(j) * r.w + i] == comp.label;
  thin(img, w, h);

  std::vector<std::uint32_t> cells;
  for (std::size_t c = 0; c < img.size(); ++c)
    if (img[c]) cells.push_back(std::uint32_t(c));
  if (cells.empty()) return;
  // Read and written at skeleton cells only (set by each search): left uninitialised, the
  // pages of the other cells are never touched.
  const std::unique_ptr<double[]> dist(new double[img.size()]);
  const std::unique_ptr<std::int64_t[]> prev(new std::int64_t[img.size()]);
  const auto search = [&](std::uint32_t from) {
    for (std::uint32_t c : cells) {
      dist[c] = std::numeric_limits<double>::infinity();
      prev[c] = -1;
    }
    using Item = std::pair<double, std::uint32_t>;
    std::priority_queue<Item, std::vector<Item>, std::greater<Item>> pq;
    dist[from] = 0;
    pq.emplace(0.0, from);
    std::uint32_t far = from;
    while (!pq.empty()) {
      auto [d, c] = pq.top();
      pq.pop();
      if (d > dist[c]) continue;
      if (d > dist[far]) far = c;
      const int i = int(c % w), j = int(c / w);
      for (int y = j - 1; y <= j + 1; ++y)
        for (int x = i - 1; x <= i + 1; ++x) {
          const std::uint32_t e = std::uint32_t(y) * w + x;
          if (e == c || !img[e]) continue;
          const double nd = d + ((x != i && y != j) ? std::sqrt(2.0) : 1.0);
          if (nd < dist[e]) {
            dist[e] = nd;
            prev[e] = c;
            pq.emplace(nd, e);
          }
        }
    }
    return far;
  };
  const std::uint32_t a = search(cells[0]);
  const std::uint32_t b = search(a);
  Points path;
  std::vector<double> radius;
  for (std::int64_t c = b; c >= 0; c = prev[c]) {
    const int i = int(c % w) - 1 + i0, j = int(c / w) - 1 + j0;
    path.push_back(r.to_world(Vec(i, j)));
    radius.push_back(std::max(0.0, double(pass.g[std::size_t(j) * r.w + i])) * r.cell);
  }
  // Light smoothing of the staircase, ends kept.
  for (int pass_k = 0; pass_k < 2 && path.size() > 2; ++pass_k) {
    Points q = path;
    for (std::size_t i = 1; i + 1 < path.size(); ++i)
      q[i] = 0.25 * path[i - 1] + 0.5 * path[i] + 0.25 * path[i + 1];
    path.swap(q);
  }
  // Start at the blunter end (usually the leading edge).
  const std::size_t m = std::max<std::size_t>(1, path.size() / 10);
  double head = 0, tail = 0;
  for (std::size_t i = 0; i < m; ++i) {
    head += radius[i];
    tail += radius[radius.size() - 1 - i];
  }
  if (tail > head) {
    std::reverse(path.begin(), path.end());
    std::reverse(radius.begin(), radius.end());
  }
  result.skeleton = std::move(path);
  result.skeleton_radius = std::move(radius);
}

/// Drops the points of one ordered loop that stand off the curve of their neighbours along
/// the loop: an outlier close to the profile is in the raster, so the closing passes
/// through it and its distance to the boundary is small; a quadratic fitted to its
/// neighbours along the loop (up to 3 each side within 12 cells, the point left out) shows
/// its offset. Returns the number dropped.
std::size_t drop_spikes(const Points& points, const std::vector<Vec>& normal_at,
                        const Points& boundary, double h, double limit,
                        std::vector<std::pair<double, std::size_t>>& mem) {
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

struct Found {
  int pass = 0;
  int component = 0;  // index into pass.components
  Points boundary;
  double area = 0;
};

}  // namespace

double spacing_2d(const std::vector<Eigen::Vector2d>& points, std::size_t sample) {
  std::vector<std::size_t> all(points.size());
  std::iota(all.begin(), all.end(), std::size_t(0));
  for (const Vec& p : points)
    if (!p.allFinite()) throw Error("morphology: a point has a non-finite coordinate");
  return median_spacing(points, all, std::max<std::size_t>(1, sample));
}

MorphologyResult order_section(const std::vector<Eigen::Vector2d>& points,
                               const MorphologyOptions& opt) {
  if (points.empty()) throw Error("morphology: no points");
  if (!(opt.cell >= 0) || !std::isfinite(opt.cell)) throw Error("morphology: cell must be >= 0, got " + num(opt.cell));
  if (opt.max_dilation < 1) throw Error("morphology: max_dilation must be >= 1");
  if (!(opt.outlier_distance >= 0) || !(opt.isolated_distance >= 0))
    throw Error("morphology: outlier_distance and isolated_distance must be >= 0");
  if (!(opt.normal_sigma > 0) || opt.normal_sigma > 10) throw Error("morphology: normal_sigma must be in (0, 10] cells");
  const std::size_t min_points = std::max<std::size_t>(3, opt.min_points);
  if (points.size() < min_points)
    throw Error("morphology: " + std::to_string(points.size()) + " points, at least " +
                std::to_string(min_points) + " are needed");
  for (std::size_t k = 0; k < points.size(); ++k)
    if (!points[k].allFinite()) throw Error("morphology: point " + std::to_string(k) + " is not finite");

  std::vector<std::size_t> all(points.size());
  std::iota(all.begin(), all.end(), std::size_t(0));
  double h = opt.cell;
  if (h == 0) {
    h = median_spacing(points, all, 20000);
    Vec lo, hi;
    robust_box(points, all, 0.001, lo, hi);
    const Vec ext = hi - lo;
    h = std::max(h, std::sqrt(ext.x() * ext.y() / double(std::max<std::size_t>(1, opt.auto_cells))));
    h = std::max(h, 1e-4 * ext.norm());
    if (!(h > 0)) throw Error("morphology: the points are all equal; no loop can be formed");
  }
  {
    // Refuse an oversized raster before anything is allocated (its size with no margin is
    // a lower bound of every pass's raster).
    Vec lo = points[0], hi = lo;
    for (const Vec& p : points) {
      lo = lo.cwiseMin(p);
      hi = hi.cwiseMax(p);
    }
    const double wc = std::floor((hi.x() - lo.x()) / h) + 1, hc = std::floor((hi.y() - lo.y()) / h) + 1;
    if (wc * hc > double(opt.max_cells))
      throw Error("morphology: a raster of " + num(wc) + " x " + num(hc) + " cells (cell " + num(h) +
                  " mm) exceeds max_cells " + std::to_string(opt.max_cells) +
                  "; use a larger cell or raise max_cells");
  }
  const double outlier = opt.outlier_distance > 0 ? opt.outlier_distance : 2.5 * h;
  const double isolated = opt.isolated_distance > 0 ? opt.isolated_distance : 6 * h;

  // Isolated points stay out of the raster so that they cannot make loops or bumps.
  std::vector<std::size_t> subset;
  {
    const PointGrid grid(points, all, isolated);
    for (std::size_t k : all)
      if (grid.has_neighbour(k, isolated)) subset.push_back(k);
  }

  MorphologyResult result;
  result.cell = h;
  std::vector<Pass> passes;
  std::vector<Found> found;
  // The points of the last grid built in the loop below (ascending, as `subset`) and their
  // feet on it: that grid is built over `found` as the loop leaves it, so they are reused
  // when sorting by area leaves that order as it is.
  std::vector<std::size_t> footed;
  std::vector<Foot> feet;
  while (subset.size() >= min_points && int(found.size()) < opt.max_loops) {
    Pass pass;
    if (!run_pass(points, subset, h, opt, pass)) break;
    if (passes.empty()) result.raster_cells = pass.raster.size();
    const std::size_t before = found.size();
    for (std::size_t ci = 0; ci < pass.components.size(); ++ci) {
      const Component& comp = pass.components[ci];
      if (comp.enclosed == 0) continue;
      Found f;
      f.pass = int(passes.size());
      f.component = int(ci);
      f.boundary = component_boundary(pass, comp);
      if (f.boundary.size() < 3) continue;
      f.area = signed_area(f.boundary);
      found.push_back(std::move(f));
    }
    passes.push_back(std::move(pass));
    if (found.size() == before) break;
    // Points far from every loop so far are processed again on their own.
    std::vector<const Points*> bounds;
    for (const Found& f : found) bounds.push_back(&f.boundary);
    const SegmentGrid segs(bounds, outlier);
    footed = subset;
    feet.clear();
    std::vector<std::size_t> left;
    for (std::size_t k : subset) {
      feet.push_back(segs.nearest(points[k]));
      if (feet.back().loop < 0) left.push_back(k);
    }
    if (left.size() == subset.size()) break;
    subset.swap(left);
  }
  if (found.empty())
    throw Error("morphology: the " + std::to_string(points.size()) +
                " points do not close into a loop up to a dilation of " +
                std::to_string(opt.max_dilation) + " cells (cell " + num(h) +
                " mm); the section may be open or too sparse: try a larger cell or max_dilation");

  // Largest area first.
  const auto larger = [](const Found& a, const Found& b) { return a.area > b.area; };
  if (!std::is_sorted(found.begin(), found.end(), larger)) {
    std::stable_sort(found.begin(), found.end(), larger);
    footed.clear();
  }
  std::vector<const Points*> bounds;
  for (const Found& f : found) bounds.push_back(&f.boundary);
  const SegmentGrid segs(bounds, outlier);

  // Every input point joins the loop nearest to it, or is dropped.
  std::vector<std::vector<std::pair<double, std::size_t>>> members(found.size());
  std::vector<Vec> fallback(points.size());
  std::size_t dropped = 0;
  for (std::size_t k = 0, next = 0; k < points.size(); ++k) {
    const bool known = next < footed.size() && footed[next] == k;
    const Foot foot = known ? feet[next++] : segs.nearest(points[k]);
    if (foot.loop < 0) {
      ++dropped;
      continue;
    }
    members[foot.loop].emplace_back(foot.s, k);
    fallback[k] = foot.normal;
  }

  for (std::size_t l = 0; l < found.size(); ++l) {
    auto& mem = members[l];
    std::sort(mem.begin(), mem.end());
    dropped += drop_spikes(points, fallback, found[l].boundary, h, outlier, mem);
    if (mem.size() < min_points) {
      dropped += mem.size();
      continue;
    }
    const Found& f = found[l];
    const Pass& pass = passes[f.pass];
    const Component& comp = pass.components[f.component];
    Loop loop;
    loop.boundary = f.boundary;
    loop.area = f.area;
    for (std::size_t i = 0; i < f.boundary.size(); ++i)
      loop.length += (f.boundary[(i + 1) % f.boundary.size()] - f.boundary[i]).norm();
    loop.dilation = pass.radius;
    loop.points.reserve(mem.size());
    loop.normals.reserve(mem.size());
    loop.index.reserve(mem.size());
    for (const auto& [s, k] : mem) {
      Vec n = image_normal(pass, comp.label, points[k], opt.normal_sigma);
      if (n.isZero()) n = fallback[k];
      loop.points.push_back(points[k]);
      loop.normals.push_back(n);
      loop.index.push_back(k);
    }
    if (result.loops.empty()) {
      result.dilation = pass.radius;
      if (opt.skeleton) skeleton_of(pass, comp, result);
    }
    result.loops.push_back(std::move(loop));
  }
  if (result.loops.empty())
    throw Error("morphology: no loop keeps at least " + std::to_string(min_points) + " points");
  result.dropped = dropped;
  return result;
}

}  // namespace section
